// Study "friction": every integrator on the Coulomb friction problems (docs/method.md section 6);
// the schemes that do not treat friction decline in bind() and get one n/a row per table,
// with their reason.
//
// Cases (kCases, one line of data each), each run at its steps:
// - sliding mass, alpha = 30 deg, v0 = 2 m/s down the slope: mu = 0.8 (stops at t_s and
//   sticks, tan alpha < mu) and mu = 0.3 (slides on for ever); steps 1e-2, 1e-3, 1e-4
//   (--full: and 1e-5), to t = 2 s.
// - rolling disk on the floor: h0 = 0, v0 = 1, omega0 = 0, mu = 0.3, kappa = 1/2; same steps,
//   to t = 0.5 s (rolling from t* = 0.113 s on).
// - block-2d at its defaults (8 x 4 Q4) with mu = 0.5 and vx = 1 (it lands sliding),
//   dt = 1e-4 (--full: and 5e-5), to t = 0.3 s: the momentum identities.
// - hard cases, dt = 1e-3: sticking below the friction angle for 10^5 steps, mu = tan alpha,
//   a sliding reversal, mu = 10, a disk dropped with spin at e = 0 and e = 0.5.
//
// Measures, all from one observed run per case (the problem's observables looked up by name:
// x, v, v_exact, px; the slip u_T = T v - w of the contacts' rows):
// - stop time (studies/slip_stop.hpp, as the study files' stop-time and onset-time measures):
//   the first step at which |u_T| <= kSlipTol after which it stays so (rest, or rolling for
//   the disk); where the exact solution does not stay at rest (the reversal), the first step
//   at which u_T has lost its initial sign (|u_T| <= kSlipTol or reversed). Against
//   SlidingMass::stop_time() (-v0 / a1) and RollingDisk::rolling_onset_time().
// - stop distance: the contact point's tangential path sum |T (U_{k+1} - U_k)| up to the stop
//   time, against SlidingMass::stop_distance() (v0^2 / (2 |a1|)).
// - max |v - v_exact| over the steps; the final speed error |v - v_exact| at t_end (for the
//   disk v_exact(t_end) = v_f = (v0 - kappa R omega0) / (1 + kappa), rolling by then); the
//   speed just after the first impact (end of the first step with a normal impulse) against
//   RollingDisk::impacts()[0].v (ExactValue::first_rebound_speed).
// - energy gain: max over steps of (E_{k+1} - E_k) / E scale, E the integrator's own energy,
//   E scale = |E0| (m g (1 m) when E0 = 0): no case has an energy source, so a positive gain
//   beyond round-off is the scheme's.
// - creep, where the exact solution rests for the whole run: |x(t_end) - x(0)| / t_end, and
//   the same over the second half of the run (a sustained creep, not a start-up step).
// - block: max over steps of |P_x,k - P_x,0 - sum_{j<=k} sum_i Lambda_T,i| / sum m |v0| (the
//   T rows are +1 on x dofs, gravity is vertical and F_int sums to zero, so this is round-off
//   for any scheme whose impulses are the ones it applied), and over the steps where every
//   closed contact (Lambda_N,i > 0) slides the same way s (|u_T,i| > kSlipTol, sign s, from
//   the reported velocity) max |Delta P_x + s sum mu Lambda_N| / sum m |v0| (Coulomb: a
//   sliding contact's impulse is -s mu Lambda_N).
// Orders: log-log slope between consecutive steps. Each run has a budget of kStepBudget F_int
// evaluations per step (an adaptive scheme whose step collapses stops, "over budget").
// Trajectory (table friction_disk_trajectory, figure of the same name): the disk's slip
// s = x' + R theta' after every step of the disk case at dt = kTrajectoryStep, each scheme in
// its panel over the exact s(t) (sampled at kExactSamples times).
// Ranking (studies/ranking.hpp): the cheapest integrator reaching a stop-time error (sliding
// mass, mu = 0.8) and a rolling-onset error (disk) of 1e-2, 1e-3 and 1e-4 s, cost the median
// CPU time of 3 unobserved runs.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

