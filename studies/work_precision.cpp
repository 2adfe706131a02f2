// Study "precision": work-precision and convergence of every integrator on every problem
// listed below, one line of data per problem, against an exact solution: the problem's own
// (exact_state) or, where it has none or its own holds a mesh error, the exact solution of
// the semi-discrete system (a reference integrator stepped in lockstep with the scheme,
// modal-exact: reference/modal_exact.hpp).
//
// Error norm: e = max over the steps of the window of ||u - u_ref||_inf, divided by
// max |u_ref| over the run (relative displacement error). Two windows, reported
// separately: a smooth window (no impact inside, the scheme's own order) and the whole
// run (with impacts, where time-stepping schemes drop to order 1).
// CPU: median_cpu_seconds (three timed runs after a warm-up, none of them observed).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/registry.hpp"
#include "studies/ranking.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

struct PrecisionProblem {
  std::string label;
  std::string problem;
  std::map<std::string, std::string> params;
  double t_end;
  double smooth_end;            // the smooth window is [0, smooth_end]
  std::vector<double> steps;    // default sweep
  std::vector<double> full_steps;
  long budget;  // F_int evaluations per run (RunOptions::max_force_evaluations)
  // The reference integrator stepped in lockstep ("": the problem's exact_state), what err
  // is measured against as the captions state it, and that source's own error in the same
  // norm (0: exact).
  std::string reference;
  std::string error_source;
  double error_floor;
  std::vector<double> targets;  // relative errors of the headline ranking (whole run)
};

// Bouncing mass (h0 = 1, g = 9.81): first impact at 0.4515 s.
// Signorini bar (nondimensional, N = 100, lumped, stable step h/c = 0.01): g0 = 0.4937 so that
// the bar flies rigidly until t0 = 0.4937, then stays in contact for about T = 2; run to 3.5.
// t0 is on no step grid of the sweep (with g0 = 0.5 every sweep met the wall at a zero gap,
// and round-off decided whether the contact began a step early). The error with impacts is
// O(dt) times a factor set by where the impact falls inside its step, so the whole-run
// curves are not monotone; the least-squares order reads through that.
// The error is against the same semi-discrete bar solved exactly (modal-exact, round-off
// about 1e-12 at N = 100): the time-discretisation error alone (the continuum solution would
// add the 1.8e-2 mesh error, a floor; the bar study refines h and dt together). In the
// flight window every scheme is exact (rigid motion, no force): round-off, no order. The
// adaptive scheme's step collapses on the bar's contact (12e6 steps at dt = 2.5e-4): the
// budget stops it at 3e5 F_int evaluations ("over budget", no error; dt = 8e-3 takes 1.9e5).
// Spring chain (10 masses 1, 2, 1, ... joined by springs k = 100, wall on the left at 0.1,
// e = 1, drift v0 = 1 plus vibration a = 0.5; stable step about 0.1): first impact at
// t = 0.133, then five more by t = 1. The smooth window [0, 0.12] is the one place in this
// study where the schemes' smooth order shows (CD-Lagrange and Moreau-Jean theta = 1/2: 2).
// Against modal-exact. Budget 1e6 F_int evaluations: the adaptive scheme's step collapses at
// dt <= 1e-4 (7.7e6 steps at 1e-4); the fixed-step schemes need at most 1e5.
// Each step of an observed run also steps modal-exact (O(N^2)): the budgets are what keep a
// collapsed adaptive run from costing more than the rest of the study.
// Ranking targets: 1e-2, 1e-4, 1e-6 and 1e-3 on the bouncing mass (the time-stepping schemes
// end near 3e-4).
const std::vector<PrecisionProblem> kProblems = {
    {"bouncing mass, e = 0.9", "bouncing-mass", {{"e", "0.9"}}, 3.0, 0.4,
     {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5}, {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6, 1e-6}, 10'000'000,
     "", "the exact solution", 0.0, {1e-2, 1e-3, 1e-4, 1e-6}},
    {"Signorini bar, N = 100, lumped", "signorini-bar", {{"N", "100"}, {"mass", "lumped"}, {"g0", "0.4937"}}, 3.5, 0.45,
     {8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4}, {8e-3, 4e-3, 2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4, 6.25e-5}, 300'000,
     "modal-exact", "the same semi-discrete bar solved exactly (modal-exact): the time error alone", 1e-12,
     {1e-2, 1e-3, 1e-4, 1e-6}},
    {"spring chain, 10 masses, wall, e = 1", "spring-chain", {{"n", "10"}, {"wall", "left"}}, 1.0, 0.12,
     {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5}, {1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5, 3e-6}, 1'000'000,
     "modal-exact", "the chain solved exactly (modal-exact)", 1e-13, {1e-2, 1e-3, 1e-4, 1e-6}},
};

