// Study "hausdorff": convergence in the non-smooth sense. For every scheme of the suite (peers
// and reference solvers left out) on six problems, at four refinements, the velocity graph
// {(t_k, v_k)} of the run against the reference graph, both polylines in the scaled coordinates
// (t / T, v / V), T = t_end, V = the reference's largest |v| (studies/hausdorff.hpp):
//   max err     max over the steps of |v_k - v_ref(t_k)| / V: O(1) at a jump computed a step
//               late, so it does not converge across impacts
//   Hausdorff   H = max(h(run, ref), h(ref, run)), jumps as vertical segments: O(dt) when
//               every jump is at most a few steps late and the smooth parts are O(dt)
// and the least-squares order of each in dt with its 95% interval (Student t).
// Problems (v: the velocity the problem observes, or that of dof 0):
//   bouncing-mass  e 0.9, h0 1, to 0.2 s past the 3rd impact; exact (impacts as jumps)
//   signorini-bar  lumped, to t0 + 1.5 T; exact; N = 25, 50, 100, 200 with dt = 0.9 h / c
//                  (space-time refinement), v at the contact node
//   bouncing-bar   DEP bar (N as above, dt = 0.9 h/c) to t1 + one period 16 L / c; exact
//   spring-chain   3 masses, wall left, to 2 s; against modal-exact at output step 2e-5 s
//   sliding-mass   30 deg, mu 0.8, v0 2 (stops, sticks), to 1.5 stop times; exact
//   rolling-disk   h0 0.05, omega0 20, e 0.5, mu 0.3, to 1.2 rest times; exact
// Steps 4, 2, 1, 0.5 ms except the bars. The exact graphs: 20000 uniform samples plus both
// sides of every impact (impact_times) and of every other jump (bisection, studies/hausdorff.hpp);
// the modal-exact graph's jumps are steep segments one output step wide (1e-5 in t / T).
// A scheme that declines a problem (friction, a singular mass) is a row with its reason.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/bouncing_bar.hpp"
#include "problems/registry.hpp"
#include "reference/modal_exact.hpp"
#include "studies/hausdorff.hpp"
#include "studies/hausdorff_study.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr double kModalOutputStep = 2e-5;

using Overrides = std::map<std::string, std::string>;

struct Subject {
  std::string problem;
  Overrides parameters;
  bool space_time = false;  // N doubles with each level, dt = 0.9 h / c
  std::string observable;   // a problem observable, or "" for the velocity of dof 0
};

const std::vector<Subject>& subjects() {
  static const std::vector<Subject> s = {
      {"bouncing-mass", {{"e", "0.9"}, {"h0", "1"}}, false, "v"},
      {"signorini-bar", {{"mass", "lumped"}}, true, "v_contact"},
      {"bouncing-bar", {{"mass", "lumped"}}, true, "v_contact"},
      {"spring-chain", {{"n", "3"}, {"wall", "left"}}, false, ""},
      {"sliding-mass", {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "2"}}, false, "v"},
      {"rolling-disk", {{"h0", "0.05"}, {"omega0", "20"}, {"e", "0.5"}, {"mu", "0.3"}}, false, "v"},
  };
  return s;
}

Overrides level_parameters(const Subject& s, int level) {
  Overrides p = s.parameters;
  if (s.space_time) p["N"] = fmt::format("{}", 25L << level);
  return p;
}

double level_step(const Subject& s, const Problem& problem, int level) {
  return s.space_time ? 0.9 * problem.stable_step() : 4e-3 / std::pow(2.0, level);
}

