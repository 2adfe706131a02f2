#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "studies/ranking.hpp"

using Catch::Detail::Approx;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A curve through (cost, error) runs named r0, r1, ..., each cost timed with a relative spread
// `spread` (NaN: timed once).
nsb::WorkCurve curve(const std::string& name, std::vector<std::pair<double, double>> runs, bool reference = false,
                     double spread = 0.05) {
  nsb::WorkCurve c{name, reference, {}};
  for (std::size_t i = 0; i < runs.size(); ++i)
    c.points.push_back({fmt::format("r{}", i), runs[i].first, runs[i].second, "", spread});
  return c;
}

std::string text(const nsb::Cell& c) { return std::get<std::string>(c); }
}  // namespace

TEST_CASE("ranking: the cost at a target is interpolated log-log between runs, never extrapolated", "[studies][ranking]") {
  const auto c = curve("a", {{1.0, 1e-1}, {10.0, 1e-3}});
  const auto mid = nsb::cost_at_target(c, 1e-2, 0.0);
  REQUIRE(mid.reached);
  CHECK(mid.cost == Approx(std::sqrt(10.0)).epsilon(1e-12));
  CHECK(mid.runs == "r0 .. r1");
  const auto exact_hit = nsb::cost_at_target(c, 1e-3, 0.0);
  CHECK(exact_hit.cost == Approx(10.0).epsilon(1e-12));
  // The cheapest run already reaches it: its cost, an upper bound, not an extrapolation.
  const auto loose = nsb::cost_at_target(c, 1.0, 0.0);
  CHECK(loose.cost == 1.0);
  CHECK(loose.runs == "r0 (cheapest run)");
  // Beyond the most accurate run: not reached, no cost.
  const auto tight = nsb::cost_at_target(c, 1e-4, 0.0);
  CHECK_FALSE(tight.reached);
  CHECK(std::isnan(tight.cost));
}

TEST_CASE("ranking: diverged, over-budget and zero-error runs are left out", "[studies][ranking]") {
  // r1 diverged (no error), r2 has no cost, r3 an error of 0: none of them counts.
  const auto c = curve("a", {{1.0, 1e-1}, {2.0, kNaN}, {kNaN, 1e-6}, {3.0, 0.0}, {10.0, 1e-3}});
  const auto at = nsb::cost_at_target(c, 1e-2, 0.0);
  CHECK(at.cost == Approx(std::sqrt(10.0)).epsilon(1e-12));
  CHECK(at.runs == "r0 .. r4");
  CHECK_FALSE(nsb::cost_at_target(curve("b", {{1.0, kNaN}, {2.0, std::numeric_limits<double>::infinity()}}), 1.0, 0.0).reached);
}

TEST_CASE("ranking: runs are taken by cost, a dominated run is skipped, the input order does not matter", "[studies][ranking]") {
  // By cost: r3 (1, 1e-1), r1 (2, 1e-2), r0 (3, 5e-2: costlier and worse than r1), r2 (4, 1e-4).
  const auto c = curve("a", {{3.0, 5e-2}, {2.0, 1e-2}, {4.0, 1e-4}, {1.0, 1e-1}});
  const auto at = nsb::cost_at_target(c, 1e-3, 0.0);
  CHECK(at.cost == Approx(2.0 * std::sqrt(2.0)).epsilon(1e-12));  // half way from (2, 1e-2) to (4, 1e-4)
  CHECK(at.runs == "r1 .. r2");
  auto reversed = c;
  std::reverse(reversed.points.begin(), reversed.points.end());
  CHECK(nsb::cost_at_target(reversed, 1e-3, 0.0).cost == at.cost);
}

TEST_CASE("ranking: errors below the error source's own error count as that error", "[studies][ranking]") {
  const auto c = curve("a", {{1.0, 1e-2}, {10.0, 1e-12}});
  CHECK(nsb::cost_at_target(c, 1e-3, 1e-4).cost == Approx(std::sqrt(10.0)).epsilon(1e-12));
  CHECK(nsb::cost_at_target(c, 1e-3, 0.0).cost == Approx(std::pow(10.0, 0.1)).epsilon(1e-12));
}

TEST_CASE("ranking: cheapest first, equal costs in the curves' order, then those not reaching the target", "[studies][ranking]") {
  const std::vector<nsb::WorkCurve> curves = {curve("slow", {{2.0, 1e-3}}), curve("never", {{0.5, 1.0}}),
                                              curve("fast", {{1.0, 1e-3}}), curve("fast-too", {{1.0, 1e-3}}),
                                              curve("never-too", {})};
  std::vector<std::size_t> order;
  for (const auto& s : nsb::rank_at_target(curves, 1e-2, 0.0)) order.push_back(s.curve);
  CHECK(order == std::vector<std::size_t>{2, 3, 0, 1, 4});
}