#include "core/deterministic_math.hpp"
#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/registry.hpp"
#include "problems/rolling_disk.hpp"
#include "problems/sliding_mass.hpp"
#include "studies/ranking.hpp"
#include "studies/slip_stop.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr long kFrictionStepBudget = 20;   // F_int evaluations allowed per step of the requested size
constexpr double kHardStep = 1e-3;
const std::vector<double> kFrictionRankingTargets = {1e-2, 1e-3, 1e-4};  // [s]
// The disk's slip history: the coarsest step, where the schemes' steps are told apart.
const std::string kFrictionTrajectoryCase = "disk";
constexpr double kTrajectoryStep = 1e-2;
constexpr int kFrictionExactSamples = 500;

enum class FrictionGroup { Sliding, Disk, Block, Hard };

struct FrictionCase {
  std::string id;  // the case's name in the case list (tests run one by it)
  FrictionGroup group;
  std::string label;
  std::string problem;
  std::map<std::string, std::string> params;
  std::vector<double> steps, full_steps;
  double t_end;
  bool ranked = false;  // its stop-time error and CPU time enter the ranking
};

const std::vector<double> kSteps = {1e-2, 1e-3, 1e-4};
const std::vector<double> kFullSteps = {1e-2, 1e-3, 1e-4, 1e-5};

// mu = tan(30 deg) to the last digit (the sliding mass takes it as tan alpha).
const std::string kTan30 = fmt::format("{:.17g}", nsb::dmath::tan(std::numbers::pi / 6));

const std::vector<FrictionCase> kFrictionCases = {
    {"slide-stop", FrictionGroup::Sliding, "alpha 30, mu 0.8, v0 2: stops, sticks", "sliding-mass",
     {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "2"}}, kSteps, kFullSteps, 2.0, true},
    {"slide-on", FrictionGroup::Sliding, "alpha 30, mu 0.3, v0 2: slides on", "sliding-mass",
     {{"alpha", "30"}, {"mu", "0.3"}, {"v0", "2"}}, kSteps, kFullSteps, 2.0},
    {"disk", FrictionGroup::Disk, "h0 0, v0 1, omega0 0, mu 0.3, kappa 1/2", "rolling-disk",
     {{"h0", "0"}, {"v0", "1"}, {"omega0", "0"}, {"mu", "0.3"}, {"kappa", "0.5"}}, kSteps, kFullSteps, 0.5, true},
    {"block", FrictionGroup::Block, "block-2d 8x4, mu 0.5, vx 1", "block-2d", {{"mu", "0.5"}, {"vx", "1"}}, {1e-4},
     {1e-4, 5e-5}, 0.3},
    {"stick", FrictionGroup::Hard, "stick below the friction angle (alpha 20, mu 0.5, v0 0), 10^5 steps", "sliding-mass",
     {{"alpha", "20"}, {"mu", "0.5"}, {"v0", "0"}}, {kHardStep}, {kHardStep}, 1e5 * kHardStep},
    {"tan-alpha", FrictionGroup::Hard, "mu = tan alpha (alpha 30, v0 1): slides at v0", "sliding-mass",
     {{"alpha", "30"}, {"mu", kTan30}, {"v0", "1"}}, {kHardStep}, {kHardStep}, 2.0},
    {"reversal", FrictionGroup::Hard, "reversal (alpha 30, mu 0.3, v0 -2 up the slope): stops, slides down", "sliding-mass",
     {{"alpha", "30"}, {"mu", "0.3"}, {"v0", "-2"}}, {kHardStep}, {kHardStep}, 2.0},
    {"mu-10", FrictionGroup::Hard, "mu 10 (alpha 30, v0 2)", "sliding-mass", {{"alpha", "30"}, {"mu", "10"}, {"v0", "2"}},
     {kHardStep}, {kHardStep}, 2.0},
    {"drop-e0", FrictionGroup::Hard, "disk dropped with spin (h0 0.1, omega0 20, v0 0), e 0", "rolling-disk",
     {{"h0", "0.1"}, {"omega0", "20"}, {"v0", "0"}, {"e", "0"}}, {kHardStep}, {kHardStep}, 1.0},
    {"drop-e05", FrictionGroup::Hard, "disk dropped with spin (h0 0.1, omega0 20, v0 0), e 0.5", "rolling-disk",
     {{"h0", "0.1"}, {"omega0", "20"}, {"v0", "0"}, {"e", "0.5"}}, {kHardStep}, {kHardStep}, 1.0},
};

