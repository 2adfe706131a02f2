// Study "bodies": every integrator on the contacts between bodies (issue 23), where the
// Delassus operator H = L M^{-1} L^T is not diagonal; a scheme that declines a problem gets one
// n/a row per table, with its reason.
//
// Cases (kCases, one line of data each), each run at its knobs:
// - ball-chain, n = 3, v0 = 1, m = 1, e = 1 and 0.5: touching (gap = 0, dt = 1e-3) and
//   gap = 0.1 at dt v0 / gap = 0.01, 0.1, 1, 10; to t = max(3, 20 dt) (the last collision of
//   the march, e = 0.5, is at 1.8). The final velocities v against the sequential outcome
//   (binary collisions) and Moreau's simultaneous one (BallChain::sequential_outcome(),
//   simultaneous_outcome()): distances max_i |v_i - v_i,law| / v0, and the verdict: the law
//   within kLawTol v0 (the nearer one), else "neither". Momentum change |P - P0| / (m v0),
//   kinetic energy change (K - K0) / K0.
// - two-blocks at its defaults (lower 5 x 2, upper 7 x 2 Q4, non-matching), no gravity (the
//   total momentum then changes by the floor's impulses alone: the node-to-segment weights
//   sum to zero), upper block at (0.5, -1) m/s, e = 0, mu = 0 and 0.3, dt = 1e-4, to t = 0.1 s
//   (it lands at 0.05 s). Momentum residual max_k |Delta P_k - (floor impulses)_k| /
//   sum_a m_a |v_a,0|; energy: the largest step increase (E_{k+1} - E_k) / E0 and
//   (max E - E0) / E0 (e = 0, no gravity: no energy source); CPU per step and LCP iterations
//   per step; the same for the two blocks run apart as block-2d problems (the same blocks,
//   each on the floor alone: every contact row on one node, H diagonal), and the cost ratio
//   (together / apart): the measured verdict on the "matrix-free explicit LCP" claim.
// - two-bars (L1 = 1, L2 = 2, N2 = 2 N1, lumped, v0 = 1, c = 1) and mass-on-bar (M = 1 = the
//   bar's mass, N elements, lumped), N = 10, 20, 40 (the Siconos peers' size limit), dt = 0.9 h/c. two-bars to t = 3 (the
//   contact lasts 2 L1/c = 2): contact duration (from the start of the first step with an
//   impulse to the end of the last one whose force Lambda/dt >= F0/2, F0 = rho c v0 / 2),
//   bar 1's mean velocity at t = 3 (exact 0), contact force error in the time-L1 norm
//   sum_k |Lambda_k/dt - F(t_k - dt/2)| dt / int F dt. mass-on-bar to its last separation
//   plus L/c: the same force error and the mass's exit velocity |V - V_exact| / v0 at the end.
//   Orders between consecutive meshes, errors at round-off (kRoundOffError) carry none.
// Trajectories (table bodies_cradle_trajectory, figure of the same name): each ball's position
// x_i = (i - 1) gap + U_i relative to the centre of mass, x_i - mean_j x_j, after every step of
// the cradle with gap 0.1, e = 0.5 at dt v0 / gap = 0.1, each scheme in its panel over the exact
// march (BallChain::state, its ExactSolution). In the centre-of-mass frame (it drifts at v0 / n) each
// collision is a kink between flat or sloped lines, which the drift would flatten out.
// Deformed blocks (tables bodies_blocks_deformed and bodies_blocks_deformed_impulses, figure
// bodies_blocks_deformed): the mu = 0 two-blocks run of kSnapshotSchemes at the initial state,
// the first contact, the largest strain energy and the end (studies/snapshots.hpp).
// Each run has a budget of kStepBudget F_int evaluations per step of the requested size.
// Ranking (studies/ranking.hpp): the cheapest integrator reaching a contact-force error (the
// time-L1 one above) of 1e-1, 5e-2, 3e-2 (two-bars) and 3e-1, 2e-1, 1e-1 (mass-on-bar; the
// explicit schemes reach 0.09 at N = 40), cost the median CPU time of 3
// unobserved runs. (The exit errors are not ranked: they do not fall monotonically with the
// mesh.)
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/ball_chain.hpp"
#include "problems/mass_on_bar.hpp"
#include "problems/registry.hpp"
#include "problems/two_bars.hpp"
#include "problems/two_blocks.hpp"
#include "studies/ranking.hpp"
#include "studies/snapshots.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr long kBodiesStepBudget = 20;
constexpr double kLawTol = 0.05;     // [v0]: a final velocity this close to a law reproduces it
constexpr double kGap = 0.1;         // [m]: the cradle's gap when not touching
const std::vector<double> kBarsTargets = {1e-1, 5e-2, 3e-2}, kStrikerTargets = {3e-1, 2e-1, 1e-1};

