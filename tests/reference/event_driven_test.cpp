#include "reference/event_driven.hpp"

#include <catch2/catch.hpp>
#include <cmath>

#include "run/run.hpp"
#include "problems/bouncing_mass.hpp"

using nsb::BouncingMass;
using nsb::EventDriven;
using nsb::Params;

namespace {

BouncingMass falling_mass(double e, double h0 = 1.0, double v0 = 0.0) {
  return BouncingMass(Params(BouncingMass::parameters_spec(),
                             {{"e", std::to_string(e)}, {"h0", std::to_string(h0)}, {"v0", std::to_string(v0)}}));
}

EventDriven make_ed(const std::string& method, const std::string& zeno_velocity = "1e-4") {
  return EventDriven(Params(EventDriven::parameters_spec(), {{"method", method}, {"zeno_velocity", zeno_velocity}}));
}

void advance_events(EventDriven& ed, double t_end, double dt) {
  while (ed.state().t < t_end - 1e-12) ed.step(std::min(dt, t_end - ed.state().t));
}

}  // namespace

TEST_CASE("event-driven: bouncing-mass impact times and rebound speeds within 1e-9 of the exact ones",
          "[reference][event-driven]") {
  for (const char* method : {"bdf", "adams"}) {
    for (double e : {1.0, 0.9, 0.5}) {
      DYNAMIC_SECTION(method << " e=" << e) {
        const BouncingMass p = falling_mass(e, 1.0, 0.7);
        const int impacts = 8;
        auto ed = make_ed(method);
        ed.init(p, p.initial_state());
        // A step that is no divisor of the flights: impacts fall inside steps.
        advance_events(ed, 0.5 * (p.impact_time(impacts) + p.impact_time(impacts + 1)), 0.0137);
        // Exactly the impacts of the exact solution: a restart at zero gap fires no root.
        REQUIRE(ed.events().size() == static_cast<std::size_t>(impacts));
        for (int i = 1; i <= impacts; ++i) {
          const auto& imp = ed.events()[static_cast<std::size_t>(i - 1)];
          CHECK(imp.kind == nsb::ContactEventKind::Impact);
          CHECK(imp.impulse == Approx(p.parameters().real("m") * (imp.rate_after - imp.rate_before)).epsilon(1e-12));
          CAPTURE(i);
          CHECK(std::abs(imp.t - p.impact_time(i)) <= 1e-9);
          const double rebound = std::pow(e, i) * p.first_impact_speed();
          CHECK(std::abs(imp.rate_after - rebound) <= 1e-9);
          CHECK(std::abs(imp.rate_before + rebound / e) <= 1e-9);
        }
        // The interpolated state between events, against the exact solution: local errors
        // of at most rtol |y| (default rtol = 1e-11, |y| < 5) add up at most linearly over
        // the steps in a flow that does not expand errors (free flight).
        const auto exact = *p.state(ed.state().t);
        const double global = static_cast<double>(ed.work().steps) * 1e-11 * 5.0;
        CHECK(std::abs(ed.state().u[0] - exact.u[0]) <= global);
        CHECK(std::abs(ed.state().v[0] - exact.v[0]) <= global);
        CHECK(ed.work().extra.at("events") == impacts);
      }
    }
  }
}

