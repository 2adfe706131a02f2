// Study "bar": every integrator on the Signorini bar (problems/signorini_bar.hpp) against the
// exact d'Alembert solution, nondimensional (L = E = rho = A = v0 = 1, g0 = 0: c = 1, contact
// on [0, T], T = 2, force 1, E0 = 1/2), run to 1.5 T.
// Grid: N in {50, 100, 200, 400, 800} (--full: also 1600, 3200, 6400), dt = alpha * stable step with
// alpha in {0.25, 0.5, 0.9, 1}, mass lumped | consistent | singular, every registered
// integrator (references, whose accuracy is their tolerance, at alpha = 1 only: there alpha
// only sets the output step). A scheme that declines a mass model (InputError at init, e.g. CD-Lagrange with
// the consistent mass) gives a row "n/a" with its reason; a diverging run gives "diverged".
// Per case:
//   u max / u L2   contact-node displacement error, max over the steps and L2 in time,
//                  sqrt(sum dt (u_0 - u_0,exact)^2), at the step times
//   u time err     the time-discretisation error alone: max |u_0 - u_0,semi| against the
//                  exact solution of the same semi-discrete bar (same N and mass model,
//                  reference/modal_exact.hpp), sampled at the step times, at most once per
//                  nominal step dt (the adaptive scheme's small steps are not all sampled);
//                  n/a above modal-exact's max_dofs
//   duration err   |(t_last - t_first + dt) - T|, t_first/t_last: first/last step with an
//                  impulse (each such step carries one step of contact force)
//   rebound err    |P_end / M - v0| / v0 (P = 1^T M v, constant after the release)
//   E max / E end  relative energy error, max over the steps and at the end (the scheme's
//                  own energy, Integrator::energy)
//   force osc.     RMS of (Lambda_k / dt - A rho c v0) / (A rho c v0) over the steps k whose
//                  interval [t_k - dt, t_k + dt] lies inside the exact contact (0, T): the
//                  dispersive overshoot of the discrete fronts and any chatter
//   chatter        RMS over the same steps of the period-2 component of the force,
//                  (F_{k+1} - 2 F_k + F_{k-1}) / (4 A rho c v0): an alternation of amplitude
//                  a gives a, a smooth overshoot O(dt^2)
//   lost steps     steps without impulse inside the exact contact (contact lost and regained)
//   CPU            thread CPU time of the stepping (observer and sampling excluded)
// Orders under joint refinement (dt proportional to h = L/N): pairwise against the previous
// N and least-squares over all N, per (integrator, mass, alpha). Time orders at a fixed mesh:
// least-squares slope of log(u time err) against log(dt) over the alphas, per (integrator,
// mass, N).
// Contact-force history (figure bar_contact_force): the impulses summed over each nominal
// step (t_j - dt, t_j], t_j = j dt, over dt A rho c v0, in the N = 100, alpha = 0.9 runs of
// the grid, lumped and singular mass, against the exact 0 -> 1 -> 0. For fixed-step schemes
// a bin is a step; the adaptive scheme's many small steps are summed into the bins.
// Space-time stress (table bar_space_time, figure of the same name): the element stresses
// (Problem::cell_stress) after every step of the N = 50, alpha = 0.9 runs of the grid of the
// kSpaceTimeSchemes, lumped and singular mass, and the exact d'Alembert stress at the element
// centres at kSpaceTimeSamples times: where the lumped model's contact node chatters, its
// spurious stress waves run into the bar (the picture of Doyen, Ern and Piperno, "Time-
// integration schemes for the finite element dynamic Signorini problem", SIAM J. Sci. Comput.
// 33 (2011), figures of the stress in the (x, t) plane).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <tuple>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/signorini_bar.hpp"
#include "reference/modal_exact.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

const std::vector<double> kAlphas = {0.25, 0.5, 0.9, 1.0};
const std::vector<std::string> kBarMasses = {"lumped", "consistent", "singular"};
constexpr double kHorizon = 1.5;  // t_end in contact durations
// The runs whose contact-force history is kept.
bool keeps_history(const Json& c) {
  return c["N"].get<long>() == 100 && c["alpha"].get<double>() == 0.9 && c["mass"] != "consistent";
}

