// Study "block": every integrator on the 2D hyperelastic block (block-2d defaults: 1 x 0.5 m,
// SVK, E = 1 MPa, nu = 0.3, rho = 1000, tilted 15 degrees, lowest corner 0.1 m up, falling
// at 1 m/s, gravity; here also sliding at vx = 0.5 m/s so that P_x is not trivially zero)
// on N x N meshes, N = 4 .. 32, steps 2e-4 and 1e-4, to t = 0.15 s (the first impact);
// --full adds N = 64, the step 5e-5 and runs to t = 0.3 s (rebound and second contact).
//
// Per case:
// - centre-of-mass height error: max over t = 0, 0.01, .. of |y_c - y_c,ref| against the
//   reference: penalty-bdf (reference/penalty.hpp; no scheme under test) on the finest mesh,
//   k = 1e10 N/m, rtol 1e-7, a cached reference run (reference/cache.hpp) whose y_c comes
//   from its gravity energy, y_c = V_g / (M g). On the finest mesh, not per mesh: the column
//   is the error of the whole discretisation (mesh and step), as a user of a coarse mesh
//   sees it. The penalty's damping cannot give e = 0 (it is floored at e = 1e-3, see
//   penalty.cpp): the reference's restitution is read from the run and stated. Its own
//   error, in the same norm: against k / 10 (penalty), 10 rtol (tolerance), twice the
//   floored e (restitution: the effect is linear in small e, so this is its distance to
//   e = 0), and the next coarser mesh (mesh); all stated in the caption and metadata.
// - energy error (E - E0) / E0, max and final: the continuum (elastic, frictionless)
//   conserves energy, so all of it is discretisation error (lumped mass, node-wise e = 0).
// - horizontal momentum error max_k |P_x,k - P_x,0| / sum_a m_a |v_a,0| (round-off expected).
// - angular momentum balance residual, max over steps k >= 2 of
//       |J_k - J_{k-1} - tau sum_a x_a (-m_a g) - sum_i x_i Lambda_i| / sum_a m_a |x_a,0| |v_a,0|
//   with J = sum_a m_a x_a x v_a of the reported state and the torques at the end-of-step
//   positions: CD-Lagrange's exact discrete balance (tests/integrators/block_momentum_test.cpp).
//   Moreau-Jean's forces act at other points (theta-weighted, linearised), so it shows
//   that scheme's balance error and the choice of point together.
// - impacts (a contact whose impulse turns positive), largest number of simultaneously
//   active contacts, LCP iterations and largest LCP residual, steps, CPU time.
// Cost growth: CPU time per step (observer time removed) against dofs at dt = 1e-4, and
// the least-squares log-log slope per integrator.
// Momentum histories at dt = 1e-4 (table block_momentum_history, figures
// block_momentum_px and block_momentum_j): the largest P_x error and J residual over each of
// 150 equal intervals of the run, at the interval's last step.
// Deformed block (tables block_deformed and block_deformed_impulses, figure block_deformed):
// the 8x8 mesh at dt = 1e-4 of kSnapshotSchemes at the initial state, the first contact, the
// largest compression (largest strain energy) and the end of the run, cells coloured by
// sigma_yy (Cauchy, cell mean), contact impulses as arrows (studies/snapshots.hpp).
// Ranking (studies/ranking.hpp): the cheapest integrator, over every mesh and step, whose
// y_c error reaches 1e-3, 1e-4, 3e-5 and 1e-5 m (3e-5: the explicit schemes' best on
// 32x32). The floor is the reference's own error as a solution of the 32x32 problem
// (penalty + tolerance + restitution estimates; not its mesh error: the distance to the
// 32x32 solution is what the column measures).
#include <fmt/format.h>

