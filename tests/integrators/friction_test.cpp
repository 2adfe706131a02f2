// Every registered integrator on the frictional problems with exact solutions (docs/method.md
// section 6): a scheme that treats friction must stop the sliding mass within O(dt) of the
// exact stop time and then hold it (no creep: a complementarity law sticks exactly), bring
// the rolling disk to rolling within O(dt) of the onset time at the exact final speed, and
// never gain energy; a scheme that does not must decline with mu named.
#include <catch2/catch.hpp>
#include <cmath>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/rolling_disk.hpp"
#include "problems/sliding_mass.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

// The penalty schemes regularise the law (their parameter friction_velocity): they creep and
// reach stick only asymptotically, by design; their own tests (cd_penalty_test.cpp,
// penalty_test.cpp) hold them to the regularised law's creep and stop time.
// The physics engines keep their own laws (nsb::testing::is_engine_peer).
bool complementarity(const nsb::IntegratorEntry& entry) {
  if (nsb::testing::is_engine_peer(entry.name)) return false;
  for (const auto& spec : entry.parameters())
    if (spec.name == "friction_velocity") return false;
  return true;
}

// The integrator, or null when it declines; a scheme without friction must decline, naming mu
// when the problem is otherwise within its reach (`mu_named`: a linear problem with e = 0 and
// a positive diagonal mass, which every scheme runs when frictionless).
std::unique_ptr<nsb::Integrator> init_or_check_decline(const nsb::IntegratorEntry& entry, const nsb::Problem& p,
                                                       bool mu_named) {
  auto integ = nsb::testing::init_or_decline(entry, p);
  auto other = entry.make(nsb::Params(entry.parameters()));
  if (other->treats_friction()) return integ;
  CHECK(!integ);
  if (mu_named) CHECK_THROWS_WITH(other->init(p, p.initial_state()), Catch::Contains("mu = "));
  return nullptr;
}

// nsga treats friction at its velocity jump only: the friction force never enters its smooth
// accelerations, so a stuck contact's position still follows gravity's tangential pull in the
// smooth step, h^2/2 g sin(alpha) per step: creep at about h g sin(alpha) / 2 (nsga.hpp). The
// test holds it to that rate instead of zero, and fails if it stops creeping (update it then).
double expected_creep_rate(const std::string& integrator, double h, double g_sin_alpha) {
  return integrator == "nsga" ? 0.5 * h * g_sin_alpha : 0.0;
}

// Largest increase of the integrator's energy between consecutive steps.
struct EnergyWatch {
  double previous = NAN, worst_gain = 0.0;
  void operator()(const nsb::Integrator& it) {
    const double e = it.energy().total();
    if (!std::isnan(previous)) worst_gain = std::max(worst_gain, e - previous);
    previous = e;
  }
};

}  // namespace

TEST_CASE("every friction scheme on the sliding mass: stop time within O(dt), then no creep, no energy gain",
          "[integrators][friction][sliding-mass]") {
  const nsb::SlidingMass p(nsb::Params(nsb::SlidingMass::parameters_spec(), {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "2"}}));
  REQUIRE(p.sticks());
  const double dt = 1e-3, t_s = p.stop_time(), d_s = p.stop_distance();
  for (const auto& entry : nsb::integrator_registry()) {
    SECTION(entry.name) {
      auto integ = init_or_check_decline(entry, p, true);
      if (!integ || !complementarity(entry)) continue;
      double t_stop = NAN, x_stop = NAN, worst_creep = 0.0;
      EnergyWatch energy;
      nsb::RunOptions options{dt, 2.0 * t_s, 1, false};
      const auto r = nsb::run(p, *integ, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
        const nsb::State& s = it.state();
        energy(it);
        if (std::isnan(t_stop) && std::abs(s.v[0]) <= 1e-12) {
          t_stop = s.t;
          x_stop = s.u[0];
        }
        if (!std::isnan(t_stop)) worst_creep = std::max(worst_creep, std::abs(s.u[0] - x_stop) + std::abs(s.v[0]));
      });
      REQUIRE(r.status == nsb::RunStatus::Ok);
      INFO("stop at " << t_stop << " (exact " << t_s << "), distance " << x_stop << " (exact " << d_s << ")");
      REQUIRE(!std::isnan(t_stop));
      // Stopped within the step that crosses t_s, reported one step on at most (staggered
      // schemes), at the distance travelled to O(dt v0).
      CHECK(std::abs(t_stop - t_s) <= 2.0 * dt);
      CHECK(std::abs(x_stop - d_s) <= 2.0 * dt * 2.0);
      const double rate = expected_creep_rate(entry.name, dt, 9.81 * 0.5);
      if (rate == 0.0) {
        CHECK(worst_creep <= 1e-12);
      } else {
        const double measured = worst_creep / (2.0 * t_s - t_stop);
        INFO("creep " << measured << " m/s, expected about " << rate);
        CHECK(measured == Approx(rate).epsilon(0.2));
      }
      // Energy scale m g d = 10 J: a gain is round-off or a wrong friction sign.
      CHECK(energy.worst_gain <= 1e-12 * 10.0);
    }
  }
}

TEST_CASE("every friction scheme on the rolling disk: rolling onset within O(dt), the exact final speed, "
          "no energy gain",
          "[integrators][friction][rolling-disk]") {
  const nsb::RollingDisk p(nsb::Params(nsb::RollingDisk::parameters_spec(),
                                       {{"v0", "1"}, {"omega0", "0"}, {"mu", "0.3"}, {"h0", "0"}}));
  const double dt = 1e-3, t_star = p.rolling_onset_time(), v_f = p.final_velocity(), R = 0.1, mu_g = 0.3 * 9.81;
  for (const auto& entry : nsb::integrator_registry()) {
    SECTION(entry.name) {
      auto integ = init_or_check_decline(entry, p, false);
      if (!integ || !complementarity(entry)) continue;
      double t_roll = NAN;
      EnergyWatch energy;
      nsb::RunOptions options{dt, 4.0 * t_star, 1, false};
      const auto r = nsb::run(p, *integ, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
        const nsb::State& s = it.state();
        energy(it);
        if (std::isnan(t_roll) && std::abs(s.v[0] + R * s.v[2]) <= 1e-12) t_roll = s.t;
      });
      REQUIRE(r.status == nsb::RunStatus::Ok);
      const nsb::State& s = integ->state();
      INFO("rolling from " << t_roll << " (exact " << t_star << "), v " << s.v[0] << " (exact " << v_f << ")");
      REQUIRE(!std::isnan(t_roll));
      CHECK(std::abs(t_roll - t_star) <= 2.0 * dt);
      // Rolling keeps x' - kappa R theta' and so the final speed: the scheme's error is the
      // slip phase's, at most a step of deceleration mu g dt.
      CHECK(std::abs(s.v[0] - v_f) <= mu_g * dt);
      CHECK(std::abs(s.v[0] + R * s.v[2]) <= 1e-12);
      CHECK(energy.worst_gain <= 1e-12 * 0.5);
    }
  }
}
