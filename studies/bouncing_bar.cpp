// Study "bouncing-bar": the Doyen-Ern-Piperno bouncing bar (problems/bouncing_bar.hpp: L = 10,
// E = 900, rho = A = 1, g = 10, dropped from rest 5 above the wall; c = 30, first impact at
// t1 = 1, period P = 16 L/c = 16/3) over many periods against its exact continuum solution.
// DEP's finding to check: modified/singular masses keep the energy, lumped masses lose it.
// Grid: every registered integrator x mass lumped | consistent | singular x N x alpha, dt =
// alpha * stable step (h/c lumped and singular, h/(sqrt(3) c) consistent), to t1 + K P.
//   default  K = 20, N in {50, 100, 200, 400} at alpha = 0.9, and alpha = 0.5 at N = 100
//   --full   K = 50, N in {50, 100, 200, 400, 800}, alpha in {0.25, 0.5, 0.9}
// Peers in the default grid at N = 50 only (kPeerMaxN). References (accuracy set by their
// tolerance, alpha only their output step) at alpha = 0.9, and in the default grid at N <= 100
// only (modal-exact costs O(N^2) per output step, with no F_int evaluations to budget; at
// N = 400 a case took minutes).
// Budget: 4 F_int evaluations per nominal step (RunOptions::max_force_evaluations): a count,
// so a slow scheme (event-driven root finding on 400 elements, an adaptive step collapsing)
// stops at the same step everywhere, marked "over budget" with its figures so far.
// Per case (energies: the scheme's own Integrator::energy; the exact one is 0, the drop's
// potential being the origin; scale E_imp = rho A L V^2 / 2 = 500, the kinetic energy at impact):
//   E err k      (E(t1 + k P) - 0) / E_imp at the first step past t1 + k P, k = 1..K
//   drift        least-squares slope of E err k against k (per period)
//   u max / RMS  contact-end displacement error |u_0 - u_0,exact| over the steps: max (over the
//                first period, and over the run), and sqrt(sum dt e^2 / t) (RMS in time over
//                the run), relative to the drop height g0 = 5
//   force osc.   RMS of (Lambda/dt - lambda_exact(t)) / (rho A c V) over the steps of the first
//                period whose [t - dt, t + dt] lies inside an exact contact phase
// Figures (N = 100, alpha = 0.9): E err against periods, panels by mass; contact-end
// displacement over the last two periods against the exact one.
#include <fmt/format.h>

#include <cmath>
#include <map>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/bouncing_bar.hpp"
#include "problems/signorini_bar.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

const std::vector<std::string> kBouncingBarMasses = {"lumped", "consistent", "singular"};
constexpr double kBudgetPerStep = 4.0;
constexpr long kFigureN = 100;
constexpr double kFigureAlpha = 0.9;
// References cost O(N^2) per output step (modal-exact) or many CVODE steps per output step
// (event-driven): N <= 100 only in the default grid.
constexpr long kReferenceMaxN = 100;
// The peers (Siconos, dense algebra) took 184 of the default grid's 228 CPU seconds at N = 100
// while they agree with our schemes (the peers study): N <= 50 only in the default grid.
constexpr long kPeerMaxN = 50;
constexpr int kTrajectoryPoints = 400;
constexpr double kBlowUp = 10.0;  // |E err| beyond which a run is left out of the trajectory figure

int periods(const StudyOptions& opt) { return opt.full ? 50 : 20; }

Params bar_params(const std::string& mass, long N) {
  return Params(SignoriniBar::bouncing_parameters_spec(), {{"mass", mass}, {"N", fmt::format("{}", N)}});
}

std::vector<Json> bouncing_bar_cases(const StudyOptions& opt) {
  std::vector<std::pair<long, double>> grid;  // (N, alpha)
  if (opt.full) {
    for (long N : {50, 100, 200, 400, 800})
      for (double alpha : {0.25, 0.5, 0.9}) grid.emplace_back(N, alpha);
  } else {
    for (long N : {50, 100, 200, 400}) grid.emplace_back(N, 0.9);
    grid.emplace_back(100, 0.5);
  }
  std::vector<Json> cases;
  for (const auto& entry : integrator_registry())
    for (const auto& mass : kBouncingBarMasses)
      for (const auto& [N, alpha] : grid)
        if ((!entry.reference && (!entry.peer || opt.full || N <= kPeerMaxN)) ||
            (entry.reference && alpha == kFigureAlpha && (opt.full || N <= kReferenceMaxN)))
          cases.push_back({{"integrator", entry.name}, {"mass", mass}, {"N", N}, {"alpha", alpha},
                           {"periods", periods(opt)}});
  return cases;
}

