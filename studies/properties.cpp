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
//   robustness    the claims study's long run (the bouncing mass, e = 1, dt 0.02 s, to its 1e5th
//                 impact): finite states, |E_end - E_1| / E_1 <= 1e-2, penetration <= one step
//                 of travel (robustness_verdict)
// A scheme that declines a problem (a singular mass, a nonlinear body) has n/a there.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "integrators/registry.hpp"
#include "studies/claims.hpp"
#include "studies/claims_conditions.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

constexpr long kFreeSteps = 10'000, kFloorSteps = 2000, kLongRunImpacts = 100'000;

std::vector<Json> properties_cases(const StudyOptions&) {
  std::vector<Json> cases;
  for (const auto& entry : integrator_registry())
    if (!entry.reference) cases.push_back({{"integrator", entry.name}});
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

Json properties_case(const Json& c) {
  const std::string name = c["integrator"];
  Json out;
  const SpinningBlock b = spinning_block(name, kFreeSteps, kFloorSteps);
  if (b.note.empty()) {
    const double steps = static_cast<double>(std::max(1L, b.work.steps));
    out["block"] = {{"factorizations_per_step", static_cast<double>(b.work.factorizations) / steps},
                    {"solves_per_step", static_cast<double>(b.work.linear_solves) / steps},
                    {"lcp_per_contact_step", b.contact_steps > 0 ? real(static_cast<double>(b.work.lcp_iterations) / static_cast<double>(b.contact_steps)) : Json(nullptr)},
                    {"linear", real(b.free_linear)},
                    {"angular", real(std::max(b.free_angular, b.floor_angular))}};
  } else {
    out["block"] = {{"note", b.note}};
  }
  const auto fits = bar_hausdorff(name, {"singular", "lumped"});
  out["hausdorff"] = {{"singular", bar_counts(fits, "singular")}, {"lumped", bar_counts(fits, "lumped")}};
  const EnergyFigures energy = energy_runs(name);
  if (!energy.note.empty())
    out["energy"] = {{"note", energy.note}};
  else if (name == "cd-lagrange-adaptive")
    out["energy"] = {{"adaptive", real(energy.adaptive)}, {"completed", energy.adaptive_ok}, {"cfl", real(energy.cfl)}};
  else
    out["energy"] = {{"first", real(energy.first)}, {"second", real(energy.second)}};
  const BodiesCost bodies = bodies_contact_cost(name);
  if (bodies.note.empty())
    out["bodies"] = {{"lcp_per_contact_step", bodies.contact_steps > 0 ? real(static_cast<double>(bodies.work.lcp_iterations) / static_cast<double>(bodies.contact_steps)) : Json(nullptr)}};
  else
    out["bodies"] = {{"note", bodies.note}};
  const LongRun l = long_run(name, kLongRunImpacts);
  if (l.note.empty())
    out["robust"] = {{"ok", l.ok}, {"impacts", l.impacts}, {"energy", real(l.energy)}, {"penetration", real(l.penetration)}};
  else
    out["robust"] = {{"note", l.note}};
  out["impact"] = {{"singular", impact_json(bar_impact_energy(name, "singular", 0.0), "singular")},
                   {"lumped", impact_json(bar_impact_energy(name, "lumped", 1.0), "lumped e=1")}};
  return out;
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

std::vector<Table> properties_tables(const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions&) {
  Table t;
  t.id = "properties";
  t.title = "Properties matrix: every scheme and peer against the talk's claims, measured";
  t.caption = fmt::format(
      "One row per scheme or peer (references left out), each figure measured by the claims study's measurement for that "
      "scheme and judged by its rule (studies/properties.cpp, studies/claims.hpp); n/a: the scheme declined the problem. "
      "Explicit: factorisations and linear solves per step of the spinning 2D block on the frictionless floor ({} steps): "
      "holds when both are 0. Hausdorff: graphs converging (order >= {}, 95% interval above 0) of the {} per mass model on "
      "the Signorini and bouncing bars (N = 25..200, dt = 0.9 h/c; observables as in "
      "[claims_hausdorff_bars](claims_hausdorff_bars.md)), singular mass as claimed, lumped beyond: all, some "
      "(conditional) or none. Momentum: the spinning block's linear and angular momentum, free flight ({} steps) and the "
      "angular balance with the impulses' moments on the floor, relative: <= {:g}. Impact energy: the largest |jump| in "
      "total energy across a contact phase of the bouncing bar ([claims_impact_energy](claims_impact_energy.md)), "
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
      kFloorSteps, kHausdorffMinOrder, 2 * bar_graph_observables().size(), kFreeSteps, kMomentumTolerance, kImpactEnergy,
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
  t.lead = true;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& r = results[k];
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
    t.add_row({cases[k]["integrator"].get<std::string>(), num("factorizations_per_step"), num("solves_per_step"), explicit_v,
               hausdorff_cell(hs), hausdorff_verdict_cell(hs), hausdorff_cell(hl), hausdorff_verdict_cell(hl), num("linear"),
               num("angular"), momentum_v, impact_cell(is), impact_verdict_cell(is), impact_cell(il), impact_verdict_cell(il),
               field(r["energy"], "first"), field(r["energy"], "second"), drift_verdict_cell(r["energy"]), field(r["energy"], "adaptive"),
               adaptive_verdict_cell(r["energy"]),
               num("lcp_per_contact_step"), bodies_cell(r["bodies"]), robust_impacts(r["robust"]), field(r["robust"], "energy"),
               field(r["robust"], "penetration"), robust_verdict_cell(r["robust"]), notes(r)});
  }
  return {t};
}

}  // namespace

extern const StudyEntry properties_study = {
    "properties", "every scheme and peer against the talk's claims: a matrix of measured figures and verdicts", nullptr,
    &properties_cases, &properties_case, &properties_tables};

}  // namespace nsb