double horizon(const Subject& s, const Problem& problem) {
  const ExactSolution* exact = problem.exact();
  if (s.problem == "bouncing-mass") return exact->impact_times(1e3).at(2) + 0.2;
  if (s.problem == "signorini-bar")
    return exact->event_time(ExactEvent::contact_start).value() + 1.5 * exact->value(ExactValue::contact_duration).value();
  if (s.problem == "bouncing-bar") {
    const BouncingBarExact bouncing(problem.parameters(), 1e3);
    return bouncing.impact_time() + 16.0 * bouncing.wave_time();
  }
  if (s.problem == "sliding-mass") return 1.5 * exact->event_time(ExactEvent::slip_stop).value();
  if (s.problem == "rolling-disk") return 1.2 * exact->event_time(ExactEvent::rest).value();
  return 2.0;
}

// The observed velocity of a state (after a step of length dt with these impulses).
double observed(const Problem& problem, const Subject& s, const State& state, const Vec& impulses, double dt) {
  if (s.observable.empty()) return state.v[0];
  const auto& names = problem.observable_names();
  std::vector<double> buffer(names.size());
  problem.observe(state, impulses, dt, buffer);
  return buffer[static_cast<std::size_t>(std::find(names.begin(), names.end(), s.observable) - names.begin())];
}

}  // namespace

Polyline run_graph(const Problem& problem, Integrator& integrator, double dt, double t_end,
                   const std::function<double(const State&, const Vec&, double)>& value, RunResult* result) {
  Polyline g;
  g.add(integrator.state().t, value(integrator.state(), Vec::Zero(problem.ncontacts()), 0.0));
  RunOptions options;
  options.dt = dt;
  options.t_end = t_end;
  options.record_series = false;
  const RunResult r = run(problem, integrator, options, [&](const Integrator& it, const StepInfo& info) {
    g.add(it.state().t, value(it.state(), it.impulses(), info.dt));
  });
  if (result) *result = r;
  return g;
}

Polyline exact_graph(const Problem& problem, const std::function<double(const State&)>& value, double t_end) {
  const ExactSolution& exact = *problem.exact();
  return sampled_graph([&](double t) { return value(*exact.state(t)); }, t_end, kHausdorffExactSamples, exact.impact_times(t_end),
                       kHausdorffJumpFraction);
}

double interpolate(const Polyline& g, double t) {
  const auto k = static_cast<std::size_t>(std::upper_bound(g.t.begin(), g.t.end(), t) - g.t.begin());
  if (k == 0) return g.x.front();
  if (k == g.size()) return g.x.back();
  const double w = (t - g.t[k - 1]) / (g.t[k] - g.t[k - 1]);
  return (1 - w) * g.x[k - 1] + w * g.x[k];
}

GraphErrors graph_errors(const Polyline& run, const Polyline& reference, const std::function<double(double)>& reference_at,
                         double time_scale, double value_scale) {
  GraphErrors e;
  e.time_scale = time_scale;
  e.value_scale = value_scale;
  if (!(value_scale > 0.0))
    for (double x : reference.x) e.value_scale = std::max(e.value_scale, std::abs(x));
  if (!(e.value_scale > 0.0)) e.value_scale = 1.0;
  for (std::size_t k = 0; k < run.size(); ++k) e.max_error = std::max(e.max_error, std::abs(run.x[k] - reference_at(run.t[k])));
  e.max_error /= e.value_scale;
  const Polyline a = scaled(run, e.time_scale, e.value_scale), b = scaled(reference, e.time_scale, e.value_scale);
  e.to_reference = directed_hausdorff(a, b);
  e.from_reference = directed_hausdorff(b, a);
  e.hausdorff = std::max(e.to_reference, e.from_reference);
  return e;
}

