// Study "properties": every scheme and peer of the suite (references left out) against the
// claims of the CD-Lagrange talk, as the benchmark of explicit schemes for impact asks them of
// every scheme (Di Stasio, Dureisseix, Gravouil, Georges, Homolle, "Benchmark cases for robust
// explicit time integrators in non-smooth transient dynamics", AMSES 2019). Each cell is the
// claims study's measurement (studies/claims_conditions.hpp) run for that scheme, with the
// claims study's verdict rule (studies/claims.hpp):
//   explicit      factorisations and linear solves per step of the spinning block on the floor:
//                 holds when both are 0
//   Hausdorff     graphs converging (order >= 0.5, interval above 0) of the 8 on the bars
//                 (2 bars x 4 observables, N = 25..200, dt = 0.9 h/c): as claimed with the
//                 singular mass, beyond with the lumped one; all / some / none
//   momentum      the spinning block: free flight (10^4 steps, P and J) and on the floor (the J
//                 balance with the impulses' moments), relative: <= 1e-10
//   impact energy the largest |energy jump| across a contact phase of the bouncing bar, singular
//                 mass (as claimed) and lumped mass with e = 1 (beyond): <= 1e-2
//   energy drift  the claims study's long runs (e = 1): max |E - E_1| / E_1 over each half, the
//                 bounded-without-drift rule; the adaptive step (cd-lagrange-adaptive) exact rule
//   contact cost  LCP iterations per step with a contact, on the block's floor run (H diagonal)
//                 and between two deformable blocks (two-blocks, H not diagonal) (reported)
// and two tables whose figures go to the first page beside the claims':
//   properties_explicit      claim (1): factorisations, linear solves and F_int evaluations per
//                            step, on the Signorini bar of the claims study (linear, lumped, as
//                            claimed) and the spinning block on the floor (nonlinear, beyond);
//                            the suite's schemes only (the peers do not count their solves)
//   properties_contact_cost  claim (6): LCP iterations per step with a contact, node on the rigid
//                            floor (H diagonal), two bars through one contact row (H 1 x 1),
//                            two blocks (H not diagonal)
//   robustness    the claims study's long run (the bouncing mass, e = 1, dt 0.02 s, to its 1e5th
//                 impact): finite states, |E_end - E_1| / E_1 <= 1e-2, penetration <= one step
//                 of travel (robustness_verdict)
// A scheme that declines a problem (a singular mass, a nonlinear body) has n/a there.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

#include "integrators/registry.hpp"
#include "studies/claims.hpp"
#include "studies/claims_conditions.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr long kFreeSteps = 10'000, kPropertiesFloorSteps = 2000, kLongRunImpacts = 100'000;

// A row's measurements in four parts, each a case of its own so that the cores share one
// scheme's work (one case per row left a core idle while the last rows ran: docs/measurements.md).
// The case list starts with the long runs, the longest part. Each case's result holds its part
// of each row, by integrator; the table merges them (the same numbers whatever the order the
// cases ran in).
const std::vector<std::string> kParts = {"long-run", "bars", "block", "runs"};

std::vector<Json> properties_cases(const StudyOptions&) {
  std::vector<std::string> names;
  for (const auto& entry : integrator_registry())
    if (!entry.reference) names.push_back(entry.name);
  std::vector<Json> cases;
  for (const auto& part : kParts)
    for (const auto& name : names) cases.push_back({{"integrators", {name}}, {"part", part}});
  return cases;
}

// Converging graphs of the bars for one mass model, and how many were run (declined ones out).
// A run that did not happen or did not finish: the first such note of its group, else empty.
std::string first_note(const std::vector<BarGraphFit>& fits, const std::string& mass) {
  for (const auto& f : fits)
    if (f.mass == mass && !f.note.empty()) return f.note;
  return {};
}

Json bar_counts(const std::vector<BarGraphFit>& fits, const std::string& mass) {
  long tested = 0, converging = 0;
  for (const auto& f : fits)
    if (f.mass == mass && f.note.rfind("declined", 0) != 0) {
      ++tested;
      converging += hausdorff_converges(f.fit);
    }
  return {{"tested", tested}, {"converging", converging}, {"note", first_note(fits, mass)}};
}

Json impact_json(const ImpactEnergy& e, const std::string& which) {
  if (!e.note.empty()) return {{"note", e.note}};
  Json j = {{"phases", e.phases}, {"jump", e.worst_jump}};
  if (!e.remark.empty()) j["remark"] = fmt::format("impact jump, {}: {}", which, e.remark);
  return j;
}

