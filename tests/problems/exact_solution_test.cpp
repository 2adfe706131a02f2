// The exact-solution interface (problems/exact_solution.hpp): every registered problem's
// exact(), when it has one, starts where the problem starts; the typed queries the studies ask
// give the problems' own closed-form figures, and nothing for what a solution does not time.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "problems/painleve_rod.hpp"
#include "problems/registry.hpp"
#include "problems/rocking_block.hpp"
#include "problems/rolling_disk.hpp"
#include "problems/signorini_bar.hpp"
#include "problems/sliding_mass.hpp"
#include "problems/sphere.hpp"

using nsb::ExactEvent;
using nsb::ExactValue;

TEST_CASE("exact solution: where a problem has one, its state at 0 is the initial state", "[problems][exact-solution]") {
  int with_exact = 0;
  for (const auto& entry : nsb::problem_registry()) {
    const auto p = nsb::make_problem(entry.name);
    INFO(entry.name);
    const nsb::ExactSolution* exact = p->exact();
    if (!exact) continue;
    ++with_exact;
    const auto s0 = exact->state(0.0);
    if (!s0) continue;  // known for other parameters only (mass-on-bar: no field at all)
    const nsb::State initial = p->initial_state();
    CHECK(s0->t == 0.0);
    const auto close = [](const nsb::Vec& a, const nsb::Vec& b) {
      return a.size() == b.size() && (a - b).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + b.cwiseAbs().maxCoeff());
    };
    CHECK(close(s0->u, initial.u));
    CHECK(close(s0->v, initial.v));
  }
  CHECK(with_exact >= 10);
  CHECK(nsb::make_problem("block-2d")->exact() == nullptr);
  CHECK(nsb::make_problem("spring-chain")->exact() == nullptr);
}

TEST_CASE("exact solution: the typed events and values are the problems' own figures", "[problems][exact-solution]") {
  SECTION("rolling-disk dropped with spin: rest, roll onset, the speed after the first impact") {
    const nsb::RollingDisk d(nsb::Params(nsb::RollingDisk::parameters_spec(), {{"h0", "0.05"}, {"omega0", "20"}, {"e", "0.5"}, {"mu", "0.3"}}));
    const nsb::ExactSolution& exact = *d.exact();
    REQUIRE(!d.impacts().empty());
    CHECK(exact.event_time(ExactEvent::rest) == d.rest_time());
    CHECK(exact.event_time(ExactEvent::roll_onset) == d.rolling_onset_time());
    CHECK(exact.value(ExactValue::first_rebound_speed) == d.impacts().front().v);
    CHECK_FALSE(exact.event_time(ExactEvent::jam));
    CHECK_FALSE(exact.event_time(ExactEvent::slip_stop));
  }
  SECTION("rolling-disk on the floor: no impact, no rebound speed") {
    const nsb::RollingDisk d(nsb::Params(nsb::RollingDisk::parameters_spec()));
    CHECK(d.impacts().empty());
    CHECK_FALSE(d.exact()->value(ExactValue::first_rebound_speed));
  }
  SECTION("sliding-mass: the stop, its distance, whether it stays") {
    for (const char* mu : {"0.8", "0.2"}) {
      const nsb::SlidingMass s(nsb::Params(nsb::SlidingMass::parameters_spec(), {{"alpha", "30"}, {"mu", mu}, {"v0", "2"}}));
      INFO("mu " << mu);
      CHECK(s.exact()->event_time(ExactEvent::slip_stop) == s.stop_time());
      CHECK(s.exact()->value(ExactValue::stop_distance) == s.stop_distance());
      CHECK(s.exact()->value(ExactValue::stays_stopped) == (s.sticks() ? 1.0 : 0.0));
    }
  }
  SECTION("rocking-block: both impact laws, the amplitudes, the rest") {
    const nsb::RockingBlock b(nsb::Params(nsb::RockingBlock::parameters_spec()));
    const nsb::ExactSolution& exact = *b.exact();
    CHECK(exact.value(ExactValue::housner_ratio) == nsb::housner_ratio(b.closed_form().alpha()));
    CHECK(exact.value(ExactValue::impact_ratio) == b.closed_form().impact_ratio());
    const auto amplitudes = exact.amplitudes_after_impacts();
    REQUIRE(amplitudes.size() == b.closed_form().impacts().size());
    REQUIRE(amplitudes.size() > 3);
    CHECK(amplitudes[2] == b.closed_form().impacts()[2].amplitude_after);
    CHECK(exact.impact_times(std::numeric_limits<double>::infinity()).size() == amplitudes.size());
    CHECK(exact.event_time(ExactEvent::rest) == b.closed_form().rest_time());
  }
  SECTION("painleve-rod: the jam, and nothing when the sliding phase ends otherwise") {
    const nsb::PainleveRod rod(nsb::Params(nsb::PainleveRod::parameters_spec()));
    CHECK(rod.exact()->event_time(ExactEvent::jam) == rod.closed_form().end_time());
    CHECK(rod.exact()->event_time(ExactEvent::jam).value() == Approx(0.814549658670072).epsilon(1e-12));
    CHECK_FALSE(rod.exact()->event_time(ExactEvent::rest));
  }
  SECTION("sphere: the roll onset on the incline, none when dropped") {
    const nsb::Sphere on(nsb::Params(nsb::Sphere::parameters_spec()));
    CHECK(on.exact()->event_time(ExactEvent::roll_onset) == on.roll_time());
    const nsb::Sphere dropped(nsb::Params(nsb::Sphere::parameters_spec(), {{"h0", "0.1"}}));
    CHECK_FALSE(dropped.exact()->event_time(ExactEvent::roll_onset));
  }
  SECTION("signorini-bar: the contact phase") {
    const nsb::SignoriniBar bar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"g0", "0.3"}, {"E", "4"}}));
    CHECK(bar.exact()->event_time(ExactEvent::contact_start) == bar.contact_start());
    CHECK(bar.exact()->value(ExactValue::contact_duration) == bar.contact_duration());
    CHECK_FALSE(bar.exact()->value(ExactValue::impact_ratio));
  }
}