Json bouncing_bar_case(const Json& c) {
  const long N = c["N"];
  const std::string mass = c["mass"];
  const Params params = bar_params(mass, N);
  const SignoriniBar p(params, "bouncing-bar");
  const int K = c["periods"];
  const double dt = c["alpha"].get<double>() * p.stable_step();
  auto integrator = make_integrator(c["integrator"]);
  if (const auto declined = init_or_decline(*integrator, p)) return {{"dt", dt}, {"status", "n/a"}, {"message", *declined}};
  Json out = {{"dt", dt}, {"status", "ok"}, {"message", ""}};
  const double g0 = params.real("g0");
  RunOptions options;
  options.dt = dt;
  const BouncingBarExact fall(params, 0.0);  // t1 and L/c, to size the horizon
  const double t1 = fall.impact_time(), P = 16.0 * fall.wave_time();
  const BouncingBarExact ex(params, t1 + K * P + 2.0 * dt);
  const double E_imp = ex.impact_energy();
  const double F_scale = params.real("rho") * params.real("A") * std::sqrt(params.real("E") / params.real("rho")) * ex.impact_speed();
  options.t_end = t1 + K * P;
  options.record_series = false;
  options.sample_every = 1L << 40;
  options.max_force_evaluations = static_cast<long>(kBudgetPerStep * options.t_end / dt);
  const bool figure = N == kFigureN && c["alpha"].get<double>() == kFigureAlpha;
  std::vector<double> e_period, traj_t, traj_u;
  double u_max = 0.0, u_max1 = 0.0, u_sq = 0.0, osc_sq = 0.0;
  long osc_n = 0;
  const double traj_start = options.t_end - 2.0 * P;
  const RunResult r = run(p, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const double t = it.state().t, u0 = it.state().u[0];
    const double du = std::abs(u0 - ex.displacement(0.0, t)) / g0;
    u_max = std::max(u_max, du);
    if (t <= t1 + P) u_max1 = std::max(u_max1, du);
    u_sq += info.dt * du * du;
    while (static_cast<int>(e_period.size()) < K && t >= t1 + (e_period.size() + 1) * P - 0.5 * dt)
      e_period.push_back((it.energy().total() - ex.energy()) / E_imp);
    if (t < t1 + P && ex.contact_force(t - info.dt) > 0.0 && ex.contact_force(t) > 0.0 && ex.contact_force(t + info.dt) > 0.0) {
      const double d = (it.impulses()[0] / info.dt - ex.contact_force(t)) / F_scale;
      osc_sq += d * d;
      ++osc_n;
    }
    if (figure && t >= traj_start + 2.0 * P * static_cast<double>(traj_t.size()) / kTrajectoryPoints &&
        static_cast<int>(traj_t.size()) <= kTrajectoryPoints) {
      traj_t.push_back(t);
      traj_u.push_back(u0);
    }
  });
  std::vector<double> k(e_period.size());
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<double>(i + 1);
  // Least-squares slope of E err against the period number.
  double drift = NAN;
  if (k.size() >= 2) {
    double mk = 0.0, me = 0.0, skk = 0.0, ske = 0.0;
    for (std::size_t i = 0; i < k.size(); ++i) mk += k[i], me += e_period[i];
    mk /= k.size(), me /= k.size();
    for (std::size_t i = 0; i < k.size(); ++i) skk += (k[i] - mk) * (k[i] - mk), ske += (k[i] - mk) * (e_period[i] - me);
    drift = ske / skk;
  }
  out["status"] = r.status == RunStatus::Ok ? "ok" : status_name(r.status);
  if (r.status != RunStatus::Ok) out["message"] = r.message;
  out["t_final"] = r.t_final;
  out["steps"] = r.steps;
  out["force_evaluations"] = r.work.force_evaluations;
  out["cpu"] = r.step_cpu_seconds;
  out["e_period"] = reals(e_period);
  out["drift"] = real(drift);
  out["u_max"] = real(u_max);
  out["u_max1"] = real(u_max1);
  out["u_rms"] = real(r.t_final > 0.0 ? std::sqrt(u_sq / r.t_final) : NAN);
  out["force_osc"] = real(osc_n ? std::sqrt(osc_sq / osc_n) : NAN);
  if (figure) {
    out["traj_t"] = traj_t;
    out["traj_u"] = reals(traj_u);
  }
  return out;
}