const FrictionCase& find_friction_case(const std::string& id) {
  for (const auto& c : kFrictionCases)
    if (c.id == id) return c;
  throw InputError(fmt::format("friction study: no case {}", id));
}

// The speed just after the disk's first impact (NaN: no disk, or no impact).
double first_impact_speed(const Problem& p) {
  const ExactSolution* exact = p.exact();
  return exact ? exact->value(ExactValue::first_rebound_speed).value_or(kNaN) : kNaN;
}

// The problem's observables after a step, by name; NaN for a name it does not have.
class Observables {
 public:
  explicit Observables(const Problem& p) : problem_(p), names_(p.observable_names()), values_(names_.size(), kNaN) {}
  void update(const State& s, const Vec& impulses, double dt) { problem_.observe(s, impulses, dt, values_); }
  std::size_t index(const std::string& name) const {
    return static_cast<std::size_t>(std::find(names_.begin(), names_.end(), name) - names_.begin());
  }
  double operator[](std::size_t i) const { return i < values_.size() ? values_[i] : kNaN; }

 private:
  const Problem& problem_;
  std::vector<std::string> names_;
  std::vector<double> values_;
};

Json measure(const FrictionCase& fc, const std::string& integrator_name, double dt) {
  auto problem = make_problem(fc.problem, fc.params);
  auto integrator = make_integrator(integrator_name);
  if (const auto declined = init_or_decline(*integrator, *problem)) return {{"status", kDeclinedStatus}, {"message", *declined}};
  const ExactStop exact = exact_stop(*problem);
  const Contacts& contacts = problem->contacts();
  const Vec& mu = contacts.mu;
  const State s0 = problem->initial_state();
  const Vec m = diagonal_mass(problem->mass_matrix()).value();
  const double p_scale = m.dot(s0.v.cwiseAbs());

  const bool trajectory = fc.id == kFrictionTrajectoryCase && dt == kTrajectoryStep;
  std::vector<double> trajectory_t, trajectory_slip;
  Observables obs(*problem);
  const std::size_t ix = obs.index("x"), iv = obs.index("v"), iv_exact = obs.index("v_exact"), ipx = obs.index("px");
  const bool has_px = ipx < problem->observable_names().size();
  obs.update(s0, Vec::Zero(contacts.size()), 0.0);
  const double x0 = obs[ix];
  double px_prev = obs[ipx], px0 = px_prev;

  SlipStop stop(*problem, s0);
  const Vec& slip = stop.slip();
  if (trajectory) {
    trajectory_t.push_back(s0.t);
    trajectory_slip.push_back(slip[0]);
  }
  double v_err = kNaN, v_after_impact = kNaN, x_half = kNaN, t_half = kNaN;
  double energy_gain = 0.0, energy_gain_t = kNaN;
  double sum_tangential = 0.0, px_residual = 0.0, slide_residual = 0.0;
  long slide_steps = 0;
  double E_prev = integrator->energy().total();
  // E0 = 0 only for a mass at rest (sliding mass, v0 = 0): its weight over 1 m instead.
  const double E_scale = E_prev != 0.0 ? std::abs(E_prev)
                                       : problem->parameters().real("m") * problem->parameters().real("g") * 1.0;

  RunOptions options;
  options.dt = dt;
  options.t_end = fc.t_end;
  options.record_series = false;
  options.max_force_evaluations = kFrictionStepBudget * static_cast<long>(std::ceil(fc.t_end / dt));
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const State& s = it.state();
    const Vec& normal = it.impulses();
    const Vec& tangential = it.tangential_impulses();
    obs.update(s, normal, info.dt);
    stop.add(s);
    if (trajectory) {
      trajectory_t.push_back(s.t);
      trajectory_slip.push_back(slip[0]);
    }
    v_err = std::fmax(v_err, std::abs(obs[iv] - obs[iv_exact]));  // NaN while neither is a number
    if (std::isnan(v_after_impact) && normal.size() && normal.maxCoeff() > 0.0) v_after_impact = obs[iv];
    if (std::isnan(x_half) && s.t >= 0.5 * fc.t_end) {
      x_half = obs[ix];
      t_half = s.t;
    }
    const double E = it.energy().total();
    if ((E - E_prev) / E_scale > energy_gain) {
      energy_gain = (E - E_prev) / E_scale;
      energy_gain_t = s.t;
    }
    E_prev = E;
    if (!has_px) return;
    // The momentum identities.
    const double px = obs[ipx];
    sum_tangential += tangential.sum();
    px_residual = std::max(px_residual, std::abs(px - px0 - sum_tangential) / p_scale);
    int way = 0;  // the common sign of the closed contacts' slips; 2: none common
    double mu_normal = 0.0;
    for (Index i = 0; i < normal.size(); ++i) {
      if (!(normal[i] > 0.0)) continue;
      const int s_i = std::abs(slip[i]) <= kSlipTol ? 2 : slip[i] > 0.0 ? 1 : -1;
      way = way == 0 || way == s_i ? s_i : 2;
      mu_normal += mu[i] * normal[i];
    }
    if (way == 1 || way == -1) {
      ++slide_steps;
      slide_residual = std::max(slide_residual, std::abs(px - px_prev + way * mu_normal) / p_scale);
    }
    px_prev = px;
  });

  Json out = {{"status", status_name(r.status)}, {"message", r.message}, {"steps", r.steps}, {"cpu", r.step_cpu_seconds}};
  if (r.status != RunStatus::Ok) return out;
  const double t_stop = stop.time(exact.stays);
  const double d_stop = stop.path(exact.stays);
  const bool at_rest_throughout = exact.stop_time == 0.0 && exact.stays;
  out.update({{"t_stop", real(t_stop)},
              {"never_stops", exact.never_stops},
              {"t_stop_err", real(std::abs(t_stop - exact.stop_time))},
              {"d_stop_err", real(std::abs(d_stop - exact.stop_distance))},
              {"v_err", real(v_err)},
              {"v_final_err", real(std::abs(obs[iv] - obs[iv_exact]))},
              {"v_impact_err", real(std::abs(v_after_impact - first_impact_speed(*problem)))},
              {"creep", real(at_rest_throughout ? std::abs(obs[ix] - x0) / r.t_final : kNaN)},
              {"late_creep", real(at_rest_throughout ? std::abs(obs[ix] - x_half) / (r.t_final - t_half) : kNaN)},
              {"energy_gain", energy_gain},
              {"energy_gain_t", real(energy_gain_t)},
              {"px_residual", real(has_px ? px_residual : kNaN)},
              {"slide_residual", real(slide_steps ? slide_residual : kNaN)}});
  if (has_px) out["slide_steps"] = slide_steps;
  if (trajectory) {
    out["trajectory_t"] = trajectory_t;
    out["trajectory_slip"] = reals(trajectory_slip);
  }
  if (fc.ranked) {
    const CpuCost cpu = cpu_cost(*problem, integrator_name, {}, options);
    out["cpu_median"] = cpu.median;
    out["cpu_spread"] = real(cpu.spread);
  }
  return out;
}

