// Study "energy": long-time energy and momentum behaviour, fixed against adaptive
// CD-Lagrange (every variant of cd-lagrange-adaptive) and Moreau-Jean: every registered
// integrator, at its defaults, plus the adaptive variants.
//
// Long runs (table energy_long_time):
//   - bouncing mass, e = 1, h0 = 1, dt = 1e-3, 1000 impacts (10^4 with --full);
//   - spring chain (3 masses 1, 2, 1 kg, k = 100 N/m) rattling between two walls 0.5 m
//     away, e = 1, dt = 0.02 s (0.14 of the stable step 0.141 s), 40 s (400 s with --full):
//     about 45 contact phases;
//   - Signorini bar bouncing under gravity (problems/signorini_bar.hpp), nondimensional
//     (L = E = rho = A = v0 = 1), g = 0.25 (g L / (c v0) = 1/4: contact 2L/c = 2, first
//     flight about 2 v0 / g = 8), lumped and singular mass, dt = h / (2c) (half the stable
//     step), to t = 210: 21 cycles of the first period 10 (later flights shorten as the
//     bar's vibrations take energy from its rigid motion). N = 50; with --full N = 100 to
//     t = 2100. The default mesh is coarse because the references cost 10-15 s CPU per
//     case at N = 50 (event-driven: CVODE over the bar's vibrations) and the adaptive scheme
//     takes ~3e6 steps (its step collapses in the contacts). Cycles: contact phases that
//     start after at least L/c = 1 without contact impulse (a chattering contact node
//     restarts phases within a contact). Energy history: E(t)/E_0 at 400 evenly spaced
//     times (table energy_bar_history, figure energy_bar_history, log scale: a blow-up
//     reaches E/E_0 = 600 while the lumped bar's rigid motion loses most of its energy).
//   A scheme that declines a mass model (InputError at init: the adaptive scheme and the
//   references need positive masses) gives a row "n/a" with its reason.
//   Energy: each integrator's own (CD-Lagrange: E_{k+1/2}). Errors are relative to E_1, the
//   energy after the first step (CD-Lagrange balances E_{1/2}, which differs from the
//   continuous E_0 by O(dt^2): shown apart as the offset). Drift: least-squares slope of
//   (E - E_1)/E_1 against t over every step. Momentum residual (problems with F_ext = 0,
//   sum F_int = 0): max over steps of |sum M v - sum M v_0 - sum of the impulses' resultant
//   1^T L^T Lambda| / sum_i m_i |v_0,i|; gravity makes it n/a on the bouncing mass. Its
//   history (table energy_momentum_history, figure of the same name): the largest residual
//   over each of 400 equal intervals of the run, at the interval's last step.
// Energy target (table energy_targets): bouncing mass e = 0.9, dt = 1e-3, first 10 impacts:
//   flight energy at the exact mid-flight times against E0 e^(2i), where the no-work target
//   (the talk) and the impact-law target differ.
#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <map>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/registry.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct EnergyProblem {
  std::string label;
  std::string problem;
  std::map<std::string, std::string> params;
  double dt;
  double t_end, full_t_end;
  int flights;  // > 0: flight-energy table over that many impacts (bouncing mass only)
  double min_flight = 0.0;  // a contact phase counts after at least this long without impulse
  bool history = false;     // E(t)/E_0 history for the figure
  std::map<std::string, std::string> full_params = {};  // with --full, on top of params
  double full_dt = 0.0;                                 // with --full when > 0
};

constexpr int kHistoryPoints = 400;

// Bouncing mass h0 = 1: first impact 0.4515 s, period 0.9030 s, so 904 s holds 1001 impacts.
const std::vector<EnergyProblem> kProblems = {
    {"bouncing mass, e = 1", "bouncing-mass", {{"e", "1"}}, 1e-3, 904.0, 9031.0, 0},
    {"spring chain between walls, e = 1", "spring-chain", {{"wall", "both"}, {"gap", "0.5"}}, 0.02, 40.0, 400.0, 0},
    {"bouncing mass, e = 0.9", "bouncing-mass", {{"e", "0.9"}}, 1e-3, 0.0, 0.0, 10},
    {"Signorini bar, g = 0.25, lumped", "signorini-bar", {{"g", "0.25"}, {"mass", "lumped"}, {"N", "50"}}, 0.01,
     210.0, 2100.0, 0, 1.0, true, {{"N", "100"}}, 0.005},
    {"Signorini bar, g = 0.25, singular", "signorini-bar", {{"g", "0.25"}, {"mass", "singular"}, {"N", "50"}}, 0.01,
     210.0, 2100.0, 0, 1.0, true, {{"N", "100"}}, 0.005},
};

