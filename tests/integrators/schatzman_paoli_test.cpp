// schatzman-paoli (integrators/schatzman_paoli.hpp): the position-level law at e = 0 leaves
// no penetration at the end of any step (the projection is exact, closed form or LCP), for
// the explicit and the implicit variants; what it declines, it declines by name.
#include <catch2/catch.hpp>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/block_2d.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/signorini_bar.hpp"

namespace {

nsb::SignoriniBar sp_bar(const std::string& mass) {
  return nsb::SignoriniBar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"mass", mass}, {"N", "50"}, {"g", "0.25"}}));
}

// Largest penetration max(0, -g) at the end of a step, over the run.
double max_penetration(const nsb::Problem& p, const std::string& theta, double dt, double t_end) {
  auto integ = nsb::make_integrator("schatzman-paoli", {{"theta", theta}});
  integ->init(p, p.initial_state());
  nsb::RunOptions opt{dt, t_end, 1, false};
  const nsb::RunResult r = nsb::run(p, *integ, opt);
  REQUIRE(r.status == nsb::RunStatus::Ok);
  return r.max_penetration;
}

}  // namespace

TEST_CASE("schatzman-paoli, e = 0: no penetration beyond round-off at the end of a step", "[integrators][schatzman-paoli]") {
  SECTION("bouncing mass (Zeno, then resting), explicit") {
    const nsb::BouncingMass p(nsb::Params(nsb::BouncingMass::parameters_spec(), {{"e", "0"}}));
    CHECK(max_penetration(p, "0", 1e-3, 2.0) <= 1e-15);
  }
  // The bar with gravity towards the wall: it hits, leaves and comes back (many contacts).
  for (const std::string theta : {"0", "0.25", "0.5"}) {
    DYNAMIC_SECTION("lumped bar, theta = " << theta) {
      const auto p = sp_bar("lumped");
      CHECK(max_penetration(p, theta, 0.9 * p.stable_step(), 6.0) <= 1e-14);
    }
  }
  SECTION("singular bar (massless contact node), theta = 1/4, a step 4x the CFL step") {
    const auto p = sp_bar("singular");
    CHECK(max_penetration(p, "0.25", 4.0 * p.stable_step(), 6.0) <= 1e-14);
  }
}

TEST_CASE("schatzman-paoli declines what it cannot do, naming theta", "[integrators][schatzman-paoli]") {
  const auto singular = sp_bar("singular");
  const auto consistent = sp_bar("consistent");
  const nsb::Block2d block(nsb::Params(nsb::Block2d::parameters_spec()));
  auto explicit_sp = nsb::make_integrator("schatzman-paoli");
  CHECK_THROWS_AS(explicit_sp->init(singular, singular.initial_state()), nsb::InputError);
  CHECK_THROWS_AS(explicit_sp->init(consistent, consistent.initial_state()), nsb::InputError);
  CHECK_NOTHROW(explicit_sp->init(block, block.initial_state()));
  auto implicit_sp = nsb::make_integrator("schatzman-paoli", {{"theta", "0.25"}});
  CHECK_THROWS_WITH(implicit_sp->init(block, block.initial_state()), Catch::Contains("theta"));
  CHECK_NOTHROW(implicit_sp->init(consistent, consistent.initial_state()));
}
