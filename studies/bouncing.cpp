// Study "bouncing": every integrator on the bouncing mass against the exact solution.
// e in {1, 0.9, 0.5}, steps 1e-2 .. 1e-5 (1e-6 with --full). Per case: impact-time errors
// (first impact, max over the first K impacts), flight energy after each impact against
// E0 e^{2i}, detected accumulation (Zeno) time against the exact one, max penetration,
// steps, CPU time; observed orders (pairwise and least-squares) per (integrator, e).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/bouncing_mass.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr int kComparedImpacts = 5;  // impacts compared one by one
constexpr double kG = 9.81;

struct StepRecord {
  double t, q, v, energy, impulse;
};

constexpr double kHistoryStep = 1e-3;  // the step whose energy history is drawn
constexpr int kEnergyHistoryPoints = 400;

struct BouncingCaseResult {
  bool diverged = false;
  std::vector<double> history_t, history_energy;  // E/E0 at about kHistoryPoints times
  std::string message;
  std::vector<double> impact_time_error;  // detected - exact, impact i = 1..
  std::vector<double> flight_energy;      // energy at numerical mid-flight after impact i
  double zeno_detected = std::numeric_limits<double>::quiet_NaN();
  double max_penetration = 0.0, cpu = 0.0;
  long steps = 0;
};

BouncingMass make_bouncing_mass(double e) {
  return BouncingMass(Params(BouncingMass::parameters_spec(), {{"e", fmt::format("{}", e)}}));
}

double horizon(const BouncingMass& p, double e) {
  return e < 1.0 ? p.zeno_time() + 0.5 : p.impact_time(kComparedImpacts + 1) + 0.1;
}

BouncingCaseResult simulate(const std::string& integrator_name, double e, double dt) {
  const BouncingMass problem = make_bouncing_mass(e);
  auto integrator = make_integrator(integrator_name);
  integrator->init(problem, problem.initial_state());
  RunOptions options;
  options.dt = dt;
  options.t_end = horizon(problem, e);
  options.record_series = false;
  std::vector<StepRecord> steps;
  steps.reserve(static_cast<std::size_t>(options.t_end / dt) + 2);
  const RunResult r = run(problem, *integrator, options, [&](const Integrator& it, const StepInfo&) {
    steps.push_back({it.state().t, it.state().u[0], it.state().v[0], it.energy().total(), it.impulses()[0]});
  });
  BouncingCaseResult c;
  if (dt == kHistoryStep) {
    const std::size_t stride = std::max<std::size_t>(1, steps.size() / kEnergyHistoryPoints);
    for (std::size_t k = 0; k < steps.size(); k += stride) {
      c.history_t.push_back(steps[k].t);
      c.history_energy.push_back(steps[k].energy / problem.initial_energy());
    }
  }
  c.steps = r.steps;
  c.cpu = r.step_cpu_seconds;
  c.max_penetration = r.max_penetration;
  if (r.status != RunStatus::Ok) {
    c.diverged = true;
    c.message = r.message;
    return c;
  }
  // Impacts: first step of each run of steps with a positive impulse.
  std::vector<std::size_t> starts;
  for (std::size_t k = 0; k < steps.size(); ++k)
    if (steps[k].impulse > 0.0 && (k == 0 || steps[k - 1].impulse == 0.0)) starts.push_back(k);
  // Impacts compared: those whose exact flight lasts at least 10 steps (shorter flights are
  // below the step's resolution and belong to the Zeno phase).
  for (int i = 1; i <= static_cast<int>(starts.size()) && i <= kComparedImpacts; ++i) {
    if (problem.impact_time(i + 1) - problem.impact_time(i) < 10 * dt) break;
    c.impact_time_error.push_back(steps[starts[i - 1]].t - problem.impact_time(i));
    if (static_cast<std::size_t>(i) < starts.size())
      c.flight_energy.push_back(steps[(starts[i - 1] + starts[i]) / 2].energy);
  }
  // At rest: rebound speed below two steps of gravity and height below what that reaches.
  if (e < 1.0) {
    std::size_t k = steps.size();
    while (k > 0 && std::abs(steps[k - 1].v) <= 2 * kG * dt && steps[k - 1].q <= 2 * kG * dt * dt) --k;
    if (k < steps.size() && steps.back().t - steps[k].t > 0.25) c.zeno_detected = steps[k].t;
  }
  return c;
}


std::vector<double> study_steps(const StudyOptions& opt) {
  std::vector<double> steps = {1e-2, 1e-3, 1e-4, 1e-5};
  if (opt.full) steps.push_back(1e-6);
  return steps;
}
const std::vector<double> kRestitutions = {1.0, 0.9, 0.5};

