// The 2D block sliding on a floor with Coulomb friction (docs/method.md section 6), for every
// registered integrator that treats friction (the others must decline with mu named):
//   - the horizontal momentum changes by the tangential impulses only, step by step:
//       P_x,k+1 - P_x,k = sum_i Lambda_T,i     (T rows are +1 on the x dofs, sum F_int = 0)
//     and so, on the steps where every closed contact slides forwards, by -mu sum Lambda_N;
//   - the impulses satisfy the law: Lambda_N >= 0, |Lambda_T| <= mu Lambda_N, and the slip
//     after the step opposes Lambda_T (Lambda_T u_T(+) <= 0: friction takes energy);
//   - mu = 0 is the frictionless block, bit for bit.
#include <catch2/catch.hpp>

#include "integrators/registry.hpp"
#include "tests/integrators/every_integrator.hpp"
#include "tests/support/sliding_block.hpp"

using nsb::testing::sliding_block;

TEST_CASE("every integrator on the block with friction: P_x changes by the tangential impulses, the "
          "Coulomb law holds, friction takes energy",
          "[integrators][block-2d][contact][friction]") {
  const auto b = sliding_block("0.4");
  const double mu = 0.4, dt = 1e-4;
  for (const auto& entry : nsb::integrator_registry()) {
    SECTION(entry.name) {
      std::unique_ptr<nsb::Integrator> integ;
      try {
        integ = nsb::testing::init_or_decline(entry, b);
      } catch (const nsb::InputError& e) {
        FAIL(e.what());
      }
      if (!integ) {
        // A scheme without friction must say so (bind() names mu), never run the block.
        auto other = entry.make(nsb::Params(entry.parameters()));
        if (!other->treats_friction()) CHECK_THROWS_AS(other->init(b, b.initial_state()), nsb::InputError);
        continue;
      }
      const auto c = nsb::testing::check_block_friction(b, *integ, mu, dt, 0.1);
      INFO(c.run.message);
      REQUIRE(c.run.status == nsb::RunStatus::Ok);
      REQUIRE(c.total_tangential > 1.0);  // friction did act (weight 4900 N x 0.1 s x mu)
      REQUIRE(c.sliding_steps > 10);
      // Each step adds rounding of a few eps_mach of the momentum scale.
      CHECK(c.worst_identity <= 1e-12 * c.scale);
      CHECK(c.worst_sliding <= 1e-12 * c.scale);
      CHECK(c.worst_cone <= 1e-12 * c.scale);
      // Lambda_T u_T(+) <= 0: the slip after the step never runs along the impulse (round-off
      // of the velocities, |v| ~ 2 m/s, times the impulse).
      CHECK(c.worst_work <= 1e-12 * c.scale * 2.0);
    }
  }
}

TEST_CASE("block with mu = 0 is the frictionless block bit for bit", "[integrators][block-2d][friction]") {
  const auto frictionless = nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(), {{"vx", "2"}, {"tilt", "0"},
                                                                                          {"height", "0.01"}, {"nx", "6"}, {"ny", "3"}}));
  const auto zero_mu = sliding_block("0");
  CHECK(!zero_mu.contacts().has_friction());
  CHECK(zero_mu.contacts().tangent.rows() == 0);
  for (const char* name : {"cd-lagrange", "moreau-jean", "cd-penalty", "penalty-bdf"}) {
    auto a = nsb::make_integrator(name), c = nsb::make_integrator(name);
    a->init(frictionless, frictionless.initial_state());
    c->init(zero_mu, zero_mu.initial_state());
    for (int k = 0; k < 300; ++k) {
      a->step(1e-4);
      c->step(1e-4);
    }
    CHECK(a->state().u == c->state().u);
    CHECK(a->state().v == c->state().v);
  }
}

TEST_CASE("block-2d: a bad mu is refused with its name and range", "[problems][block-2d][friction]") {
  for (const char* bad : {"-0.1", "nan", "inf"}) {
    INFO(bad);
    CHECK_THROWS_WITH(nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(), {{"mu", bad}})), Catch::Contains("mu"));
  }
}
