// Study "hard": cases that break integrators, one line of data each, run by every
// registered integrator. Each run ends as
//   ok | diverged (non-finite state or solver failure) | penetration (max penetration
//   beyond the case's tolerance) | energy blow-up (energy above E0 by more than the case's
//   relative tolerance: no case here has an energy source).
// A diverging case is a row like any other; the study goes on.
#include <fmt/format.h>

#include <cmath>
#include <map>

#include "integrators/registry.hpp"
#include "integrators/run.hpp"
#include "problems/registry.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

struct HardCase {
  std::string label;  // what makes the case hard
  std::string problem;
  std::map<std::string, std::string> params;
  double step;        // seconds, or a multiple of the problem's stable step when in_cfl
  bool in_cfl;
  double t_end;
  double penetration_tol;  // [m]
  double energy_tol;       // growth of the energy above E0, relative to the energy scale
  double energy_scale;     // [J]; 0: |E0|
};

// 9030 s of flight at w1 = 4.43 m/s (period 0.903 s): 10^4 impacts with e = 1.
const std::vector<HardCase> kCases = {
    {"Zeno accumulation, e = 0.5", "bouncing-mass", {{"e", "0.5"}}, 1e-3, false, 3.0, 1e-2, 1e-3, 0},
    {"chattering through Zeno at a coarse step, e = 0.9", "bouncing-mass", {{"e", "0.9"}}, 1e-2, false, 12.0, 5e-2, 1e-3, 0},
    {"10^4 impacts, e = 1", "bouncing-mass", {{"e", "1"}}, 1e-3, false, 9031.0, 1e-2, 1e-2, 0},
    // E0 = 0 at rest: energies measured against m g (1 m).
    {"resting contact (h0 = 0, v0 = 0)", "bouncing-mass", {{"e", "0.5"}, {"h0", "0"}}, 1e-3, false, 10.0, 1e-4, 1e-6, 9.81},
    {"grazing drop below one step of fall (h0 = 1e-9)", "bouncing-mass", {{"e", "1"}, {"h0", "1e-9"}}, 1e-3, false, 1.0, 1e-4, 1e-2, 9.81},
};

struct Outcome {
  std::string status;
  long steps = 0, impacts = 0;
  double max_penetration = 0, energy_growth = 0, final_energy_error = 0, cpu = 0, dt = 0, scale = 0;
  std::string message;
};

Outcome run_hard_case(const HardCase& c, const std::string& integrator_name) {
  auto problem = make_problem(c.problem, c.params);
  auto integrator = make_integrator(integrator_name);
  integrator->init(*problem, problem->initial_state());
  RunOptions options;
  options.dt = c.in_cfl ? c.step * problem->stable_step() : c.step;
  options.t_end = c.t_end;
  options.record_series = false;
  options.sample_every = 1000;
  Outcome o;
  o.dt = options.dt;
  const double E0 = integrator->energy().total();
  const double scale = o.scale = c.energy_scale > 0.0 ? c.energy_scale : std::abs(E0);
  bool in_contact = false;
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo&) {
    const bool contact = it.impulses().sum() > 0.0;
    if (contact && !in_contact) ++o.impacts;
    in_contact = contact;
    o.energy_growth = std::max(o.energy_growth, (it.energy().total() - E0) / scale);
  });
  o.steps = r.steps;
  o.cpu = r.cpu_seconds;
  o.max_penetration = r.max_penetration;
  o.final_energy_error = std::abs(r.final_energy - r.initial_energy) / scale;
  if (r.status != RunStatus::Ok) {
    o.status = "diverged";
    o.message = r.message;
  } else if (!(o.energy_growth <= c.energy_tol)) {
    o.status = "energy blow-up";
  } else if (o.max_penetration > c.penetration_tol) {
    o.status = "penetration";
  } else {
    o.status = "ok";
  }
  return o;
}

std::vector<Json> hard_cases(const StudyOptions&) {
  std::vector<Json> cases;
  for (std::size_t k = 0; k < kCases.size(); ++k)
    for (const auto& entry : integrator_registry()) cases.push_back({{"case", k}, {"integrator", entry.name}});
  return cases;
}

Json hard_case(const Json& c) {
  const Outcome o = run_hard_case(kCases[c["case"].get<std::size_t>()], c["integrator"]);
  return {{"status", o.status}, {"steps", o.steps}, {"impacts", o.impacts}, {"max_penetration", o.max_penetration},
          {"energy_growth", o.energy_growth}, {"final_energy_error", o.final_energy_error}, {"cpu", o.cpu},
          {"dt", o.dt}, {"scale", o.scale}, {"message", o.message}};
}

std::vector<Table> hard_tables(const std::vector<Json>& cases, const std::vector<Json>& outcomes, const StudyOptions&) {
  Table t;
  t.id = "hard_cases";
  t.title = "Hard cases: outcome of every integrator";
  t.caption = "Outcome: ok, diverged, penetration (max penetration above the case's tolerance) or energy blow-up "
              "(energy above E0 by more than the case's relative tolerance). Impacts: contact phases started.";
  t.columns = {{"case", "", "", ""},
               {"problem", "", "", ""},
               {"integrator", "", "", ""},
               {"dt", "s", "{:.2e}", ""},
               {"t_end", "s", "{}", ""},
               {"outcome", "", "", ""},
               {"impacts", "", "", "contact phases started"},
               {"steps", "", "", ""},
               {"max pen.", "m", "{:.2e}", "max penetration"},
               {"pen. tol", "m", "{:.0e}", ""},
               {"E scale", "J", "{:.3g}", "energy scale: |E0|, or m g (1 m) when E0 = 0"},
               {"energy growth", "", "{:.2e}", "max (E - E0) / E scale"},
               {"growth tol", "", "{:.0e}", ""},
               {"final E err", "", "{:.2e}", "|E_end - E0| / E scale"},
               {"CPU", "s", "{:.2e}", ""},
               {"note", "", "", "why a run diverged"}};
  t.metadata = {{"study", "hard"}};
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const HardCase& c = kCases[cases[i]["case"].get<std::size_t>()];
    const Json& o = outcomes[i];
    t.add_row({c.label, c.problem, cases[i]["integrator"].get<std::string>(), o["dt"].get<double>(), c.t_end,
               o["status"].get<std::string>(), o["impacts"].get<long>(), o["steps"].get<long>(),
               o["max_penetration"].get<double>(), c.penetration_tol, o["scale"].get<double>(),
               o["energy_growth"].get<double>(), c.energy_tol, o["final_energy_error"].get<double>(),
               o["cpu"].get<double>(), o["message"].get<std::string>()});
  }
  return {t};
}

}  // namespace

extern const StudyEntry hard_cases_study = {
    "hard", "hard cases: Zeno, chattering, 10^4 impacts, resting and grazing contact; ok / diverged / penetration / energy blow-up",
    nullptr, &hard_cases, &hard_case, &hard_tables};

}  // namespace nsb
