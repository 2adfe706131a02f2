// Every registered integrator on a small block-3d (problems/block_3d.hpp), frictionless and on
// the Coulomb cone: it declines in one line or lands the block without diverging. Every scheme
// that runs it with friction and spin (CD-Lagrange and Moreau–Jean at least) keeps, step by step
// after its first,
//     P_k+1 - P_k = dt F_ext,total + sum_i (Lambda_T1,i, Lambda_T2,i, Lambda_N,i)
// to round-off (T1, T2, L are +1 on a node's x, y, z dofs; sum F_int = 0), and the cone
// |Lambda_T,i| <= mu Lambda_N,i, Lambda_N,i >= 0 at every contact.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "integrators/registry.hpp"
#include "problems/block_3d.hpp"
#include "run/run.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

nsb::Block3d landing_block(const char* mu) {
  // 2 x 2 x 1 elements, tilted, just above the floor, sliding and spinning about the vertical.
  return nsb::Block3d(nsb::Params(nsb::Block3d::parameters_spec(), {{"nx", "2"}, {"ny", "2"}, {"nz", "1"}, {"tilt", "10"},
                                                                    {"height", "0.005"}, {"vx", "1"}, {"spin", "4"}, {"mu", mu}}));
}

struct Balance {
  double worst_momentum = 0.0;  // |P_k+1 - P_k - dt F_ext - sum of impulses|
  double worst_cone = 0.0;      // max |Lambda_T| - mu Lambda_N
  double worst_sign = 0.0;      // max -Lambda_N
  double total_normal = 0.0, total_tangential = 0.0;
};

// From the state after the first step (its momentum increment is the scheme's start: CD-Lagrange's
// half kick adds dt/2 of gravity to it), before the block lands.
Balance momentum_balance(const nsb::Block3d& b, nsb::Integrator& integ, double mu, double dt, int steps) {
  Balance out;
  nsb::Vec fext(b.ndof());
  b.external_force(0.0, fext);
  const Eigen::Vector3d weight(0.0, 0.0, fext.sum());
  integ.step(dt);
  REQUIRE(integ.impulses().lpNorm<Eigen::Infinity>() == 0.0);
  Eigen::Vector3d P = b.linear_momentum(integ.state().v);
  for (int k = 0; k < steps; ++k) {
    integ.step(dt);
    const nsb::Vec& N = integ.impulses();
    const nsb::Vec& T1 = integ.tangential_impulses();
    const nsb::Vec& T2 = integ.tangential_impulses2();
    const Eigen::Vector3d impulses(T1.sum(), T2.sum(), N.sum());
    const Eigen::Vector3d next = b.linear_momentum(integ.state().v);
    out.worst_momentum = std::max(out.worst_momentum, (next - P - dt * weight - impulses).norm());
    P = next;
    for (nsb::Index i = 0; i < N.size(); ++i) {
      out.worst_cone = std::max(out.worst_cone, std::hypot(T1[i], T2[i]) - mu * N[i]);
      out.worst_sign = std::max(out.worst_sign, -N[i]);
      out.total_tangential += std::hypot(T1[i], T2[i]);
    }
    out.total_normal += N.sum();
  }
  return out;
}

}  // namespace

TEST_CASE("block-3d: every integrator declines it in one line or lands the block", "[integrators][block-3d]") {
  for (const char* mu : {"0", "0.4"}) {
    const auto b = landing_block(mu);
    long ran = 0;
    for (const auto& entry : nsb::integrator_registry()) {
      INFO(entry.name << " on block-3d, mu = " << mu);
      auto integ = nsb::testing::init_or_decline(entry, b);
      if (!integ) continue;
      nsb::RunOptions options;
      options.dt = 0.25 * b.stable_step();
      options.t_end = 0.05;  // falls 5 mm in 0.02 s, then lands
      options.record_series = false;
      options.max_steps = 100'000;  // an adaptive step may shrink far on the stiff block
      const nsb::RunResult r = nsb::run(b, *integ, options);
      INFO(r.message);
      CHECK(r.status == nsb::RunStatus::Ok);
      CHECK(integ->state().u.allFinite());
      CHECK(integ->state().v.allFinite());
      // Nothing went far through the floor.
      CHECK((b.contacts().gap_offset + b.contacts().normal * integ->state().u).minCoeff() >= -0.02);
      ++ran;
    }
    CHECK(ran > 0);
  }
}

TEST_CASE("block-3d with friction and spin: P changes by gravity and the impulses only, the cone holds",
          "[integrators][block-3d][friction_cone]") {
  const double mu = 0.4;
  const auto b = landing_block("0.4");
  const double dt = 2e-4;
  long ran = 0;
  for (const auto& entry : nsb::integrator_registry()) {
    auto integ = nsb::testing::init_or_decline(entry, b);
    if (!integ) {
      for (const char* cone : {"cd-lagrange", "moreau-jean", "nsga", "d1-minus-linear", "cd-penalty", "penalty-bdf"})
        CHECK(entry.name != cone);
      continue;
    }
    if (nsb::testing::is_engine_peer(entry.name)) continue;  // their own contact models
    INFO(entry.name);
    const Balance c = momentum_balance(b, *integ, mu, dt, 250);
    // The block landed and friction acted (weight 2450 N over the last 0.03 s or so).
    REQUIRE(c.total_normal > 10.0);
    REQUIRE(c.total_tangential > 1.0);
    // Momentum scale: M |v| ~ 250 kg x 1 m/s; round-off of a few eps per step.
    CHECK(c.worst_momentum <= 1e-12 * 250.0);
    CHECK(c.worst_cone <= 1e-12 * c.total_normal);
    CHECK(c.worst_sign <= 0.0);
    ++ran;
  }
  CHECK(ran >= 6);
}