// The adaptive scheme's variants; the other integrators run at their defaults.
const std::vector<std::map<std::string, std::string>> kAdaptiveVariants = {
    {{"momentum", "variational"}, {"energy_target", "impact-law"}},
    {{"momentum", "variational"}, {"energy_target", "no-work"}},
    {{"momentum", "talk"}, {"energy_target", "impact-law"}},
    {{"momentum", "talk"}, {"energy_target", "no-work"}},
};
const std::vector<std::string> kCounters = {"energy_iterations", "no_root_steps", "cfl_capped_steps", "max_rel_residual"};

std::string variant_text(const std::map<std::string, std::string>& v) {
  if (v.empty()) return "default";
  std::vector<std::string> items;
  for (const auto& [k, x] : v) items.push_back(k + "=" + x);
  return fmt::format("{}", fmt::join(items, " "));
}


std::vector<Json> energy_cases(const StudyOptions& opt) {
  std::vector<Json> cases;
  for (std::size_t p = 0; p < kProblems.size(); ++p) {
    const EnergyProblem& ep = kProblems[p];
    auto params = ep.params;
    if (opt.full)
      for (const auto& [k, x] : ep.full_params) params[k] = x;
    const double dt = opt.full && ep.full_dt > 0.0 ? ep.full_dt : ep.dt;
    for (const auto& entry : integrator_registry()) {
      const bool adaptive = entry.name == "cd-lagrange-adaptive";
      for (const auto& v : adaptive ? kAdaptiveVariants : std::vector<std::map<std::string, std::string>>{{}})
        cases.push_back({{"problem", p}, {"params", params}, {"dt", dt}, {"integrator", entry.name}, {"variant", v},
                         {"t_end", opt.full ? ep.full_t_end : ep.t_end}});
    }
  }
  return cases;
}

Json energy_case(const Json& c) {
  const EnergyProblem& ep = kProblems[c["problem"].get<std::size_t>()];
  auto problem = make_problem(ep.problem, c["params"].get<std::map<std::string, std::string>>());
  auto integrator = make_integrator(c["integrator"], c["variant"].get<std::map<std::string, std::string>>());
  if (const auto declined = init_or_decline(*integrator, *problem))
    return {{"status", "n/a"}, {"message", *declined}, {"t_end", c["t_end"]}};
  const auto* bouncing = dynamic_cast<const BouncingMass*>(problem.get());
  RunOptions options;
  options.dt = c["dt"];
  options.t_end = ep.flights > 0 ? bouncing->impact_time(ep.flights + 1) : c["t_end"].get<double>();
  options.record_series = false;
  options.sample_every = 1000;

  Vec f_ext(problem->ndof());
  problem->external_force(0.0, f_ext);
  const bool momentum_balance = problem->external_force_is_constant() && f_ext.isZero(0.0);
  const Vec& v0 = problem->initial_state().v;
  const double p_scale = problem->mass_matrix().diagonal().cwiseProduct(v0).cwiseAbs().sum();
  MomentumBalance balance(*problem, v0);

  const double E0 = integrator->energy().total();
  double E1 = kNaN, err = 0.0, max_err = 0.0, momentum = 0.0;
  double dt_min = 1e300, dt_max = 0.0;
  RunningSlope drift;
  ContactPhases impacts(ep.min_flight);
  std::vector<double> flight_err, history_t, history_e;
  IntervalMax momentum_history(options.t_end, kHistoryPoints, 1);
  const auto observer = [&](const Integrator& it, const StepInfo& info) {
    const double t = it.state().t, E = it.energy().total();
    if (std::isnan(E1)) E1 = E;
    err = (E - E1) / std::abs(E1);
    max_err = std::max(max_err, std::abs(err));
    drift.add(t, err);
    dt_min = std::min(dt_min, info.dt);
    dt_max = std::max(dt_max, info.dt);
    impacts.add(t, it.impulses().sum() > 0.0);
    if (ep.history && t >= options.t_end * static_cast<double>(history_t.size()) / kHistoryPoints) {
      history_t.push_back(t);
      history_e.push_back(E / E0);
    }
    balance.add(it, info.dt);
    if (momentum_balance) {
      const double res = balance.residual(it.state().v) / p_scale;
      momentum = std::max(momentum, res);
      momentum_history.add(t, {res});
    }
    const int i = static_cast<int>(flight_err.size()) + 1;
    if (ep.flights > 0 && i <= ep.flights && t >= 0.5 * (bouncing->impact_time(i) + bouncing->impact_time(i + 1)))
      flight_err.push_back(E / bouncing->energy_after_impact(i) - 1.0);
  };
  const RunResult r = run(*problem, *integrator, options, observer);
  momentum_history.finish();
  double flight_max = flight_err.empty() ? kNaN : 0.0;
  for (double x : flight_err) flight_max = std::max(flight_max, std::abs(x));
  Json counters = Json::object();
  for (const auto& name : kCounters) {
    const auto it = r.work.extra.find(name);
    counters[name] = real(it == r.work.extra.end() ? kNaN : it->second);
  }
  return {{"status", r.status == RunStatus::Ok ? "ok" : "diverged"}, {"message", r.message},
          {"t_end", options.t_end}, {"steps", r.steps}, {"cpu", r.step_cpu_seconds}, {"impacts", static_cast<long>(impacts.starts().size())},
          {"offset", real((E1 - E0) / std::abs(E0))}, {"max_err", real(max_err)}, {"final_err", real(std::abs(err))},
          {"drift", real(drift.slope())}, {"momentum", real(momentum_balance ? momentum : kNaN)},
          {"dt_min", dt_min}, {"dt_max", dt_max}, {"flight_max", real(flight_max)},
          {"flights", static_cast<long>(flight_err.size())}, {"counters", counters},
          {"history_t", history_t}, {"history_e", history_e}, {"momentum_t", momentum_history.times()},
          {"momentum_res", reals(momentum_history.largest(0))}};
}