// The runs whose stress field over (x, t) is kept: one mesh and step, the schemes of the
// DEP paper's comparison and ours, the two mass models that CD-Lagrange takes.
const std::vector<std::string> kSpaceTimeSchemes = {"cd-lagrange", "moreau-jean", "schatzman-paoli", "newmark-lm",
                                                    "cd-penalty"};
constexpr long kSpaceTimeN = 50;
constexpr double kSpaceTimeAlpha = 0.9;
constexpr int kSpaceTimeSamples = 300;  // times of the exact field over [0, t_end]
bool keeps_space_time(const Json& c) {
  return c["N"].get<long>() == kSpaceTimeN && c["alpha"].get<double>() == kSpaceTimeAlpha && c["mass"] != "consistent" &&
         std::find(kSpaceTimeSchemes.begin(), kSpaceTimeSchemes.end(), c["integrator"]) != kSpaceTimeSchemes.end();
}

std::vector<long> study_meshes(const StudyOptions& opt) {
  // The grid; the references and the adaptive scheme cost seconds per case at
  // N = 400 (event-driven: ~60 CVODE steps per output), so finer meshes are --full only.
  std::vector<long> meshes = {50, 100, 200, 400, 800};
  if (opt.full) meshes.insert(meshes.end(), {1600, 3200, 6400});
  return meshes;
}


// Error columns, in table order (JSON keys, headers, descriptions).
struct ErrorColumn {
  const char* key;
  const char* header;
  const char* description;
};
const std::vector<ErrorColumn> kErrors = {
    {"u_max", "u max err", "max over steps of |u_0 - u_0,exact|"},
    {"u_l2", "u L2 err", "sqrt(sum dt (u_0 - u_0,exact)^2)"},
    {"u_time", "u time err", "max over steps of |u_0 - u_0,semi-discrete| (same mesh, modal-exact)"},
    {"duration", "duration err", "|(t_last - t_first + dt) - 2L/c|"},
    {"rebound", "rebound err", "|P_end / M - v0| / v0"},
    {"e_max", "E max err", "max |E - E0| / E0"},
    {"e_end", "E end err", "|E_end - E0| / E0"},
    {"force_osc", "force osc.", "RMS (Lambda/dt - A rho c v0) / (A rho c v0) inside the contact"},
    {"chatter", "chatter", "RMS (F_{k+1} - 2 F_k + F_{k-1}) / (4 A rho c v0) inside the contact"},
};

std::vector<Json> bar_cases(const StudyOptions& opt) {
  std::vector<Json> cases;
  for (const auto& entry : integrator_registry())
    for (const auto& mass : kBarMasses)
      for (double alpha : kAlphas)
        // A reference's accuracy is set by its tolerance, alpha only sets its output step:
        // one alpha (the largest) says all, and the others would cost as much again each.
        if (!entry.reference || alpha == kAlphas.back())
          for (long N : study_meshes(opt))
          cases.push_back({{"integrator", entry.name}, {"mass", mass}, {"alpha", alpha}, {"N", N}});
  return cases;
}

