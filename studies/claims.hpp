#pragma once
// The claims of CD-Lagrange (A. Gravouil, "CD-Lagrange", talk 2022, last slide), each with the
// figure nsbench measures for it and a verdict computed from that figure by the rules below
// (studies/claims.cpp runs the measurements; the thresholds are in the claims table's caption).
#include <string>
#include <vector>

#include "studies/study.hpp"

namespace nsb {

enum class Verdict { Holds, Conditional, Fails };
// "holds", "holds under the stated conditions", "fails".
const char* verdict_name(Verdict v);

// (1) Explicit: no factorisation, no linear solve, at most one F_int evaluation per step
// (+ 1 at the start of each of `runs` runs).
Verdict explicit_verdict(long runs, long steps, long force_evaluations, long factorizations, long linear_solves);

// (2) Hausdorff convergence: a problem converges when its fitted Hausdorff order is >= 0.5 with
// the 95% interval's low end > 0. Holds: on every problem; conditional: on some; fails: none.
constexpr double kHausdorffMinOrder = 0.5;
bool hausdorff_converges(const OrderFit& fit);
Verdict hausdorff_verdict(const std::vector<OrderFit>& per_problem);

// The verdict of a claim tested under several conditions: holds when every one is met, holds
// under the stated conditions when some are, fails when none is (or there is none).
Verdict conditions_verdict(const std::vector<bool>& met);
// "not tested": a claim's column for which nsbench has no measurement.
constexpr const char* kNotTested = "not tested";

// (3) Momentum balances: the largest residual (linear and angular, relative to the largest
// momentum) <= 1e-10.
constexpr double kMomentumTolerance = 1e-10;
Verdict momentum_verdict(double linear_residual, double angular_residual);

// (4) Energy (E the scheme's own at every step, contact steps included, errors relative to
// E_1, the energy after the first step, as in the energy study): fixed step bounded without
// drift: bounded, max |E - E_1| / E_1 over each half of a long run <= 0.1 (an error of the
// order of E itself is not conservation, however steady: the drift test alone passed a scheme
// whose reported energy falls to 0 at every impact step), and no drift, the second half's <=
// 2 x the first half's, + 1e-12 for round-off; adaptive step exact (max <= 1e-9). Each figure
// is the worst over the problems. Holds: both; conditional: one; fails: neither.
constexpr double kEnergyBounded = 0.1;
constexpr double kEnergyDriftFactor = 2.0;
constexpr double kEnergyRoundOff = 1e-12;
constexpr double kEnergyExact = 1e-9;
Verdict energy_verdict(double fixed_first_half, double fixed_second_half, double adaptive_max);
bool energy_no_drift(double fixed_first_half, double fixed_second_half);
// Energy at impact: every contact phase changes the total energy by at most 1e-2 of the
// kinetic energy at the first impact (and at least one phase happened).
constexpr double kImpactEnergy = 1e-2;
bool impact_energy_kept(long phases, double worst_jump);

// (5) Adaptive step with a CFL check: the run completes, every step <= the stable step, the
// step changes (largest / smallest > 1 + 1e-6), and no step collapsed to the scheme's floor
// tau_min (a step pinned at its lower bound is the rule failing, not the step adapting).
Verdict adaptive_verdict(bool completed, double largest_step_over_stable, double largest_step, double smallest_step,
                         long collapsed_steps);

// (6) Matrix-free explicit contact: contacts were active, and no LCP iteration, factorisation
// or linear solve was spent.
Verdict lcp_verdict(long contact_steps, long lcp_iterations, long factorizations, long linear_solves);

// (7) Robustness over long times: the run (stopped at its `target`-th impact) gets there with
// finite states, |E_end - E_1| / E_1 <= 1e-2 and the largest penetration <= one step of travel
// at the impact speed.
constexpr double kRobustEnergy = 1e-2;
Verdict robustness_verdict(bool completed, long impacts, long target, double energy_error, double penetration_over_step);

}  // namespace nsb