std::vector<Json> friction_cases(const StudyOptions& opt) {
  std::vector<Json> cases;
  for (const auto& entry : integrator_registry())
    for (const auto& fc : kFrictionCases)
      for (double dt : opt.full ? fc.full_steps : fc.steps)
        cases.push_back({{"case", fc.id}, {"integrator", entry.name}, {"dt", dt}});
  return cases;
}

Json friction_case(const Json& c) { return measure(find_friction_case(c["case"]), c["integrator"], c["dt"]); }

// A measured error with its order against the previous step of the same case.
struct Measure {
  std::string key;
  Column column;
};

// Why a run is n/a, diverged or over budget, or that it stopped where the exact solution never does.
std::string friction_note(const Json& r) {
  if (r["status"] != status_name(RunStatus::Ok)) return status_note(r);
  if (r["never_stops"].get<bool>() && !r["t_stop"].is_null())
    return fmt::format("stops at {:.4g} s; the exact solution never does", r["t_stop"].get<double>());
  return "";
}

// The columns of every table: integrator, case, dt, the group's own, then the run's largest
// energy gain and when, steps, CPU time and the note.
std::vector<Column> friction_group_columns(const std::vector<Column>& own) {
  std::vector<Column> columns = {{"integrator", "", "", ""}, {"case", "", "", ""}, {"dt", "s", "{:.0e}", "step"}};
  columns.insert(columns.end(), own.begin(), own.end());
  columns.insert(columns.end(), {{"max E gain", "", "{:.1e}", "max over steps of (E_{k+1} - E_k) / E scale"},
                                 {"at t", "s", "{:.4g}", "end of the step of the largest gain"},
                                 {"steps", "", "", ""},
                                 cost_column(),
                                 {"note", "", "", "why a run is n/a, diverged or over budget, or a stop where the "
                                                  "exact solution has none"}});
  return columns;
}