Json bar_case(const Json& c) {
  const SignoriniBar p(Params(SignoriniBar::parameters_spec(),
                              {{"mass", c["mass"].get<std::string>()}, {"N", fmt::format("{}", c["N"].get<long>())}}));
  const double dt = c["alpha"].get<double>() * p.stable_step();
  auto integrator = make_integrator(c["integrator"]);
  if (const auto declined = init_or_decline(*integrator, p)) return {{"dt", dt}, {"status", "n/a"}, {"message", *declined}};
  Json out = {{"dt", dt}, {"status", "ok"}, {"message", ""}};
  // The same semi-discrete bar solved exactly: the reference of the time error alone (none
  // against itself, whose error is 0 by construction: no row in bar_time_orders).
  std::optional<ModalExact> semi;
  if (c["integrator"] != ModalExact::kName) {
    semi.emplace(Params(ModalExact::parameters_spec()));
    try {
      semi->init(p, p.initial_state());
    } catch (const InputError& e) {
      semi.reset();
      out["message"] = fmt::format("u time err n/a: {}", e.what());
    }
  }
  double u_time = 0.0, next_sample = 0.0;
  const double T = p.contact_duration(), t0 = p.contact_start(), F = p.contact_force_level();
  double u_max = 0.0, u_sq = 0.0, first = NAN, last = NAN;
  std::vector<double> force;     // relative contact force of the steps inside the contact
  std::vector<double> history;  // impulse per nominal step
  const bool keep_history = keeps_history(c);
  // The element stresses after every step, step by step (the first row: the initial state).
  const bool keep_field = keeps_space_time(c);
  std::vector<double> field_t, field_stress;
  Eigen::MatrixXd stress;
  const auto keep_stress = [&](const State& s) {
    p.cell_stress(s.u, stress);
    field_t.push_back(s.t);
    field_stress.insert(field_stress.end(), stress.col(0).begin(), stress.col(0).end());
  };
  if (keep_field) {
    const FieldMesh mesh = p.field_mesh().value();
    stress.resize(mesh.ncells(), static_cast<Index>(mesh.stress_components.size()));
    keep_stress(integrator->state());
  }
  RunOptions options;
  options.dt = dt;
  options.t_end = t0 + kHorizon * T;
  options.record_series = false;
  force.reserve(static_cast<std::size_t>(T / dt) + 1);
  const RunResult r = run(p, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const double t = it.state().t, lambda = it.impulses()[0];
    const double du = it.state().u[0] - p.exact_displacement(0.0, t);
    u_max = std::max(u_max, std::abs(du));
    u_sq += info.dt * du * du;
    if (semi && t >= next_sample) {
      semi->advance_to(t);
      u_time = std::max(u_time, std::abs(it.state().u[0] - semi->displacement(0)));
      next_sample = t + (1.0 - 1e-9) * dt;
    }
    if (lambda > 0.0) {
      if (std::isnan(first)) first = t;
      last = t;
    }
    if (t - info.dt > t0 && t + info.dt < t0 + T) force.push_back(lambda / info.dt / F);
    if (keep_field) keep_stress(it.state());
    if (keep_history) {
      const auto j = static_cast<std::size_t>(std::ceil(t / dt - 1e-9));
      if (history.size() <= j) history.resize(j + 1, 0.0);
      history[j] += lambda;
    }
  });
  if (keep_history) {
    std::vector<double> history_t, history_force;
    for (std::size_t j = 1; j < history.size(); ++j) {
      history_t.push_back(static_cast<double>(j) * dt);
      history_force.push_back(history[j] / dt / F);
    }
    out["history_t"] = history_t;
    out["history_force"] = history_force;
  }
  if (keep_field) {
    out["field_t"] = field_t;
    out["field_stress"] = reals(field_stress);
  }
  double osc_sq = 0.0, chatter_sq = 0.0;
  long lost = 0;
  for (std::size_t k = 0; k < force.size(); ++k) {
    osc_sq += (force[k] - 1.0) * (force[k] - 1.0);
    lost += force[k] == 0.0;
    if (k > 0 && k + 1 < force.size()) {
      const double d2 = 0.25 * (force[k + 1] - 2.0 * force[k] + force[k - 1]);
      chatter_sq += d2 * d2;
    }
  }
  out["steps"] = r.steps;
  out["cpu"] = r.step_cpu_seconds;
  if (r.status != RunStatus::Ok) {
    out["status"] = "diverged";
    out["message"] = r.message;
    return out;
  }
  const double v0 = p.rebound_velocity();
  out["u_max"] = u_max;
  out["u_l2"] = std::sqrt(u_sq);
  out["u_time"] = real(semi ? u_time : NAN);
  out["duration"] = real(std::abs(last - first + dt - T));
  out["rebound"] = std::abs(p.momentum(integrator->state().v) / p.total_mass() - v0) / v0;
  out["e_max"] = real(r.max_energy_error);
  out["e_end"] = real(relative_error(r.final_energy, r.initial_energy));
  out["force_osc"] = real(force.empty() ? NAN : std::sqrt(osc_sq / static_cast<double>(force.size())));
  out["chatter"] = real(force.size() < 3 ? NAN : std::sqrt(chatter_sq / static_cast<double>(force.size() - 2)));
  out["lost"] = lost;
  return out;
}