// The counters the figures of claims (1) and (6) show, raw (the tables divide).
Json work_json(const WorkCounters& w, long contact_steps) {
  return {{"steps", w.steps},           {"factorizations", w.factorizations}, {"solves", w.linear_solves},
          {"forces", w.force_evaluations}, {"lcp", w.lcp_iterations},          {"contact_steps", contact_steps}};
}
Json run_work_json(const RunWork& r) { return r.note.empty() ? Json{{"work", work_json(r.work, r.contact_steps)}} : Json{{"note", r.note}}; }

Json block_part(const std::string& name) {
  Json out;
  const SpinningBlock b = spinning_block(name, kFreeSteps, kPropertiesFloorSteps);
  if (b.note.empty()) {
    const double steps = static_cast<double>(std::max(1L, b.work.steps));
    out["block"] = {{"factorizations_per_step", static_cast<double>(b.work.factorizations) / steps},
                    {"solves_per_step", static_cast<double>(b.work.linear_solves) / steps},
                    {"work", work_json(b.work, b.contact_steps)},
                    {"lcp_per_contact_step", b.contact_steps > 0 ? real(static_cast<double>(b.work.lcp_iterations) / static_cast<double>(b.contact_steps)) : Json(nullptr)},
                    {"linear", real(b.free_linear)},
                    {"angular", real(std::max(b.free_angular, b.floor_angular))}};
  } else {
    out["block"] = {{"note", b.note}};
  }
  return out;
}

Json bars_part(const std::string& name) {
  Json out;
  const auto fits = bar_hausdorff(name, {"singular", "lumped"});
  out["hausdorff"] = {{"singular", bar_counts(fits, "singular")}, {"lumped", bar_counts(fits, "lumped")}};
  out["impact"] = {{"singular", impact_json(bar_impact_energy(name, "singular", 0.0), "singular")},
                   {"lumped", impact_json(bar_impact_energy(name, "lumped", 1.0), "lumped e=1")}};
  out["bar_work"] = run_work_json(signorini_bar_work(name));
  return out;
}

Json runs_part(const std::string& name) {
  Json out;
  const EnergyFigures energy = energy_runs(name);
  if (!energy.note.empty())
    out["energy"] = {{"note", energy.note}};
  else if (name == "cd-lagrange-adaptive")
    out["energy"] = {{"adaptive", real(energy.adaptive)}, {"completed", energy.adaptive_ok}, {"cfl", real(energy.cfl)}};
  else
    out["energy"] = {{"first", real(energy.first)}, {"second", real(energy.second)}};
  out["two_bars"] = run_work_json(two_bars_contact_cost(name));
  const RunWork bodies = bodies_contact_cost(name);
  if (bodies.note.empty())
    out["bodies"] = {{"lcp_per_contact_step", bodies.contact_steps > 0 ? real(static_cast<double>(bodies.work.lcp_iterations) / static_cast<double>(bodies.contact_steps)) : Json(nullptr)},
                     {"work", work_json(bodies.work, bodies.contact_steps)}};
  else
    out["bodies"] = {{"note", bodies.note}};
  return out;
}

Json long_run_part(const std::string& name) {
  const LongRun l = long_run(name, kLongRunImpacts);
  if (!l.note.empty()) return {{"robust", {{"note", l.note}}}};
  return {{"robust", {{"ok", l.ok}, {"impacts", l.impacts}, {"energy", real(l.energy)}, {"penetration", real(l.penetration)}}}};
}

// One case: its part of each of its integrators' rows, by integrator.
Json properties_case(const Json& c) {
  const std::string part = c["part"];
  const auto measure = part == "long-run" ? &long_run_part : part == "bars" ? &bars_part : part == "block" ? &block_part : &runs_part;
  Json out = Json::object();
  for (const auto& name : c["integrators"]) out[name.get<std::string>()] = measure(name.get<std::string>());
  return out;
}

// The rows, one per integrator in the order of the cases of one part (the registry's, the
// Siconos peers last as before), each the union of its parts.
using Rows = std::vector<std::pair<std::string, Json>>;
Rows merged_rows(const std::vector<Json>& cases, const std::vector<Json>& results) {
  Rows rows;
  for (const auto& c : cases)
    if (c["part"] == "bars") rows.emplace_back(c["integrators"][0].get<std::string>(), Json::object());
  for (auto& [name, row] : rows)
    for (std::size_t k = 0; k < cases.size(); ++k)
      if (results[k].contains(name)) row.update(results[k][name]);
  return rows;
}

