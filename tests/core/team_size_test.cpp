// The run's team size (core/team_size.hpp), fed with step times: it probes T threads, then
// one (each probe stopping once it has lost), steps on the faster, probes again after its
// window (doubled when the decision is confirmed).
#include <catch2/catch.hpp>
#include <cmath>

#include "core/team_size.hpp"

namespace {

constexpr int kWindow = nsb::TeamSize::kProbeSteps + 1;  // a whole probe's steps (the first uncounted)

// One step taking many_seconds on the full team, one_seconds on one thread.
void step(nsb::TeamSize& team, double many_seconds, double one_seconds) {
  team.step_done(team.threads() == 1 ? one_seconds : many_seconds);
}

// Steps while the team probes; returns how many.
long probe(nsb::TeamSize& team, double many_seconds, double one_seconds) {
  long steps = 0;
  for (; team.timing(); ++steps) {
    REQUIRE(steps <= 2 * kWindow);
    step(team, many_seconds, one_seconds);
  }
  return steps;
}

// Steps until the team probes again; returns how many.
long exploit(nsb::TeamSize& team, double many_seconds, double one_seconds) {
  long steps = 0;
  for (; !team.timing(); ++steps) {
    REQUIRE(steps < 100'000'000);
    step(team, many_seconds, one_seconds);
  }
  return steps;
}

}  // namespace

TEST_CASE("team size: the faster of all threads and one wins, and is probed again", "[core][threads]") {
  SECTION("a quiet machine: the team, after a one-thread probe cut short") {
    nsb::TeamSize team(2);
    CHECK(team.threads() == 2);
    CHECK(team.timing());
    const long probed = probe(team, 1e-3, 2e-3);
    CHECK(probed > kWindow);      // the team's whole probe, then part of one thread's
    CHECK(probed < 2 * kWindow);  // cut short: 5 one-thread steps outweigh the team's 8
    CHECK(team.threads() == 2);
    // The window: kFirstExploitSeconds at the team's 1 ms per step; confirmed, twice that.
    const long window = exploit(team, 1e-3, 2e-3);
    CHECK(window == std::lround(nsb::TeamSize::kFirstExploitSeconds / 1e-3));
    probe(team, 1e-3, 2e-3);
    CHECK(team.threads() == 2);
    CHECK(exploit(team, 1e-3, 2e-3) == 2 * window);
  }
  SECTION("the other cores busy: one thread; the team's next probe cut short; back to the team when they are free") {
    nsb::TeamSize team(2);
    CHECK(probe(team, 5e-3, 2e-3) == 2 * kWindow);  // nothing to compare with yet: both whole
    CHECK(team.threads() == 1);
    const long window = exploit(team, 5e-3, 2e-3);
    CHECK(window == std::lround(nsb::TeamSize::kFirstExploitSeconds / 2e-3));
    CHECK(probe(team, 5e-3, 2e-3) < kWindow);  // 4 team steps outweigh 8 of one thread
    CHECK(team.threads() == 1);
    CHECK(exploit(team, 5e-3, 2e-3) == 2 * window);
    probe(team, 1e-3, 2e-3);  // the cores freed
    CHECK(team.threads() == 2);
  }
  SECTION("the first step of a probe (the team waking up) is not counted") {
    nsb::TeamSize team(2);
    team.step_done(1.0);  // a very slow first step on the team
    probe(team, 1e-3, 2e-3);
    CHECK(team.threads() == 2);
  }
  SECTION("one thread: nothing to choose, nothing timed") {
    nsb::TeamSize team(1);
    CHECK(team.threads() == 1);
    CHECK_FALSE(team.timing());
    for (int k = 0; k < 10000; ++k) step(team, 1e-3, 1e-3);
    CHECK_FALSE(team.timing());
    CHECK(team.threads() == 1);
  }
}