// Cases in table order: integrator, e, dt.
std::vector<Json> bouncing_cases(const StudyOptions& opt) {
  std::vector<Json> cases;
  for (const auto& entry : integrator_registry())
    for (double e : kRestitutions)
      for (double dt : study_steps(opt)) cases.push_back({{"integrator", entry.name}, {"e", e}, {"dt", dt}});
  return cases;
}

Json bouncing_case(const Json& c) {
  BouncingCaseResult r;
  try {
    r = simulate(c["integrator"], c["e"], c["dt"]);
  } catch (const InputError& e) {  // the scheme declines the problem (e.g. newmark-lm at e > 0)
    return {{"declined", e.what()}};
  }
  return {{"diverged", r.diverged}, {"message", r.message}, {"impact_time_error", r.impact_time_error},
          {"flight_energy", r.flight_energy}, {"zeno_detected", real(r.zeno_detected)},
          {"max_penetration", r.max_penetration}, {"cpu", r.cpu}, {"steps", r.steps},
          {"history_t", r.history_t}, {"history_energy", r.history_energy}};
}

double max_abs(const std::vector<double>& v) {
  double m = std::numeric_limits<double>::quiet_NaN();
  for (double x : v) m = std::isnan(m) ? std::abs(x) : std::max(m, std::abs(x));
  return m;
}