enum class BodiesGroup { Cradle, Blocks, Bars };

struct BodiesCase {
  std::string id;  // the case's name in the case list (tests run one by it)
  BodiesGroup group;
  std::string label;
  std::string problem;
  std::map<std::string, std::string> params;
  std::vector<double> knobs;  // cradle: dt v0 / gap (touching: dt); blocks: dt; bars: N
};

const std::vector<double> kRatios = {0.01, 0.1, 1, 10};
// The run whose ball positions are kept, and the exact march's samples for its figure.
const std::string kBodiesTrajectoryCase = "cradle-gap-e05";
constexpr double kTrajectoryRatio = 0.1;
constexpr int kBodiesExactSamples = 600;
// The two-blocks case whose runs of kSnapshotSchemes are pictured deformed.
const std::string kSnapshotCase = "blocks";
// The Siconos peers take at most 128 dofs (dense matrices): two-bars at N = 40 has 122.
const std::vector<double> kMeshes = {10, 20, 40};
const std::map<std::string, std::string> kBlocks = {{"g", "0"}, {"upper_vx", "0.5"}, {"upper_vy", "-1"}, {"e", "0"}};

std::map<std::string, std::string> with(std::map<std::string, std::string> p, const std::string& key,
                                        const std::string& value) {
  p[key] = value;
  return p;
}

const std::vector<BodiesCase> kBodiesCases = {
    {"cradle-touching-e1", BodiesGroup::Cradle, "e 1, touching", "ball-chain", {{"n", "3"}, {"gap", "0"}, {"e", "1"}}, {1e-3}},
    {"cradle-gap-e1", BodiesGroup::Cradle, "e 1, gap 0.1", "ball-chain", {{"n", "3"}, {"gap", "0.1"}, {"e", "1"}}, kRatios},
    {"cradle-touching-e05", BodiesGroup::Cradle, "e 0.5, touching", "ball-chain", {{"n", "3"}, {"gap", "0"}, {"e", "0.5"}}, {1e-3}},
    {"cradle-gap-e05", BodiesGroup::Cradle, "e 0.5, gap 0.1", "ball-chain", {{"n", "3"}, {"gap", "0.1"}, {"e", "0.5"}}, kRatios},
    {"blocks", BodiesGroup::Blocks, "mu 0", "two-blocks", kBlocks, {1e-4}},
    {"blocks-mu", BodiesGroup::Blocks, "mu 0.3", "two-blocks", with(kBlocks, "mu", "0.3"), {1e-4}},
    {"two-bars", BodiesGroup::Bars, "two-bars, L1 1, L2 2, lumped", "two-bars", {{"L1", "1"}, {"L2", "2"}}, kMeshes},
    {"mass-on-bar", BodiesGroup::Bars, "mass-on-bar, M 1, lumped", "mass-on-bar", {{"M", "1"}}, kMeshes},
};

const BodiesCase& find_bodies_case(const std::string& id) {
  for (const auto& c : kBodiesCases)
    if (c.id == id) return c;
  throw InputError(fmt::format("bodies study: no case {}", id));
}

RunOptions options_for(double dt, double t_end) {
  RunOptions options;
  options.dt = dt;
  options.t_end = t_end;
  options.record_series = false;
  options.max_force_evaluations = kBodiesStepBudget * static_cast<long>(std::ceil(t_end / dt));
  return options;
}

Json status_of(const RunResult& r) {
  return {{"status", status_name(r.status)}, {"message", r.message}, {"steps", r.steps}, {"cpu", r.step_cpu_seconds}};
}

