// Study "hard": cases that break integrators, one line of data each, run by every
// registered integrator. Each run ends as
//   ok | diverged (non-finite state or solver failure) | energy blow-up (energy above E0 by
//   more than the case's relative tolerance: no case here has an energy source) |
//   penetration (max penetration beyond the case's tolerance) | over budget (the case's
//   budget of F_int evaluations ran out before t_end: RunOptions::max_force_evaluations).
// or n/a when the scheme declines the problem at init (its reason in the note).
// The first that applies is the outcome (a blow-up or penetration seen before the budget ran
// out is reported as such). A diverging case is a row like any other; the study goes on.
// Budgets are work counts, not clocks: the same run stops at the same step everywhere, and
// slow schemes (event-driven root finding, the adaptive step collapsing on a stiff contact)
// cannot hold the study up.
// Energy: the integrator's energy(), for penalty-bdf including the springs of the contacts
// that are on. Its contact mode switches (on and off, located by root finding inside the
// steps) have columns of their own: they are its cost on the grazing drop (e = 1, an
// undamped spring: every bounce is resolved, see reference/penalty.hpp), and a missed one
// (found only at a step's end) is how a contact left off inside the obstacle showed up as
// an energy blow-up on the block.
//
// Steps near the CFL limit: the step is a multiple of the problem's stable_step() (bar:
// h/c for the lumped and the singular mass alike; block: the element bound).
//
// Histories (one CSV-only table and two figures per problem): over each of kHistoryPoints
// equal intervals of [0, t_end], the largest energy deviation |E - E0| / E scale and the
// largest penetration max(0, -g), recorded at the interval's last step (a run that stops
// early ends with its last, partial interval). Log scales: the deviation spans round-off
// to a blow-up's 1e300; intervals without penetration have none to draw.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "integrators/registry.hpp"
#include "run/run.hpp"
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
  long budget;             // F_int evaluations
  bool full_only = false;  // --full only: most of the default set's time otherwise
};

const std::map<std::string, std::string> kBar = {{"N", "100"}, {"mass", "lumped"}};
const std::map<std::string, std::string> kBarSingular = {{"N", "100"}, {"mass", "singular"}};
const std::map<std::string, std::string> kBarStiff = {{"N", "20"}, {"mass", "lumped"}, {"stiff_ratio", "1e6"}};

