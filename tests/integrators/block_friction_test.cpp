// The 2D block sliding on a floor with Coulomb friction (DESIGN.md section 6), for every
// registered integrator that treats friction (the others must decline with mu named):
//   - the horizontal momentum changes by the tangential impulses only, step by step:
//       P_x,k+1 - P_x,k = sum_i Lambda_T,i     (T rows are +1 on the x dofs, sum F_int = 0)
//     and so, on the steps where every closed contact slides forwards, by -mu sum Lambda_N;
//   - the impulses satisfy the law: Lambda_N >= 0, |Lambda_T| <= mu Lambda_N, and the slip
//     after the step opposes Lambda_T (Lambda_T u_T(+) <= 0: friction takes energy);
//   - mu = 0 is the frictionless block, bit for bit.
#include <catch2/catch.hpp>
#include <cmath>

#include "integrators/registry.hpp"
#include "integrators/run.hpp"
#include "problems/block_2d.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

nsb::Block2d sliding_block(const std::string& mu) {
  return nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(), {{"mu", mu}, {"vx", "2"}, {"tilt", "0"},
                                                                     {"height", "0.01"}, {"nx", "6"}, {"ny", "3"}}));
}

}  // namespace

TEST_CASE("every integrator on the block with friction: P_x changes by the tangential impulses, the "
          "Coulomb law holds, friction takes energy",
          "[integrators][block-2d][contact][friction]") {
  const auto b = sliding_block("0.4");
  const double mu = 0.4, dt = 1e-4;
  const nsb::SpMat& T = b.contacts().tangent;
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
      double px_prev = b.linear_momentum(b.initial_state().v).x();
      double worst_identity = 0.0, worst_sliding = 0.0, worst_cone = 0.0, worst_work = 0.0;
      double total_tangential = 0.0, scale = 0.0;
      long sliding_steps = 0;
      nsb::Vec slip(T.rows());
      nsb::RunOptions options{dt, 0.1, 1, false};
      const auto r = nsb::run(b, *integ, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
        const nsb::Vec& n = it.impulses();
        const nsb::Vec& t = it.tangential_impulses();
        const double px = b.linear_momentum(it.state().v).x();
        scale = std::max(scale, std::abs(px));
        worst_identity = std::max(worst_identity, std::abs(px - px_prev - t.sum()));
        bool all_forward = n.sum() > 0.0;
        for (nsb::Index i = 0; i < n.size(); ++i)
          if (n[i] > 0.0) all_forward = all_forward && t[i] == -mu * n[i];
        if (all_forward) {
          ++sliding_steps;
          worst_sliding = std::max(worst_sliding, std::abs(px - px_prev + mu * n.sum()));
        }
        slip.noalias() = T * it.state().v;
        for (nsb::Index i = 0; i < n.size(); ++i) {
          worst_cone = std::max(worst_cone, std::abs(t[i]) - mu * n[i]);
          worst_work = std::max(worst_work, t[i] * slip[i]);
        }
        total_tangential += std::abs(t.sum());
        px_prev = px;
      });
      INFO(r.message);
      REQUIRE(r.status == nsb::RunStatus::Ok);
      REQUIRE(total_tangential > 1.0);  // friction did act (weight 4900 N x 0.1 s x mu)
      REQUIRE(sliding_steps > 10);
      // Each step adds rounding of a few eps_mach of the momentum scale.
      CHECK(worst_identity <= 1e-12 * scale);
      CHECK(worst_sliding <= 1e-12 * scale);
      CHECK(worst_cone <= 1e-12 * scale);
      // Lambda_T u_T(+) <= 0: the slip after the step never runs along the impulse (round-off
      // of the velocities, |v| ~ 2 m/s, times the impulse).
      CHECK(worst_work <= 1e-12 * scale * 2.0);
    }
  }
}

TEST_CASE("block with mu = 0 is the frictionless block bit for bit", "[integrators][block-2d][friction]") {
  const auto frictionless = nsb::Block2d(nsb::Params(nsb::Block2d::parameters_spec(), {{"vx", "2"}, {"tilt", "0"},
                                                                                          {"height", "0.01"}, {"nx", "6"}, {"ny", "3"}}));
  const auto zero_mu = sliding_block("0");
  CHECK(!zero_mu.contacts().has_friction());
  CHECK(zero_mu.contacts().tangent.rows() == 0);
  for (const char* name : {"cd-lagrange", "moreau-jean"}) {
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
