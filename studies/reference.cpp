// Study "reference": accuracy and cost of the SUNDIALS references against exact solutions.
//
// Bouncing mass (e = 0.9, h0 = 1, 4 impacts in [0, 3] s), sampled every 1e-3 s:
//   - tolerance sweep rtol = 1e-3 .. 1e-10 (atol = rtol / 100) of event-driven (BDF + KLU and
//     Adams) and penalty-bdf (k = 1e10): err u = max over the samples of |u - u_exact|,
//     impact-time error (event-driven: max over the located impacts), the reference's own
//     error estimate (max |u_tol - u_{tol/10}| against the next tighter run), CPU (median of
//     3 unobserved runs after a warm-up) and CVODE's work counts;
//   - penalty sweep k = 1e6 .. 1e10 (rtol 1e-10): error against the exact solution and
//     against the cached tight event-driven reference, the penalty's own error estimate
//     |u_k - u_{10k}| / (1 - 10^-1/2) (rate 1/2 in k, see reference/penalty.hpp), observed rate.
// The tight event-driven run is a cached reference run (reference/cache.hpp) under
// $NSBENCH_REFERENCE_CACHE (default .nsbench-cache/reference).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/bouncing_mass.hpp"
#include "reference/cache.hpp"
#include "reference/event_driven.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

const std::map<std::string, std::string> kProblemParams = {{"e", "0.9"}};
constexpr double kReferenceSample = 1e-3, kReferenceEnd = 3.0;
const std::vector<double> kTolerances = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
const std::vector<double> kStiffness = {1e6, 1e7, 1e8, 1e9, 1e10};

std::string text(double x) { return fmt::format("{}", x); }

std::vector<Json> reference_cases(const StudyOptions&) {
  std::vector<Json> cases;
  for (const char* method : {"bdf", "adams"})
    for (double tol : kTolerances)
      cases.push_back({{"sweep", "tolerance"}, {"integrator", "event-driven"}, {"label", fmt::format("event-driven {}", method)},
                       {"params", {{"method", method}, {"rtol", text(tol)}, {"atol", text(tol / 100)}}}, {"x", tol}});
  for (double tol : kTolerances)
    cases.push_back({{"sweep", "tolerance"}, {"integrator", "penalty-bdf"}, {"label", "penalty-bdf k=1e10"},
                     {"params", {{"rtol", text(tol)}, {"atol", text(tol / 100)}}}, {"x", tol}});
  for (double k : kStiffness)
    cases.push_back({{"sweep", "stiffness"}, {"integrator", "penalty-bdf"}, {"label", "penalty-bdf"},
                     {"params", {{"stiffness", text(k)}, {"rtol", "1e-10"}, {"atol", "1e-14"}}}, {"x", k}});
  return cases;
}

Json reference_case(const Json& c) {
  const auto problem = std::make_unique<BouncingMass>(Params(BouncingMass::parameters_spec(), kProblemParams));
  const auto params = c["params"].get<std::map<std::string, std::string>>();
  RunOptions options;
  options.dt = kReferenceSample;
  options.t_end = kReferenceEnd;
  options.record_series = false;
  auto integrator = make_integrator(c["integrator"], params);
  integrator->init(*problem, problem->initial_state());
  std::vector<double> u;
  double err = 0.0;
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo&) {
    u.push_back(it.state().u[0]);
    err = std::max(err, std::abs(it.state().u[0] - problem->state(it.state().t)->u[0]));
  });
  const WorkCounters& w = r.work;
  const auto extra = [&](const char* key) { return w.extra.count(key) ? w.extra.at(key) : 0.0; };
  Json out = {{"status", r.status == RunStatus::Ok ? "ok" : "diverged"}, {"message", r.message}, {"u", u},
              {"err_u", err}, {"steps", w.steps}, {"rhs", w.force_evaluations}, {"jacobians", w.tangent_evaluations},
              {"factorizations", w.factorizations}, {"roots", extra("root_evaluations")},
              {"events", extra("events") + extra("switches")}};
  if (const auto* ed = dynamic_cast<const EventDriven*>(integrator.get())) {
    double t_err = 0.0;
    const auto impacts = events_of_kind(ed->events(), {ContactEventKind::Impact, ContactEventKind::ZenoStop});
    for (std::size_t i = 0; i < impacts.size(); ++i)
      t_err = std::max(t_err, std::abs(impacts[i].t - problem->impact_time(static_cast<int>(i) + 1)));
    out["err_t"] = t_err;
  }
  if (c["sweep"] == "stiffness") {
    ReferenceRequest req{"bouncing-mass", kProblemParams, "event-driven", {{"rtol", "1e-12"}, {"atol", "1e-14"}}, kReferenceSample, kReferenceEnd, 1};
    const CachedReference ref = cached_reference(reference_cache_dir(), req);
    const std::size_t col = ref.series.column("q");
    double d = 0.0;
    for (std::size_t k = 0; k < u.size() && k + 1 < ref.series.rows(); ++k) d = std::max(d, std::abs(u[k] - ref.series.at(k + 1, col)));
    out["err_ref"] = d;
  }
  out["cpu"] = median_cpu_seconds(*problem, c["integrator"], params, options);
  return out;
}