// 9030 s of flight at w1 = 4.43 m/s (period 0.903 s): 10^4 impacts with e = 1.
// Bar: nondimensional (L = c = v0 = 1, contact on [0, 2]), h = 0.01, run to 1.5 contact
// durations. Stiff bar (N = 20, h = 0.05): E 10^6 times larger on the half at the wall, so
// the stable step is 1000 times smaller than the soft half's h/c; 900 x CFL is 0.9 h/c of
// the soft half, the step an implicit scheme would choose. Its budget is 3 times what the
// fixed-step explicit scheme needs at 0.9 x CFL (66 667 steps).
// Penetration tolerance of the bar and the block: 0.025 m, above one step of travel at the
// impact speed at 2 x CFL (bar: v0 dt = 0.02; block: about 1e-2). Every impulse scheme
// penetrates by up to that much (the node moves a step before its impulse), so the outcome
// flags a contact that is lost, not that O(dt) penetration. Energy tolerance 10%: beyond the
// limit the energy grows without bound (1e60 within 300 steps at 1.01 x CFL), while a stable
// explicit run's own energy oscillates by O((omega dt)^2) near it (about 1% here).
// Block: block-2d defaults (8 x 4 Q4, 1 x 0.5 m, E = 1 MPa), first impact near 0.09 s, run
// through the rebound.
const std::vector<HardCase> kCases = {
    {"Zeno accumulation, e = 0.5", "bouncing-mass", {{"e", "0.5"}}, 1e-3, false, 3.0, 1e-2, 1e-3, 0, 1'000'000},
    {"chattering through Zeno at a coarse step, e = 0.9", "bouncing-mass", {{"e", "0.9"}}, 1e-2, false, 12.0, 5e-2, 1e-3, 0, 1'000'000},
    // 9e6 steps per scheme, the peers' and penalty-bdf's runs minutes each: --full only (the
    // default set's long runs: 10^3 impacts in `energy`, 10^5 of cd-lagrange in `claims`).
    {"10^4 impacts, e = 1", "bouncing-mass", {{"e", "1"}}, 1e-3, false, 9031.0, 1e-2, 1e-2, 0, 40'000'000, true},
    // E0 = 0 at rest: energies measured against m g (1 m).
    {"resting contact (h0 = 0, v0 = 0)", "bouncing-mass", {{"e", "0.5"}, {"h0", "0"}}, 1e-3, false, 10.0, 1e-4, 1e-6, 9.81, 1'000'000},
    {"grazing drop below one step of fall (h0 = 1e-9)", "bouncing-mass", {{"e", "1"}, {"h0", "1e-9"}}, 1e-3, false, 1.0, 1e-4, 1e-2, 9.81, 1'000'000},
    {"bar, lumped, 0.9 x CFL", "signorini-bar", kBar, 0.9, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"bar, lumped, 1.0 x CFL", "signorini-bar", kBar, 1.0, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"bar, lumped, 1.01 x CFL", "signorini-bar", kBar, 1.01, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"bar, lumped, 2 x CFL", "signorini-bar", kBar, 2.0, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"bar, singular, 0.9 x CFL", "signorini-bar", kBarSingular, 0.9, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"bar, singular, 1.0 x CFL", "signorini-bar", kBarSingular, 1.0, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"bar, singular, 1.01 x CFL", "signorini-bar", kBarSingular, 1.01, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"bar, singular, 2 x CFL", "signorini-bar", kBarSingular, 2.0, true, 3.0, 2.5e-2, 0.1, 0, 1'000'000},
    {"stiff/soft bar, stiffness ratio 1e6, 0.9 x CFL", "signorini-bar", kBarStiff, 0.9, true, 3.0, 2.5e-2, 0.1, 0, 200'000},
    {"stiff/soft bar, stiffness ratio 1e6, 900 x CFL", "signorini-bar", kBarStiff, 900.0, true, 3.0, 2.5e-2, 0.1, 0, 200'000},
    {"block, 0.9 x CFL", "block-2d", {}, 0.9, true, 0.3, 2.5e-2, 0.1, 0, 1'000'000},
    {"block, 1.01 x CFL", "block-2d", {}, 1.01, true, 0.3, 2.5e-2, 0.1, 0, 1'000'000},
    {"block, 2 x CFL", "block-2d", {}, 2.0, true, 0.3, 2.5e-2, 0.1, 0, 1'000'000},
};

constexpr int kHistoryPoints = 200;

struct Outcome {
  std::string status;
  long steps = 0, impacts = 0, force_evaluations = 0;
  // Contact mode switches an integrator locates inside its steps, and those it found only
  // at a step's end (the contact was in the wrong mode meanwhile); NaN: it counts none.
  double switches = NAN, missed_switches = NAN;
  double t_reached = 0, max_penetration = 0, energy_growth = 0, final_energy_error = 0, cpu = 0, dt = 0, scale = 0;
  std::string message;
  IntervalMax history;  // energy deviation, penetration; see above
};

Outcome run_hard_case(const HardCase& c, const std::string& integrator_name) {
  auto problem = make_problem(c.problem, c.params);
  auto integrator = make_integrator(integrator_name);
  Outcome o;
  o.dt = c.in_cfl ? c.step * problem->stable_step() : c.step;
  if (const auto declined = init_or_decline(*integrator, *problem)) {
    o.status = "n/a";
    o.message = *declined;
    return o;
  }
  RunOptions options;
  options.dt = o.dt;
  options.t_end = c.t_end;
  options.record_series = false;
  options.sample_every = 1000;
  options.max_force_evaluations = c.budget;
  const double E0 = integrator->energy().total();
  const double scale = o.scale = c.energy_scale > 0.0 ? c.energy_scale : std::abs(E0);
  const SpMat& L = problem->gap_operator();
  Vec gap(L.rows());
  bool in_contact = false;
  o.history = IntervalMax(c.t_end, kHistoryPoints, 2);
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo&) {
    const bool contact = it.impulses().sum() > 0.0;
    if (contact && !in_contact) ++o.impacts;
    in_contact = contact;
    const double E = it.energy().total();
    o.energy_growth = std::max(o.energy_growth, (E - E0) / scale);
    gap.noalias() = L * it.state().u;
    gap += problem->gap_offset();
    o.history.add(it.state().t, {std::abs(E - E0) / scale, -gap.minCoeff()});
  });
  o.history.finish();
  o.steps = r.steps;
  o.force_evaluations = r.work.force_evaluations;
  o.t_reached = r.t_final;
  o.cpu = r.step_cpu_seconds;
  o.max_penetration = r.max_penetration;
  if (const auto it = r.work.extra.find("switches"); it != r.work.extra.end()) o.switches = it->second;
  if (const auto it = r.work.extra.find("missed_switches"); it != r.work.extra.end()) o.missed_switches = it->second;
  o.final_energy_error = std::abs(r.final_energy - r.initial_energy) / scale;
  o.message = r.message;
  if (r.status == RunStatus::Diverged)
    o.status = status_name(r.status);
  else if (!(o.energy_growth <= c.energy_tol))
    o.status = "energy blow-up";
  else if (o.max_penetration > c.penetration_tol)
    o.status = "penetration";
  else
    o.status = status_name(r.status);  // ok or over budget
  return o;
}