// The reasons of the row's n/a cells, each once.
std::string notes(const Json& r) {
  std::vector<std::string> seen;
  const auto add = [&](const Json& j) {
    for (const char* key : {"remark", "note"}) {
      if (!j.contains(key) || j[key].get<std::string>().empty()) continue;
      const std::string n = j[key];
      if (std::find(seen.begin(), seen.end(), n) == seen.end()) seen.push_back(n);
    }
  };
  add(r["block"]);
  add(r["hausdorff"]["singular"]);
  add(r["hausdorff"]["lumped"]);
  add(r["impact"]["singular"]);
  add(r["impact"]["lumped"]);
  add(r["bodies"]);
  add(r["energy"]);
  add(r["robust"]);
  return fmt::format("{}", fmt::join(seen, "; "));
}

const char* short_verdict(Verdict v) { return v == Verdict::Holds ? "holds" : v == Verdict::Conditional ? "conditional" : "fails"; }

Cell hausdorff_cell(const Json& h) { return h["tested"].get<long>() > 0 ? Cell{h["converging"].get<long>()} : Cell{}; }
std::string hausdorff_verdict_cell(const Json& h) {
  const long n = h["tested"], k = h["converging"];
  if (n == 0) return "n/a";
  return short_verdict(k == n ? Verdict::Holds : k > 0 ? Verdict::Conditional : Verdict::Fails);
}
Cell bodies_cell(const Json& b) { return b.contains("lcp_per_contact_step") && !b["lcp_per_contact_step"].is_null() ? Cell{real(b["lcp_per_contact_step"])} : Cell{}; }
Cell field(const Json& j, const char* key) { return j.contains(key) && !j[key].is_null() ? Cell{real(j[key])} : Cell{}; }
std::string drift_verdict_cell(const Json& e) {
  if (!e.contains("first")) return "n/a";
  return energy_no_drift(real(e["first"]), real(e["second"])) ? "holds" : "fails";
}
std::string adaptive_verdict_cell(const Json& e) {
  if (!e.contains("adaptive")) return "n/a";
  return e["completed"].get<bool>() && real(e["adaptive"]) <= kEnergyExact ? "holds" : "fails";
}
Cell robust_impacts(const Json& l) { return l.contains("impacts") ? Cell{l["impacts"].get<long>()} : Cell{}; }
std::string robust_verdict_cell(const Json& l) {
  if (!l.contains("impacts")) return "n/a";
  return short_verdict(robustness_verdict(l["ok"], l["impacts"], kLongRunImpacts, real(l["energy"]), real(l["penetration"])));
}
Cell impact_cell(const Json& e) { return e.contains("jump") ? Cell{real(e["jump"])} : Cell{}; }
std::string impact_verdict_cell(const Json& e) {
  if (!e.contains("jump")) return "n/a";
  return impact_energy_kept(e["phases"], real(e["jump"])) ? "holds" : "fails";
}

// A run's counter `what` per `by` (steps, contact steps); n/a when it did not run or `by` is 0.
Cell per(const Json& run, const char* what, const char* by) {
  if (!run.contains("work") || run["work"][by].get<long>() == 0) return Cell{};
  return Cell{static_cast<double>(run["work"][what].get<long>()) / static_cast<double>(run["work"][by].get<long>())};
}
Cell count(const Json& run, const char* what) { return run.contains("work") ? Cell{run["work"][what].get<long>()} : Cell{}; }
std::string run_note(const Json& run) { return run.contains("note") ? run["note"].get<std::string>() : std::string(); }

