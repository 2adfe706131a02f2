// Study "claims": one row per claim of the last slide of A. Gravouil's talk "CD-Lagrange"
// (2022), each with the measurement that tests it, the figure, and the verdict computed from
// the figure by the rules of studies/claims.hpp. The few runs it needs are redone here (a few
// seconds), so the verdicts never depend on what else was run into the output directory:
//   (1), (6)  cd-lagrange on the Signorini bar (lumped, N 100, dt 0.9 h/c, to t0 + 1.5 T), the
//             rolling disk (h0 0.05, omega0 20, e 0.5, mu 0.3; dt 1e-3 to 1.2 rest times) and the
//             spring chain between two walls (n 3, e 1, dt 0.5 stable step, to 20 s): work counters
//   (2)       cd-lagrange in the hausdorff study's grid (studies/builtin/hausdorff.toml, hausdorff_orders)
//   (3)       the rolling disk run: linear (x, y) and angular momentum about the origin,
//                 J = m (x_c v_y - y_c v_x) + I omega,  x_c = x, y_c = y + R,
//             against the impulses: J_{k} - J_{k-1} = x_c G_y - y_c G_x + G_theta with
//             G = tau F_ext + L^T Lambda_N + T^T Lambda_T at the step's position (the discrete
//             momentum map q_{k+1} x p_{k+3/2}: q_{k+1} - q_k is parallel to p_{k+1/2}); the
//             chain run: 1^T M v against the wall impulses (the springs' forces cancel). From the
//             state after the first step (the start's half kick is not a full step)
//   (4), (5)  the energy study's long runs with e = 1 (bouncing mass, dt 1e-3, 100 impacts;
//             spring chain between walls, dt 0.02 s, 40 s): cd-lagrange's own energy over each
//             half; cd-lagrange-adaptive's over the run, its steps against the stable step
//   (5)       as claimed, the talk's adaptive algorithm (its update of tau_{k+2}), beyond it the
//             suite's energy-balance step, on the lumped bouncing bar through its first impact
//             (studies/claims_conditions.hpp, adaptive_steps): the steps against time
//   (7)       the bouncing mass, e = 1, h0 = 1 (period 0.903 s), dt = 0.02 s, stepped to its
//             1e5th impact (1e6 with --full): final energy error, largest penetration
#include "studies/claims.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/registry.hpp"
#include "studies/claims_conditions.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"

namespace nsb {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Holds: return "holds";
    case Verdict::Conditional: return "holds under the stated conditions";
    case Verdict::Fails: return "fails";
  }
  return "";
}

Verdict explicit_verdict(long runs, long steps, long force_evaluations, long factorizations, long linear_solves) {
  return steps > 0 && factorizations == 0 && linear_solves == 0 && force_evaluations <= steps + runs ? Verdict::Holds : Verdict::Fails;
}

bool hausdorff_converges(const OrderFit& fit) { return fit.order >= kHausdorffMinOrder && fit.low > 0.0; }

Verdict hausdorff_verdict(const std::vector<OrderFit>& per_problem) {
  const auto n = std::count_if(per_problem.begin(), per_problem.end(), hausdorff_converges);
  if (n == 0) return Verdict::Fails;
  return n == static_cast<long>(per_problem.size()) ? Verdict::Holds : Verdict::Conditional;
}

Verdict conditions_verdict(const std::vector<bool>& met) {
  const auto n = std::count(met.begin(), met.end(), true);
  if (n == 0) return Verdict::Fails;
  return n == static_cast<long>(met.size()) ? Verdict::Holds : Verdict::Conditional;
}

Verdict momentum_verdict(double linear_residual, double angular_residual) {
  return linear_residual <= kMomentumTolerance && angular_residual <= kMomentumTolerance ? Verdict::Holds : Verdict::Fails;
}

bool energy_no_drift(double fixed_first_half, double fixed_second_half) {
  return fixed_first_half <= kEnergyBounded && fixed_second_half <= kEnergyBounded &&
         fixed_second_half <= kEnergyDriftFactor * fixed_first_half + kEnergyRoundOff;
}

bool impact_energy_kept(long phases, double worst_jump) { return phases > 0 && worst_jump <= kImpactEnergy; }

Verdict energy_verdict(double fixed_first_half, double fixed_second_half, double adaptive_max) {
  const bool fixed = energy_no_drift(fixed_first_half, fixed_second_half);
  const bool adaptive = adaptive_max <= kEnergyExact;
  return fixed && adaptive ? Verdict::Holds : fixed || adaptive ? Verdict::Conditional : Verdict::Fails;
}

Verdict adaptive_verdict(bool completed, double largest_step_over_stable, double largest_step, double smallest_step,
                         long collapsed_steps) {
  return completed && largest_step_over_stable <= 1.0 && largest_step > (1.0 + 1e-6) * smallest_step && collapsed_steps == 0
             ? Verdict::Holds
             : Verdict::Fails;
}

Verdict lcp_verdict(long contact_steps, long lcp_iterations, long factorizations, long linear_solves) {
  return contact_steps > 0 && lcp_iterations == 0 && factorizations == 0 && linear_solves == 0 ? Verdict::Holds : Verdict::Fails;
}

Verdict robustness_verdict(bool completed, long impacts, long target, double energy_error, double penetration_over_step) {
  return completed && impacts >= target && std::abs(energy_error) <= kRobustEnergy && penetration_over_step <= 1.0 ? Verdict::Holds
                                                                                                                   : Verdict::Fails;
}