#include <cmath>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/block_2d.hpp"
#include "reference/cache.hpp"
#include "studies/ranking.hpp"
#include "studies/snapshots.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr double kVx = 0.5;
constexpr long kBlockStepBudget = 20;  // F_int evaluations allowed per step of the requested size
constexpr double kBlockSamplePeriod = 0.01;  // y_c sampling period [s]
const std::vector<double> kBlockRankingTargets = {1e-3, 1e-4, 3e-5, 1e-5};  // y_c error [m]
constexpr double kDetailDt = 1e-4;  // the step of the cost table and the momentum histories
constexpr int kBlockHistoryPoints = 150;
// The runs pictured deformed (kSnapshotSchemes) on a mesh whose cells can be seen, at the
// detail step.
constexpr long kSnapshotMesh = 8;

Block2d make_block(long n) {
  return Block2d(Params(Block2d::parameters_spec(),
                        {{"nx", fmt::format("{}", n)}, {"ny", fmt::format("{}", n)}, {"vx", fmt::format("{}", kVx)}}));
}

struct BlockCaseResult {
  bool diverged = false;  // or over budget: `status` says which
  std::string status = status_name(RunStatus::Ok), message;
  std::vector<double> yc;  // centre-of-mass height at t = j kSample
  double energy_max = 0, energy_final = 0, px_error = 0, j_residual = 0, cpu = 0;
  double lcp_residual = NAN;
  long impacts = 0, max_active = 0, steps = 0, lcp_iterations = 0;
  IntervalMax history;  // P_x error, J residual (when asked for)
  Json snapshots = Json::array();  // the deformed mesh at chosen instants (when asked for)
};

BlockCaseResult run_case(const std::string& integrator_name, long n, double dt, double t_end, bool history, bool snapshots) {
  const Block2d b = make_block(n);
  auto integ = make_integrator(integrator_name);
  const State s0 = b.initial_state();
  integ->init(b, s0);
  const Vec& m = b.lumped_mass();
  const double g = b.parameters().real("g");
  const SpMat& L = b.gap_operator();
  double p_scale = 0.0, j_scale = 0.0;
  for (Index a = 0; a < b.nodes(); ++a) {
    p_scale += m[2 * a] * s0.v.segment<2>(2 * a).norm();
    j_scale += m[2 * a] * s0.v.segment<2>(2 * a).norm() * b.reference_position(a).norm();
  }
  const auto centre_height = [&](const Vec& u) {
    double y = 0.0;
    for (Index a = 0; a < b.nodes(); ++a) y += m[2 * a + 1] * (b.reference_position(a).y() + u[2 * a + 1]);
    return y / (m.sum() / 2);
  };

  BlockCaseResult c;
  c.yc.push_back(centre_height(s0.u));
  const double px0 = b.linear_momentum(s0.v).x();
  double J_prev = b.angular_momentum(s0.u, s0.v);
  Vec lambda_prev = Vec::Zero(L.rows()), force(b.ndof());
  long k = 0;
  c.history = IntervalMax(t_end, kBlockHistoryPoints, 2);
  std::optional<MeshSnapshots> pictures;
  if (snapshots) {
    pictures.emplace(b, "sigma_yy");
    pictures->add(s0, Vec(), Vec());
  }
  RunOptions options;
  options.dt = dt;
  options.t_end = t_end;
  options.record_series = false;
  // Work budget: an adaptive scheme whose step collapses on the stiff block (1000x the
  // fixed scheme's steps) stops here, deterministically, and its row says so.
  options.max_force_evaluations = kBlockStepBudget * static_cast<long>(std::ceil(t_end / dt));
  const RunResult r = run(b, *integ, options, [&](const Integrator& it, const StepInfo& info) {
    const State& s = it.state();
    const Vec& lambda = it.impulses();
    ++k;
    const double px = std::abs(b.linear_momentum(s.v).x() - px0) / p_scale;
    c.px_error = std::max(c.px_error, px);
    double j_res = 0.0;
    const double J = b.angular_momentum(s.u, s.v);
    if (k >= 2) {
      force.noalias() = L.transpose() * lambda;
      double torque = 0.0;
      for (Index a = 0; a < b.nodes(); ++a)
        torque += (b.reference_position(a).x() + s.u[2 * a]) * (force[2 * a + 1] - info.dt * m[2 * a + 1] * g);
      j_res = std::abs(J - J_prev - torque) / j_scale;
      c.j_residual = std::max(c.j_residual, j_res);
    }
    J_prev = J;
    if (history) c.history.add(s.t, {px, j_res});
    if (pictures) pictures->add(s, lambda, it.tangential_impulses());
    long active = 0;
    for (Index i = 0; i < lambda.size(); ++i) {
      active += lambda[i] > 0.0;
      c.impacts += lambda[i] > 0.0 && lambda_prev[i] == 0.0;
    }
    c.max_active = std::max(c.max_active, active);
    lambda_prev = lambda;
    if (std::abs(s.t - kBlockSamplePeriod * static_cast<double>(c.yc.size())) < 0.5 * info.dt) c.yc.push_back(centre_height(s.u));
  });
  c.history.finish();
  if (pictures) c.snapshots = pictures->finish();
  c.steps = r.steps;
  c.cpu = r.step_cpu_seconds;  // the observer's time excluded by run()
  c.lcp_iterations = r.work.lcp_iterations;
  if (r.work.extra.count("lcp_max_residual")) c.lcp_residual = r.work.extra.at("lcp_max_residual");
  c.energy_max = r.max_energy_error;
  c.energy_final = (r.final_energy - r.initial_energy) / r.initial_energy;
  if (r.status != RunStatus::Ok) {
    c.diverged = true;
    c.status = status_name(r.status);
    c.message = r.message;
  }
  return c;
}