// Claim (1)'s figure: the work of a step per scheme, on a linear and a nonlinear problem.
Table explicit_work_table(const Rows& rows) {
  Table t;
  t.id = "properties_explicit";
  t.title = "Claim (1) per scheme: factorisations, linear solves and F_int evaluations per step";
  t.caption = fmt::format(
      "Work counters of each of the suite's schemes (the peers are left out: the Siconos and engine peers do not count "
      "their factorisations and solves) over a run, per step. As claimed: the Signorini bar of the claims study's claim (1) "
      "(linear, lumped mass, N 100, dt 0.9 h/c, to the contact's start + 1.5 contact durations; H diagonal). Beyond: the 2D "
      "SVK block spinning at 3 rad/s dropped on the frictionless floor ({} steps of 0.5 x its stable step; nonlinear "
      "F_int). An explicit step has 0 factorisations, 0 solves and 1 F_int evaluation (+ 1 at the start of the run); an "
      "implicit scheme on the linear bar factorises once per run, on the nonlinear block once per Newton iteration.",
      kPropertiesFloorSteps);
  t.columns = {{"integrator", "", "", ""},       {"problem", "", "", ""}, {"quantity", "", "", ""},
               {"per step", "", "{:.3g}", ""},      {"count", "", "", "over the run"}, {"steps", "", "", ""},
               {"note", "", "", "why a row is n/a"}};
  Figure f{"properties_explicit", "Claim (1): work per step, per scheme", "integrator", "per step", {"quantity"}, {"problem"}};
  f.kind = "bars";
  f.caption = "Factorisations, linear solves and F_int evaluations per step of each scheme on the Signorini bar (linear, "
              "lumped, N 100, dt 0.9 h/c: as claimed) and the spinning SVK block on the floor (nonlinear: beyond); "
              "explicit: 0, 0 and 1. Counts, deterministic; the table properties_explicit has them with the steps.";
  t.figures = {f};
  t.lead_figures = true;
  for (const auto& [name, r] : rows) {
    if (find_integrator(name).peer) continue;
    for (const auto& [problem, run] : {std::pair<const char*, const Json*>{"Signorini bar (as claimed)", &r["bar_work"]},
                                       std::pair<const char*, const Json*>{"SVK block on the floor (beyond)", &r["block"]}})
      for (const auto& [quantity, key] : {std::pair<const char*, const char*>{"factorisations", "factorizations"},
                                          std::pair<const char*, const char*>{"linear solves", "solves"},
                                          std::pair<const char*, const char*>{"F_int evaluations", "forces"}})
        t.add_row({name, problem, quantity, per(*run, key, "steps"), count(*run, key), count(*run, "steps"), run_note(*run)});
  }
  return t;
}

// Claim (6)'s figure: LCP iterations per contact step, per scheme and kind of contact.
Table contact_cost_table(const Rows& rows) {
  Table t;
  t.id = "properties_contact_cost";
  t.title = "Claim (6) per scheme: LCP iterations per contact step, H diagonal and not";
  t.caption = fmt::format(
      "LCP iterations per step with a contact (an impulse > 0) of each scheme and peer, counted by the scheme (an LCP "
      "with a diagonal Delassus operator H = L M^-1 L^T is solved in closed form: 0 iterations; otherwise projected "
      "Gauss-Seidel to 1e-12, solvers/lcp.hpp; Siconos' Lemke pivots for its peers). Node on the rigid floor: the spinning "
      "SVK block's floor run ({} steps; H diagonal). Two bars: two-bars with its defaults (L1 1, L2 2, N1 50, N2 100, "
      "lumped, e = 0), dt 0.9 x its stable step, to t = 2 L2 / c: contact between two bodies through one contact row (H "
      "1 x 1). Two blocks: two-blocks as the bodies study runs it (no gravity, upper block at (0.5, -1) m/s, e = 0, "
      "mu = 0), dt 1e-4 s to 0.1 s: node-to-segment contacts between two deformable bodies (H not diagonal). n/a: the "
      "scheme declined the problem (note).",
      kPropertiesFloorSteps);
  t.columns = {{"integrator", "", "", ""},     {"contact", "", "", ""},       {"H", "", "", "Delassus operator"},
               {"contact steps", "", "", ""}, {"LCP iterations", "", "", ""}, {"LCP it./contact step", "", "{:.3g}", ""},
               {"note", "", "", "why a row is n/a"}};
  Figure f{"properties_contact_cost", "Claim (6): LCP iterations per contact step, per scheme", "integrator",
           "LCP it./contact step", {"contact"}, {}};
  f.kind = "bars";
  f.caption = "LCP iterations per step with a contact: a node on the rigid floor (the spinning SVK block: H diagonal), two "
              "bars through one contact row (H 1 x 1), two deformable blocks in node-to-segment contact (H not diagonal). "
              "Counts, deterministic; schemes that declined all three are left out (the table properties_contact_cost).";
  t.figures = {f};
  t.lead_figures = true;
  for (const auto& [name, r] : rows) {
    for (const auto& [contact, h, run] : {std::tuple<const char*, const char*, const Json*>{"node on the rigid floor", "diagonal", &r["block"]},
                                          std::tuple<const char*, const char*, const Json*>{"two bars", "1 x 1", &r["two_bars"]},
                                          std::tuple<const char*, const char*, const Json*>{"two blocks", "not diagonal", &r["bodies"]}})
      t.add_row({name, contact, h, count(*run, "contact_steps"), count(*run, "lcp"),
                 per(*run, "lcp", "contact_steps"), run_note(*run)});
  }
  return t;
}