TEST_CASE("ranking: the table names the winner, the runner-up, their ratio and who does not reach", "[studies][ranking]") {
  nsb::RankingProblem p{"problem", "the exact solution", 0.0, {1e-2, 1e-4}, {}};
  p.curves = {curve("a", {{1.0, 1e-1}, {10.0, 1e-3}}), curve("ref", {{2.0, 1e-5}}, true), curve("b", {{5.0, 1e-1}})};
  nsb::RankingProblem floored{"floored", "a reference", 1e-3, {1e-4}, {curve("a", {{1.0, 1e-6}})}};
  const nsb::Table t = nsb::ranking_table("rank", "Ranking", {"err", "", "", ""}, "CPU", {p, floored});
  CHECK(t.headline);
  REQUIRE(t.rows.size() == 3);
  // 1e-2: ref (2, its cheapest run) beats a (sqrt 10); b never gets there.
  CHECK(text(t.rows[0][2]) == "ref (reference)");
  CHECK(std::get<double>(t.rows[0][3]) == 2.0);
  CHECK(text(t.rows[0][4]) == "r0 (cheapest run)");
  CHECK(text(t.rows[0][5]) == "a");
  CHECK(std::get<double>(t.rows[0][8]) == Approx(std::sqrt(10.0) / 2.0).epsilon(1e-12));
  CHECK(std::get<double>(t.rows[0][9]) == 0.05);
  CHECK(text(t.rows[0][10]) == "b");
  // 1e-4: the reference alone; no runner-up, no ratio.
  CHECK(text(t.rows[1][2]) == "ref (reference)");
  CHECK(text(t.rows[1][5]) == "none");
  CHECK(std::holds_alternative<std::monostate>(t.rows[1][8]));
  CHECK(std::holds_alternative<std::monostate>(t.rows[1][9]));
  CHECK(text(t.rows[1][10]) == "a, b");
  // A target below the error source's own error is not ranked.
  CHECK_THAT(text(t.rows[2][2]), Catch::StartsWith("not ranked"));
  // Nobody reaches it: "none".
  nsb::RankingProblem hard{"hard", "the exact solution", 0.0, {1e-9}, {curve("a", {{1.0, 1e-1}})}};
  const nsb::Table none = nsb::ranking_table("rank", "Ranking", {"err", "", "", ""}, "CPU", {hard});
  CHECK(text(none.rows[0][2]) == "none");
  CHECK(text(none.rows[0][10]) == "a");
  // An integrator that declined the problem (a curve without runs) is not "not reached".
  hard.curves.push_back({"declined", true, {}});
  const nsb::Table declined = nsb::ranking_table("rank", "Ranking", {"err", "", "", ""}, "CPU", {hard});
  CHECK(text(declined.rows[0][10]) == "a");
}

TEST_CASE("ranking: a peer (another code's implementation) is ranked and marked", "[studies][ranking]") {
  nsb::WorkCurve peer = curve("other", {{1.0, 1e-3}});
  peer.peer = true;
  nsb::RankingProblem p{"problem", "the exact solution", 0.0, {1e-2}, {curve("a", {{3.0, 1e-3}}), peer}};
  const nsb::Table t = nsb::ranking_table("rank", "Ranking", {"err", "", "", ""}, "CPU", {p});
  REQUIRE(t.rows.size() == 1);
  CHECK(text(t.rows[0][2]) == "other (peer)");
  CHECK(text(t.rows[0][5]) == "a");
}

// The tie rule (ranking.hpp): a winner only when the runner-up costs more than (1 + s) times it,
// s the larger spread of the two costs (an interpolated cost carries the larger spread of its
// two runs); inside it, or with a cost timed once, the winner cell says "tie".
TEST_CASE("ranking: a winner only beyond the timings' spread, otherwise a tie", "[studies][ranking]") {
  const auto winner = [](double cost_b, double spread_a, double spread_b) {
    nsb::RankingProblem p{"problem", "the exact solution", 0.0, {1e-2},
                          {curve("a", {{1.0, 1e-3}}, false, spread_a), curve("b", {{cost_b, 1e-3}}, false, spread_b)}};
    const nsb::Table t = nsb::ranking_table("rank", "Ranking", {"err", "", "", ""}, "CPU", {p});
    REQUIRE(t.rows.size() == 1);
    CHECK(text(t.rows[0][5]) == "b");  // the runner-up is named either way
    return text(t.rows[0][2]);
  };
  CHECK(winner(1.16, 0.10, 0.05) == "a");       // 16 % apart, timings 10 % apart
  CHECK(winner(1.16, 0.05, 0.20) == "tie: a, b");  // the runner-up's spread is the larger
  CHECK(winner(1.10, 0.10, 0.10) == "tie: a, b");  // exactly at the spread: not told apart
  CHECK(winner(3.00, kNaN, 0.05) == "tie (timed once): a, b");  // no spread: cannot tell
  CHECK(winner(3.00, 0.05, kNaN) == "tie (timed once): a, b");
  // Interpolated: the cost between r0 (spread 0.3) and r1 (spread 0.01) carries 0.3.
  nsb::WorkCurve mixed = curve("m", {{1.0, 1e-1}, {10.0, 1e-3}});
  mixed.points[0].spread = 0.3;
  mixed.points[1].spread = 0.01;
  CHECK(nsb::cost_at_target(mixed, 1e-2, 0.0).spread == 0.3);
  CHECK(nsb::cost_at_target(mixed, 1.0, 0.0).spread == 0.3);   // r0 alone
  CHECK(nsb::cost_at_target(mixed, 1e-3, 0.0).spread == 0.3);  // r0 .. r1 at r1
  nsb::TargetCost a{true, 1.0, "", 0.2}, b{true, 1.21, "", 0.1};
  CHECK(nsb::told_apart(a, b));
  b.cost = 1.2;
  CHECK_FALSE(nsb::told_apart(a, b));
}