Json run_cradle(const BodiesCase& bc, const std::string& integrator_name, double knob) {
  const bool touching = bc.params.at("gap") == "0";
  const double dt = touching ? knob : knob * kGap;  // v0 = 1
  const BallChain chain(Params(BallChain::parameters_spec(), bc.params));
  auto integrator = make_integrator(integrator_name);
  if (const auto declined = init_or_decline(*integrator, chain)) return {{"status", kDeclinedStatus}, {"message", *declined}};
  const Vec v0 = chain.initial_state().v;
  const bool trajectory = bc.id == kBodiesTrajectoryCase && knob == kTrajectoryRatio;
  std::vector<double> trajectory_t = {0.0}, trajectory_u(v0.size(), 0.0);
  const RunResult r = run(chain, *integrator, options_for(dt, std::max(3.0, 20 * dt)), [&](const Integrator& it, const StepInfo&) {
    if (!trajectory) return;
    trajectory_t.push_back(it.state().t);
    trajectory_u.insert(trajectory_u.end(), it.state().u.begin(), it.state().u.end());
  });
  Json out = status_of(r);
  out["dt"] = dt;
  if (r.status != RunStatus::Ok) return out;
  if (trajectory) {
    out["trajectory_t"] = trajectory_t;
    out["trajectory_u"] = reals(trajectory_u);  // step by step, ball by ball
  }
  const Vec& v = integrator->state().v;
  const double scale = std::abs(v0[0]), seq = (v - chain.sequential_outcome()).cwiseAbs().maxCoeff() / scale,
               sim = (v - chain.simultaneous_outcome()).cwiseAbs().maxCoeff() / scale;
  const bool is_sim = sim <= kLawTol && sim <= seq, is_seq = seq <= kLawTol && seq < sim;
  out.update({{"d_sequential", seq},
              {"d_simultaneous", sim},
              {"verdict", is_sim ? "simultaneous" : is_seq ? "sequential" : "neither"},
              {"v", reals({v.begin(), v.end()})},
              {"dP", std::abs(chain.momentum(v) - chain.momentum(v0)) / (chain.parameters().real("m") * scale)},
              {"dK", (chain.kinetic_energy(v) - chain.kinetic_energy(v0)) / chain.kinetic_energy(v0)}});
  return out;
}

// CPU time per step (median of 3 unobserved runs) and LCP iterations per step of one run of
// `integrator_name` on `problem`; NaN when the run is not ok.
std::pair<double, double> cost_per_step(const Problem& problem, const std::string& integrator_name,
                                        const RunOptions& options) {
  auto integrator = make_integrator(integrator_name);
  integrator->init(problem, problem.initial_state());
  const RunResult r = run(problem, *integrator, options);
  if (r.status != RunStatus::Ok) return {kNaN, kNaN};
  const double steps = static_cast<double>(r.steps);
  return {median_cpu_seconds(problem, integrator_name, {}, options) / steps,
          static_cast<double>(integrator->work().lcp_iterations) / steps};
}

Json run_blocks(const BodiesCase& bc, const std::string& integrator_name, double dt) {
  constexpr double kEnd = 0.1;
  const TwoBlocks blocks(Params(TwoBlocks::parameters_spec(), bc.params));
  auto integrator = make_integrator(integrator_name);
  if (const auto declined = init_or_decline(*integrator, blocks)) return {{"status", kDeclinedStatus}, {"message", *declined}};
  const Index pf = blocks.floor_contacts();
  const SpMat M = blocks.mass_matrix();
  Vec v_prev = integrator->state().v;
  double p_scale = 0.0;
  for (Index a = 0; a < blocks.ndof() / 2; ++a) p_scale += M.coeff(2 * a, 2 * a) * v_prev.segment<2>(2 * a).norm();
  const double e0 = integrator->energy().total();
  double residual = 0.0, between = 0.0, e_prev = e0, e_max = e0, step_gain = 0.0;
  std::optional<MeshSnapshots> pictures;
  if (bc.id == kSnapshotCase && std::count(kSnapshotSchemes.begin(), kSnapshotSchemes.end(), integrator_name)) {
    pictures.emplace(blocks, "sigma_yy");
    pictures->add(integrator->state(), Vec(), Vec());
  }
  const RunOptions options = options_for(dt, kEnd);
  const RunResult r = run(blocks, *integrator, options, [&](const Integrator& it, const StepInfo&) {
    if (pictures) pictures->add(it.state(), it.impulses(), it.tangential_impulses());
    const Eigen::Vector2d dP = blocks.linear_momentum(it.state().v) - blocks.linear_momentum(v_prev);
    const Eigen::Vector2d floor(it.tangential_impulses().head(pf).sum(), it.impulses().head(pf).sum());
    residual = std::max(residual, (dP - floor).norm() / p_scale);
    between += it.impulses().tail(blocks.ncontacts() - pf).sum();
    v_prev = it.state().v;
    const double e = it.energy().total();
    step_gain = std::max(step_gain, (e - e_prev) / e0);
    e_max = std::max(e_max, e);
    e_prev = e;
  });
  Json out = status_of(r);
  if (pictures) out["snapshots"] = pictures->finish();
  if (r.status != RunStatus::Ok) return out;
  const auto [cpu, lcp] = cost_per_step(blocks, integrator_name, options);
  // The same blocks apart: block-2d problems with the two-blocks' own block parameters.
  const Block2d lower(blocks.lower().parameters()), upper(blocks.upper().parameters());
  const auto [cpu_lower, lcp_lower] = cost_per_step(lower, integrator_name, options);
  const auto [cpu_upper, lcp_upper] = cost_per_step(upper, integrator_name, options);
  out.update({{"p_residual", residual},
              {"between", between},
              {"step_gain", step_gain},
              {"e_gain", (e_max - e0) / e0},
              {"cpu_step", real(cpu)},
              {"lcp_step", real(lcp)},
              {"cpu_apart", real(cpu_lower + cpu_upper)},
              {"lcp_apart", real(lcp_lower + lcp_upper)}});
  return out;
}

