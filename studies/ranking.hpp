#pragma once
// Headline ranking: which integrator reaches a target error at the least cost, read off a
// study's work-precision data (one curve of runs, cost and error, per integrator).
//
// Cost of a curve at a target error T. A run counts when its cost and its error are finite
// and positive (diverged, over-budget and n/a runs have neither; a zero error has no place on
// the log scales of the figures this reads like). An error below the error source's own
// error (its floor: 0 for an exact solution) is only known to be at most the floor, so it is
// raised to it. Runs are taken by increasing cost (then error, then their order in the
// curve); the first with error <= T is the cheapest that reaches T. When there is a cheaper
// run, the cost is interpolated linearly in log(cost) against log(error), at T, between the
// most accurate cheaper run (the previous point of the curve's Pareto front) and that one.
// When the cheapest run already reaches T, its cost is kept as it is: an upper bound, since
// nothing is extrapolated beyond the sweep. No run with error <= T: not reached.
//
// Telling the winner from the runner-up. Each run's cost carries its spread, the relative
// distance between its repeated timings (study.hpp's CpuCost; unknown, NaN, for a run timed
// once); a cost read off two runs carries the larger of their spreads (the log-linear
// interpolation moves by at most that). The cheapest is the winner only when the runner-up
// costs more than (1 + s) times it, s the larger spread of the two costs; otherwise the winner
// cell reads "tie: A, B", and "tie (timed once): A, B" when a spread is unknown: a regenerated
// ranking keeps its winners or says tie, where a cost ratio inside the timing noise would flip.
#include <limits>
#include <string>
#include <vector>

#include "studies/table.hpp"

namespace nsb {

struct WorkPoint {
  std::string run;  // which run of the sweep, e.g. "dt = 1.0e-03"
  double cost;      // CPU seconds; NaN when the run has none
  double error;     // NaN when the run has none (diverged, over budget, n/a)
  // The rule that removed the run from the ranking (e.g. "energy blow-up", "diverged"), which
  // an empty winner or runner-up cell then names; empty: the run is ranked.
  std::string removed = {};
  double spread = std::numeric_limits<double>::quiet_NaN();  // of the cost, relative; NaN: timed once
};

struct WorkCurve {
  std::string integrator;
  bool reference = false;  // a reference integrator (IntegratorEntry::reference)
  std::vector<WorkPoint> points;
  bool peer = false;  // another code's implementation (IntegratorEntry::peer)
};

struct TargetCost {
  bool reached = false;
  double cost;       // NaN when not reached
  std::string runs;  // "A .. B" (interpolated between runs A and B) or "A (cheapest run)"
  double spread = std::numeric_limits<double>::quiet_NaN();  // the larger of those runs' spreads
};

// Whether `winner` is told from `runner_up` (both reached): the rule above.
bool told_apart(const TargetCost& winner, const TargetCost& runner_up);

TargetCost cost_at_target(const WorkCurve& curve, double target, double floor);

struct Standing {
  std::size_t curve;  // index into the curves
  TargetCost cost;
};

// Every curve at a target: those reaching it, cheapest first (equal costs keep the curves'
// order), then those not reaching it, in the curves' order.
std::vector<Standing> rank_at_target(const std::vector<WorkCurve>& curves, double target, double floor);

struct RankingProblem {
  std::string label;
  std::string error_source;  // what the error is measured against, as the caption states it
  double floor = 0.0;        // the error source's own error, same norm; 0: exact
  std::vector<double> targets;
  std::vector<WorkCurve> curves;
};

// One row per problem and target: the winner, its cost and the runs it is read between, the
// runner-up, its cost and runs, their cost ratio and the spread it is judged against ("tie: A,
// B" in the winner cell when the ratio is inside it), and the integrators not reaching the target
// (a curve without points is an integrator that declined the problem, n/a: not listed).
// Where no integrator (or no second one) reaches the target, the winner (runner-up) cell says
// "none" and, when rules removed runs (WorkPoint::removed), which rule removed which runs.
// References are ranked with the others (they are peers in cost against error) and marked
// "(reference)", peers (other codes' implementations) "(peer)". A target below the problem's floor is not ranked (its row says so).
// `error` names the error column (name, unit, format, description); `cost` says what the
// CPU time is. The table is a headline table (index.md shows it first).
Table ranking_table(const std::string& id, const std::string& title, const Column& error, const std::string& cost,
                    const std::vector<RankingProblem>& problems);

}  // namespace nsb