namespace {

std::vector<Json> hausdorff_cases(const StudyOptions&) {
  std::vector<Json> cases;
  for (std::size_t s = 0; s < subjects().size(); ++s)
    for (const auto& entry : integrator_registry())
      if (!entry.reference && !entry.peer)
        for (int level = 0; level < kHausdorffLevels; ++level) cases.push_back({{"subject", s}, {"integrator", entry.name}, {"level", level}});
  return cases;
}

Json hausdorff_case(const Json& c) {
  const Subject& s = subjects()[c["subject"].get<std::size_t>()];
  const int level = c["level"];
  const auto problem = make_problem(s.problem, level_parameters(s, level));
  const double dt = level_step(s, *problem, level), t_end = horizon(s, *problem);
  Json out = {{"dt", dt}, {"t_end", t_end}, {"N", s.space_time ? Json(25L << level) : Json(nullptr)}};
  auto integrator = make_integrator(c["integrator"].get<std::string>());
  if (const auto why = init_or_decline(*integrator, *problem)) {
    out.update({{"status", "n/a"}, {"message", *why}, {"steps", 0}});
    return out;
  }
  const auto value = [&](const State& st, const Vec& impulses, double h) { return observed(*problem, s, st, impulses, h); };
  RunResult r;
  const Polyline graph = run_graph(*problem, *integrator, dt, t_end, value, &r);
  out.update({{"status", status_name(r.status)}, {"message", r.message}, {"steps", r.steps}});
  if (r.status != RunStatus::Ok) return out;
  Polyline reference;
  std::function<double(double)> reference_at;
  if (s.problem == "spring-chain") {
    auto modal = make_integrator(ModalExact::kName);
    modal->init(*problem, problem->initial_state());
    reference = run_graph(*problem, *modal, kModalOutputStep, t_end, value, nullptr);
    reference_at = [&](double t) { return interpolate(reference, t); };
  } else if (s.problem == "bouncing-bar") {
    const BouncingBarExact exact(problem->parameters(), t_end);
    reference_at = [exact](double t) { return exact.velocity(0.0, t); };
    reference = sampled_graph(reference_at, t_end, kHausdorffExactSamples, {}, kHausdorffJumpFraction);
  } else {
    const auto exact_value = [&](const State& st) { return observed(*problem, s, st, Vec::Zero(problem->ncontacts()), 0.0); };
    reference = exact_graph(*problem, exact_value, t_end);
    reference_at = [&](double t) { return exact_value(*problem->exact()->state(t)); };
  }
  const GraphErrors e = graph_errors(graph, reference, reference_at, t_end);
  out.update({{"max_error", real(e.max_error)}, {"hausdorff", real(e.hausdorff)}, {"to_reference", real(e.to_reference)},
              {"from_reference", real(e.from_reference)}, {"value_scale", e.value_scale}});
  return out;
}

std::vector<Table> hausdorff_tables(const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions&) {
  Table t;
  t.id = "hausdorff";
  t.title = "Convergence in the non-smooth sense: max-norm and Hausdorff errors of the velocity";
  t.caption = "Velocity graph of each run against the reference's (exact, or modal-exact for the spring chain), in scaled "
              "coordinates (t / T, v / V), T = t_end, V = the reference's largest |v|. max err: max over the steps of "
              "|v_k - v_ref(t_k)| / V. Hausdorff: max of the directed distances run -> ref and ref -> run between the two "
              "polylines, jumps as vertical segments, computed exactly to a relative 1e-9 (certified bisection, "
              "studies/hausdorff.hpp). The bars refine space and time together (N, dt = 0.9 h/c).";
  t.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"dt", "s", "{:.2e}", "step"}, {"N", "", "", "elements (bars)"},
               {"T", "s", "{:.3g}", "time scale t_end"}, {"V", "", "{:.3g}", "value scale"},
               {"max err", "", "{:.3e}", "max-norm velocity error / V"}, {"Hausdorff", "", "{:.3e}", "H(run, ref), scaled"},
               {"run->ref", "", "{:.3e}", "directed"}, {"ref->run", "", "{:.3e}", "directed"}, {"steps", "", "", ""},
               {"status", "", "", ""}};
  t.figures = {{"hausdorff_convergence", "Hausdorff distance of the velocity graphs", "dt", "Hausdorff", {"integrator"}, {"problem"}, true, true},
               {"hausdorff_max_error", "Max-norm velocity error", "dt", "max err", {"integrator"}, {"problem"}, true, true}};
  Table o;
  o.id = "hausdorff_orders";
  o.title = "Orders in dt: max-norm against Hausdorff";
  o.caption = "Least-squares slope of log(error) against log(dt) over the refinements with its 95% confidence interval "
              "(Student t, n - 2 degrees of freedom); errors below 1e-11 are round-off and left out. n/a: the scheme "
              "declined the problem or a run failed (see the hausdorff table).";
  o.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"max-err order", "", "{:.2f}", ""},
               {"CI low", "", "{:.2f}", ""}, {"CI high", "", "{:.2f}", ""}, {"Hausdorff order", "", "{:.2f}", ""},
               {"H CI low", "", "{:.2f}", ""}, {"H CI high", "", "{:.2f}", ""}, {"points", "", "", ""}, {"note", "", "", ""}};
  std::size_t k = 0;
  while (k < cases.size()) {
    const std::size_t s = cases[k]["subject"];
    const std::string name = cases[k]["integrator"];
    std::vector<double> h, emax, eh;
    std::string note;
    for (; k < cases.size() && cases[k]["subject"] == s && cases[k]["integrator"] == name; ++k) {
      const Json& r = results[k];
      const std::string status = r["status"];
      t.add_row({subjects()[s].problem, name, r["dt"].get<double>(), r["N"].is_null() ? Cell{} : Cell{r["N"].get<long>()},
                 r["t_end"].get<double>(), number_cell(real_or_nan(r, "value_scale")), number_cell(real_or_nan(r, "max_error")),
                 number_cell(real_or_nan(r, "hausdorff")), number_cell(real_or_nan(r, "to_reference")),
                 number_cell(real_or_nan(r, "from_reference")), r["steps"].get<long>(),
                 status == "ok" ? status : status + ": " + r["message"].get<std::string>()});
      if (status != "ok" && note.empty()) note = status == "n/a" ? "declined" : status;
      h.push_back(r["dt"]);
      const auto clean = [](double x) { return x > 1e-11 ? x : std::numeric_limits<double>::quiet_NaN(); };
      emax.push_back(clean(real_or_nan(r, "max_error")));
      eh.push_back(clean(real_or_nan(r, "hausdorff")));
    }
    const OrderFit fm = fit_order(h, emax), fh = fit_order(h, eh);
    o.add_row({subjects()[s].problem, name, number_cell(fm.order), number_cell(fm.low), number_cell(fm.high),
               number_cell(fh.order), number_cell(fh.low), number_cell(fh.high), static_cast<long>(fh.points), note});
  }
  return {t, o};
}

}  // namespace

std::vector<HausdorffOrders> hausdorff_orders(const std::string& integrator) {
  std::vector<Json> cases;
  for (const auto& c : hausdorff_cases({}))
    if (c["integrator"] == integrator) cases.push_back(c);
  std::vector<Json> results;
  for (const auto& c : cases) results.push_back(hausdorff_case(c));
  const Table orders = hausdorff_tables(cases, results, {})[1];
  std::vector<HausdorffOrders> out;
  const auto value = [](const Cell& c) { return std::holds_alternative<double>(c) ? std::get<double>(c) : std::numeric_limits<double>::quiet_NaN(); };
  for (const auto& row : orders.rows)
    out.push_back({std::get<std::string>(row[0]), {value(row[2]), value(row[3]), value(row[4]), 0},
                   {value(row[5]), value(row[6]), value(row[7]), static_cast<int>(std::get<long>(row[8]))}, std::get<std::string>(row[9])});
  return out;
}

extern const StudyEntry hausdorff_study = {
    "hausdorff", "velocity graphs against the exact ones: max-norm error vs Hausdorff distance, orders per scheme",
    nullptr, &hausdorff_cases, &hausdorff_case, &hausdorff_tables};

}  // namespace nsb