std::vector<Json> precision_cases(const StudyOptions& opt) {
  std::vector<Json> cases;
  for (std::size_t p = 0; p < kProblems.size(); ++p)
    for (const auto& entry : integrator_registry())
      for (double dt : opt.full ? kProblems[p].full_steps : kProblems[p].steps)
        cases.push_back({{"problem", p}, {"integrator", entry.name}, {"dt", dt}});
  return cases;
}

Json precision_case(const Json& c) {
  const PrecisionProblem& pp = kProblems[c["problem"].get<std::size_t>()];
  auto problem = make_problem(pp.problem, pp.params);
  RunOptions options;
  options.dt = c["dt"];
  options.t_end = pp.t_end;
  options.record_series = false;
  options.max_force_evaluations = pp.budget;

  if (c["integrator"] == pp.reference)  // against itself its error is 0 by construction
    return {{"status", "n/a"}, {"message", "the reference of this problem"}, {"steps", 0}, {"force_evaluations", 0},
            {"factorizations", 0}, {"lcp_iterations", 0}};
  // Observed run: errors.
  auto integrator = make_integrator(c["integrator"]);
  if (const auto declined = init_or_decline(*integrator, *problem))
    return {{"status", "n/a"}, {"message", *declined}, {"steps", 0}, {"force_evaluations", 0},
            {"factorizations", 0}, {"lcp_iterations", 0}};
  std::unique_ptr<Integrator> reference;
  if (!pp.reference.empty()) {
    reference = make_integrator(pp.reference);
    reference->init(*problem, problem->initial_state());
  }
  double err_all = 0.0, err_smooth = 0.0, scale = 0.0;
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const State& s = it.state();
    if (reference) reference->step(info.dt);
    const Vec u_ref = reference ? reference->state().u : problem->exact_state(s.t)->u;
    const double e = (s.u - u_ref).lpNorm<Eigen::Infinity>();
    scale = std::max(scale, u_ref.lpNorm<Eigen::Infinity>());
    err_all = std::max(err_all, e);
    if (s.t <= pp.smooth_end) err_smooth = std::max(err_smooth, e);
  });
  Json out = {{"status", status_name(r.status)}, {"message", r.message},
              {"steps", r.steps}, {"force_evaluations", r.work.force_evaluations},
              {"factorizations", r.work.factorizations}, {"lcp_iterations", r.work.lcp_iterations}};
  if (r.status != RunStatus::Ok) return out;
  out["err_all"] = err_all / scale;
  out["err_smooth"] = err_smooth / scale;
  out["cpu"] = median_cpu_seconds(*problem, c["integrator"], {}, options);
  return out;
}

