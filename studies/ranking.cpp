#include "studies/ranking.hpp"
#include "core/deterministic_math.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <tuple>

#include "studies/measures.hpp"

namespace nsb {

namespace {
// The larger of two relative spreads; unknown (NaN) when either is.
double larger_spread(double a, double b) { return std::isnan(a) || std::isnan(b) ? kNaN : std::max(a, b); }

// "none", and which rule removed which runs: "none (removed: energy blow-up: A dt = 1e-2, A dt =
// 5e-3; diverged: B dt = 1e-1)".
std::string none_text(const RankingProblem& p, const std::function<std::string(const WorkCurve&)>& name) {
  std::vector<std::pair<std::string, std::vector<std::string>>> rules;  // in order of first appearance
  for (const auto& c : p.curves)
    for (const auto& point : c.points) {
      if (point.removed.empty()) continue;
      auto rule = std::find_if(rules.begin(), rules.end(), [&](const auto& r) { return r.first == point.removed; });
      if (rule == rules.end()) rule = rules.insert(rules.end(), {point.removed, {}});
      rule->second.push_back(name(c) + " " + point.run);
    }
  if (rules.empty()) return "none";
  std::vector<std::string> parts;
  for (const auto& [rule, runs] : rules) parts.push_back(fmt::format("{}: {}", rule, fmt::join(runs, ", ")));
  return fmt::format("none (removed: {})", fmt::join(parts, "; "));
}

}  // namespace

TargetCost cost_at_target(const WorkCurve& curve, double target, double floor) {
  struct Run {
    double cost, error;
    std::size_t index;
  };
  std::vector<Run> runs;
  for (std::size_t i = 0; i < curve.points.size(); ++i) {
    const WorkPoint& p = curve.points[i];
    if (p.removed.empty() && usable(p.cost) && usable(p.error)) runs.push_back({p.cost, std::max(p.error, floor), i});
  }
  const auto spread = [&](const Run& r) { return curve.points[r.index].spread; };
  std::sort(runs.begin(), runs.end(), [](const Run& a, const Run& b) {
    return std::tie(a.cost, a.error, a.index) < std::tie(b.cost, b.error, b.index);
  });
  const auto hit = std::find_if(runs.begin(), runs.end(), [&](const Run& r) { return r.error <= target; });
  if (hit == runs.end()) return {false, kNaN, ""};
  const std::string& at = curve.points[hit->index].run;
  if (hit == runs.begin()) return {true, hit->cost, at + " (cheapest run)", spread(*hit)};
  // The first of equally accurate cheaper runs is the cheapest of them.
  const Run& before = *std::min_element(runs.begin(), hit, [](const Run& a, const Run& b) { return a.error < b.error; });
  const double f = nsb::dmath::log(before.error / target) / nsb::dmath::log(before.error / hit->error);  // in (0, 1]
  return {true, before.cost * nsb::dmath::pow(hit->cost / before.cost, f), curve.points[before.index].run + " .. " + at,
          larger_spread(spread(before), spread(*hit))};
}

bool told_apart(const TargetCost& winner, const TargetCost& runner_up) {
  const double spread = larger_spread(winner.spread, runner_up.spread);
  return !std::isnan(spread) && runner_up.cost > (1.0 + spread) * winner.cost;
}

std::vector<Standing> rank_at_target(const std::vector<WorkCurve>& curves, double target, double floor) {
  std::vector<Standing> all;
  for (std::size_t i = 0; i < curves.size(); ++i) all.push_back({i, cost_at_target(curves[i], target, floor)});
  const auto reached_end = std::stable_partition(all.begin(), all.end(), [](const Standing& s) { return s.cost.reached; });
  std::stable_sort(all.begin(), reached_end, [](const Standing& a, const Standing& b) { return a.cost.cost < b.cost.cost; });
  return all;
}

Table ranking_table(const std::string& id, const std::string& title, const Column& error, const std::string& cost,
                    const std::vector<RankingProblem>& problems) {
  Table t;
  t.id = id;
  t.title = title;
  std::vector<std::string> sources;
  for (const auto& p : problems)
    sources.push_back(p.floor > 0.0 ? fmt::format("{}: against {} (its own error {:.1e}{}{})", p.label, p.error_source,
                                                  p.floor, error.unit.empty() ? "" : " ", error.unit)
                                    : fmt::format("{}: against {}", p.label, p.error_source));
  t.caption = fmt::format(
      "Cheapest integrator reaching each target error. Cost: {}, interpolated log-log between an integrator's runs "
      "(by increasing cost: the first reaching the target and the most accurate cheaper one), never extrapolated "
      "(\"cheapest run\": that run already reaches the target, its cost is an upper bound); diverged, over-budget "
      "and n/a runs left out. References are ranked as peers, marked. The cheapest wins only when the runner-up costs "
      "more than (1 + spread) times it, spread the larger relative spread of the two costs' timings; otherwise the "
      "winner cell reads \"tie\" (\"tie (timed once)\" for costs timed once, whose spread is unknown). Errors: {}; below the "
      "source's own error they count as it, and no target below it is ranked.",
      cost, fmt::join(sources, "; "));
  t.columns = {{"problem", "", "", ""},
               {"target " + error.name, error.unit, "{:.0e}", error.description},
               {"winner", "", "", "cheapest integrator reaching the target", true},
               {"winner CPU", "s", "{:.2e}", "its CPU time at the target", true},
               {"winner runs", "", "", "the runs its cost is interpolated between", true},
               {"runner-up", "", "", "second cheapest", true},
               {"runner-up CPU", "s", "{:.2e}", "", true},
               {"runner-up runs", "", "", "", true},
               {"ratio", "", "{:.2f}", "runner-up CPU / winner CPU", true},
               {"spread", "", "{:.2f}", "the larger relative spread of the two CPU times (n/a: timed once)", true},
               {"not reached", "", "", "integrators whose runs never reach the target"}};
  t.headline = true;
  const std::function<std::string(const WorkCurve&)> name = [](const WorkCurve& c) {
    return c.reference ? c.integrator + " (reference)" : c.peer ? c.integrator + " (peer)" : c.integrator;
  };
  for (const auto& p : problems)
    for (double target : p.targets) {
      if (target < p.floor) {
        t.add_row({p.label, target, fmt::format("not ranked: below the error source's own error {:.1e}", p.floor),
                   {}, {}, {}, {}, {}, {}, {}, {}});
        continue;
      }
      const auto standings = rank_at_target(p.curves, target, p.floor);
      std::vector<std::string> missed;
      for (const auto& s : standings)  // a curve without runs: the integrator declined the problem
        if (!s.cost.reached && !p.curves[s.curve].points.empty()) missed.push_back(name(p.curves[s.curve]));
      // Name, cost and runs of the k-th placed integrator; "none" (and the runs rules removed)
      // when there is none.
      const auto placed = [&](std::size_t k) -> std::array<Cell, 3> {
        if (k >= standings.size() || !standings[k].cost.reached) return {none_text(p, name), {}, {}};
        const Standing& s = standings[k];
        return {name(p.curves[s.curve]), s.cost.cost, s.cost.runs};
      };
      auto first = placed(0);
      const auto second = placed(1);
      const bool two = standings.size() > 1 && standings[1].cost.reached;
      const double spread = two ? larger_spread(standings[0].cost.spread, standings[1].cost.spread) : kNaN;
      if (two && !told_apart(standings[0].cost, standings[1].cost))
        first[0] = fmt::format("tie{}: {}, {}", std::isnan(spread) ? " (timed once)" : "", std::get<std::string>(first[0]),
                               std::get<std::string>(second[0]));
      t.add_row({p.label, target, first[0], first[1], first[2], second[0], second[1], second[2],
                 two ? Cell{standings[1].cost.cost / standings[0].cost.cost} : Cell{},
                 std::isnan(spread) ? Cell{} : Cell{spread},
                 missed.empty() ? std::string("none") : fmt::format("{}", fmt::join(missed, ", "))});
    }
  return t;
}

}  // namespace nsb