std::vector<Table> energy_tables(const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions& opt) {
  Table lt;
  lt.id = "energy_long_time";
  lt.title = "Long-time energy and momentum: fixed vs adaptive CD-Lagrange vs Moreau-Jean";
  lt.caption =
      "Energy: each integrator's own (CD-Lagrange: E_{k+1/2}); errors relative to E_1, the energy after the first "
      "step; offset (E_1 - E_0)/E_0. Drift: least-squares slope of (E - E_1)/E_1 over every step. Momentum: max "
      "|sum M v - sum M v_0 - sum of impulse resultants| / sum |m v_0| (n/a under gravity). Adaptive counters: "
      "residual evaluations, steps without a root of the energy equation (least residual taken), steps held at "
      "the CFL bound or user cap, max |residual| / energy terms. Signorini bar: nondimensional (L = E = rho = A = "
      "v0 = 1), g = 0.25, dt = h/(2c); N = 50 to t = 210 (about 21 cycles), N = 100 to t = 2100 with --full only "
      "(the references cost 10-15 s CPU per case at N = 50); its impacts count contact phases after at least L/c "
      "without impulse (cycles). n/a: the scheme declines the mass model (reason in status).";
  lt.columns = {{"problem", "", "", ""},
                {"integrator", "", "", ""},
                {"variant", "", "", "parameters of the adaptive scheme"},
                {"dt", "s", "{:.0e}", "requested (initial) step"},
                {"t_end", "s", "{}", ""},
                {"impacts", "", "", "contact phases started (bar: after at least L/c without impulse)"},
                {"steps", "", "", ""},
                {"min step", "s", "{:.2e}", ""},
                {"max step", "s", "{:.2e}", ""},
                {"E offset", "", "{:.2e}", "(E_1 - E_0) / E_0"},
                {"max E err", "", "{:.2e}", "max |E - E_1| / E_1"},
                {"final E err", "", "{:.2e}", "|E_end - E_1| / E_1"},
                {"drift", "1/s", "{:.2e}", "slope of (E - E_1)/E_1 against t"},
                {"momentum res.", "", "{:.2e}", "relative momentum balance residual"},
                {"energy iters", "", "{:.0f}", ""},
                {"no root", "", "{:.0f}", ""},
                {"capped", "", "{:.0f}", ""},
                {"max residual", "", "{:.2e}", ""},
                {"CPU", "s", "{:.2e}", "thread CPU time of the stepping, per-step observation excluded", true},
                {"status", "", "", ""}};
  Table tg;
  tg.id = "energy_targets";
  tg.title = "Energy target on the bouncing mass, e = 0.9, dt = 1e-3, first 10 impacts";
  tg.caption = "Flight energy at the exact mid-flight times against the exact E0 e^(2i): max relative error over "
               "the flights. no-work (the talk) asks the impulses to do no work, impact-law gives them the Newton "
               "impact's work (1 - e)/2 Lambda g'-.";
  tg.columns = {{"integrator", "", "", ""}, {"variant", "", "", ""}, {"flights", "", "", "flights compared"},
                {"max flight E err", "", "{:.2e}", "max |E_i / (E0 e^(2i)) - 1|"}, {"steps", "", "", ""},
                {"min step", "s", "{:.2e}", ""}, {"max step", "s", "{:.2e}", ""}, {"no root", "", "{:.0f}", ""},
                {"capped", "", "{:.0f}", ""}, {"status", "", "", ""}};
  Table history;
  history.id = "energy_bar_history";
  history.title = "Signorini bar bouncing under gravity: energy history";
  history.caption = "E(t) / E_0 with each integrator's own energy (CD-Lagrange: E_{k+1/2}), at 400 evenly spaced times.";
  history.columns = {{"integrator", "", "", ""}, {"variant", "", "", ""}, {"mass", "", "", ""},
                     {"t", "s", "{:.4f}", ""}, {"E/E0", "", "{:.6f}", ""}};
  history.csv_only = true;
  history.figures = {{"energy_bar_history", history.title, "t", "E/E0", {"integrator", "variant"}, {"mass"}, false, false, {}, true, true}};
  Table momentum;
  momentum.id = "energy_momentum_history";
  momentum.title = "Momentum balance residual history";
  momentum.caption = "Problems without external force. Largest |sum M v - sum M v_0 - sum of impulse resultants| / sum |m v_0| over each of 400 equal "
                     "intervals of the run, at the interval's last step.";
  momentum.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"variant", "", "", ""},
                      {"t", "s", "", "end of the interval"}, {"momentum res.", "", "", "largest over the interval"}};
  momentum.csv_only = true;
  momentum.figures = {{"energy_momentum_history", momentum.title, "t", "momentum res.", {"integrator", "variant"},
                       {"problem"}, false, true}};
  lt.metadata = {{"study", "energy"}, {"full", opt.full ? "yes" : "no"}};
  tg.metadata = history.metadata = momentum.metadata = lt.metadata;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const EnergyProblem& ep = kProblems[cases[i]["problem"].get<std::size_t>()];
    const Json& o = results[i];
    const Json& n = o["counters"];
    const std::string integrator = cases[i]["integrator"], variant = variant_text(cases[i]["variant"]);
    const Json& params = cases[i]["params"];
    const std::string label = ep.label + (params.contains("N") ? ", N = " + params["N"].get<std::string>() : "");
    const std::string status = o["status"].get<std::string>() + (o["message"].get<std::string>().empty() ? "" : ": " + o["message"].get<std::string>());
    if (o["status"] == "n/a") {
      std::vector<Cell> row(lt.columns.size());
      row[0] = label, row[1] = integrator, row[2] = variant, row[3] = cases[i]["dt"].get<double>();
      row[4] = o["t_end"].get<double>(), row.back() = status;
      lt.add_row(row);
      continue;
    }
    const std::vector<double> mt = o["momentum_t"];
    for (std::size_t j = 0; j < mt.size(); ++j)
      momentum.add_row({label, integrator, variant, mt[j], number_cell(o["momentum_res"][j])});
    const std::vector<double> ht = o["history_t"], he = o["history_e"];
    for (std::size_t j = 0; j < ht.size(); ++j)
      history.add_row({integrator, variant, params["mass"].get<std::string>(), ht[j], he[j]});
    if (ep.flights > 0) {
      tg.add_row({integrator, variant, o["flights"].get<long>(), number_cell(o["flight_max"]), o["steps"].get<long>(),
                  o["dt_min"].get<double>(), o["dt_max"].get<double>(), number_cell(n["no_root_steps"]),
                  number_cell(n["cfl_capped_steps"]), status});
      continue;
    }
    lt.add_row({label, integrator, variant, cases[i]["dt"].get<double>(), o["t_end"].get<double>(), o["impacts"].get<long>(),
                o["steps"].get<long>(), o["dt_min"].get<double>(), o["dt_max"].get<double>(), number_cell(o["offset"]),
                number_cell(o["max_err"]), number_cell(o["final_err"]), number_cell(o["drift"]), number_cell(o["momentum"]),
                number_cell(n["energy_iterations"]), number_cell(n["no_root_steps"]), number_cell(n["cfl_capped_steps"]),
                number_cell(n["max_rel_residual"]), o["cpu"].get<double>(), status});
  }
  return {lt, tg, history, momentum};
}

}  // namespace

extern const StudyEntry energy_study = {
    "energy", "long-time energy and momentum: fixed vs adaptive CD-Lagrange (all variants) vs Moreau-Jean",
    nullptr, &energy_cases, &energy_case, &energy_tables};

}  // namespace nsb