// The bars: the contact force's time-L1 error (relative) and the exit quantity of each problem.
Json run_bars(const BodiesCase& bc, const std::string& integrator_name, double n) {
  const std::string N = fmt::format("{}", n), N2 = fmt::format("{}", 2 * n);
  // Built as themselves (the registry's two-bars and mass-on-bar): the exact force, the wave
  // speed and the exit quantities are theirs.
  std::unique_ptr<TwoBars> bars;
  std::unique_ptr<MassOnBar> striker;
  if (bc.problem == "two-bars")
    bars = std::make_unique<TwoBars>(Params(TwoBars::parameters_spec(), with(with(bc.params, "N1", N), "N2", N2)));
  else
    striker = std::make_unique<MassOnBar>(Params(MassOnBar::parameters_spec(), with(bc.params, "N", N)));
  const Problem* problem = bars ? static_cast<const Problem*>(bars.get()) : striker.get();
  auto integrator = make_integrator(integrator_name);
  if (const auto declined = init_or_decline(*integrator, *problem)) return {{"status", kDeclinedStatus}, {"message", *declined}};
  const double h = bars ? bars->element_size(1) : problem->parameters().real("L") / n;
  const double c = bars ? bars->wave_speed() : std::sqrt(problem->parameters().real("E") / problem->parameters().real("rho"));
  const double dt = 0.9 * h / c;
  const double t_end = bars ? 1.5 * bars->contact_end() : striker->contact_end() + 0.5 * striker->round_trip();
  const auto exact_force = [&](double t) {
    return bars ? bars->exact_contact_force(t) : striker->exact_contact_force(t);
  };
  const double level = bars ? bars->contact_force_level() : kNaN;
  double force_err = 0.0, force_int = 0.0, start = kNaN, end = kNaN;
  const RunOptions options = options_for(dt, t_end);
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const double lambda = it.impulses()[0], t = it.state().t, f = exact_force(t - 0.5 * info.dt);
    force_err += std::abs(lambda - f * info.dt);
    force_int += f * info.dt;
    if (lambda > 0.0 && std::isnan(start)) start = t - info.dt;
    if (lambda >= 0.5 * level * info.dt) end = t;
  });
  Json out = status_of(r);
  out["dt"] = dt;
  if (r.status != RunStatus::Ok) return out;
  const Vec& v = integrator->state().v;
  const double v0 = problem->parameters().real("v0");
  out["force_err"] = force_err / force_int;
  if (bars) {
    out["duration_err"] = real(std::abs(end - start - (bars->contact_end() - bars->contact_start())));
    out["exit_err"] = std::abs(bars->mean_velocity(1, v)) / v0;
  } else {
    out["exit_err"] = std::abs(v[striker->mass_dof()] - striker->exact_mass_velocity(r.t_final)) / v0;
  }
  const CpuCost cpu = cpu_cost(*problem, integrator_name, {}, options);
  out["cpu_median"] = cpu.median;
  out["cpu_spread"] = real(cpu.spread);
  return out;
}