// max_j |a_j - b_j| over the common samples; NaN when either is missing.
double history_error(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.empty() || b.empty()) return NAN;
  double e = 0.0;
  for (std::size_t j = 0; j < std::min(a.size(), b.size()); ++j) e = std::max(e, std::abs(a[j] - b[j]));
  return e;
}

struct Reference {
  std::vector<double> yc;  // at t = j kSample
  CachedReference run;
};

constexpr double kRefStiffness = 1e10, kRefRtol = 1e-7;

// penalty-bdf on the n x n block, cached; `e` empty: the problem's default restitution.
Reference penalty_reference(long n, double t_end, double stiffness, double rtol, const std::string& e = "") {
  std::map<std::string, std::string> problem = {
      {"nx", fmt::format("{}", n)}, {"ny", fmt::format("{}", n)}, {"vx", fmt::format("{}", kVx)}};
  if (!e.empty()) problem["e"] = e;
  // atol: displacements ~0.1 m, velocities ~1 m/s, impulses ~10 N s; 1e-3 rtol is below them all.
  const ReferenceRequest request{"block-2d", problem, "penalty-bdf",
                                 {{"stiffness", fmt::format("{}", stiffness)}, {"rtol", fmt::format("{}", rtol)},
                                  {"atol", fmt::format("{}", 1e-3 * rtol)}},
                                 kBlockSamplePeriod, t_end, 1};
  Reference r{{}, cached_reference(reference_cache_dir(), request)};
  if (r.run.summary["status"] != status_name(RunStatus::Ok))
    throw std::runtime_error(fmt::format("block reference: penalty-bdf failed: {}", r.run.summary["message"].get<std::string>()));
  const Block2d b = make_block(n);
  const double weight = b.parameters().real("g") * b.lumped_mass().sum() / 2;
  const std::size_t col = r.run.series.column("gravity_energy");
  for (std::size_t j = 0; j < r.run.series.rows(); ++j) r.yc.push_back(r.run.series.at(j, col) / weight);
  return r;
}


struct Grid {
  std::vector<long> meshes = {4, 8, 16, 32};
  std::vector<double> steps = {2e-4, 1e-4};
  double t_end = 0.15;  // the first impact, whole (contact from about 0.09 s to 0.14 s)
};