std::vector<Table> bouncing_tables(const std::vector<Json>& cases, const std::vector<Json>& results,
                                   const StudyOptions& opt) {
  const std::vector<double>& restitutions = kRestitutions;
  const std::vector<double> steps = study_steps(opt);

  Table table;
  table.id = "bouncing_mass";
  table.title = "Bouncing mass: every integrator against the exact solution";
  table.caption = fmt::format(
      "m = 1, g = 9.81, h0 = 1, v0 = 0. Impact times compared for the first {} impacts whose flight lasts "
      "at least 10 steps; flight energy taken at the numerical mid-flight, relative to E0 e^(2i). Zeno time "
      "detected as the first step after which |v| <= 2 g dt and q <= 2 g dt^2 for the rest of the run. "
      "Errors at or below {:.0e} are round-off and carry no order (n/a). "
      "n/a: the scheme declines the problem (its reason in the next cell).",
      kComparedImpacts, kRoundOffError);
  table.columns = {
      {"integrator", "", "", ""},
      {"e", "", "{}", "restitution"},
      {"dt", "s", "{:.0e}", "step"},
      {"t1 err", "s", "{:.2e}", "|detected - exact| first impact time"},
      {"max t_i err", "s", "{:.2e}", "max over compared impacts of |detected - exact| impact time"},
      {"order t_i", "", "{:.2f}", "observed order of max t_i err against the previous dt"},
      {"max E_i err", "", "{:.2e}", "max over compared impacts of |E_i / (E0 e^(2i)) - 1|"},
      {"order E_i", "", "{:.2f}", "observed order of max E_i err against the previous dt"},
      {"impacts", "", "", "impacts compared"},
      {"Zeno detected", "s", "{:.5f}", ""},
      {"Zeno err", "s", "{:.2e}", "|detected - exact| accumulation time"},
      {"max pen.", "m", "{:.2e}", "max penetration max(0, -q)"},
      {"steps", "", "", ""},
      {"CPU", "s", "{:.2e}", "thread CPU time of the stepping, per-step observation excluded (timed runs: study precision)", true},
  };
  table.figures = {
      {"bouncing_convergence", "Bouncing mass: impact-time error against the step", "dt", "max t_i err", {"integrator"}, {"e"}, true, true, {1, 2}},
      {"bouncing_work_precision", "Bouncing mass: impact-time error against CPU time", "CPU", "max t_i err", {"integrator"}, {"e"}, true, true},
      {"bouncing_energy_convergence", "Bouncing mass: flight-energy error against the step", "dt", "max E_i err", {"integrator"}, {"e"}, true, true, {1, 2}},
  };
  Table orders;
  orders.id = "bouncing_mass_orders";
  orders.title = "Bouncing mass: least-squares convergence orders";
  orders.caption = fmt::format("Slope of log(error) against log(dt) over the steps of the study (errors as in the main "
                               "table); errors at or below {:.0e} are round-off and left out (n/a: fewer than two left).",
                               kRoundOffError);
  orders.columns = {{"integrator", "", "", ""}, {"e", "", "{}", ""},
                    {"order t_i", "", "{:.2f}", "impact times"}, {"order E_i", "", "{:.2f}", "flight energies"},
                    {"order Zeno", "", "{:.2f}", "accumulation time"}};
  Table history;
  history.id = "bouncing_mass_energy_history";
  history.title = fmt::format("Bouncing mass: energy history, dt = {}", kHistoryStep);
  history.caption = "E(t) / E0 with each integrator's own energy (CD-Lagrange: its discrete energy E_{k+1/2}).";
  history.columns = {{"integrator", "", "", ""}, {"e", "", "{}", ""}, {"t", "s", "{:.4f}", ""}, {"E/E0", "", "{:.6f}", ""}};
  history.csv_only = true;
  history.figures = {{"bouncing_energy_history", history.title, "t", "E/E0", {"integrator"}, {"e"}, false, false, {}, true, true}};
  Table energies;
  energies.id = "bouncing_mass_energy";
  energies.title = "Bouncing mass: flight energy after each impact, dt = 1e-3";
  energies.caption = "E_i / E0 at the numerical mid-flight after impact i, against the exact e^(2i).";
  energies.columns = {{"integrator", "", "", ""}, {"e", "", "{}", ""}, {"impact", "", "", ""},
                      {"E_i/E0", "", "{:.6f}", "numerical"}, {"e^(2i)", "", "{:.6f}", "exact"},
                      {"rel. err", "", "{:.2e}", ""}};
  table.metadata = {{"study", "bouncing"}, {"steps", fmt::format("{}", fmt::join(steps, " "))},
                    {"restitutions", fmt::format("{}", fmt::join(restitutions, " "))}};
  orders.metadata = energies.metadata = history.metadata = table.metadata;

  std::size_t next = 0;
  while (next < cases.size()) {
    const std::string integrator = cases[next]["integrator"];
    for (double e : restitutions) {
      const BouncingMass problem = make_bouncing_mass(e);
      std::vector<double> t_err, e_err, z_err;
      for (std::size_t s = 0; s < steps.size(); ++s) {
        const double dt = steps[s];
        const Json& c = results[next++];
        if (c.contains("declined")) {
          table.add_row({integrator, e, dt, "n/a", c["declined"].get<std::string>(), {}, {}, {}, {}, {}, {}, {}, {}, {}});
          t_err.push_back(NAN), e_err.push_back(NAN), z_err.push_back(NAN);
          continue;
        }
        const std::vector<double> impact_time_error = c["impact_time_error"], flight_energy = c["flight_energy"];
        const double zeno_detected = real(c["zeno_detected"]), max_penetration = c["max_penetration"], cpu = c["cpu"];
        const long n_steps = c["steps"];
        const std::vector<double> ht = c["history_t"], he = c["history_energy"];
        for (std::size_t i = 0; i < ht.size(); ++i) history.add_row({integrator, e, ht[i], he[i]});
        if (c["diverged"]) {
          table.add_row({integrator, e, dt, "diverged", c["message"].get<std::string>(), {}, {}, {}, {}, {}, {}, max_penetration, n_steps, cpu});
          t_err.push_back(NAN), e_err.push_back(NAN), z_err.push_back(NAN);
          continue;
        }
        std::vector<double> rel;
        for (std::size_t i = 0; i < flight_energy.size(); ++i) {
          const double exact = problem.energy_after_impact(static_cast<int>(i) + 1);
          rel.push_back(flight_energy[i] / exact - 1.0);
          if (dt == 1e-3)
            energies.add_row({integrator, e, static_cast<long>(i + 1), flight_energy[i] / problem.initial_energy(),
                              exact / problem.initial_energy(), std::abs(rel.back())});
        }
        t_err.push_back(max_abs(impact_time_error));
        e_err.push_back(max_abs(rel));
        z_err.push_back(e < 1.0 ? std::abs(zeno_detected - problem.zeno_time()) : NAN);
        const double order_t = s ? observed_order(steps[s - 1], above_round_off(t_err[s - 1]), dt, above_round_off(t_err[s])) : NAN;
        const double order_e = s ? observed_order(steps[s - 1], above_round_off(e_err[s - 1]), dt, above_round_off(e_err[s])) : NAN;
        table.add_row({integrator, e, dt,
                       impact_time_error.empty() ? Cell{} : Cell{std::abs(impact_time_error[0])},
                       number_cell(t_err[s]), number_cell(order_t), number_cell(e_err[s]), number_cell(order_e),
                       static_cast<long>(impact_time_error.size()), number_cell(zeno_detected), number_cell(z_err[s]),
                       max_penetration, n_steps, cpu});
      }
      const auto fit = [&](std::vector<double> err) {  // errors at round-off carry no order
        for (double& x : err) x = above_round_off(x);
        return number_cell(fitted_order(steps, err));
      };
      orders.add_row({integrator, e, fit(t_err), fit(e_err), fit(z_err)});
    }
  }
  return {table, orders, energies, history};
}

}  // namespace

extern const StudyEntry bouncing_study = {
    "bouncing", "bouncing mass: impact times, flight energies, Zeno time, orders, against the exact solution",
    nullptr, &bouncing_cases, &bouncing_case, &bouncing_tables};

}  // namespace nsb