// The rows of one group's table (columns from group_columns), integrator by integrator, one per
// run (add_integrator_rows): `own` gives the group's own cells of run i.
void add_friction_group_rows(Table& t, FrictionGroup group, const std::vector<Json>& cases, const std::vector<Json>& results,
                    const std::function<std::vector<Cell>(std::size_t i, std::optional<std::size_t> previous)>& own) {
  add_integrator_rows(
      t, cases, results, [&](std::size_t k) { return find_friction_case(cases[k]["case"]).group == group; },
      [&](std::size_t i, std::optional<std::size_t> previous) {
        const Json& r = results[i];
        std::vector<Cell> row = {cases[i]["integrator"].get<std::string>(), find_friction_case(cases[i]["case"]).label,
                                 cases[i]["dt"].get<double>()};
        for (Cell& cell : own(i, previous)) row.push_back(std::move(cell));
        row.insert(row.end(), {number_cell(real_or_nan(r, "energy_gain")), number_cell(real_or_nan(r, "energy_gain_t")),
                               r["steps"].get<long>(), r["cpu"].get<double>(), friction_note(r)});
        return row;
      });
}

// The table of a convergence group: each measure and its order.
Table convergence_table(const std::string& id, const std::string& title, const std::string& caption, FrictionGroup group,
                        const std::vector<Measure>& measures, const std::vector<Json>& cases,
                        const std::vector<Json>& results) {
  Table t;
  t.id = id;
  t.title = title;
  t.caption = caption;
  std::vector<Column> own;
  for (const auto& m : measures) {
    own.push_back(m.column);
    own.push_back({"order", "", kOrderFormat, "log-log slope of " + m.column.name + " against the previous dt"});
  }
  t.columns = friction_group_columns(own);
  add_friction_group_rows(t, group, cases, results, [&](std::size_t i, std::optional<std::size_t> previous) {
    std::vector<Cell> cells;
    for (const auto& m : measures) {
      const double e = real_or_nan(results[i], m.key);
      cells.push_back(number_cell(e));
      cells.push_back(previous ? number_cell(observed_order(cases[*previous]["dt"],
                                                            above_round_off(real_or_nan(results[*previous], m.key)),
                                                            cases[i]["dt"], above_round_off(e)))
                               : Cell{});
    }
    return cells;
  });
  return t;
}