std::vector<Table> bar_tables(const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions& opt) {
  const std::vector<long> meshes = study_meshes(opt);
  const std::string setup =
      "Nondimensional Signorini bar: L = E = rho = A = v0 = 1, g0 = 0 (contact on [0, 2], force 1, E0 = 1/2), "
      "run to t = 3; dt = alpha * stable step (h/c lumped and singular, h/(sqrt(3) c) consistent).";
  const auto metadata = std::vector<std::pair<std::string, std::string>>{
      {"study", "bar"}, {"N", fmt::format("{}", fmt::join(meshes, " "))},
      {"alpha", fmt::format("{}", fmt::join(kAlphas, " "))}, {"mass", fmt::format("{}", fmt::join(kBarMasses, " "))}};

  Table table;
  table.id = "bar";
  table.title = "Signorini bar: every integrator and mass model against the exact solution";
  table.caption = setup + " Errors: u = contact-node displacement; duration of contact; rebound velocity from the "
                          "momentum; scheme energy; contact-force oscillation. Order: against the previous N "
                          "(dt proportional to h). n/a: the scheme declines the mass model.";
  table.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"alpha", "", "{}", "dt / stable step"},
                   {"N", "", "", "elements"}, {"dt", "", "{:.2e}", ""}};
  for (const auto& e : kErrors) {
    table.columns.push_back({e.header, "", "{:.2e}", e.description});
    if (std::string(e.key) == "u_max" || std::string(e.key) == "duration")
      table.columns.push_back({fmt::format("order {}", e.key), "", "{:.2f}", "observed order against the previous N"});
  }
  table.columns.push_back({"lost steps", "", "", "steps without impulse inside the exact contact"});
  table.columns.push_back({"CPU", "s", "{:.2e}", "thread CPU time of the stepping (observer and sampling excluded)", true});
  table.columns.push_back({"note", "", "", "why a case is n/a or diverged"});
  table.metadata = metadata;
  table.figures = {
      {"bar_convergence", "Signorini bar: contact-node displacement error against N", "N", "u max err", {"integrator", "mass"}, {"alpha"}, true, true, {-1, -2}},
      {"bar_energy", "Signorini bar: max energy error against N", "N", "E max err", {"integrator", "mass"}, {"alpha"}, true, true},
      {"bar_force_oscillation", "Signorini bar: contact-force oscillation against N", "N", "force osc.", {"integrator", "mass"}, {"alpha"}, true, true},
  };

  Table orders;
  orders.id = "bar_orders";
  orders.title = "Signorini bar: least-squares orders under joint refinement";
  orders.caption = setup + " Slope of log(error) against log(h) over N = " + fmt::format("{}", fmt::join(meshes, ", ")) +
                   " with dt = alpha * stable step (errors as in table bar).";
  orders.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"alpha", "", "{}", ""}};
  for (const auto& e : kErrors) orders.columns.push_back({fmt::format("order {}", e.header), "", "{:.2f}", e.description});
  orders.metadata = metadata;

  Table headline;
  headline.id = "bar_n100";
  headline.title = "Signorini bar, N = 100, alpha = 0.9: energy and contact-force oscillation";
  headline.caption = setup + " The talk's claims: with the singular mass, CD-Lagrange conserves energy and has no "
                             "spurious contact-force oscillation.";
  headline.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"E max err", "", "{:.2e}", ""},
                      {"E end err", "", "{:.2e}", ""}, {"force osc.", "", "{:.2e}", ""}, {"chatter", "", "{:.2e}", ""},
                      {"duration err", "", "{:.2e}", ""}, {"rebound err", "", "{:.2e}", ""}, {"note", "", "", ""}};
  headline.metadata = metadata;

  Table time_orders;
  time_orders.id = "bar_time_orders";
  time_orders.title = "Signorini bar: time-discretisation error and its order at a fixed mesh";
  time_orders.caption = setup + " u time err: max over the steps of |u_0 - u_0,semi| against the same semi-discrete bar "
                                "solved exactly (modal-exact: same N and mass model), so the mesh error is out. Order: "
                                "least-squares slope of log(u time err) against log(dt) over alpha = " +
                        fmt::format("{}", fmt::join(kAlphas, ", ")) + " at each N (n/a with fewer than two alphas: references).";
  time_orders.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"N", "", "", "elements"}};
  for (double alpha : kAlphas)
    time_orders.columns.push_back({fmt::format("u time err, alpha = {}", alpha), "", "{:.2e}", ""});
  time_orders.columns.push_back({"time order", "", "{:.2f}", "slope of log(u time err) against log(dt)"});
  time_orders.metadata = metadata;
  time_orders.figures = {{"bar_time_error", "Signorini bar: time error at a fixed mesh against N (alpha = 0.5)", "N",
                          "u time err, alpha = 0.5", {"integrator"}, {"mass"}, true, true, {-1, -2}}};
  // (integrator, mass, N) -> u time err per alpha, in case order.
  std::vector<std::tuple<std::string, std::string, long>> time_keys;
  std::map<std::tuple<std::string, std::string, long>, std::map<double, std::pair<double, double>>> time_errors;

  Table history;
  history.id = "bar_contact_force_history";
  history.title = "Signorini bar, N = 100, alpha = 0.9: contact force history";
  history.caption = setup + " Contact force: the impulses of each nominal step (t - dt, t] over dt, over A rho c v0 "
                            "(the adaptive scheme's small steps summed); exact: 1 on (0, 2), else 0.";
  history.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"t", "", "{:.4f}", ""},
                     {"F / (A rho c v0)", "", "{:.4f}", ""}};
  history.csv_only = true;
  history.figures = {{"bar_contact_force", history.title, "t", "F / (A rho c v0)", {"mass"}, {"integrator"}, false, false}};
  history.metadata = metadata;

  // The exact field first: its panel leads the figure.
  const SignoriniBar field_bar(Params(SignoriniBar::parameters_spec(), {{"N", fmt::format("{}", kSpaceTimeN)}}));
  const FieldMesh field_mesh = field_bar.field_mesh().value();
  std::vector<double> centres;
  for (Index e = 0; e < field_mesh.ncells(); ++e)
    centres.push_back(0.5 * (field_mesh.points(field_mesh.cells(e, 0), 0) + field_mesh.points(field_mesh.cells(e, 1), 0)));
  Table space_time;
  space_time.id = "bar_space_time";
  space_time.title = fmt::format("Signorini bar, N = {}, alpha = {}: stress over (x, t), lumped against singular mass",
                                 kSpaceTimeN, kSpaceTimeAlpha);
  space_time.caption = fmt::format(
      "{} Element stress sigma_e = E (u_e+1 - u_e) / h (over rho c v0 = 1; negative: compression) after every step of "
      "dt = {} * h / c = {:g} (N = {} elements), lumped and singular mass; exact: the d'Alembert stress at the element "
      "centres, -rho c v0 where t - x/c > 0 and t < (2L - x)/c, else 0, at {} times. The wall is at x = 0.",
      setup, kSpaceTimeAlpha, kSpaceTimeAlpha * field_bar.stable_step(), kSpaceTimeN, kSpaceTimeSamples + 1);
  space_time.columns = {{"integrator", "", "", ""}, {"mass", "", "", ""}, {"t", "", "{:.4f}", ""}};
  std::vector<std::string> field_columns;
  for (double x : centres) {
    field_columns.push_back(fmt::format("sigma(x = {:g})", x));
    space_time.columns.push_back({field_columns.back(), "", "{:.4f}", "element stress over rho c v0"});
  }
  space_time.csv_only = true;
  space_time.metadata = metadata;
  space_time.metadata.emplace_back("space-time schemes", fmt::format("{}", fmt::join(kSpaceTimeSchemes, " ")));
  space_time.figures = {{"bar_space_time", space_time.title, "", "t", {}, {"integrator", "mass"}, false, false, {}, false,
                         false, "", "", "space_time", field_columns, centres, "sigma / (rho c v0)"}};
  const double t_end = field_bar.contact_start() + kHorizon * field_bar.contact_duration();
  for (int k = 0; k <= kSpaceTimeSamples; ++k) {
    const double t = t_end * k / kSpaceTimeSamples;
    std::vector<Cell> row = {std::string("exact"), std::string(), t};
    for (double x : centres) row.push_back(field_bar.exact_stress(x, t));
    space_time.add_row(std::move(row));
  }
  std::vector<std::string> declined;

  // Cases come in blocks of meshes for each (integrator, mass, alpha).
  for (std::size_t b = 0; b < cases.size(); b += meshes.size()) {
    const std::string integrator = cases[b]["integrator"], mass = cases[b]["mass"];
    const double alpha = cases[b]["alpha"];
    std::vector<double> h;
    std::vector<std::vector<double>> err(kErrors.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      const Json& r = results[b + m];
      const long N = meshes[m];
      h.push_back(1.0 / static_cast<double>(N));
      const bool ok = r["status"] == "ok";
      for (std::size_t e = 0; e < kErrors.size(); ++e) err[e].push_back(ok ? real(r[kErrors[e].key]) : NAN);
      const std::string status = r["status"];
      // A case that did not run to the end shows its status in the error columns.
      const auto value = [&](const char* key) { return ok ? Cell(real(r[key])) : Cell(status); };
      std::vector<Cell> row = {integrator, mass, alpha, N, r["dt"].get<double>()};
      for (std::size_t e = 0; e < kErrors.size(); ++e) {
        row.push_back(value(kErrors[e].key));
        const std::string key = kErrors[e].key;
        if (key == "u_max" || key == "duration")
          row.emplace_back(std::in_place_type<double>, m ? observed_order(h[m - 1], err[e][m - 1], h[m], err[e][m]) : NAN);
      }
      row.push_back(ok ? Cell(r["lost"].get<long>()) : Cell(status));
      row.push_back(r.contains("cpu") ? r["cpu"].get<double>() : NAN);
      row.push_back(r["message"].get<std::string>());
      table.add_row(std::move(row));
      if (r.contains("field_t")) {
        const std::vector<double> ft = r["field_t"];
        const Json& fs = r["field_stress"];
        for (std::size_t k = 0; k < ft.size(); ++k) {
          std::vector<Cell> row = {integrator, mass, ft[k]};
          for (std::size_t e = 0; e < centres.size(); ++e) row.push_back(number_cell(fs[k * centres.size() + e]));
          space_time.add_row(std::move(row));
        }
      } else if (keeps_space_time(cases[b + m])) {
        declined.push_back(fmt::format("{} ({}): {}", integrator, mass, status));
      }
      if (r.contains("history_t")) {
        const std::vector<double> ht = r["history_t"], hf = r["history_force"];
        const SignoriniBar exact(Params(SignoriniBar::parameters_spec(), {}));
        for (std::size_t i = 0; i < ht.size(); ++i) history.add_row({integrator, mass, ht[i], hf[i]});
        if (mass == "lumped")  // the exact force once per panel, at the same times
          for (double t : ht) history.add_row({integrator, "exact", t, exact.exact_contact_force(t) / exact.contact_force_level()});
      }
      const auto key = std::make_tuple(integrator, mass, N);
      if (!time_errors.count(key)) time_keys.push_back(key);
      time_errors[key][alpha] = {r["dt"].get<double>(), ok ? real(r["u_time"]) : NAN};
      if (N == 100 && alpha == 0.9)
        headline.add_row({integrator, mass, value("e_max"), value("e_end"), value("force_osc"), value("chatter"),
                          value("duration"), value("rebound"), r["message"].get<std::string>()});
    }
    std::vector<Cell> row = {integrator, mass, alpha};
    for (std::size_t e = 0; e < kErrors.size(); ++e) row.push_back(fitted_order(h, err[e]));
    orders.add_row(std::move(row));
  }
  for (const auto& key : time_keys) {
    if (std::get<0>(key) == ModalExact::kName) continue;
    const auto& by_alpha = time_errors[key];
    std::vector<Cell> row = {std::get<0>(key), std::get<1>(key), std::get<2>(key)};
    std::vector<double> dts, errs;
    for (double alpha : kAlphas) {
      const auto it = by_alpha.find(alpha);
      row.push_back(number_cell(it == by_alpha.end() ? NAN : it->second.second));
      if (it != by_alpha.end()) {
        dts.push_back(it->second.first);
        errs.push_back(it->second.second);
      }
    }
    row.push_back(number_cell(dts.size() < 2 ? NAN : fitted_order(dts, errs)));
    time_orders.add_row(std::move(row));
  }
  auto& figure = space_time.figures.front();
  figure.caption = space_time.caption + " One panel per scheme and mass model, one colour scale" +
                   (declined.empty() ? "." : fmt::format("; no panel for {}.", fmt::join(declined, ", ")));
  return {table, orders, time_orders, headline, history, space_time};
}

}  // namespace

extern const StudyEntry bar_study = {
    "bar", "Signorini bar: contact-node error, contact duration, rebound, energy, force oscillation, orders (exact solution)",
    nullptr, &bar_cases, &bar_case, &bar_tables};

}  // namespace nsb
