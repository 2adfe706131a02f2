// The run's team size (core/team_size.hpp), fed with step times: it probes T threads, then
// one, steps on the faster, probes again after its window (doubled when confirmed).
#include <catch2/catch.hpp>

#include "core/team_size.hpp"

namespace {

constexpr int kWindow = nsb::TeamSize::kProbeSteps + 1;  // a probe window's steps (the first uncounted)

// Runs `steps` steps, each taking many_seconds on the full team and one_seconds on one thread;
// returns the team of the last step.
int run(nsb::TeamSize& team, long steps, double many_seconds, double one_seconds) {
  int last = 0;
  for (long k = 0; k < steps; ++k) {
    last = team.threads();
    team.step_done(last == 1 ? one_seconds : many_seconds);
  }
  return last;
}

}  // namespace

TEST_CASE("team size: the faster of all threads and one wins, and is probed again", "[core][threads]") {
  SECTION("a quiet machine: the team") {
    nsb::TeamSize team(2);
    CHECK(team.threads() == 2);
    CHECK(team.timing());
    run(team, kWindow, 1e-3, 2e-3);
    CHECK(team.threads() == 1);  // now the one-thread probe
    run(team, kWindow, 1e-3, 2e-3);
    CHECK(team.threads() == 2);
    CHECK_FALSE(team.timing());
    // The window: kFirstExploitSeconds at the chosen 1 ms per step, then a probe again.
    const long window = static_cast<long>(nsb::TeamSize::kFirstExploitSeconds / 1e-3);
    run(team, window - 1, 1e-3, 2e-3);
    CHECK_FALSE(team.timing());
    run(team, 1, 1e-3, 2e-3);
    CHECK(team.timing());
  }
  SECTION("the other cores busy: one thread, and back to the team when they are free") {
    nsb::TeamSize team(2);
    run(team, 2 * kWindow, 5e-3, 2e-3);
    CHECK(team.threads() == 1);
    const long window = static_cast<long>(nsb::TeamSize::kFirstExploitSeconds / 2e-3);
    run(team, window, 5e-3, 2e-3);
    CHECK(team.timing());  // probing again
    run(team, 2 * kWindow, 5e-3, 2e-3);
    CHECK(team.threads() == 1);
    // Confirmed: the window doubled (twice the steps before the next probe).
    run(team, 2 * window - 1, 5e-3, 2e-3);
    CHECK_FALSE(team.timing());
    run(team, 1, 5e-3, 2e-3);
    CHECK(team.timing());
    run(team, 2 * kWindow, 1e-3, 2e-3);  // the cores freed
    CHECK(team.threads() == 2);
  }
  SECTION("the first step of a probe window (the team waking up) is not counted") {
    nsb::TeamSize team(2);
    team.step_done(1.0);  // a very slow first step on the team
    run(team, kWindow - 1 + kWindow, 1e-3, 2e-3);
    CHECK(team.threads() == 2);
  }
  SECTION("one thread: nothing to choose, nothing timed") {
    nsb::TeamSize team(1);
    CHECK(team.threads() == 1);
    CHECK_FALSE(team.timing());
    run(team, 10000, 1e-3, 1e-3);
    CHECK_FALSE(team.timing());
  }
}