std::vector<Table> properties_tables(const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions&) {
  Table t;
  t.id = "properties";
  t.title = "Properties matrix: every scheme and peer against the talk's claims, measured";
  t.caption = fmt::format(
      "One row per scheme or peer (references left out), each figure measured for that scheme and judged by the rules of "
      "studies/claims.hpp (studies/properties.cpp); n/a: the scheme declined the problem. These rules and conditions are "
      "not the claims page's (claims.md: the talk's own conditions, the discrete energy balance, one-sided growth, 10^4 "
      "contact phases of a deformable body); where they differ, the claims page's verdict is the one under the talk's "
      "conditions. "
      "Explicit: factorisations and linear solves per step of the spinning 2D block on the frictionless floor ({} steps): "
      "holds when both are 0. Hausdorff: graphs converging (order >= {}, 95% interval above 0) of the {} per mass model on "
      "the Signorini and bouncing bars (N = 25..200, dt = 0.9 h/c; the contact node's displacement and velocity, the velocity "
      "at L/2, the contact force), singular mass as claimed, lumped beyond: all, some "
      "(conditional) or none. Momentum: the spinning block's linear and angular momentum, free flight ({} steps) and the "
      "angular balance with the impulses' moments on the floor, relative: <= {:g}. Impact energy: the largest |jump| in "
      "total energy across a contact phase of the bouncing bar, "
      "singular mass and lumped mass with e = 1: <= {:g}. Long-time energy (the claims study's runs: bouncing mass, e = 1, "
      "100 impacts, dt 1e-3; spring chain between walls, dt 0.02 s, 40 s): max |E - E_1| / E_1 over each half (the scheme's "
      "reported energy at every step, contact steps included), bounded without drift when both are <= {:g} and the second "
      "half's <= {:g} x the first's + {:g}; the adaptive step (cd-lagrange-adaptive only) exact when <= {:g}. Contact cost: LCP iterations per step with a contact (reported), on the block's floor run (H diagonal) and between "
      "two deformable blocks (two-blocks as the bodies study runs it, dt 1e-4 s to 0.1 s: H not diagonal). Robustness: the "
      "bouncing mass (e = 1, h0 1, dt 0.02 s) run to its {}th impact (at most 2x the exact flights' steps): holds with finite "
      "states, |E_end - E_1| / E_1 <= {:g} and penetration <= one step of travel at the impact speed. The notes also say what "
      "explains a large impact jump, measured in the run: a step above the scheme's own stable step with its contacts (the "
      "bar is run at 0.9 h/c for every scheme; cd-penalty's springs lower its limit, and the run is unstable), or the contact "
      "node's speed beyond 100 x the impact speed, the exact solution's being at most the impact speed and a lumped node's "
      "chatter a few times it (moreau-jean at theta = 1/2 on the "
      "singular mass: the theta-method leaves the massless node the equation theta F_k+1 + (1 - theta) F_k = 0, whose "
      "alternating mode, amplification -(1 - theta)/theta = -1, is undamped; its velocity grows in flight and the "
      "velocity-level impact law acts on it at the next impact). The long-time energy errors are of the reported energy at "
      "every step, contact steps included: schatzman-paoli's falls to about 0 and cd-penalty's by about half within an impact step (between "
      "impacts both keep it), which the bound of the no-drift rule counts.",
      kPropertiesFloorSteps, kHausdorffMinOrder, 2 * bar_graph_observables().size(), kFreeSteps, kMomentumTolerance, kImpactEnergy,
      kEnergyBounded, kEnergyDriftFactor, kEnergyRoundOff, kEnergyExact, kLongRunImpacts, kRobustEnergy);
  t.columns = {{"integrator", "", "", ""},
               {"factorisations/step", "", "{:.3g}", "spinning block on the floor"},
               {"solves/step", "", "{:.3g}", ""},
               {"explicit", "", "", "verdict"},
               {"H converging, singular", "", "", "of 8 graphs"},
               {"H as claimed", "", "", "verdict"},
               {"H converging, lumped", "", "", "of 8 graphs"},
               {"H beyond", "", "", "verdict"},
               {"P residual", "", "{:.2e}", "relative"},
               {"J residual", "", "{:.2e}", "relative"},
               {"momentum", "", "", "verdict"},
               {"impact jump, singular", "", "{:.2e}", "relative"},
               {"impact as claimed", "", "", "verdict"},
               {"impact jump, lumped e=1", "", "{:.2e}", "relative"},
               {"impact beyond", "", "", "verdict"},
               {"E err, 1st half", "", "{:.2e}", "long runs, fixed step"},
               {"E err, 2nd half", "", "{:.2e}", ""},
               {"no drift", "", "", fmt::format("verdict: bounded (<= {:g}) and no drift", kEnergyBounded)},
               {"E err, adaptive", "", "{:.2e}", "long runs, adaptive step"},
               {"adaptive exact", "", "", "verdict (n/a: no adaptive step)"},
               {"LCP it./contact step", "", "{:.3g}", "block on the floor (H diagonal), reported"},
               {"LCP it./contact step, bodies", "", "{:.3g}", "two blocks (H not diagonal), reported"},
               {"impacts reached", "", "", "of the long run's target"},
               {"E_end error", "", "{:.2e}", "(E_end - E_1) / E_1"},
               {"penetration", "", "{:.3g}", "largest, over one step of travel"},
               {"robust", "", "", "verdict"},
               {"notes", "", "", "why a cell is n/a (declined, failed), what explains a large impact jump"}};
  Figure map{"properties", "Properties matrix: verdict per scheme and property", "", "integrator", {}, {"integrator"}};
  map.kind = "verdict_map";
  map.values = {"explicit", "H as claimed", "H beyond", "momentum", "impact as claimed", "impact beyond", "no drift", "adaptive exact", "robust"};
  map.caption = "Green: holds; amber: holds under conditions (some of the graphs); red: fails; grey: n/a (declined). "
                "The figures behind each cell are in the properties table.";
  t.figures = {map};
  t.lead_figures = true;  // the matrix at the top; its table, linked, holds the figures behind each cell
  const Rows rows = merged_rows(cases, results);
  for (const auto& [name, r] : rows) {
    const Json& b = r["block"];
    const bool block = !b.contains("note");
    const auto num = [&](const char* key) { return block && !b[key].is_null() ? Cell{real(b[key])} : Cell{}; };
    const Json& hs = r["hausdorff"]["singular"];
    const Json& hl = r["hausdorff"]["lumped"];
    const Json& is = r["impact"]["singular"];
    const Json& il = r["impact"]["lumped"];
    const std::string explicit_v =
        !block ? "n/a" : real(b["factorizations_per_step"]) == 0.0 && real(b["solves_per_step"]) == 0.0 ? "holds" : "fails";
    const std::string momentum_v = !block ? "n/a" : short_verdict(momentum_verdict(real(b["linear"]), real(b["angular"])));
    t.add_row({name, num("factorizations_per_step"), num("solves_per_step"), explicit_v,
               hausdorff_cell(hs), hausdorff_verdict_cell(hs), hausdorff_cell(hl), hausdorff_verdict_cell(hl), num("linear"),
               num("angular"), momentum_v, impact_cell(is), impact_verdict_cell(is), impact_cell(il), impact_verdict_cell(il),
               field(r["energy"], "first"), field(r["energy"], "second"), drift_verdict_cell(r["energy"]), field(r["energy"], "adaptive"),
               adaptive_verdict_cell(r["energy"]),
               num("lcp_per_contact_step"), bodies_cell(r["bodies"]), robust_impacts(r["robust"]), field(r["robust"], "energy"),
               field(r["robust"], "penetration"), robust_verdict_cell(r["robust"]), notes(r)});
  }
  return {t, explicit_work_table(rows), contact_cost_table(rows)};
}

}  // namespace

extern const StudyEntry properties_study = {
    "properties", "every scheme and peer against the talk's claims: a matrix of measured figures and verdicts", nullptr,
    &properties_cases, &properties_case, &properties_tables, &integrators_named};

}  // namespace nsb