std::vector<Json> bodies_cases(const StudyOptions&) {
  std::vector<Json> cases;
  for (const auto& entry : integrator_registry())
    for (const auto& bc : kBodiesCases)
      for (double knob : bc.knobs) cases.push_back({{"case", bc.id}, {"integrator", entry.name}, {"knob", knob}});
  return cases;
}

Json bodies_case(const Json& c) {
  const BodiesCase& bc = find_bodies_case(c["case"]);
  const double knob = c["knob"];
  switch (bc.group) {
    case BodiesGroup::Cradle: return run_cradle(bc, c["integrator"], knob);
    case BodiesGroup::Blocks: return run_blocks(bc, c["integrator"], knob);
    case BodiesGroup::Bars: return run_bars(bc, c["integrator"], knob);
  }
  return {};
}

// The rows of one group's table, integrator by integrator, one per run (add_integrator_rows):
// columns integrator, case, the group's own cells of run i (previous: the run of the same case
// at the previous knob), steps, CPU and the note.
void add_bodies_group_rows(Table& t, BodiesGroup group, const std::vector<Json>& cases, const std::vector<Json>& results,
                    const std::function<std::vector<Cell>(std::size_t i, std::optional<std::size_t> previous)>& own) {
  add_integrator_rows(
      t, cases, results, [&](std::size_t k) { return find_bodies_case(cases[k]["case"]).group == group; },
      [&](std::size_t i, std::optional<std::size_t> previous) {
        const Json& r = results[i];
        std::vector<Cell> row = {cases[i]["integrator"].get<std::string>(), find_bodies_case(cases[i]["case"]).label};
        for (Cell& cell : own(i, previous)) row.push_back(std::move(cell));
        row.push_back(r.contains("steps") ? Cell{r["steps"].get<long>()} : Cell{});
        row.push_back(r.contains("cpu") ? Cell{r["cpu"].get<double>()} : Cell{});
        row.push_back(status_note(r));
        return row;
      });
}

std::vector<Column> bodies_group_columns(const std::vector<Column>& own) {
  std::vector<Column> columns = {{"integrator", "", "", ""}, {"case", "", "", ""}};
  columns.insert(columns.end(), own.begin(), own.end());
  columns.insert(columns.end(), {{"steps", "", "", ""},
                                 cost_column(),
                                 {"note", "", "", "why a run is n/a, diverged or over budget"}});
  return columns;
}

std::string peers_sentence() {
  std::vector<std::string> peers;
  for (const auto& entry : integrator_registry())
    if (entry.peer) peers.push_back(entry.name);
  return peers.empty() ? "No peer is built in."
                       : fmt::format("Peers (other codes' implementations, run side by side): {}; {}.",
                                     fmt::join(peers, ", "), peer_versions());
}