Grid grid(const StudyOptions& opt) {
  Grid g;
  if (opt.full) {
    g.meshes.push_back(64);
    g.steps.push_back(5e-5);
    g.t_end = 0.3;
  }
  return g;
}

// The reference and its four error estimates (penalty, tolerance, restitution, mesh) are
// cases of their own, so that they run in parallel with the integrators (and are cached).
enum RefCase { kRefMain, kRefSoft, kRefLoose, kRefRestitution, kRefCoarse, kRefCases };

std::vector<Json> block_cases(const StudyOptions& opt) {
  const Grid g = grid(opt);
  std::vector<Json> cases;
  for (int r = 0; r < kRefCases; ++r) cases.push_back({{"reference", r}});
  for (const auto& entry : integrator_registry())
    for (long n : g.meshes)
      for (double dt : g.steps) cases.push_back({{"integrator", entry.name}, {"n", n}, {"dt", dt}});
  return cases;
}

Json block_case(const Json& c, const StudyOptions& opt) {
  const Grid g = grid(opt);
  const long n_ref = g.meshes.back();
  if (c.contains("reference")) {
    // The restitution estimate doubles the reference's floored e, read from its main run
    // (cached, so this is a lookup once the main case has run).
    const auto e_ref = [&] {
      return penalty_reference(n_ref, g.t_end, kRefStiffness, kRefRtol).run.summary["work"]["restitution_floor"].get<double>();
    };
    Reference r;
    switch (c["reference"].get<int>()) {
      case kRefMain: r = penalty_reference(n_ref, g.t_end, kRefStiffness, kRefRtol); break;
      case kRefSoft: r = penalty_reference(n_ref, g.t_end, kRefStiffness / 10, kRefRtol); break;
      case kRefLoose: r = penalty_reference(n_ref, g.t_end, kRefStiffness, 10 * kRefRtol); break;
      case kRefRestitution: r = penalty_reference(n_ref, g.t_end, kRefStiffness, kRefRtol, fmt::format("{}", 2 * e_ref())); break;
      default: r = penalty_reference(n_ref / 2, g.t_end, kRefStiffness, kRefRtol);
    }
    return {{"yc", r.yc}, {"summary", r.run.summary}, {"from_cache", r.run.from_cache}};
  }
  BlockCaseResult r;
  try {
    const bool pictured = c["n"] == kSnapshotMesh && c["dt"] == kDetailDt &&
                          std::count(kSnapshotSchemes.begin(), kSnapshotSchemes.end(), c["integrator"]);
    r = run_case(c["integrator"], c["n"], c["dt"], g.t_end, c["dt"] == kDetailDt, pictured);
  } catch (const InputError& e) {
    r.diverged = true;
    r.status = kDeclinedStatus;
    r.message = fmt::format("unsupported: {}", e.what());
  }
  return {{"diverged", r.diverged}, {"status", r.status}, {"message", r.message}, {"yc", r.yc}, {"energy_max", real(r.energy_max)},
          {"energy_final", real(r.energy_final)}, {"px_error", r.px_error}, {"j_residual", r.j_residual},
          {"cpu", r.cpu}, {"lcp_residual", real(r.lcp_residual)}, {"impacts", r.impacts},
          {"max_active", r.max_active}, {"steps", r.steps}, {"lcp_iterations", r.lcp_iterations},
          {"history_t", r.history.times()}, {"history_px", reals(r.history.largest(0))},
          {"history_j", reals(r.history.largest(1))}, {"snapshots", r.snapshots}};
}

