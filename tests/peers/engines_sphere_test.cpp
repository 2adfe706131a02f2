// The physics-engine peers on the sphere (peers/engine_scene.hpp: a free sphere, the slope by
// tilted gravity): the engine's body mapped to the problem's six dofs, its roll onset against
// the closed form, the sphere below (2/7) tan(alpha) that never rolls.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "problems/sphere.hpp"
#include "tests/support/engine_built.hpp"

namespace {

struct EngineRollRun {
  std::string engine;
  std::map<std::string, std::string> params;
};

const EngineRollRun kSphereEngineRuns[] = {
    {"mujoco", {{"cone", "elliptic"}}}, {"mujoco", {{"cone", "pyramidal"}}}, {"bullet", {}}, {"ode", {}}};

double sphere_slip_speed(const nsb::State& s, double R) { return std::hypot(s.v[0] - R * s.v[4], s.v[1] + R * s.v[3]); }

struct EngineRoll {
  double roll_start = INFINITY;  // end of the first step with slip speed at most 1e-6 m/s
  double final_slip = NAN;
};

EngineRoll sphere_engine_roll(const EngineRollRun& run, const nsb::Sphere& p, double dt, double t_end) {
  auto integ = nsb::make_integrator(run.engine, run.params);
  integ->init(p, p.initial_state());
  const double R = p.parameters().real("R");
  EngineRoll out;
  while (integ->state().t < t_end - 0.5 * dt) {
    integ->step(dt);
    const nsb::State& s = integ->state();
    out.final_slip = sphere_slip_speed(s, R);
    if (out.final_slip <= 1e-6) out.roll_start = std::min(out.roll_start, s.t);
  }
  return out;
}

}  // namespace

TEST_CASE("engine peers: the sphere's roll onset against the closed form", "[peers][engines][three_d]") {
  const auto rolls = nsb::make_problem("sphere", {{"mu", "0.3"}});
  const auto& sphere = dynamic_cast<const nsb::Sphere&>(*rolls);
  const double t_roll = sphere.roll_time();
  REQUIRE(std::isfinite(t_roll));
  for (const EngineRollRun& run : kSphereEngineRuns) {
    if (!nsb::test::engine_built(run.engine)) continue;
    SECTION(run.engine + (run.params.empty() ? "" : ", cone " + run.params.at("cone"))) {
      const EngineRoll r = sphere_engine_roll(run, sphere, 1e-4, 0.5);
      INFO("roll start " << r.roll_start << ", exact " << t_roll << ", final slip " << r.final_slip);
      CHECK(r.final_slip < 1e-6);
      // A cone (MuJoCo's elliptic one; Bullet's first friction direction along the slip) stops
      // the turning slip when the closed form does: measured within 3e-4 s at dt = 1e-4. A
      // pyramid (ODE's along x and y, MuJoCo's pyramidal) bounds each component apart, not the
      // slip's length: the slip stops measurably off t_roll (ODE 0.033 s early, MuJoCo's
      // pyramid 0.11 s late at dt = 1e-4), bounded here, shown in the three-d study.
      const bool cone = run.engine == "bullet" || (run.engine == "mujoco" && run.params.at("cone") == "elliptic");
      CHECK(std::abs(r.roll_start - t_roll) < (cone ? 1e-3 : 0.5 * t_roll));
    }
  }
}

TEST_CASE("engine peers: the sphere below (2/7) tan(alpha) never rolls", "[peers][engines][three_d]") {
  const auto slides = nsb::make_problem("sphere", {{"mu", "0.05"}});
  const auto& sphere = dynamic_cast<const nsb::Sphere&>(*slides);
  REQUIRE(std::isinf(sphere.roll_time()));
  for (const EngineRollRun& run : kSphereEngineRuns) {
    if (!nsb::test::engine_built(run.engine)) continue;
    SECTION(run.engine + (run.params.empty() ? "" : ", cone " + run.params.at("cone"))) {
      const EngineRoll r = sphere_engine_roll(run, sphere, 1e-3, 0.5);
      // The exact slip at t = 0.5 is 2.314 m/s; ODE's pyramid slows it to 2.17.
      CHECK(r.final_slip > 2.0);
    }
  }
}