std::vector<Table> bodies_tables(const std::vector<Json>& cases, const std::vector<Json>& results,
                                 const StudyOptions&) {
  const std::vector<std::pair<std::string, std::string>> metadata = {{"study", "bodies"},
                                                                     {"law tolerance", fmt::format("{}", kLawTol)}};
  const std::string peers = peers_sentence();
  const BallChain e1(Params(BallChain::parameters_spec(), find_bodies_case("cradle-gap-e1").params));
  const BallChain e05(Params(BallChain::parameters_spec(), find_bodies_case("cradle-gap-e05").params));
  const auto vec = [](const Vec& v) { return fmt::format("({:.6g})", fmt::join(v.begin(), v.end(), ", ")); };

  Table cradle;
  cradle.id = "bodies_cradle";
  cradle.title = "Newton's cradle (3 balls): which impact law each scheme reproduces, by dt v0 / gap";
  cradle.caption = fmt::format(
      "ball-chain, n = 3, m = 1 kg, v0 = 1 m/s; touching (gap = 0, dt = 1e-3 s) or gap = {} m at dt v0 / gap = "
      "0.01, 0.1, 1, 10; to t = max(3, 20 dt). Final velocities v against the sequential outcome (binary collisions: "
      "e = 1 {}, e = 0.5 {}) and Moreau's simultaneous one (e = 1 {}, e = 0.5 {}): d = max_i |v_i - v_i,law| / v0; "
      "verdict: the nearer law when within {} v0, else neither. dP = |P - P0| / (m v0); dK = (K - K0) / K0 (kinetic "
      "energy of the final velocities). {}",
      kGap, vec(e1.sequential_outcome()), vec(e05.sequential_outcome()), vec(e1.simultaneous_outcome()),
      vec(e05.simultaneous_outcome()), kLawTol, peers);
  cradle.columns = bodies_group_columns({{"dt v0/gap", "", "{}", "n/a: touching (gap = 0)"},
                                  {"dt", "s", "{:.0e}", ""},
                                  {"d sequential", "", "{:.2e}", ""},
                                  {"d simultaneous", "", "{:.2e}", ""},
                                  {"verdict", "", "", "the law reproduced"},
                                  {"dP", "", "{:.1e}", ""},
                                  {"dK", "", "{:.2e}", ""}});
  cradle.metadata = metadata;
  add_bodies_group_rows(cradle, BodiesGroup::Cradle, cases, results, [&](std::size_t i, std::optional<std::size_t>) {
    const Json& r = results[i];
    const bool touching = find_bodies_case(cases[i]["case"]).params.at("gap") == "0";
    return std::vector<Cell>{touching ? Cell{} : Cell{cases[i]["knob"].get<double>()}, number_cell(real_or_nan(r, "dt")),
                             number_cell(real_or_nan(r, "d_sequential")), number_cell(real_or_nan(r, "d_simultaneous")),
                             r.contains("verdict") ? Cell{r["verdict"].get<std::string>()} : Cell{},
                             number_cell(real_or_nan(r, "dP")), number_cell(real_or_nan(r, "dK"))};
  });

  Table blocks;
  blocks.id = "bodies_blocks";
  blocks.title = "Two blocks (non-matching node-to-segment contact): momentum identity, energy, cost against the blocks apart";
  blocks.caption = fmt::format(
      "two-blocks defaults (lower 1 x 0.3 m, 5 x 2 Q4, on the floor; upper 0.5 x 0.3 m, 7 x 2 Q4, 0.05 m above it), "
      "SVK, E = 1 MPa, rho = 1000, g = 0, upper block at (0.5, -1) m/s, e = 0, dt = 1e-4 s, to t = 0.1 s (landing at "
      "0.05 s). P res.: max over steps of |Delta P - (floor impulses)| / sum_a m_a |v_a,0| (the node-to-segment weights "
      "sum to zero: round-off expected). Step gain: max (E_{{k+1}} - E_k) / E0; E gain: (max E - E0) / E0, E the "
      "scheme's own energy (no energy source). CPU/step: median of 3 unobserved runs over the steps; LCP it./step: "
      "the scheme's LCP iterations over the steps. Apart: the same two blocks as separate block-2d problems (each "
      "on the floor alone: contact rows on one node each, H diagonal), summed; ratio = together / apart: the cost of "
      "the non-diagonal H (the verdict on CD-Lagrange's \"matrix-free explicit LCP\" is its ratio). {}",
      peers);
  blocks.columns = bodies_group_columns({{"P res.", "", "{:.1e}", ""},
                                  {"step gain", "", "{:.1e}", ""},
                                  {"E gain", "", "{:.1e}", ""},
                                  {"CPU/step", "s", "{:.2e}", "", true},
                                  {"LCP it./step", "", "{:.2f}", ""},
                                  {"apart CPU/step", "s", "{:.2e}", "", true},
                                  {"apart LCP it./step", "", "{:.2f}", ""},
                                  {"ratio", "", "{:.2f}", "CPU/step together / apart", true}});
  blocks.metadata = metadata;
  add_bodies_group_rows(blocks, BodiesGroup::Blocks, cases, results, [&](std::size_t i, std::optional<std::size_t>) {
    const Json& r = results[i];
    std::vector<Cell> cells;
    for (const char* key : {"p_residual", "step_gain", "e_gain", "cpu_step", "lcp_step", "cpu_apart", "lcp_apart"})
      cells.push_back(number_cell(real_or_nan(r, key)));
    cells.push_back(number_cell(real_or_nan(r, "cpu_step") / real_or_nan(r, "cpu_apart")));
    return cells;
  });

  const TwoBars two_bars(Params(TwoBars::parameters_spec(), find_bodies_case("two-bars").params));
  const MassOnBar striker(Params(MassOnBar::parameters_spec(), find_bodies_case("mass-on-bar").params));
  Table bars;
  bars.id = "bodies_bars";
  bars.title = "Two bars and a mass on a bar: errors against the exact solutions and orders";
  bars.caption = fmt::format(
      "E = rho = A = 1 (c = 1), v0 = 1, lumped mass, dt = 0.9 h/c. two-bars: L1 = 1, L2 = 2, N1 = N, N2 = 2 N, to t = "
      "{:.3g}: the contact lasts 2 L1/c = {:.3g} at F0 = rho c v0 / 2 = {:.3g}, bar 1 leaves at rest. Duration err: "
      "|(end of the last step with Lambda/dt >= F0/2) - (start of the first step with an impulse) - 2 L1/c|; exit err: "
      "|bar 1's mean velocity| / v0 at the end. mass-on-bar: M = 1 (the bar's mass), N elements, to the last "
      "separation ({:.4g}) + L/c; exit err: |V - V_exact| / v0 of the mass at the end. Force err (both): "
      "sum_k |Lambda_k - F(t_k - dt/2) dt| / int F dt (time-L1, relative). Orders: log-log slope against the previous "
      "mesh; errors below {:.0e} carry none. {}",
      1.5 * two_bars.contact_end(), two_bars.contact_end(), two_bars.contact_force_level(), striker.contact_end(),
      kRoundOffError, peers);
  const auto order_column = [](const std::string& of) {
    return Column{"order", "", kOrderFormat, "log-log slope of " + of + " against the previous mesh"};
  };
  bars.columns = bodies_group_columns({{"N", "", "", "elements (bar 1)"},
                                {"dt", "", "{:.3e}", ""},
                                {"duration err", "", "{:.2e}", "two-bars"},
                                order_column("duration err"),
                                {"exit err", "", "{:.2e}", ""},
                                order_column("exit err"),
                                {"force err", "", "{:.2e}", ""},
                                order_column("force err")});
  bars.metadata = metadata;
  add_bodies_group_rows(bars, BodiesGroup::Bars, cases, results, [&](std::size_t i, std::optional<std::size_t> previous) {
    const Json& r = results[i];
    std::vector<Cell> cells = {static_cast<long>(cases[i]["knob"].get<double>()), number_cell(real_or_nan(r, "dt"))};
    for (const char* key : {"duration_err", "exit_err", "force_err"}) {
      const double e = real_or_nan(r, key);
      cells.push_back(number_cell(e));
      cells.push_back(previous ? number_cell(observed_order(1.0 / cases[*previous]["knob"].get<double>(),
                                                            above_round_off(real_or_nan(results[*previous], key)),
                                                            1.0 / cases[i]["knob"].get<double>(), above_round_off(e)))
                               : Cell{});
    }
    return cells;
  });

  // Ranking: one curve per integrator and ranked case; a declined integrator's curve is empty.
  std::vector<RankingProblem> ranking = {
      {"two-bars (L1 1, L2 2, lumped): contact force", "the exact solution", 0.0, kBarsTargets, {}},
      {"mass-on-bar (M 1, lumped): contact force", "the exact solution", 0.0, kStrikerTargets, {}}};
  const std::vector<std::string> ranked = {"two-bars", "mass-on-bar"};
  add_ranking_curves(ranking, ranked, cases, results, [&](std::size_t i) {
    return WorkPoint{fmt::format("N = {}", cases[i]["knob"].get<double>()), real_or_nan(results[i], "cpu_median"),
                     real_or_nan(results[i], "force_err"), "", real_or_nan(results[i], "cpu_spread")};
  });
  Table rank = ranking_table("bodies_ranking", "Cheapest integrator at each target error: contacts between bodies",
                             {"force err", "", "", "the relative time-L1 contact force error of bodies_bars"},
                             median_cpu_text(), ranking);
  rank.metadata = metadata;

  const BallChain chain(Params(BallChain::parameters_spec(), find_bodies_case(kBodiesTrajectoryCase).params));
  Table trajectory;
  trajectory.id = "bodies_cradle_trajectory";
  trajectory.title = fmt::format("Newton's cradle (3 balls, gap {} m, e = 0.5): ball positions against the exact ones, "
                                 "dt = {:g} s", kGap, kTrajectoryRatio * kGap);
  trajectory.caption = fmt::format(
      "ball-chain, n = 3, m = 1 kg, gap = {} m, e = 0.5, ball 1 launched at v0 = 1 m/s, dt = {:g} s (dt v0 / gap = {}), "
      "to t = 3 s: each ball's position x_i = (i - 1) gap + U_i relative to the centre of mass (x_i - x_G, x_G the "
      "mean, drifting at v0 / 3) after every step, against the exact binary-collision march (collisions at {:.4g} s; "
      "final velocities {}).",
      kGap, kTrajectoryRatio * kGap, kTrajectoryRatio, fmt::join(chain.impact_times(3.0), ", "),
      vec(chain.sequential_outcome()));
  trajectory.columns = {{"integrator", "", "", ""}, {"ball", "", "", ""}, {"t", "s", "{:.4f}", ""},
                        {"x - x_G", "m", "{:.4e}", "(i - 1) gap + U_i less the mean over the balls"}};
  trajectory.csv_only = true;
  trajectory.metadata = metadata;
  trajectory.figures = {{"bodies_cradle_trajectory", trajectory.title, "t", "x - x_G", {"integrator", "ball"}, {},
                         false, false, {}, true, false, "exact",
                         trajectory.caption + " One panel per scheme, the balls told apart by dashes; dotted: exact."}};
  const auto add_positions = [&](const std::string& name, double t, const auto& u) {
    std::vector<double> x;
    for (Index b = 0; b < chain.ndof(); ++b) x.push_back(static_cast<double>(b) * kGap + real(u[b]));
    double mean = 0.0;
    for (double xb : x) mean += xb / static_cast<double>(x.size());
    for (std::size_t b = 0; b < x.size(); ++b) trajectory.add_row({name, fmt::format("ball {}", b + 1), t, number_cell(x[b] - mean)});
  };
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (results[i].contains("trajectory_t")) {
      const std::vector<double> t = results[i]["trajectory_t"];
      const Json& u = results[i]["trajectory_u"];
      for (std::size_t k = 0; k < t.size(); ++k)
        add_positions(cases[i]["integrator"], t[k], std::vector<Json>(u.begin() + static_cast<long>(k * chain.ndof()),
                                                                      u.begin() + static_cast<long>((k + 1) * chain.ndof())));
    }
  const double t_end = 3.0;
  for (int k = 0; k <= kBodiesExactSamples; ++k) {
    const double t = t_end * k / kBodiesExactSamples;
    const Vec u = chain.state(t)->u;
    std::vector<Json> exact(u.begin(), u.end());
    add_positions("exact", t, exact);
  }
  SnapshotTables deformed = snapshot_tables(
      "bodies_blocks_deformed", "Two blocks (mu = 0): deformed meshes coloured by sigma_yy, contact impulses",
      fmt::format("The two blocks of bodies_blocks with mu = 0 (g = 0, upper block at (0.5, -1) m/s, e = 0, dt = 1e-4 s, "
                  "to t = 0.1 s), {}: the meshes deformed at true scale (the initial state, the first step with a "
                  "contact impulse, the step of largest strain energy and the end), cells coloured by sigma_yy "
                  "(Cauchy stress, mean over the cell's Gauss points; negative: compression), the step's contact "
                  "impulses L^T Lambda at the nodes as arrows (node-to-segment: spread over the segment's nodes, "
                  "opposite on the two blocks), scaled to the largest in the figure. The floor is y = 0.",
                  fmt::join(kSnapshotSchemes, " and ")),
      "sigma_yy");
  deformed.cells.metadata = deformed.arrows.metadata = metadata;
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (results[i].contains("snapshots")) add_snapshot_rows(deformed, cases[i]["integrator"], results[i]["snapshots"]);
  return {cradle, blocks, bars, rank, trajectory, deformed.cells, deformed.arrows};
}

}  // namespace

extern const StudyEntry bodies_study = {
    "bodies", "contacts between bodies: the cradle's impact law by dt v0 / gap; two blocks' momentum identity, energy "
              "and cost against the blocks apart; two bars and a mass on a bar against their exact solutions, orders; "
              "ranking",
    nullptr, &bodies_cases, &bodies_case, &bodies_tables, &integrators_named};

}  // namespace nsb