std::vector<Table> friction_tables(const std::vector<Json>& cases, const std::vector<Json>& results,
                                   const StudyOptions& opt) {
  const std::vector<std::pair<std::string, std::string>> metadata = {
      {"study", "friction"},
      {"steps", fmt::format("{}", fmt::join(opt.full ? kFullSteps : kSteps, " "))},
      {"slip tolerance", fmt::format("{}", kSlipTol)}};
  const std::string stop_rule = fmt::format(
      "t_stop: the first step at which |u_T| <= {} m/s (u_T = T v - w, the slip) and after which it stays so; for a "
      "mass that does not stay (the reversal) the first step at which u_T has lost its initial sign",
      kSlipTol);
  const std::string energy_rule =
      "max E gain: max over steps of (E_{k+1} - E_k) / E scale, E the integrator's own energy (CD-Lagrange: its "
      "discrete energy), E scale = |E0| (m g (1 m) when E0 = 0), 0 when it never increased; no case has an energy source";
  const std::string order_rule = fmt::format(
      "Orders: log-log slope against the previous dt; errors below {:.0e} are round-off and carry none", kRoundOffError);
  const std::string v_rule =
      "max |v - v_exact|: largest over the steps of the reported velocity (CD-Lagrange: v = M^-1 P_{k+3/2}, half a step "
      "ahead) against the exact one";

  const SlidingMass stopping(Params(SlidingMass::parameters_spec(), find_friction_case("slide-stop").params));
  Table sliding = convergence_table(
      "friction_sliding", "Sliding mass on a slope with Coulomb friction: stop time, stop distance, velocity",
      fmt::format("m = 1 kg, g = 9.81 m/s^2, alpha = 30 deg, v0 = 2 m/s down the slope, to t = 2 s. Exact: while "
                  "sliding x'' = a1 = g (sin alpha - mu cos alpha), stop at t_s = -v0 / a1 after d_s = v0^2 / (2 |a1|) "
                  "(mu = 0.8: t_s = {:.6f} s, d_s = {:.6f} m, then sticks, tan alpha < mu); mu = 0.3 never stops. {}. "
                  "d_stop: the contact's tangential path sum |T (U_k+1 - U_k)| up to t_stop. {}. {}. {}. n/a: the "
                  "scheme declines friction (its reason in the note), or the measure does not apply.",
                  stopping.stop_time(), stopping.stop_distance(), stop_rule, v_rule, energy_rule, order_rule),
      FrictionGroup::Sliding,
      {{"t_stop_err", {"t_stop err", "s", "{:.2e}", "|t_stop - t_s|"}},
       {"d_stop_err", {"d_stop err", "m", "{:.2e}", "|d_stop - d_s|"}},
       {"v_err", {"max |v - v_exact|", "m/s", "{:.2e}", "along the slope"}}},
      cases, results);
  const RollingDisk disk(Params(RollingDisk::parameters_spec(), find_friction_case("disk").params));
  Table rolling = convergence_table(
      "friction_disk", "Rolling disk on the floor: rolling onset and final speed",
      fmt::format("m = 1 kg, R = 0.1 m, kappa = 1/2 (inertia kappa m R^2), g = 9.81 m/s^2, on the floor (h0 = 0) at "
                  "v0 = 1 m/s, omega0 = 0, mu = 0.3, restitution e = {} (the problem's default), to t = 0.5 s. "
                  "Exact: the slip s = x' + R theta' falls at mu g "
                  "(1 + 1/kappa) until t* = |s0| / (mu g (1 + 1/kappa)) = {:.6f} s, then the disk rolls at v_f = (v0 - "
                  "kappa R omega0) / (1 + kappa) = {:.6f} m/s. t_roll: as t_stop of friction_sliding ({}). v_f err: "
                  "|v - v_exact| at t = 0.5 s. {}. {}. {}.",
                  disk.parameters().real("e"), disk.rolling_onset_time(), disk.final_velocity(), stop_rule, v_rule, energy_rule, order_rule),
      FrictionGroup::Disk,
      {{"t_stop_err", {"t_roll err", "s", "{:.2e}", "|t_roll - t*|"}},
       {"v_final_err", {"v_f err", "m/s", "{:.2e}", "|v(t_end) - v_f|"}},
       {"v_err", {"max |v - v_exact|", "m/s", "{:.2e}", "centre velocity"}}},
      cases, results);
  sliding.metadata = rolling.metadata = metadata;

  Table block;
  block.id = "friction_block";
  block.title = "2D block sliding on a floor with Coulomb friction: momentum identities, energy";
  block.caption = fmt::format(
      "block-2d defaults (8 x 4 Q4, SVK, E = 1 MPa, tilted 15 deg, lowest corner 0.1 m up, falling at 1 m/s, "
      "e = 0) with mu = 0.5 and vx = 1 m/s, to t = 0.3 s. P_x res.: max over steps of |P_x,k - P_x,0 - sum_j<=k "
      "sum_i Lambda_T,i| / sum m |v0| (the T rows are +1 on the x dofs: round-off expected). Slide res.: over the steps "
      "where every closed contact (Lambda_N > 0) slides the same way s (|u_T| > {} m/s, u_T from the reported "
      "velocity), max |Delta P_x + s mu sum Lambda_N| / sum m |v0| (round-off expected). {}; E includes the elastic "
      "energy, which the schemes' discretisation changes with or without friction.",
      kSlipTol, energy_rule);
  block.columns = friction_group_columns(
      {{"P_x res.", "", "{:.1e}", "P_x balance with the tangential impulses, relative"},
       {"sliding steps", "", "", "steps where every closed contact slides the same way"},
       {"slide res.", "", "{:.1e}", "Delta P_x + s mu sum Lambda_N on those steps, relative"}});
  block.metadata = metadata;
  add_friction_group_rows(block, FrictionGroup::Block, cases, results, [&](std::size_t i, std::optional<std::size_t>) {
    const Json& r = results[i];
    return std::vector<Cell>{number_cell(real_or_nan(r, "px_residual")),
                             r.contains("slide_steps") ? Cell{r["slide_steps"].get<long>()} : Cell{},
                             number_cell(real_or_nan(r, "slide_residual"))};
  });

  Table hard;
  hard.id = "friction_hard";
  hard.title = "Hard friction cases";
  hard.caption = fmt::format(
      "dt = {} s. Sliding mass (m = 1 kg, g = 9.81 m/s^2): sticking below the friction angle (tan 20 deg < 0.5) for "
      "10^5 steps, creep = |x(t_end) - x(0)| / t_end and late creep = |x(t_end) - x(t_end / 2)| / (t_end / 2) "
      "(exact: 0); mu = tan alpha exactly (exact: v = v0 for ever); reversal (up the slope at 2 m/s, stops at t_s = "
      "2 / (g (sin alpha + mu cos alpha)), slides down since tan alpha > mu); mu = 10 (stops at t_s = 2 / (g (mu cos "
      "alpha - sin alpha))). {}. Rolling disk (R = 0.1 m, kappa = 1/2, mu = 0.3) dropped from h0 = 0.1 m with spin "
      "omega0 = 20 rad/s: v after impact 1 err: the centre velocity at the end of the first step with a normal "
      "impulse against the exact impact law's (Newton on y', the sticking or the sliding Coulomb impulse); v_f err: "
      "|v - v_exact| at t_end (rolling at (v0 - kappa R omega0) / (1 + kappa) by then). t_stop err: as in "
      "friction_sliding (the disk: rolling onset; n/a at e = 0.5, where the slip ends in a bounce before the disk "
      "comes to lie on the floor, which the exact solution does not time). {}. n/a: the scheme declines friction "
      "(reason in the note) or the measure does not apply.",
      kHardStep, v_rule, energy_rule);
  hard.columns = friction_group_columns(
      {{"t_end", "s", "{}", ""},
       {"t_stop err", "s", "{:.2e}", "|t_stop - exact| (disk: rolling onset)"},
       {"creep", "m/s", "{:.2e}", "|x(t_end) - x(0)| / t_end where the exact mass rests throughout"},
       {"late creep", "m/s", "{:.2e}", "the same over the second half of the run: sustained, not a start-up step"},
       {"max |v - v_exact|", "m/s", "{:.2e}", ""},
       {"v after impact 1 err", "m/s", "{:.2e}", ""},
       {"v_f err", "m/s", "{:.2e}", "|v - v_exact| at t_end"}});
  hard.metadata = metadata;
  add_friction_group_rows(hard, FrictionGroup::Hard, cases, results, [&](std::size_t i, std::optional<std::size_t>) {
    std::vector<Cell> cells = {find_friction_case(cases[i]["case"]).t_end};
    for (const char* key : {"t_stop_err", "creep", "late_creep", "v_err", "v_impact_err", "v_final_err"})
      cells.push_back(number_cell(real_or_nan(results[i], key)));
    return cells;
  });

  // Ranking: one curve per integrator and ranked case; a declined integrator's curve is empty.
  std::vector<RankingProblem> ranking;
  for (const auto& fc : kFrictionCases)
    if (fc.ranked)
      ranking.push_back({fc.problem + ", " + fc.label + (fc.group == FrictionGroup::Disk ? ": rolling onset" : ": stop time"),
                         "the exact solution", 0.0, kFrictionRankingTargets, {}});
  std::vector<std::string> ranked;
  for (const auto& fc : kFrictionCases)
    if (fc.ranked) ranked.push_back(fc.id);
  add_ranking_curves(ranking, ranked, cases, results, [&](std::size_t i) {
    return WorkPoint{fmt::format("dt = {:.0e}", cases[i]["dt"].get<double>()), real_or_nan(results[i], "cpu_median"),
                     real_or_nan(results[i], "t_stop_err"), "", real_or_nan(results[i], "cpu_spread")};
  });
  Table rank = ranking_table("friction_ranking", "Cheapest integrator at each target error: Coulomb friction",
                             {"t err", "s", "", "t_stop err of friction_sliding (mu = 0.8) and t_roll err of friction_disk"},
                             median_cpu_text(), ranking);
  rank.metadata = metadata;

  Table trajectory;
  trajectory.id = "friction_disk_trajectory";
  trajectory.title = fmt::format("Rolling disk: slip velocity against the exact one, dt = {} s", kTrajectoryStep);
  trajectory.caption = fmt::format(
      "The disk of friction_disk (R = 0.1 m, kappa = 1/2, mu = 0.3, v0 = 1 m/s, omega0 = 0, on the floor): the contact "
      "point's slip s = x' + R theta' after every step of dt = {} s (the reported velocity), against the exact s(t), "
      "which falls linearly to 0 at t* = {:.4f} s and stays 0 (rolling).",
      kTrajectoryStep, disk.rolling_onset_time());
  trajectory.columns = {{"integrator", "", "", ""}, {"t", "s", "{:.4f}", ""}, {"slip", "m/s", "{:.4e}", "x' + R theta'"}};
  trajectory.csv_only = true;
  trajectory.metadata = metadata;
  trajectory.figures = {{"friction_disk_trajectory", trajectory.title, "t", "slip", {"integrator"}, {}, false, false,
                         {}, true, false, "exact", trajectory.caption + " One panel per scheme; dotted: exact."}};
  for (std::size_t i = 0; i < cases.size(); ++i)
    if (results[i].contains("trajectory_t")) {
      const std::vector<double> t = results[i]["trajectory_t"];
      for (std::size_t k = 0; k < t.size(); ++k)
        trajectory.add_row({cases[i]["integrator"].get<std::string>(), t[k], number_cell(results[i]["trajectory_slip"][k])});
    }
  const double t_end = find_friction_case(kFrictionTrajectoryCase).t_end;
  for (int k = 0; k <= kFrictionExactSamples; ++k) {
    const double t = t_end * k / kFrictionExactSamples;
    trajectory.add_row({std::string("exact"), t, (disk.contacts().tangent * disk.state(t)->v)(0)});
  }
  return {sliding, rolling, block, hard, rank, trajectory};
}

}  // namespace

extern const StudyEntry friction_study = {
    "friction", "Coulomb friction: sliding mass stop time and distance, rolling disk onset and final speed, orders; "
                "energy never increasing; block momentum identities; sticking, mu = tan alpha, reversal, mu = 10, a "
                "spinning drop; ranking",
    nullptr, &friction_cases, &friction_case, &friction_tables, &integrators_named};

}  // namespace nsb