std::vector<Json> hard_cases(const StudyOptions& opt) {
  std::vector<Json> cases;
  for (std::size_t k = 0; k < kCases.size(); ++k)
    if (opt.full || !kCases[k].full_only)
      for (const auto& entry : integrator_registry()) cases.push_back({{"case", k}, {"integrator", entry.name}});
  return cases;
}

Json hard_case(const Json& c) {
  const Outcome o = run_hard_case(kCases[c["case"].get<std::size_t>()], c["integrator"]);
  return {{"status", o.status}, {"steps", o.steps}, {"impacts", o.impacts}, {"force_evaluations", o.force_evaluations},
          {"switches", real(o.switches)}, {"missed_switches", real(o.missed_switches)},
          {"t_reached", o.t_reached}, {"max_penetration", o.max_penetration},
          {"energy_growth", o.energy_growth}, {"final_energy_error", o.final_energy_error}, {"cpu", o.cpu},
          {"dt", o.dt}, {"scale", o.scale}, {"message", o.message}, {"history_t", o.history.times()},
          {"history_energy", reals(o.history.largest(0))}, {"history_penetration", reals(o.history.largest(1))}};
}

std::vector<Table> hard_tables(const std::vector<Json>& cases, const std::vector<Json>& outcomes, const StudyOptions&) {
  Table t;
  t.id = "hard_cases";
  t.title = "Hard cases: outcome of every integrator";
  t.caption = "Outcome: ok, diverged, energy blow-up (energy above E0 by more than the case's relative tolerance), "
              "penetration (max penetration above the case's tolerance) or over budget (the case's budget of F_int "
              "evaluations ran out before t_end); n/a: the scheme declines the problem. Impacts: contact phases started. x CFL: dt over the problem's stable step.";
  t.columns = {{"case", "", "", ""},
               {"problem", "", "", ""},
               {"integrator", "", "", ""},
               {"dt", "s", "{:.2e}", ""},
               {"x CFL", "", "{}", "dt / stable step, when the case sets it so"},
               {"t_end", "s", "{}", ""},
               {"outcome", "", "", ""},
               {"t reached", "s", "{:.4g}", ""},
               {"impacts", "", "", "contact phases started, as seen at the steps (several inside one step of a reference count once)"},
               {"switches", "", "{:.0f}", "contact mode switches located inside the steps (penalty-bdf: on and off)"},
               {"missed", "", "{:.0f}", "switches found only at a step's end, not by a root: the contact was in the wrong mode meanwhile"},
               {"steps", "", "", ""},
               {"F_int evals", "", "", "internal force evaluations"},
               {"budget", "", "", "F_int evaluations allowed"},
               {"max pen.", "m", "{:.2e}", "max penetration"},
               {"pen. tol", "m", "{:.2g}", ""},
               {"E scale", "J", "{:.3g}", "energy scale: |E0|, or m g (1 m) when E0 = 0"},
               {"energy growth", "", "{:.2e}", "max (E - E0) / E scale"},
               {"growth tol", "", "{:.0e}", ""},
               {"final E err", "", "{:.2e}", "|E_end - E0| / E scale"},
               {"CPU", "s", "{:.2e}", "thread CPU time of the stepping (observer excluded)", true},
               {"note", "", "", "why a run diverged, stopped or is n/a"}};
  t.metadata = {{"study", "hard"}};
  // One history table per problem, in the order the cases first use them.
  std::vector<Table> histories;
  std::map<std::string, std::size_t> history_of;
  for (const auto& c : kCases) {
    if (history_of.count(c.problem)) continue;
    history_of[c.problem] = histories.size();
    Table h;
    h.id = "hard_history_" + c.problem;
    std::replace(h.id.begin(), h.id.end(), '-', '_');
    h.title = fmt::format("Hard cases, {}: energy and penetration histories", c.problem);
    h.caption = fmt::format("Over each of {} equal intervals of [0, t_end]: the largest |E - E0| / E scale (E scale as "
                            "in hard_cases) and the largest penetration, at the interval's last step.", kHistoryPoints);
    h.columns = {{"case", "", "", ""}, {"integrator", "", "", ""}, {"t", "s", "", "end of the interval"},
                 {"|E - E0| / E scale", "", "", "largest over the interval"},
                 {"penetration", "m", "", "largest max(0, -g) over the interval"}};
    h.csv_only = true;
    h.metadata = t.metadata;
    h.figures = {{h.id + "_energy", fmt::format("Hard cases, {}: energy deviation", c.problem), "t",
                  "|E - E0| / E scale", {"integrator"}, {"case"}, false, true},
                 {h.id + "_penetration", fmt::format("Hard cases, {}: penetration", c.problem), "t", "penetration",
                  {"integrator"}, {"case"}, false, true}};
    histories.push_back(h);
  }
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const HardCase& c = kCases[cases[i]["case"].get<std::size_t>()];
    const Json& o = outcomes[i];
    t.add_row({c.label, c.problem, cases[i]["integrator"].get<std::string>(), o["dt"].get<double>(),
               c.in_cfl ? Cell{c.step} : Cell{}, c.t_end, o["status"].get<std::string>(), o["t_reached"].get<double>(),
               o["impacts"].get<long>(), number_cell(o["switches"]), number_cell(o["missed_switches"]), o["steps"].get<long>(), o["force_evaluations"].get<long>(), c.budget,
               o["max_penetration"].get<double>(), c.penetration_tol, o["scale"].get<double>(),
               o["energy_growth"].get<double>(), c.energy_tol, o["final_energy_error"].get<double>(),
               o["cpu"].get<double>(), o["message"].get<std::string>()});
    Table& h = histories[history_of.at(c.problem)];
    const std::vector<double> ht = o["history_t"];
    for (std::size_t j = 0; j < ht.size(); ++j)
      h.add_row({c.label, cases[i]["integrator"].get<std::string>(), ht[j], number_cell(o["history_energy"][j]),
                 number_cell(o["history_penetration"][j])});
  }
  histories.insert(histories.begin(), t);
  return histories;
}

}  // namespace

extern const StudyEntry hard_cases_study = {
    "hard", "hard cases: Zeno, chattering, 10^4 impacts (--full), resting and grazing contact, steps around the CFL limit (bar, "
            "block), stiffness ratio 1e6; ok / diverged / energy blow-up / penetration / over budget",
    nullptr, &hard_cases, &hard_case, &hard_tables};

}  // namespace nsb
