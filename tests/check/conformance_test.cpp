// The deformable case of the integrator check (check/conformance.hpp): its bound is the energy
// oscillation a conservative scheme shows at that step, and newmark-lm, which holds the bouncing
// mass, fails it while the schemes with an impact law pass (every other built-in scheme passes
// it with the rest of the check: tests/app/check_test.cpp).
#include <catch2/catch.hpp>
#include <algorithm>
#include <cmath>

#include "check/conformance.hpp"
#include "integrators/registry.hpp"

using Catch::Detail::Approx;

namespace {

const nsb::CheckVerdict& deformable_verdict(const std::vector<nsb::CheckVerdict>& verdicts) {
  const auto it = std::find_if(verdicts.begin(), verdicts.end(), [](const nsb::CheckVerdict& v) { return v.property == "deformable"; });
  REQUIRE(it != verdicts.end());
  return *it;
}

}  // namespace

TEST_CASE("check deformable: the bound is what symplectic Euler's energy reaches on a mode at that step", "[check][conformance]") {
  // On u'' = -omega^2 u at omega dt = 2 p (the bar's highest mode at dt = p stable_step), from
  // its conserved H's smallest E_n: the reported energy's largest rise over H (E0 = H, the
  // rigid start) approaches p / (1 - p) and stays below it.
  const double p = nsb::kDeformableStepRatio, omega = 1.0, dt = 2.0 * p / omega;
  double u = 1.0, v = 0.0, h = 0.0, worst = 0.0;
  for (int n = 0; n < 20000; ++n) {
    const double e = 0.5 * (v * v + omega * omega * u * u);
    const double invariant = e - 0.5 * omega * omega * dt * u * v;
    if (n == 0) h = invariant;
    CHECK(std::abs(invariant - h) <= 1e-12);  // H is conserved...
    worst = std::max(worst, e / h - 1.0);
    v -= dt * omega * omega * u;
    u += dt * v;
  }
  CHECK(worst <= nsb::deformable_rise_bound() * (1.0 + 1e-12));  // ...and E_n stands at most 1 / (1 - p) above it
  CHECK(worst >= 0.99 * nsb::deformable_rise_bound());           // and reaches it: not a bound left loose
}

TEST_CASE("check deformable: newmark-lm, stable on the bouncing mass, fails; the schemes with an impact law pass",
          "[check][conformance]") {
  const auto newmark = nsb::deformable_energy(nsb::find_integrator("newmark-lm"));
  REQUIRE(newmark);
  CHECK(newmark->worst_rise > nsb::deformable_rise_bound());
  const auto verdicts = nsb::check_integrator(nsb::find_integrator("newmark-lm"));
  const nsb::CheckVerdict& v = deformable_verdict(verdicts);
  CHECK(v.outcome == nsb::CheckVerdict::Outcome::Fail);
  CHECK_THAT(v.figure, Catch::Contains("signorini-bar N = 20, e = 0"));
  // It holds the bouncing mass's plastic impact all the same: the deformable case is what catches it.
  for (const char* property : {"impulse sign", "impact times"}) {
    const auto it = std::find_if(verdicts.begin(), verdicts.end(), [&](const nsb::CheckVerdict& c) { return c.property == property; });
    REQUIRE(it != verdicts.end());
    CHECK(it->outcome == nsb::CheckVerdict::Outcome::Pass);
  }
  for (const char* name : {"cd-lagrange", "moreau-jean"}) {
    CAPTURE(name);
    const auto d = nsb::deformable_energy(nsb::find_integrator(name));
    REQUIRE(d);
    CHECK(d->finished);
    CHECK(d->t_final == Approx(nsb::kDeformableEnd));  // the run's last step reaches t_end to its rounding
    CHECK(d->worst_rise <= nsb::deformable_rise_bound());
    CHECK(d->final_change < 0.0);  // the e = 0 node impacts lose energy
  }
}