TEST_CASE("event-driven: Zeno accumulation ends in closed contact near the accumulation time",
          "[reference][event-driven]") {
  const double e = 0.5, g = 9.81, v_zeno = 1e-4, atol = 1e-13;
  const BouncingMass p = falling_mass(e);
  auto ed = make_ed("bdf", "1e-4");
  ed.init(p, p.initial_state());
  advance_events(ed, p.zeno_time() + 0.5, 0.01);
  REQUIRE(ed.work().extra.at("zeno_stops") == 1);
  // The plastic impact comes at the first impact whose rebound would be slower than
  // v_zeno; the flights it cuts last 2 e v / (g (1 - e)) < 2 v_zeno / (g (1 - e)) together.
  // Each landing at speed v is located within atol / v (the gap's absolute accuracy): over
  // the ~15 impacts down to v_zeno that is below 2 atol / (v_zeno (1 - e)).
  const double located = 2 * atol / (v_zeno * (1 - e));
  REQUIRE(ed.events().back().kind == nsb::ContactEventKind::ZenoStop);
  const double t_close = ed.events().back().t;
  CHECK(t_close <= p.zeno_time() + located);
  CHECK(p.zeno_time() - t_close <= 2 * v_zeno / (g * (1 - e)) + located);
  CHECK(ed.events().back().rate_after == 0.0);
  // At rest on the floor, held there exactly, with no release under gravity.
  CHECK(ed.state().u[0] == 0.0);
  CHECK(ed.state().v[0] == 0.0);
  CHECK(ed.work().extra.at("releases") == 0);
}

TEST_CASE("event-driven: a mass resting on the floor stays closed from t = 0", "[reference][event-driven]") {
  const BouncingMass p = falling_mass(0.5, 0.0, 0.0);
  auto ed = make_ed("bdf");
  ed.init(p, p.initial_state());
  advance_events(ed, 2.0, 0.1);
  CHECK(ed.state().u[0] == 0.0);
  CHECK(ed.state().v[0] == 0.0);
  // No impact; the floor holds the weight: the step's impulse is m g dt (the reaction
  // integrated under CVODE's error control), as a time-stepping scheme reports it.
  CHECK(ed.impulses()[0] == Approx(9.81 * 0.1).epsilon(1e-9));
}

TEST_CASE("event-driven: tolerances are checked", "[reference][event-driven]") {
  CHECK_THROWS_AS(EventDriven(Params(EventDriven::parameters_spec(), {{"rtol", "0"}})), nsb::InputError);
  CHECK_THROWS_AS(EventDriven(Params(EventDriven::parameters_spec(), {{"method", "rk4"}})), nsb::InputError);
}

// Issue 20: both ran to t = 10 with status ok, one through the floor (q = -9.89), one
// starting on it.
TEST_CASE("event-driven: zeno_velocity = 0 is refused; a missed impact stops the run as diverged", "[reference][event-driven]") {
  CHECK_THROWS_WITH(make_ed("bdf", "0"), Catch::Contains("zeno_velocity") && Catch::Contains("(0, inf)"));
  // A rebound threshold far below any speed the root finder can resolve: the impacts
  // accumulate until one is missed, and the run says so instead of falling through.
  const BouncingMass p = falling_mass(0.5);
  auto ed = make_ed("bdf", "1e-300");
  ed.init(p, p.initial_state());
  nsb::RunOptions options;
  options.dt = 0.01;
  options.t_end = 10.0;
  options.record_series = false;
  const nsb::RunResult r = nsb::run(p, ed, options);
  CHECK(r.status == nsb::RunStatus::Diverged);
  CHECK_THAT(r.message, Catch::Contains("contact 0 was passed through unseen"));
  CHECK(r.max_penetration < 1e-3);  // stopped at the first step beyond the tolerance
}

TEST_CASE("event-driven: an open initial gap within atol is refused, not started on the floor", "[reference][event-driven]") {
  const BouncingMass p = falling_mass(0.9, 1.0);
  auto ed = EventDriven(Params(EventDriven::parameters_spec(), {{"atol", "1"}}));
  CHECK_THROWS_WITH(ed.init(p, p.initial_state()),
                    "event-driven: contact 0 starts at gap 1, within atol = 1 of the obstacle, where it counts as "
                    "touching; valid: atol < 1 (the smallest open initial gap)");
  auto fine = EventDriven(Params(EventDriven::parameters_spec(), {{"atol", "1e-3"}}));
  fine.init(p, p.initial_state());
  CHECK(fine.state().u[0] == 1.0);
}