namespace {


struct Work {
  long runs = 0, steps = 0, forces = 0, factorizations = 0, solves = 0, lcp = 0, contact_steps = 0;
  void add(const WorkCounters& w, long contacts) {
    ++runs;
    steps += w.steps;
    forces += w.force_evaluations;
    factorizations += w.factorizations;
    solves += w.linear_solves;
    lcp += w.lcp_iterations;
    contact_steps += contacts;
  }
};

struct Momentum {
  double linear = 0.0, angular = 0.0;  // largest residuals, relative
};

std::unique_ptr<Problem> problem_of(const std::string& name, const std::map<std::string, std::string>& p) { return make_problem(name, p); }

// cd-lagrange on the rolling disk: work, and the linear and angular momentum residuals.
void disk_run(Work& work, Momentum& m) {
  const auto problem = problem_of("rolling-disk", {{"h0", "0.05"}, {"omega0", "20"}, {"e", "0.5"}, {"mu", "0.3"}});
  const double R = problem->parameters().real("R");
  const double t_end = 1.2 * problem->exact()->event_time(ExactEvent::rest).value();
  const Vec M = problem->mass_matrix().diagonal();
  auto it = make_integrator("cd-lagrange");
  it->init(*problem, problem->initial_state());
  Vec f(3), G(3);
  problem->external_force(0.0, f);
  const SpMat Lt = SpMat(problem->contacts().normal.transpose()), Tt = SpMat(problem->contacts().tangent.transpose());
  double px = 0, py = 0, J = 0, scale_p = 0, scale_j = 0, res_p = 0, res_j = 0;
  bool first = true;
  long contacts = 0;
  RunOptions o;
  o.dt = 1e-3;
  o.t_end = t_end;
  o.record_series = false;
  run(*problem, *it, o, [&](const Integrator& in, const StepInfo& info) {
    const State& s = in.state();
    const double xc = s.u[0], yc = s.u[1] + R;
    const double qx = M[0] * s.v[0], qy = M[1] * s.v[1], q = M[0] * (xc * s.v[1] - yc * s.v[0]) + M[2] * s.v[2];
    contacts += in.impulses().sum() > 0.0;
    if (!first) {
      G = info.dt * f + Lt * in.impulses() + Tt * in.tangential_impulses();
      px += G[0], py += G[1], J += xc * G[1] - yc * G[0] + G[2];
      res_p = std::max({res_p, std::abs(qx - px), std::abs(qy - py)});
      res_j = std::max(res_j, std::abs(q - J));
    } else {
      px = qx, py = qy, J = q;
      first = false;
    }
    scale_p = std::max({scale_p, std::abs(qx), std::abs(qy)});
    scale_j = std::max(scale_j, std::abs(q));
  });
  work.add(it->work(), contacts);
  m.linear = std::max(m.linear, res_p / scale_p);
  m.angular = std::max(m.angular, res_j / scale_j);
}

// cd-lagrange on the spring chain between two walls: work and 1^T M v against the impulses.
void chain_run(Work& work, Momentum& m) {
  const auto problem = problem_of("spring-chain", {{"n", "3"}, {"wall", "both"}, {"e", "1"}});
  const Vec M = problem->mass_matrix().diagonal();
  auto it = make_integrator("cd-lagrange");
  it->init(*problem, problem->initial_state());
  double P = 0, scale = 0, res = 0;
  bool first = true;
  long contacts = 0;
  RunOptions o;
  o.dt = 0.5 * problem->stable_step();
  o.t_end = 20.0;
  o.record_series = false;
  run(*problem, *it, o, [&](const Integrator& in, const StepInfo&) {
    const double p = M.dot(in.state().v);
    contacts += in.impulses().sum() > 0.0;
    if (first) {
      P = p;
      first = false;
    } else {
      P += (problem->gap_operator().transpose() * in.impulses()).sum();
      res = std::max(res, std::abs(p - P));
    }
    scale = std::max(scale, std::abs(p));
  });
  work.add(it->work(), contacts);
  m.linear = std::max(m.linear, res / scale);
}

void bar_run(Work& work) {
  const RunWork bar = signorini_bar_work("cd-lagrange");
  work.add(bar.work, bar.contact_steps);
}

std::string fmt_g(double v) { return std::isnan(v) ? "n/a" : fmt::format("{:.3g}", v); }

// The new measurements of the two-column table (studies/claims_conditions.hpp), for cd-lagrange.
struct Conditions {
  std::vector<BarGraphFit> bars;
  ImpactEnergy singular, lumped_inelastic, lumped_elastic, consistent;
  SpinningBlock block;
  RunWork bodies;
  std::vector<AdaptiveSteps> adaptive;  // the talk's rule, then the energy balance
};

constexpr long kFreeFlightSteps = 100'000, kClaimsFloorSteps = 2000;

Conditions conditions_runs() {
  Conditions c;
  c.bars = bar_hausdorff("cd-lagrange", {"singular", "lumped", "consistent"});
  c.singular = bar_impact_energy("cd-lagrange", "singular", 0.0);
  c.lumped_inelastic = bar_impact_energy("cd-lagrange", "lumped", 0.0);
  c.lumped_elastic = bar_impact_energy("cd-lagrange", "lumped", 1.0);
  c.consistent = bar_impact_energy("cd-lagrange", "consistent", 1.0);
  c.block = spinning_block("cd-lagrange", kFreeFlightSteps, kClaimsFloorSteps);
  c.bodies = bodies_contact_cost("cd-lagrange");
  c.adaptive = {adaptive_steps("talk"), adaptive_steps("energy-balance")};
  return c;
}

// The Hausdorff table of the bars: one row per (problem, mass, observable), distances per level.
Table bar_hausdorff_table(const std::vector<BarGraphFit>& bars) {
  Table t;
  t.id = "claims_hausdorff_bars";
  t.title = "Claim (2) on the bars: Hausdorff distance per mass model and observable, cd-lagrange";
  t.caption = fmt::format(
      "Graph of each observable of cd-lagrange's run against the exact one (jumps as vertical segments), Hausdorff distance "
      "in scaled (t / T, x / X) coordinates, T = t_end, X = the exact graph's largest |value| (studies/claims_conditions.hpp). "
      "Space and time refined together: N = 25, 50, 100, 200, dt = 0.9 h / c. signorini-bar: v0 1, to 1.5 contact durations; "
      "bouncing-bar: Doyen-Ern-Piperno's drop, to one period after the first impact. Order: least-squares slope in dt with "
      "its 95% interval; converges: order >= {} with the interval's low end > 0.",
      kHausdorffMinOrder);
  t.columns = {{"problem", "", "", ""}, {"mass", "", "", ""}, {"observable", "", "", ""}, {"dt", "", "{:.3e}", "step"},
               {"Hausdorff", "", "{:.3e}", "scaled distance"}, {"order", "", kOrderFormat, ""}, {"CI low", "", kOrderFormat, ""},
               {"converges", "", "", ""}, {"note", "", "", ""}};
  t.figures = {{"claims_hausdorff_bars", "Claim (2): Hausdorff distance on the bars against the step", "dt", "Hausdorff",
                {"mass", "observable"}, {"problem"}, true, true, {1.0, 0.5}}};
  t.figures[0].caption = "cd-lagrange on the Signorini and bouncing bars, N and dt refined together; the rows of "
                         "claims_hausdorff_bars give the orders and which graphs converge.";
  t.lead_figures = true;
  for (const auto& f : bars)
    for (std::size_t k = 0; k < f.dt.size(); ++k)
      t.add_row({f.problem, f.mass, f.observable, f.dt[k], number_cell(f.distance[k]), number_cell(f.fit.order),
                 number_cell(f.fit.low), f.note.empty() ? (hausdorff_converges(f.fit) ? "yes" : "no") : "n/a", f.note});
  return t;
}

// A csv-only table behind one figure of the first page (a claim's figure).
Table claim_figure_table(std::string id, std::string title, std::vector<Column> columns, Figure figure) {
  Table t;
  t.id = std::move(id);
  t.csv_only = true;
  t.lead_figures = true;
  t.title = std::move(title);
  t.columns = std::move(columns);
  t.figures = {std::move(figure)};
  return t;
}

// The adaptive steps of (5) against time, thinned to the rows where the step moved by more than
// 1e-3 (relative), the contact flag changed, or 100 steps went by (the figure's line is the same).
Table adaptive_steps_table(const std::vector<AdaptiveSteps>& runs) {
  Figure f{"claims_adaptive_steps", "Claim (5): the adaptive step against time, the talk's update and the energy balance", "t", "dt",
           {"rule"}, {}, false, true};
  f.caption = "cd-lagrange-adaptive on the lumped bouncing bar (N 100, e 0), first step 0.9 h/c, to the first impact + one period; "
              "the rows of claims_adaptive_step say where the contact phases are and where the step collapsed.";
  Table t = claim_figure_table("claims_adaptive_steps", "Claim (5): the adaptive step against time through the bouncing bar's first impact",
                               {{"rule", "", "", ""}, {"t", "s", "{:.6e}", ""}, {"dt", "s", "{:.6e}", ""}, {"contact", "", "", "impulse on the contact node"}},
                               f);
  for (const auto& r : runs) {
    std::size_t kept = 0;
    for (std::size_t k = 0; k < r.t.size(); ++k) {
      const bool keep = k == 0 || k + 1 == r.t.size() || r.contact[k] != r.contact[kept] || k - kept >= 100 ||
                        std::abs(r.dt[k] / r.dt[kept] - 1.0) > 1e-3;
      if (!keep) continue;
      t.add_row({r.rule, r.t[k], r.dt[k], r.contact[k] ? 1L : 0L});
      kept = k;
    }
  }
  return t;
}

// Claim (3)'s figure: the spinning block's angular momentum balance residual per step on the floor.
Table momentum_history_table(const SpinningBlock& b) {
  Figure f{"claims_momentum_history", "Claim (3): angular momentum balance residual of the spinning block on the floor", "t",
           "J residual", {}, {}};
  f.caption = "cd-lagrange, 2D SVK block spinning at 3 rad/s dropped on the frictionless floor: |J_k - J_{k-1} - the moments "
              "of the weight and of the impulses| per step, relative to the momentum scale (round-off: holds at <= 1e-10).";
  Table t = claim_figure_table("claims_momentum_history", "Claim (3): the spinning block's angular momentum balance on the floor, per step",
                               {{"t", "s", "{:.6e}", ""}, {"J residual", "", "{:.3e}", "relative"}}, f);
  for (const auto& [time, residual] : b.floor_history) t.add_row({time, residual});
  return t;
}

// Claim (4)'s figure: the bouncing bar's total energy against time, per mass model and e.
Table impact_history_table(const std::vector<std::pair<std::string, const ImpactEnergy*>>& runs) {
  Figure f{"claims_impact_energy_history", "Claim (4): total energy of the bouncing bar across its contact phases", "t", "E - E_0",
           {"run"}, {}};
  f.caption = "cd-lagrange on Doyen-Ern-Piperno's bouncing bar (N 100, dt 0.9 h/c), every 10th step; the jumps per contact "
              "phase are in claims_impact_energy.";
  Table t = claim_figure_table("claims_impact_energy_history", "Claim (4) at impact: the bouncing bar's total energy against time",
                               {{"run", "", "", ""}, {"t", "s", "{:.6e}", ""}, {"E - E_0", "", "{:.6e}", "over the impact's kinetic energy"}},
                               f);
  for (const auto& [name, r] : runs)
    for (const auto& [time, e] : r->history) t.add_row({name, time, e});
  return t;
}

// Claim (7)'s figure: the long run's energy error against the impact count.
Table long_run_table(const LongRun& l) {
  Figure f{"claims_long_run", "Claim (7): energy error of the bouncing mass over its impacts", "impacts", "(E - E_1)/E_1", {}, {}, true};
  f.caption = fmt::format("cd-lagrange, bouncing mass, e = 1, h0 = 1, dt = 0.02 s, to its {}th impact; every {}th impact.",
                          l.target, std::max(1L, l.target / 100));
  Table t = claim_figure_table("claims_long_run", "Claim (7): the bouncing mass's energy error against its impacts",
                               {{"impacts", "", "", ""}, {"(E - E_1)/E_1", "", "{:.6e}", ""}}, f);
  for (const auto& [impacts, e] : l.history) t.add_row({impacts, e});
  return t;
}

// The first step at tau_min: its time, and whether the contact node was in contact then.
std::string first_collapse(const AdaptiveSteps& r) {
  for (std::size_t k = 0; k < r.t.size(); ++k)
    if (r.dt[k] <= r.tau_min * (1.0 + 1e-12)) return fmt::format("t = {:.4g} s ({})", r.t[k], r.contact[k] ? "in contact" : "in flight");
  return "none";
}

Table adaptive_step_table(const std::vector<AdaptiveSteps>& runs) {
  Table t;
  t.id = "claims_adaptive_step";
  t.lead = true;  // short: on the first page beside the claims
  t.title = "Claim (5): the talk's update of tau_{k+2} beside the energy-balance step, cd-lagrange-adaptive on the bouncing bar";
  t.caption = fmt::format(
      "Doyen-Ern-Piperno's bouncing bar, lumped mass, N = 100, e = 0 (the talk's LCP), first requested step 0.9 h / c, to the "
      "first impact (t = {:.4g} s) + one period 16 L / c, at most {} steps. talk: the talk's algorithm (step_rule talk: its "
      "equation for tau_{{k+2}} iterated to a fixed point; momentum talk; impulses doing no work); energy-balance: the suite's "
      "step, the root of the discrete energy balance (integrators/cd_lagrange_adaptive.hpp). Collapsed: steps at the floor "
      "tau_min = 1e-3 x the first step. Energy residual: the largest |E_{{k+3/2}} - E_{{k+1/2}} - W| over the energy terms of the "
      "steps taken. Why the talk's step runs to a bound: U_{{k+2}} - U_{{k+1}} = tau_{{k+2}} M^{{-1}} P_{{k+3/2}} makes its update's "
      "numerator tau_{{k+2}} T(P_{{k+3/2}}), so each update multiplies the step by T(P_{{k+3/2}}) / D, and D holds F_ext^T U and "
      "Psi(U) at U_{{k+1}}, not differences: its fixed point T = D has no isolated root in tau_{{k+2}}, the ratio stays on one "
      "side of 1 and the step goes to the CFL cap in flight (U = 0 at the drop, D - T a small defect) and to tau_min once the "
      "contact has turned the defect's sign; on the bouncing mass, whose U = 0 is the floor, it falls to tau_min in free flight "
      "(tests/integrators/cd_lagrange_adaptive_test.cpp).",
      runs.front().impact_time, kAdaptiveMaxSteps);
  t.columns = {{"rule", "", "", ""}, {"steps", "", "", ""}, {"contact steps", "", "", ""}, {"smallest dt / stable", "", "{:.3e}", ""},
               {"largest dt / stable", "", "{:.3f}", ""}, {"collapsed", "", "", "steps at tau_min"}, {"first collapse", "", "", ""},
               {"at tau_up", "", "", "CFL or user cap"}, {"unsettled", "", "", "no fixed point / root in max_iter"},
               {"energy residual", "", "{:.2e}", "relative"}, {"max |E - E_1|", "", "{:.2e}", "over the impact's kinetic energy"}, {"t reached", "s", "{:.4g}", ""},
               {"verdict", "", "", "adaptive-step rule"}, {"note", "", "", ""}};
  for (const auto& r : runs)
    t.add_row({r.rule, r.steps, r.contact_steps, number_cell(r.dt_min / r.stable_step), number_cell(r.dt_max / r.stable_step),
               r.collapsed, first_collapse(r), r.capped, r.unconverged, number_cell(r.energy_residual), number_cell(r.energy_error),
               r.t_reached, verdict_name(adaptive_verdict(r.completed, r.dt_max / r.stable_step, r.dt_max, r.dt_min, r.collapsed)),
               r.note});
  return t;
}

Table impact_energy_table(const Conditions& c) {
  Table t;
  t.id = "claims_impact_energy";
  t.lead = true;  // short: on the first page beside the claims
  t.title = "Claim (4) at impact: the jump in total energy across each contact phase, cd-lagrange on the bouncing bar";
  t.caption = fmt::format(
      "Doyen-Ern-Piperno's bouncing bar, N = 100, dt = 0.9 h / c, to the first impact + 3 periods 16 L / c. A contact phase: "
      "the steps with an impulse on the contact node, gaps shorter than L / c merged. Jump: the scheme's total energy "
      "(kinetic + strain + weight) after the phase minus before it, over the kinetic energy at the first impact. Kept: "
      "every |jump| <= {:g}.",
      kImpactEnergy);
  t.columns = {{"mass", "", "", ""}, {"e", "", "", "restitution of the contact node"}, {"contact phases", "", "", ""},
               {"contact steps", "", "", ""}, {"largest |jump|", "", "{:.3e}", "relative"}, {"its sign", "", "{:.3e}", "signed"},
               {"kept", "", "", ""}, {"note", "", "", ""}};
  const auto row = [&](const char* mass, double e, const ImpactEnergy& r) {
    t.add_row({mass, e, r.phases, r.contact_steps, r.note.empty() ? Cell{r.worst_jump} : Cell{}, r.note.empty() ? Cell{r.worst_signed} : Cell{},
               r.note.empty() ? (impact_energy_kept(r.phases, r.worst_jump) ? "yes" : "no") : "n/a", r.note});
  };
  row("singular", 0.0, c.singular);
  row("lumped", 0.0, c.lumped_inelastic);
  row("lumped", 1.0, c.lumped_elastic);
  row("consistent", 1.0, c.consistent);
  return t;
}

// Verdict of the Hausdorff claim over fits (declined ones left out) and its figure text.
struct HausdorffSummary {
  Verdict verdict = Verdict::Fails;
  std::string figure, converging, not_converging;
  long tested = 0;
};
HausdorffSummary summarise(const std::vector<std::pair<std::string, OrderFit>>& fits) {
  HausdorffSummary s;
  std::vector<OrderFit> kept;
  for (const auto& [name, fit] : fits) {
    kept.push_back(fit);
    std::string& list = hausdorff_converges(fit) ? s.converging : s.not_converging;
    list += (list.empty() ? "" : ", ") + name;
    s.figure += fmt::format("{}{} {}", s.figure.empty() ? "" : "; ", name, fmt_g(fit.order));
  }
  s.tested = static_cast<long>(kept.size());
  s.verdict = hausdorff_verdict(kept);
  return s;
}

std::string verdict_text(const HausdorffSummary& s) {
  if (s.verdict != Verdict::Conditional) return verdict_name(s.verdict);
  return fmt::format("{}: converges on {}; not on {}", verdict_name(s.verdict), s.converging, s.not_converging);
}

std::vector<Table> claims_tables(const StudyOptions& options) {
  Work work, work_beyond;
  Momentum momentum;
  bar_run(work);
  disk_run(work, momentum);
  chain_run(work, momentum);
  const auto orders = hausdorff_orders("cd-lagrange");
  EnergyFigures energy = energy_runs("cd-lagrange");
  const EnergyFigures adaptive = energy_runs("cd-lagrange-adaptive");
  energy.adaptive = adaptive.adaptive, energy.cfl = adaptive.cfl, energy.dt_min = adaptive.dt_min, energy.dt_max = adaptive.dt_max;
  energy.no_root = adaptive.no_root, energy.adaptive_ok = adaptive.adaptive_ok;
  const LongRun longrun = long_run("cd-lagrange", options.full ? 1'000'000 : 100'000);
  const Conditions cond = conditions_runs();
  work_beyond.add(cond.singular.work, cond.singular.contact_steps);
  work_beyond.add(cond.block.work, cond.block.contact_steps);

  Table m;
  m.id = "claims_measures";
  m.title = "Claims of CD-Lagrange: the measured figures";
  m.caption = "The figures behind each verdict of the claims table, with the threshold the verdict rule compares them to.";
  m.columns = {{"claim", "", "", ""}, {"quantity", "", "", ""}, {"value", "", "{:.3e}", ""}, {"threshold", "", "", ""}};
  const auto measure = [&](long claim, const std::string& q, double v, const std::string& threshold) {
    m.add_row({claim, q, number_cell(v), threshold});
  };
  // A count is an integer cell: Markdown prints it whole, not in the value column's {:.3e}.
  const auto count = [&](long claim, const std::string& q, long n, const std::string& threshold) { m.add_row({claim, q, n, threshold}); };
  count(1, "steps (bar, disk, chain)", work.steps, "> 0");
  count(1, "F_int evaluations", work.forces, fmt::format("<= steps + {} (one start per run)", work.runs));
  count(1, "factorisations", work.factorizations, "0");
  count(1, "linear solves", work.solves, "0");
  count(1, "beyond: steps (singular bouncing bar, spinning block on the floor)", work_beyond.steps, "> 0");
  count(1, "beyond: F_int evaluations", work_beyond.forces, fmt::format("<= steps + {}", work_beyond.runs));
  count(1, "beyond: factorisations", work_beyond.factorizations, "0");
  count(1, "beyond: linear solves", work_beyond.solves, "0");
  std::vector<std::pair<std::string, OrderFit>> claimed_fits, beyond_fits;
  for (const auto& o : orders) {
    // The bars' lumped contact-node velocity is the bars' own row below: counted once.
    if (o.problem != "signorini-bar" && o.problem != "bouncing-bar") beyond_fits.emplace_back(o.problem + " (velocity)", o.hausdorff);
    measure(2, o.problem + ": Hausdorff order", o.hausdorff.order, fmt::format(">= {} and CI low > 0", kHausdorffMinOrder));
    measure(2, o.problem + ": Hausdorff order CI low", o.hausdorff.low, "> 0");
    measure(2, o.problem + ": max-norm order", o.max_error.order, "(reported)");
  }
  std::string declined;
  for (const auto& f : cond.bars) {
    const std::string name = fmt::format("{} {} {}", f.problem, f.mass, f.observable);
    if (f.note.rfind("declined", 0) == 0) {
      if (declined.find(f.mass) == std::string::npos) declined += (declined.empty() ? "" : ", ") + f.mass + " mass (" + f.note + ")";
      continue;
    }
    (f.mass == "singular" ? claimed_fits : beyond_fits).emplace_back(name, f.fit);
    measure(2, name + ": Hausdorff order", f.fit.order, fmt::format(">= {} and CI low > 0", kHausdorffMinOrder));
  }
  measure(3, "as claimed: spinning block, free flight: linear momentum drift", cond.block.free_linear, fmt::format("<= {:g}", kMomentumTolerance));
  measure(3, "as claimed: spinning block, free flight: angular momentum drift", cond.block.free_angular, fmt::format("<= {:g}", kMomentumTolerance));
  measure(3, "as claimed: spinning block on the floor: angular momentum balance residual", cond.block.floor_angular,
          fmt::format("<= {:g}", kMomentumTolerance));
  measure(3, "as claimed: spinning block on the floor: sum of |impulse moments|", cond.block.impulse_moment, "> 0 (reported)");
  measure(3, "linear momentum residual (disk, chain)", momentum.linear, fmt::format("<= {:g}", kMomentumTolerance));
  measure(3, "angular momentum residual (disk)", momentum.angular, fmt::format("<= {:g}", kMomentumTolerance));
  measure(4, "fixed step: max |E - E_1|/E_1, first half", energy.first, fmt::format("<= {:g}", kEnergyBounded));
  measure(4, "fixed step: max |E - E_1|/E_1, second half", energy.second,
          fmt::format("<= {:g} and <= {:g} x first half + {:g}", kEnergyBounded, kEnergyDriftFactor, kEnergyRoundOff));
  measure(4, "adaptive: max |E - E_1|/E_1", energy.adaptive, fmt::format("<= {:g}", kEnergyExact));
  count(4, "adaptive: steps without a root of the energy equation", static_cast<long>(energy.no_root), "(reported)");
  measure(4, "at impact, singular mass: largest |energy jump| per contact phase", cond.singular.worst_jump, fmt::format("<= {:g}", kImpactEnergy));
  measure(4, "at impact, lumped mass, e = 0: largest |energy jump|", cond.lumped_inelastic.worst_jump, fmt::format("<= {:g}", kImpactEnergy));
  measure(4, "at impact, lumped mass, e = 1: largest |energy jump|", cond.lumped_elastic.worst_jump, fmt::format("<= {:g}", kImpactEnergy));
  for (const auto& r : cond.adaptive) {
    const std::string on = (r.rule == "talk" ? "as claimed, the talk's update" : "beyond, the energy balance") + std::string(", bouncing bar: ");
    measure(5, on + "largest step / stable step", r.dt_max / r.stable_step, "<= 1");
    measure(5, on + "largest / smallest step", r.dt_max / r.dt_min, "> 1");
    count(5, on + "steps at tau_min", r.collapsed, "0");
    count(5, on + "reached t_end", r.completed ? 1L : 0L, "1");
  }
  measure(5, "beyond, the energy balance, long runs: largest step / stable step", energy.cfl, "<= 1");
  measure(5, "beyond, the energy balance, long runs: largest / smallest step", energy.dt_max / energy.dt_min, "> 1");
  count(5, "beyond, the energy balance, long runs: steps at tau_min", energy.collapsed, "0");
  count(6, "steps with an active contact", work.contact_steps, "> 0");
  count(6, "LCP iterations", work.lcp, "0");
  count(6, "beyond: two blocks, steps with an active contact", cond.bodies.contact_steps, "> 0");
  count(6, "beyond: two blocks, LCP iterations", cond.bodies.work.lcp_iterations, "0");
  count(7, "impacts", longrun.impacts, fmt::format(">= {}", longrun.target));
  count(7, "steps", longrun.steps, "(reported)");
  measure(7, "final (E - E_1)/E_1", longrun.energy, fmt::format("|.| <= {:g}", kRobustEnergy));
  measure(7, "largest penetration / (v_impact dt)", longrun.penetration, "<= 1");

  Table t;
  t.id = "claims";
  t.title = "Claims of CD-Lagrange (Gravouil 2022, last slide): verdicts as claimed and beyond";
  t.caption = fmt::format(
      "Each claim is tested under the talk's own conditions (as claimed: a deformable body against a rigid obstacle, a "
      "diagonal mass, the singular mass of the talk's line of work where the contact node matters) and beyond them "
      "(conditions the talk does not claim); each verdict is computed from the figures of claims_measures by a rule "
      "(studies/claims.hpp), and where a column has several conditions it holds when all are met, holds under the stated "
      "conditions when some are, fails when none is. (1) no factorisation or linear solve, <= 1 F_int evaluation per step; "
      "(2) a graph converges when the Hausdorff order of its distance to the exact graph is >= {} with the 95% interval above 0; "
      "(3) momentum residuals <= {:g} of the momentum scale; (4) energy errors against E_1 (after the first step), worst over "
      "the problems: fixed step bounded without drift (each half's error <= {:g}, the second half's <= {:g} x the first half's + {:g}), adaptive step exact (<= {:g}), "
      "and every contact phase changing the total energy by <= {:g} of the impact's kinetic energy; (5) steps <= the stable "
      "step and varying; (6) contacts active with 0 LCP iterations, factorisations and solves; (7) the run reaches its {}th "
      "impact with finite states, |E_end - E_1|/E_1 <= {:g} and penetration <= one step of travel.",
      kHausdorffMinOrder, kMomentumTolerance, kEnergyBounded, kEnergyDriftFactor, kEnergyRoundOff, kEnergyExact, kImpactEnergy, longrun.target,
      kRobustEnergy);
  t.columns = {{"#", "", "", ""}, {"claim (talk)", "", "", ""}, {"how nsbench tests it", "", "", ""}, {"figure", "", "", ""},
               {"verdict_as_claimed", "", "", ""}, {"conditions_as_claimed", "", "", ""}, {"verdict_beyond", "", "", ""},
               {"conditions_beyond", "", "", ""}, {"evidence", "", "", ""}};
  t.lead = true;
  t.add_row({1L, "Explicit time integration", "work counters of cd-lagrange's runs",
             fmt::format("{} F_int evaluations in {} steps, {} factorisations, {} linear solves; beyond: {} in {} steps, {} "
                         "factorisations, {} solves",
                         work.forces, work.steps, work.factorizations, work.solves, work_beyond.forces, work_beyond.steps,
                         work_beyond.factorizations, work_beyond.solves),
             verdict_name(explicit_verdict(work.runs, work.steps, work.forces, work.factorizations, work.solves)),
             "diagonal (lumped) mass, deformable/rigid contact: the Signorini bar (N 100), the rolling disk, a spring chain",
             verdict_name(explicit_verdict(work_beyond.runs, work_beyond.steps, work_beyond.forces, work_beyond.factorizations,
                                           work_beyond.solves)),
             "singular mass (massless contact node, solved in closed form) on the bouncing bar; a nonlinear (SVK) 2D block on the floor",
             "[claims_measures](claims_measures.md), [performance](performance.md)"});
  const HausdorffSummary claimed = summarise(claimed_fits), beyond = summarise(beyond_fits);
  t.add_row({2L, "Space-time convergence in the non-smooth sense (Hausdorff)",
             "graph of an observable against the exact one (jumps as vertical segments), Hausdorff distance in scaled "
             "coordinates, 4 refinements (bars: N and dt together)",
             fmt::format("Hausdorff orders, as claimed: {}; beyond: {}", claimed.figure, beyond.figure), verdict_text(claimed),
             "the singular mass (massless contact node) on the Signorini and bouncing bars, space and time refined together; "
             "observables: contact-node displacement and velocity, velocity at x = L/2, contact force",
             verdict_text(beyond),
             "the lumped mass on both bars (the same observables); the hausdorff study's other four problems (velocity)" +
                 (declined.empty() ? std::string() : "; not run: " + declined),
             "[claims_hausdorff_bars](claims_hausdorff_bars.md), [hausdorff_orders](hausdorff_orders.md)"});
  t.add_row({3L, "Discrete multi-symplectic form: linear and angular momentum balances, Lagrange multipliers included",
             "the reported (u, v) pair's momenta against the impulses' and forces' moments at the step's positions",
             fmt::format("spinning block: free flight ({} steps) P {:.2e}, J {:.2e}; on the floor J balance {:.2e} (impulse "
                         "moments {:.2e}); beyond: disk and chain P {:.2e}, J {:.2e} (relative)",
                         cond.block.free_steps, cond.block.free_linear, cond.block.free_angular, cond.block.floor_angular,
                         cond.block.impulse_moment, momentum.linear, momentum.angular),
             verdict_name(momentum_verdict(std::max(cond.block.free_linear, 0.0), std::max(cond.block.free_angular, cond.block.floor_angular))),
             fmt::format("a deformable body: the 2D SVK block spinning at 3 rad/s, in free flight for {} steps, then on the "
                         "frictionless floor for {} steps", kFreeFlightSteps, kClaimsFloorSteps),
             verdict_name(momentum_verdict(momentum.linear, momentum.angular)),
             "rigid bodies and friction (the rolling disk, e 0.5, mu 0.3); a spring chain between walls",
             "[claims_measures](claims_measures.md), [block](block.md)"});
  const bool no_drift = energy_no_drift(energy.first, energy.second), exact = energy.adaptive <= kEnergyExact;
  t.add_row({4L, "Discrete energy conservation (fixed step: bounded error, no drift; adaptive step from the energy balance: exact)",
             "the energy study's long runs (e = 1); the jump in total energy across each contact phase of the bouncing bar",
             fmt::format("fixed: {:.2e} (first half), {:.2e} (second half); adaptive: {:.2e} ({:.0f} steps without a root); at "
                         "impact: singular {:.2e}; beyond: lumped e = 0 {:.2e}, e = 1 {:.2e}",
                         energy.first, energy.second, energy.adaptive, energy.no_root, cond.singular.worst_jump,
                         cond.lumped_inelastic.worst_jump, cond.lumped_elastic.worst_jump),
             fmt::format("{}{}", verdict_name(conditions_verdict({no_drift, exact, impact_energy_kept(cond.singular.phases, cond.singular.worst_jump)})),
                         fmt::format(" (fixed step bounded, no drift: {}; adaptive exact: {}; singular-mass impacts: {})", no_drift ? "yes" : "no",
                                     exact ? "yes" : "no", impact_energy_kept(cond.singular.phases, cond.singular.worst_jump) ? "kept" : "not kept")),
             "fixed step over long runs with e = 1 (bouncing mass, 100 impacts; spring chain between walls, 40 s); the adaptive "
             "step of the same runs; the singular-mass bouncing bar's contact phases",
             verdict_name(conditions_verdict({impact_energy_kept(cond.lumped_inelastic.phases, cond.lumped_inelastic.worst_jump),
                                              impact_energy_kept(cond.lumped_elastic.phases, cond.lumped_elastic.worst_jump)})),
             "the lumped-mass bouncing bar's contact phases, contact node inelastic (e = 0, the talk's LCP) and elastic (e = 1)" +
                 (cond.consistent.note.empty() ? std::string() : "; consistent mass not run (" + cond.consistent.note + ")"),
             "[claims_impact_energy](claims_impact_energy.md), [energy_long_time](energy_long_time.md)"});
  const AdaptiveSteps &talk = cond.adaptive[0], &balance = cond.adaptive[1];
  const auto steps_verdict = [](const AdaptiveSteps& r) {
    return adaptive_verdict(r.completed, r.dt_max / r.stable_step, r.dt_max, r.dt_min, r.collapsed);
  };
  const Verdict long_runs = adaptive_verdict(energy.adaptive_ok, energy.cfl, energy.dt_max, energy.dt_min, energy.collapsed);
  const auto steps_text = [](const AdaptiveSteps& r) {
    return fmt::format("{} steps ({} in contact, {} at tau_min, first {}), dt {:.3g} to {:.3g} x stable, t {:.4g} of {:.4g} s", r.steps,
                       r.contact_steps, r.collapsed, first_collapse(r), r.dt_min / r.stable_step, r.dt_max / r.stable_step,
                       r.t_reached, r.t_end);
  };
  t.add_row({5L, "Automatic adaptive time step with a CFL check",
             "cd-lagrange-adaptive's steps against the stable step and against time through an impact (figure "
             "claims_adaptive_steps)",
             fmt::format("talk's update, bouncing bar: {}; beyond: energy balance, bouncing bar: {}; long runs of (4): largest "
                         "step {:.3f} x stable, steps from {:.3e} to {:.3e} s, {} at tau_min",
                         steps_text(talk), steps_text(balance), energy.cfl, energy.dt_min, energy.dt_max, energy.collapsed),
             verdict_name(steps_verdict(talk)),
             "the talk's algorithm: its update of tau_{k+2} iterated to a fixed point, its momentum weighting, impulses doing no "
             "work; the lumped bouncing bar (N 100) with the talk's LCP (e = 0), through its first impact",
             verdict_name(conditions_verdict({steps_verdict(balance) == Verdict::Holds, long_runs == Verdict::Holds})),
             "the suite's variant: tau_{k+2} the root of the discrete energy balance, KMOW momentum (the same bar; the long runs "
             "of (4): bouncing mass, spring chain)",
             "[claims_adaptive_step](claims_adaptive_step.md), [claims_measures](claims_measures.md), [energy_targets](energy_targets.md)"});
  t.add_row({6L, "Matrix-free explicit LCP for deformable and rigid contact (diagonal Delassus operator: closed form)",
             "the runs of (1): steps with an active contact, LCP iterations, factorisations, solves",
             fmt::format("{} contact steps, {} LCP iterations, {} factorisations, {} solves", work.contact_steps, work.lcp,
                         work.factorizations, work.solves),
             verdict_name(lcp_verdict(work.contact_steps, work.lcp, work.factorizations, work.solves)),
             "deformable/rigid contact with a diagonal mass (the runs of (1))",
             cond.bodies.note.empty() ? verdict_name(lcp_verdict(cond.bodies.contact_steps, cond.bodies.work.lcp_iterations,
                                                                 cond.bodies.work.factorizations, cond.bodies.work.linear_solves))
                                      : kNotTested,
             fmt::format("contact between two deformable bodies (two-blocks, non-matching node-to-segment: H not diagonal): {} "
                         "LCP iterations in {} contact steps ({:.2f} per contact step), {} factorisations, {} solves{}",
                         cond.bodies.work.lcp_iterations, cond.bodies.contact_steps,
                         static_cast<double>(cond.bodies.work.lcp_iterations) / static_cast<double>(std::max(1L, cond.bodies.contact_steps)),
                         cond.bodies.work.factorizations, cond.bodies.work.linear_solves,
                         cond.bodies.note.empty() ? std::string() : "; " + cond.bodies.note),
             "[claims_measures](claims_measures.md), [bodies_blocks](bodies_blocks.md)"});
  t.add_row({7L, "Robust over long times with very many impacts",
             fmt::format("bouncing mass, e = 1, h0 = 1, dt = 0.02 s, run to its {}th impact{}", longrun.target,
                         options.full ? "" : " (1e6 with --full)"),
             fmt::format("{} impacts in {} steps (t = {:.4g} s), final energy error {:.2e}, penetration {:.2f} step of travel",
                         longrun.impacts, longrun.steps, longrun.t_end, longrun.energy, longrun.penetration),
             verdict_name(robustness_verdict(longrun.ok, longrun.impacts, longrun.target, longrun.energy, longrun.penetration)),
             "a rigid mass bouncing elastically on a rigid floor", kNotTested, "no deformable body is run to 1e5 impacts",
             "[claims_measures](claims_measures.md), [bouncing_mass](bouncing_mass.md)"});
  const std::vector<std::pair<std::string, std::string>> meta = {{"integrator", "cd-lagrange"}, {"full", options.full ? "yes" : "no"}};
  t.metadata = meta;
  m.metadata = meta;
  Table bars = bar_hausdorff_table(cond.bars), impact = impact_energy_table(cond), steps = adaptive_step_table(cond.adaptive),
        step_history = adaptive_steps_table(cond.adaptive), momentum_history = momentum_history_table(cond.block),
        impact_history = impact_history_table({{"singular, e = 0", &cond.singular},
                                               {"lumped, e = 0", &cond.lumped_inelastic},
                                               {"lumped, e = 1", &cond.lumped_elastic}}),
        long_history = long_run_table(longrun);
  for (Table* x : {&bars, &impact, &steps, &step_history, &momentum_history, &impact_history, &long_history}) x->metadata = meta;
  // The figures in the claims' order on the first page: (2), (3), (4), (5), (7).
  return {t, m, bars, momentum_history, impact, impact_history, steps, step_history, long_history};
}

}  // namespace

extern const StudyEntry claims_study = {"claims", "the claims of the CD-Lagrange talk, each with its measurement and verdict",
                                        &claims_tables, nullptr, nullptr, nullptr};

}  // namespace nsb