double max_difference(const Json& a, const Json& b) {
  const auto ua = a["u"].get<std::vector<double>>(), ub = b["u"].get<std::vector<double>>();
  double d = 0.0;
  for (std::size_t k = 0; k < std::min(ua.size(), ub.size()); ++k) d = std::max(d, std::abs(ua[k] - ub[k]));
  return d;
}

std::vector<Table> reference_tables(const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions&) {
  const auto num = [](const Json& j, const char* key) {
    return j.contains(key) && j[key].is_number() ? Cell{j[key].get<double>()} : Cell{};
  };
  Table tol;
  tol.id = "reference_tolerance";
  tol.title = "SUNDIALS references on the bouncing mass (e = 0.9, [0, 3] s): tolerance sweep";
  tol.caption = "err u = max |u - u_exact| over samples every 1e-3 s; err t = max impact-time error (event-driven); "
                "est. = max |u(rtol) - u(rtol/10)|, the reference's own error estimate; atol = rtol/100; CPU: " + median_cpu_text() + "; steps, RHS, Jacobians, factorisations (KLU), root evaluations: CVODE's "
                "counts; events: impacts and restarts (event-driven) or penalty on/off switches.";
  tol.columns = {{"integrator", "", "", ""},      {"rtol", "", "{:.0e}", ""},          {"err u", "m", "{:.2e}", ""},
                 {"err t", "s", "{:.2e}", ""},    {"est.", "m", "{:.2e}", ""},          {"CPU", "s", "{:.2e}", "", true},
                 {"steps", "", "{:.0f}", ""},     {"RHS", "", "{:.0f}", ""},            {"Jacobians", "", "{:.0f}", ""},
                 {"factorizations", "", "{:.0f}", ""}, {"roots", "", "{:.0f}", ""},     {"events", "", "{:.0f}", ""},
                 {"status", "", "", ""}};
  tol.figures = {{"reference_work_precision", "References: error against CPU time", "CPU", "err u", {"integrator"}, {}, true, true}};
  Table pen;
  pen.id = "reference_penalty";
  pen.title = "Penalty reference on the bouncing mass: convergence as the penalty stiffens";
  pen.caption = "err exact = max |u - u_exact|; err ref = max |u - u_ED| against the cached event-driven run at rtol "
                "1e-12; est. = |u_k - u_10k| / (1 - 10^-1/2), the penalty's own error estimate (rate 1/2 in k); rate = "
                "log10(err_k / err_10k) against the exact solution; rtol 1e-10.";
  pen.columns = {{"k", "N/m", "{:.0e}", ""},        {"err exact", "m", "{:.2e}", ""}, {"err ref", "m", "{:.2e}", ""},
                 {"est.", "m", "{:.2e}", ""},        {"rate", "", "{:.2f}", ""},       {"CPU", "s", "{:.2e}", "", true},
                 {"steps", "", "{:.0f}", ""},        {"switches", "", "{:.0f}", ""},   {"status", "", "", ""}};
  tol.metadata = pen.metadata = {{"study", "reference"}, {"problem", "bouncing-mass e=0.9"}, {"t_end", "3"}};

  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& c = cases[k];
    const Json& r = results[k];
    const bool next = k + 1 < cases.size() && cases[k + 1]["label"] == c["label"] && results[k + 1]["status"] == "ok";
    const std::string status = r["status"] == "ok" ? "ok" : "diverged: " + r["message"].get<std::string>();
    const Cell est = next && r["status"] == "ok" ? Cell{max_difference(r, results[k + 1])} : Cell{};
    if (c["sweep"] == "tolerance") {
      tol.add_row({c["label"].get<std::string>(), c["x"].get<double>(), num(r, "err_u"), num(r, "err_t"), est, num(r, "cpu"),
                   num(r, "steps"), num(r, "rhs"), num(r, "jacobians"), num(r, "factorizations"), num(r, "roots"),
                   num(r, "events"), status});
    } else {
      const Cell scaled = std::holds_alternative<double>(est) ? Cell{std::get<double>(est) / (1.0 - std::pow(10.0, -0.5))} : Cell{};
      const Cell rate = next ? Cell{observed_order(1.0 / c["x"].get<double>(), r["err_u"].get<double>(),
                                                   1.0 / cases[k + 1]["x"].get<double>(), results[k + 1]["err_u"].get<double>())}
                             : Cell{};
      pen.add_row({c["x"].get<double>(), num(r, "err_u"), num(r, "err_ref"), scaled, rate, num(r, "cpu"), num(r, "steps"),
                   num(r, "events"), status});
    }
  }
  return {tol, pen};
}

}  // namespace

extern const StudyEntry reference_study = {
    "reference", "SUNDIALS references (event-driven, penalty): tolerance and penalty sweeps against exact solutions",
    nullptr, &reference_cases, &reference_case, &reference_tables};

}  // namespace nsb