std::vector<Table> block_tables(const std::vector<Json>& cases, const std::vector<Json>& results,
                                const StudyOptions& opt) {
  const Grid g = grid(opt);
  const std::vector<long>& meshes = g.meshes;
  const std::vector<double>& steps = g.steps;
  const double t_end = g.t_end;
  const long n_ref = meshes.back();
  const auto yc_of = [&](int r) { return results[static_cast<std::size_t>(r)]["yc"].get<std::vector<double>>(); };
  const Json& ref_summary = results[kRefMain]["summary"];
  const std::vector<double> ref_yc = yc_of(kRefMain);
  const double e_ref = ref_summary["work"]["restitution_floor"].get<double>();
  const double ref_penalty_error = history_error(ref_yc, yc_of(kRefSoft));
  const double ref_tolerance_error = history_error(ref_yc, yc_of(kRefLoose));
  const double ref_restitution_error = history_error(ref_yc, yc_of(kRefRestitution));
  const double ref_mesh_error = history_error(ref_yc, yc_of(kRefCoarse));
  const std::string ref_cost = fmt::format("{:.1f} s CPU, {} CVODE steps, {} factorisations{}",
                                           ref_summary["cpu_seconds"].get<double>(),
                                           ref_summary["work"]["steps"].get<long>(),
                                           ref_summary["work"]["factorizations"].get<long>(),
                                           results[kRefMain]["from_cache"].get<bool>() ? ", cached" : "");

  Table cases_table;
  cases_table.id = "block";
  cases_table.title = "2D block on a rigid floor: every integrator, meshes and steps";
  cases_table.caption = fmt::format(
      "block-2d defaults (SVK, E = 1 MPa, nu = 0.3, tilt 15 deg, falling at 1 m/s, gravity, e = 0) with vx = {} m/s, "
      "N x N Q4 elements, to t = {} s. y_c err: max over t = 0, {}, ... of the centre-of-mass height error against "
      "the penalty-bdf reference on {}x{} (k = {:.0e} N/m, rtol {:.0e}, atol {:.0e}; {}), whose dashpots give each "
      "contact node a restitution of {:.2e} instead of 0 (the damping is floored). Its own estimated error, same "
      "norm: {:.1e} m (penalty, against k/10), {:.1e} m (tolerance, against 10 rtol), {:.1e} m (restitution, "
      "against e = {:.2e}), {:.1e} m (mesh, against {}x{}). E err: (E - E0)/E0 of the integrator's energy. P_x "
      "err: max |P_x - P_x0| / sum m|v0|. J res.: angular momentum balance residual with torques at the "
      "end-of-step positions, relative to sum m|x0||v0|.",
      kVx, t_end, kBlockSamplePeriod, n_ref, n_ref, kRefStiffness, kRefRtol, 1e-3 * kRefRtol, ref_cost, e_ref,
      ref_penalty_error, ref_tolerance_error, ref_restitution_error, 2 * e_ref, ref_mesh_error, n_ref / 2, n_ref / 2);
  cases_table.columns = {
      {"integrator", "", "", ""},
      {"mesh", "", "", "N x N elements"},
      {"dofs", "", "", ""},
      {"dt", "s", "{:.1e}", "step"},
      {"dt/dt_CFL", "", "{:.2f}", "step over the problem's stable-step estimate"},
      {"y_c err", "m", "{:.2e}", "max centre-of-mass height error against the reference"},
      {"max E err", "", "{:.2e}", "max |E - E0| / E0"},
      {"final E err", "", "{:.2e}", "(E - E0) / E0 at t_end"},
      {"P_x err", "", "{:.1e}", "max horizontal momentum error, relative"},
      {"J res.", "", "{:.1e}", "max angular momentum balance residual per step, relative"},
      {"impacts", "", "", "contacts whose impulse turns positive"},
      {"max contacts", "", "", "most contacts active in one step"},
      {"LCP it.", "", "", "total LCP iterations"},
      {"LCP res.", "", "{:.1e}", "largest LCP residual (n/a: closed form)"},
      {"steps", "", "", ""},
      {"CPU", "s", "{:.2e}", "thread CPU time of the run, observer excluded", true},
  };
  Table cost;
  cost.id = "block_cost";
  cost.title = "2D block: CPU time per step against dofs";
  cost.caption = fmt::format("dt = 1e-4 s to t = {} s (impacts included), observer time excluded; slope: least-squares "
                             "log-log slope of time per step against dofs over the meshes.", t_end);
  cost.columns = {{"integrator", "", "", ""}, {"mesh", "", "", ""}, {"dofs", "", "", ""},
                  {"time/step", "s", "{:.2e}", "", true}, {"slope", "", "{:.2f}", "fitted over all meshes (last row)", true}};
  cases_table.metadata = {{"study", "block"},
                    {"meshes", fmt::format("{}", fmt::join(meshes, " "))},
                    {"steps", fmt::format("{}", fmt::join(steps, " "))},
                    {"t_end", fmt::format("{}", t_end)},
                    {"reference", fmt::format("penalty-bdf {}x{} k {} rtol {} ({})", n_ref, n_ref, kRefStiffness,
                                              kRefRtol, ref_cost)},
                    {"reference restitution", fmt::format("{:.3e}", e_ref)},
                    {"reference error (penalty)", fmt::format("{:.3e}", ref_penalty_error)},
                    {"reference error (tolerance)", fmt::format("{:.3e}", ref_tolerance_error)},
                    {"reference error (restitution)", fmt::format("{:.3e}", ref_restitution_error)},
                    {"reference error (mesh)", fmt::format("{:.3e}", ref_mesh_error)}};
  cost.metadata = cases_table.metadata;
  Table momentum;
  momentum.id = "block_momentum_history";
  momentum.title = "2D block: momentum balance histories, dt = 1e-4 s";
  momentum.caption = fmt::format("The largest P_x error and J residual (as in the block table) over each of {} equal "
                                 "intervals of [0, {}] s, at the interval's last step.", kBlockHistoryPoints, t_end);
  momentum.columns = {{"integrator", "", "", ""}, {"mesh", "", "", ""}, {"t", "s", "", "end of the interval"},
                      {"P_x err", "", "", "largest over the interval"}, {"J res.", "", "", "largest over the interval"}};
  momentum.csv_only = true;
  momentum.metadata = cases_table.metadata;
  momentum.figures = {
      {"block_momentum_px", "2D block: horizontal momentum error, dt = 1e-4 s", "t", "P_x err", {"integrator"}, {"mesh"}, false, true},
      {"block_momentum_j", "2D block: angular momentum balance residual, dt = 1e-4 s", "t", "J res.", {"integrator"}, {"mesh"}, false, true}};

  SnapshotTables deformed = snapshot_tables(
      "block_deformed",
      fmt::format("2D block, {}x{}, dt = {:g} s: deformed mesh coloured by sigma_yy, contact impulses", kSnapshotMesh,
                  kSnapshotMesh, kDetailDt),
      fmt::format("The block of the block table (vx = {} m/s) on {}x{} Q4 at dt = {:g} s, {}: the mesh deformed at "
                  "true scale (the initial state, the first step with a contact impulse, the step of largest strain "
                  "energy and t = {} s), cells coloured by sigma_yy (Cauchy stress, mean over the cell's Gauss points; "
                  "negative: compression), the step's contact impulses L^T Lambda at the nodes as arrows, scaled to "
                  "the largest in the figure. The floor is y = 0.",
                  kVx, kSnapshotMesh, kSnapshotMesh, kDetailDt, fmt::join(kSnapshotSchemes, " and "), t_end),
      "sigma_yy");
  deformed.cells.metadata = deformed.arrows.metadata = cases_table.metadata;

  RankingProblem ranking{"2D block", fmt::format("the penalty-bdf reference on {}x{}", n_ref, n_ref),
                         ref_penalty_error + ref_tolerance_error + ref_restitution_error, kBlockRankingTargets, {}};
  std::size_t k = kRefCases;
  while (k < cases.size()) {
    const std::string integrator = cases[k]["integrator"];
    const IntegratorEntry& entry = find_integrator(integrator);
    WorkCurve curve{integrator, entry.reference, {}, entry.peer};
    std::vector<double> dofs, time_per_step;
    for (long n : meshes) {
      const Block2d b = make_block(n);
      for (double dt : steps) {
        const Json& c = results[k++];
        const std::string mesh = fmt::format("{}x{}", n, n);
        const double cpu = c["cpu"].get<double>();
        const long n_steps = c["steps"].get<long>();
        const std::string run = fmt::format("{}, dt = {:.1e}", mesh, dt);
        const std::vector<double> ht = c["history_t"];  // up to where the run stopped
        for (std::size_t j = 0; j < ht.size(); ++j)
          momentum.add_row({integrator, mesh, ht[j], number_cell(c["history_px"][j]), number_cell(c["history_j"][j])});
        if (c.contains("snapshots")) add_snapshot_rows(deformed, integrator, c["snapshots"]);
        if (c["diverged"].get<bool>()) {
          if (c["status"] != kDeclinedStatus) curve.points.push_back({run, cpu, NAN});
          cases_table.add_row({integrator, mesh, static_cast<long>(b.ndof()), dt, dt / b.stable_step(), c["status"].get<std::string>(),
                               c["message"].get<std::string>(), {}, {}, {}, {}, {}, {}, {}, n_steps, cpu});
          continue;
        }
        const double yc_error = history_error(c["yc"].get<std::vector<double>>(), ref_yc);
        curve.points.push_back({run, cpu, yc_error});
        cases_table.add_row({integrator, mesh, static_cast<long>(b.ndof()), dt, dt / b.stable_step(),
                             number_cell(yc_error), number_cell(c["energy_max"]),
                             number_cell(c["energy_final"]), c["px_error"].get<double>(), c["j_residual"].get<double>(),
                             c["impacts"].get<long>(), c["max_active"].get<long>(), c["lcp_iterations"].get<long>(),
                             number_cell(c["lcp_residual"]), n_steps, cpu});
        if (dt == kDetailDt) {
          dofs.push_back(static_cast<double>(b.ndof()));
          time_per_step.push_back(cpu / static_cast<double>(n_steps));
          cost.add_row({integrator, mesh, static_cast<long>(b.ndof()), time_per_step.back(), {}});
        }
      }
    }
    cost.add_row({integrator, "all", {}, {}, number_cell(fitted_order(dofs, time_per_step))});
    ranking.curves.push_back(curve);
  }
  Table rank = ranking_table("block_ranking", "Cheapest integrator at each target error: 2D block",
                             {"y_c err", "m", "", "centre-of-mass height error, as in the block table"},
                             "thread CPU time of the run, observer excluded", {ranking});
  rank.metadata = cases_table.metadata;
  return {cases_table, cost, rank, momentum, deformed.cells, deformed.arrows};
}

}  // namespace

// The case runner needs the study options (grid): they travel in the case.
Json block_case_entry(const Json& c) { return block_case(c["case"], StudyOptions{c["full"].get<bool>()}); }
std::vector<Json> block_case_list(const StudyOptions& opt) {
  std::vector<Json> cases;
  for (const auto& c : block_cases(opt)) cases.push_back({{"case", c}, {"full", opt.full}});
  return cases;
}
std::vector<Table> block_table_entry(const std::vector<Json>& cases, const std::vector<Json>& results,
                                     const StudyOptions& opt) {
  std::vector<Json> inner;
  for (const auto& c : cases) inner.push_back(c["case"]);
  return block_tables(inner, results, opt);
}

extern const StudyEntry block_study = {
    "block", "2D hyperelastic block on a rigid floor: momentum and energy errors, error against a reference, cost growth",
    nullptr, &block_case_list, &block_case_entry, &block_table_entry,
    [](const Json& c) { return integrators_named(c["case"]); }};

}  // namespace nsb