std::vector<Table> precision_tables(const std::vector<Json>& cases, const std::vector<Json>& results,
                                    const StudyOptions&) {
  Table t;
  t.id = "work_precision";
  t.title = "Work-precision and convergence on problems with an exact solution";
  std::vector<std::string> sources;
  for (const auto& pp : kProblems) sources.push_back(pp.label + ": " + pp.error_source);
  t.caption = fmt::format(
      "err = max over the window of ||u - u_ref||_inf / max |u_ref|, u_ref: {}; smooth window: before the first impact "
      "(bar: the flight before contact, exact for every scheme); all: the whole run, impacts included. CPU: {}. Errors below 1e-11 "
      "are round-off and carry no order (n/a). Over budget: the run's F_int evaluation budget ran out (no error).",
      fmt::join(sources, "; "), median_cpu_text());
  t.columns = {{"problem", "", "", ""},
               {"integrator", "", "", ""},
               {"dt", "s", "{:.1e}", ""},
               {"err smooth", "", "{:.2e}", "relative displacement error, smooth window"},
               {"order smooth", "", "{:.2f}", "against the previous dt"},
               {"err all", "", "{:.2e}", "relative displacement error, whole run"},
               {"order all", "", "{:.2f}", "against the previous dt"},
               {"CPU", "s", "{:.2e}", "median thread CPU time of the stepping (unobserved runs)", true},
               {"steps", "", "", ""},
               {"F_int evals", "", "", "internal force evaluations"},
               {"factorizations", "", "", ""},
               {"LCP its", "", "", "LCP iterations"},
               {"status", "", "", ""}};
  t.figures = {
      {"work_precision", "Work-precision: error (whole run) against CPU time", "CPU", "err all", {"integrator"}, {"problem"}, true, true},
      {"work_precision_evals", "Error (whole run) against internal force evaluations", "F_int evals", "err all", {"integrator"}, {"problem"}, true, true},
      {"convergence_smooth", "Convergence in the smooth window", "dt", "err smooth", {"integrator"}, {"problem"}, true, true, {1, 2}},
      {"convergence_impacts", "Convergence over the whole run (with impacts)", "dt", "err all", {"integrator"}, {"problem"}, true, true, {1, 2}},
  };
  Table orders;
  orders.id = "work_precision_orders";
  orders.title = "Observed convergence orders: smooth window and with impacts";
  orders.caption = "Least-squares slope of log(err) against log(dt) over the sweep, windows as in the main table; "
                   "n/a where every error is at round-off (the scheme is exact there).";
  orders.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""},
                    {"order smooth", "", "{:.2f}", ""}, {"order all", "", "{:.2f}", ""}};
  t.metadata = {{"study", "precision"}};
  orders.metadata = t.metadata;

  const auto num = [](const Json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? j[key].get<double>() : std::numeric_limits<double>::quiet_NaN();
  };
  std::vector<RankingProblem> ranking(kProblems.size());
  for (std::size_t p = 0; p < kProblems.size(); ++p)
    ranking[p] = {kProblems[p].label, kProblems[p].error_source, kProblems[p].error_floor, kProblems[p].targets, {}};
  std::size_t k = 0;
  while (k < cases.size()) {
    const std::size_t begin = k;  // one (problem, integrator) group
    std::vector<double> dts, smooth, all, cpu;
    for (; k < cases.size() && cases[k]["problem"] == cases[begin]["problem"] &&
           cases[k]["integrator"] == cases[begin]["integrator"]; ++k) {
      const Json& r = results[k];
      const std::size_t i = dts.size();
      dts.push_back(cases[k]["dt"]);
      smooth.push_back(num(r, "err_smooth"));
      all.push_back(num(r, "err_all"));
      cpu.push_back(num(r, "cpu"));
      const double o_s = i ? observed_order(dts[i - 1], above_round_off(smooth[i - 1]), dts[i], above_round_off(smooth[i])) : NAN;
      const double o_a = i ? observed_order(dts[i - 1], above_round_off(all[i - 1]), dts[i], above_round_off(all[i])) : NAN;
      const std::string status = r["status"];
      t.add_row({kProblems[cases[k]["problem"].get<std::size_t>()].label, cases[k]["integrator"].get<std::string>(),
                 dts[i], number_cell(smooth[i]), number_cell(o_s), number_cell(all[i]), number_cell(o_a), number_cell(cpu[i]),
                 r["steps"].get<long>(), r["force_evaluations"].get<long>(), r["factorizations"].get<long>(),
                 r["lcp_iterations"].get<long>(), status == "ok" ? status : status + ": " + r["message"].get<std::string>()});
    }
    const std::string integrator = cases[begin]["integrator"];
    const IntegratorEntry& entry = find_integrator(integrator);
    WorkCurve curve{integrator, entry.reference, {}, entry.peer};
    for (std::size_t i = 0; i < dts.size(); ++i)
      if (results[begin + i]["status"] != "n/a") curve.points.push_back({fmt::format("dt = {:.1e}", dts[i]), cpu[i], all[i]});
    ranking[cases[begin]["problem"].get<std::size_t>()].curves.push_back(curve);
    const auto fit = [&](std::vector<double> e) {
      for (double& x : e) x = above_round_off(x);
      return number_cell(fitted_order(dts, e));
    };
    orders.add_row({kProblems[cases[begin]["problem"].get<std::size_t>()].label, integrator, fit(smooth), fit(all)});
  }
  Table rank = ranking_table("work_precision_ranking", "Cheapest integrator at each target error, against exact solutions",
                             {"err", "", "", "err all of work_precision: relative displacement error, whole run"},
                             median_cpu_text(), ranking);
  rank.metadata = t.metadata;
  return {t, orders, rank};
}

}  // namespace

extern const StudyEntry work_precision_study = {
    "precision", "work-precision and convergence orders (smooth window and with impacts) against exact solutions",
    nullptr, &precision_cases, &precision_case, &precision_tables};

}  // namespace nsb