std::vector<Table> bouncing_bar_tables(const std::vector<Json>& cases, const std::vector<Json>& results,
                                       const StudyOptions& opt) {
  const int K = periods(opt);
  const std::string setup = fmt::format(
      "Doyen-Ern-Piperno bouncing bar: L = 10, E = 900, rho = A = 1, g = 10, dropped from rest 5 above the wall "
      "(c = 30, impact at t1 = 1 with V = 10, period P = 16/3), run to t1 + {} P; dt = alpha * stable step. Energy "
      "error: the scheme's own energy minus the exact (conserved, 0) over E_imp = rho A L V^2 / 2 = 500, at the first "
      "step past t1 + k P. Budget: {} F_int evaluations per nominal step.",
      K, kBudgetPerStep);
  const auto metadata = std::vector<std::pair<std::string, std::string>>{
      {"study", "bouncing-bar"}, {"periods", fmt::format("{}", K)}, {"full", opt.full ? "yes" : "no"}};

  Table table;
  table.id = "bouncing_bar";
  table.title = "Bouncing bar (Doyen-Ern-Piperno): energy over the periods and contact-end error";
  table.caption = setup + " u: contact-end displacement error over g0 = 5, max and RMS in time over the run. Force "
                          "osc.: RMS of (Lambda/dt - lambda) / (rho A c V) inside the exact contact phases of the first "
                          "period. Over budget: figures up to the stop (periods done). n/a: the scheme declines the mass.";
  table.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"N", "", "", "elements"},
                   {"alpha", "", "{}", "dt / stable step"}, {"dt", "", "{:.2e}", ""},
                   {"periods", "", "", "periods completed"}, {"E err 1", "", "{:.2e}", "after the first period"},
                   {"E err end", "", "{:.2e}", "after the last period completed"},
                   {"drift", "1/period", "{:.2e}", "least-squares slope of E err against k"},
                   {"u max err 1", "", "{:.2e}", "first period"}, {"u max err", "", "{:.2e}", ""}, {"u RMS err", "", "{:.2e}", ""}, {"force osc.", "", "{:.2e}", ""},
                   {"steps", "", "", ""}, {"F_int evals", "", "", ""}, {"CPU", "s", "{:.2e}", "thread CPU time of the stepping (observer and sampling excluded)", true},
                   {"status", "", "", ""}, {"note", "", "", ""}};
  table.metadata = metadata;

  Table dep;
  dep.id = "bouncing_bar_dep";
  dep.title = fmt::format("Bouncing bar: energy error after {} periods per mass model (N = {}, alpha = {})", K, kFigureN, kFigureAlpha);
  dep.caption = setup + " DEP's finding: the singular (modified) mass keeps the energy, the lumped mass loses it. "
                        "Empty: n/a or the run stopped before the last period (table bouncing_bar).";
  dep.columns = {{"integrator", "", "", ""}};
  for (const auto& m : kBouncingBarMasses) dep.columns.push_back({fmt::format("E err, {}", m), "", "{:.2e}", ""});
  dep.metadata = metadata;
  dep.headline = false;

  Table energy;
  energy.id = "bouncing_bar_energy";
  energy.title = fmt::format("Bouncing bar: energy error after each period (N = {}, alpha = {})", kFigureN, kFigureAlpha);
  energy.caption = setup;
  energy.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"period", "", "", ""}, {"E err", "", "{:.6e}", ""},
                    {"|E err|", "", "{:.6e}", "log scale: losses (to -1: the bar at rest on the wall) and blow-ups"}};
  energy.csv_only = true;
  energy.figures = {{"bouncing_bar_energy", energy.title, "period", "E err", {"integrator"}, {"mass"}, false, false, {}, true}};
  energy.metadata = metadata;

  Table traj;
  traj.id = "bouncing_bar_trajectory";
  traj.title = fmt::format("Bouncing bar: contact-end displacement over the last two periods (N = {}, alpha = {})", kFigureN, kFigureAlpha);
  traj.caption = setup + fmt::format(" exact: the continuum solution at the same times. Runs whose final |E err| exceeds {} "
                                     "(energy blow-up) are left out: see table bouncing_bar.", kBlowUp);
  traj.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"t", "", "{:.5f}", ""}, {"u_0", "", "{:.6f}", ""}};
  traj.csv_only = true;
  traj.figures = {{"bouncing_bar_trajectory", traj.title, "t", "u_0", {"integrator"}, {"mass"}, false, false}};
  traj.metadata = metadata;

  std::map<std::string, std::map<std::string, Cell>> dep_rows;
  std::vector<std::string> dep_order;
  std::map<std::string, bool> exact_drawn;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const Json& c = cases[i];
    const Json& r = results[i];
    const std::string integrator = c["integrator"], mass = c["mass"], status = r["status"];
    const long N = c["N"];
    const double alpha = c["alpha"];
    const bool shown = N == kFigureN && alpha == kFigureAlpha;
    if (shown && !dep_rows.count(integrator)) dep_order.push_back(integrator);
    if (status == "n/a") {
      table.add_row({integrator, mass, N, alpha, r["dt"].get<double>(), "", "", "", "", "", "", "", "", "", "", "", status,
                     r["message"].get<std::string>()});
      if (shown) dep_rows[integrator][mass] = Cell("n/a");
      continue;
    }
    const std::vector<Json> ep = r["e_period"];
    const long done = static_cast<long>(ep.size());
    table.add_row({integrator, mass, N, alpha, r["dt"].get<double>(), done, done ? number_cell(ep.front()) : Cell(""),
                   done ? number_cell(ep.back()) : Cell(""), number_cell(r["drift"]), number_cell(r["u_max1"]), number_cell(r["u_max"]),
                   number_cell(r["u_rms"]), number_cell(r["force_osc"]), r["steps"].get<long>(),
                   r["force_evaluations"].get<long>(), r["cpu"].get<double>(), status, r["message"].get<std::string>()});
    if (!shown) continue;
    dep_rows[integrator][mass] = done == K ? number_cell(ep.back()) : Cell(status);
    for (std::size_t k = 0; k < ep.size(); ++k) energy.add_row({integrator, mass, static_cast<long>(k + 1), number_cell(ep[k]), number_cell(std::abs(real(ep[k])))});
    // A blown-up run would flatten its panel to nothing: left out of the trajectory figure (its
    // energy row and table bouncing_bar show it).
    const bool blown_up = std::abs(done ? real(ep.back()) : 0.0) > kBlowUp;
    if (r.contains("traj_t") && !blown_up) {
      const std::vector<double> tt = r["traj_t"];
      for (std::size_t j = 0; j < tt.size(); ++j) traj.add_row({integrator, mass, tt[j], number_cell(r["traj_u"][j])});
      if (!exact_drawn[mass] && !tt.empty()) {
        exact_drawn[mass] = true;
        const BouncingBarExact ex(bar_params(mass, N), tt.back() + 1.0);
        for (double t : tt) traj.add_row({"exact", mass, t, ex.displacement(0.0, t)});
      }
    }
  }
  for (const auto& name : dep_order) {
    std::vector<Cell> row = {name};
    for (const auto& m : kBouncingBarMasses) {
      const auto it = dep_rows[name].find(m);
      row.push_back(it == dep_rows[name].end() ? Cell("") : it->second);
    }
    dep.add_row(std::move(row));
  }
  return {dep, table, energy, traj};
}

}  // namespace

extern const StudyEntry bouncing_bar_study = {
    "bouncing-bar",
    "Doyen-Ern-Piperno bouncing bar over many periods: energy per period per mass model, contact-end error, force oscillation",
    nullptr, &bouncing_bar_cases, &bouncing_bar_case, &bouncing_bar_tables};

}  // namespace nsb
