// Contacts between bodies (issue 23) for every registered integrator: Newton's cradle
// (ball-chain, n = 3) and two stacked blocks (two-blocks); and ImpulseContact's LCP path
// (CD-Lagrange's, taken when H = L M^{-1} L^T is not diagonal) against closed forms.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "integrators/impulse_contact.hpp"
#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/ball_chain.hpp"
#include "problems/two_blocks.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

nsb::BallChain chain(std::map<std::string, std::string> overrides) {
  return nsb::BallChain(nsb::Params(nsb::BallChain::parameters_spec(), overrides));
}

nsb::TwoBlocks blocks(std::map<std::string, std::string> overrides) {
  return nsb::TwoBlocks(nsb::Params(nsb::TwoBlocks::parameters_spec(), overrides));
}

// The schemes whose impacts solve one complementarity problem over every closed contact
// (an LCP with the Delassus matrix of the closed set): with the balls touching, Moreau's
// simultaneous law. The compliant ones (cd-penalty, penalty-bdf) resolve the impact over
// several steps or a contact duration, not as one LCP.
// siconos-schatzman-paoli is not among them: from touching balls it gives (-1, 1, 1) v0
// at e = 1 and (-2/3, 5/6, 5/6) v0 at e = 1/2 (momentum kept, kinetic energy x3 and x1.8),
// while this suite's schatzman-paoli gives Moreau's outcome; measured, not explained here.
const std::set<std::string> kComplementarity = {"cd-lagrange", "cd-lagrange-adaptive", "d1-minus-linear", "moreau-jean",
                                                "nsga", "schatzman-paoli", "symplectic-euler", "siconos-moreau-jean",
                                                "siconos-d1-minus-linear"};
// Schemes that can gain energy from touching or impacting bodies, by their own header:
// penalty-bdf misses the switch-on of a contact that starts at g = 0 (reference/penalty.hpp:
// "a missed switch-on is an energy source"; the touching chain at e = 1 ends with 2.2 times
// its kinetic energy), siconos-schatzman-paoli as above, and newmark-lm, the failing control
// with a lumped mass ("energy jumps at impacts and releases", newmark_lm.hpp; 5.8 E0 on two
// blocks).
const std::set<std::string> kMayGainEnergy = {"penalty-bdf", "siconos-schatzman-paoli", "newmark-lm"};

// Final velocities of a run on the chain to t_end (long after the last collision).
nsb::Vec run_chain(const nsb::BallChain& c, nsb::Integrator& integ, double dt, double t_end) {
  const auto r = nsb::run(c, integ, {dt, t_end, 1, false});
  INFO(r.message);
  REQUIRE(r.status == nsb::RunStatus::Ok);
  return integ.state().v;
}

}  // namespace

TEST_CASE("every integrator on the ball chain with gaps: the sequential outcome within O(dt v0 / gap)",
          "[integrators][bodies][ball-chain]") {
  for (const char* e : {"1", "0.5"}) {
    const auto c = chain({{"n", "3"}, {"gap", "0.1"}, {"e", e}, {"v0", "1"}});
    for (const auto& entry : nsb::integrator_registry()) {
      SECTION(std::string(entry.name) + ", e = " + e) {
        for (const double ratio : {0.1, 0.01}) {  // dt v0 / gap
          auto integ = nsb::testing::init_or_decline(entry, c);
          if (!integ) {
            SUCCEED("declined");
            break;
          }
          const nsb::Vec v = run_chain(c, *integ, ratio * 0.1, 2.0);
          const double error = (v - c.sequential_outcome()).cwiseAbs().maxCoeff();
          INFO("dt v0 / gap = " << ratio << ": v = " << v.transpose() << ", sequential " << c.sequential_outcome().transpose());
          CHECK(std::abs(c.momentum(v) - c.momentum(c.initial_state().v)) <= 1e-12);
          // The collisions are binary and apart by gap / v0 = 1 / ratio steps: each is the
          // scheme's own two-body impact, whose restitution is exact up to O(dt) where the
          // scheme claims it (ImpactAccuracy); a compliant contact (cd-penalty) resolves
          // it over ~2 steps with a phase-dependent restitution, exact only without
          // damping (e = 1).
          if (integ->impact_accuracy().restitution_exact || std::string(e) == "1") {
            CHECK(error <= ratio);
          } else {
            CHECK(c.kinetic_energy(v) <= c.kinetic_energy(c.initial_state().v));
          }
        }
      }
    }
  }
}

TEST_CASE("every integrator on the touching ball chain: momentum to round-off; the complementarity schemes give "
          "Moreau's simultaneous outcome",
          "[integrators][bodies][ball-chain]") {
  for (const char* e : {"1", "0.5"}) {
    const auto c = chain({{"n", "3"}, {"gap", "0"}, {"e", e}, {"v0", "1"}});
    for (const auto& entry : nsb::integrator_registry()) {
      SECTION(std::string(entry.name) + ", e = " + e) {
        auto integ = nsb::testing::init_or_decline(entry, c);
        if (!integ) {
          SUCCEED("declined");
          continue;
        }
        const nsb::Vec v = run_chain(c, *integ, 0.001, 1.0);
        INFO("v = " << v.transpose() << "; simultaneous " << c.simultaneous_outcome().transpose() << ", sequential "
                    << c.sequential_outcome().transpose());
        CHECK(std::abs(c.momentum(v) - c.momentum(c.initial_state().v)) <= 1e-12);
        // PGS stops at a relative residual of 1e-12: the velocities within 1e-10 v0.
        if (kComplementarity.count(entry.name)) CHECK((v - c.simultaneous_outcome()).cwiseAbs().maxCoeff() <= 1e-10);
        if (!kMayGainEnergy.count(entry.name))
          CHECK(c.kinetic_energy(v) <= c.kinetic_energy(c.initial_state().v) * (1 + 1e-10));
      }
    }
  }
}

TEST_CASE("every integrator on two blocks: momentum changes by the floor's impulses only, energy stays below E0 (e = 0)",
          "[integrators][bodies][two-blocks]") {
  for (const char* mu : {"0", "0.3"}) {
    // No gravity: the total momentum then changes by the floor's impulses alone (the
    // node-to-segment rows' weights sum to zero).
    const auto b = blocks({{"g", "0"}, {"mu", mu}, {"upper_vx", "0.5"}, {"upper_vy", "-1"}, {"e", "0"}});
    const double dt = 1e-4, t_end = 0.15;
    for (const auto& entry : nsb::integrator_registry()) {
      SECTION(std::string(entry.name) + ", mu = " + mu) {
        auto integ = nsb::testing::init_or_decline(entry, b);
        if (!integ) {
          SUCCEED("declined");
          continue;
        }
        const nsb::Index pf = b.floor_contacts();
        nsb::Vec v_prev = integ->state().v;
        double p_scale = 0.0;
        for (nsb::Index a = 0; a < b.ndof() / 2; ++a)
          p_scale += b.mass_matrix().coeff(2 * a, 2 * a) * v_prev.segment<2>(2 * a).norm();
        const double e0 = integ->energy().total();
        double worst = 0.0, between = 0.0, e_max = e0;
        nsb::RunOptions options{dt, t_end, 1, false};
        options.max_steps = 20 * static_cast<long>(t_end / dt);  // the adaptive scheme's step collapses (issue 5)
        const auto r = nsb::run(b, *integ, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
          const Eigen::Vector2d dP = b.linear_momentum(it.state().v) - b.linear_momentum(v_prev);
          const Eigen::Vector2d floor(it.tangential_impulses().head(pf).sum(), it.impulses().head(pf).sum());
          worst = std::max(worst, (dP - floor).norm());
          between += it.impulses().tail(b.ncontacts() - pf).sum();
          v_prev = it.state().v;
          e_max = std::max(e_max, it.energy().total());
        });
        INFO(r.message);
        REQUIRE((r.status == nsb::RunStatus::Ok || r.message.rfind("step limit", 0) == 0));
        REQUIRE(between > 1.0);  // the upper block did land on the lower one
        // Per step: rounding of sums over the nodes, a few hundred eps_mach of the scale
        // (measured <= 2.4e-11 = 1.4e-13 of it, schatzman-paoli).
        CHECK(worst <= 1e-12 * p_scale);
        // e = 0, no gravity: every contact dissipates or is neutral, so the scheme's energy
        // stays at or below E0 (it oscillates from step to step below it: up to 1e-3 E0 for
        // the explicit schemes, not a gain over E0).
        if (!kMayGainEnergy.count(entry.name)) CHECK(e_max - e0 <= 1e-12 * e0);
      }
    }
  }
}

TEST_CASE("two blocks, large sliding, launched sideways: momentum changes by the floor's impulses only",
          "[integrators][bodies][two-blocks][large-sliding]") {
  // No gravity, e = 0, mu = 0.3; the upper block at 1.5 m/s sideways: its bottom nodes cross
  // the lower block's top-edge nodes (0.2 m apart) while it lands and slides.
  const auto b = blocks({{"g", "0"}, {"mu", "0.3"}, {"upper_vx", "1.5"}, {"upper_vy", "-1"}, {"e", "0"}, {"sliding", "large"}});
  REQUIRE(b.contacts_move());
  const nsb::Index pf = b.floor_contacts(), slaves = b.ncontacts() - pf;
  const double dt = 1e-4, t_end = 0.15;
  for (const char* name : {"cd-lagrange", "moreau-jean"}) {
    SECTION(name) {
      auto integ = nsb::testing::init_or_decline(nsb::find_integrator(name), b);
      REQUIRE(integ);
      nsb::Vec v_prev = integ->state().v;
      double p_scale = 0.0;
      for (nsb::Index a = 0; a < b.ndof() / 2; ++a)
        p_scale += b.mass_matrix().coeff(2 * a, 2 * a) * v_prev.segment<2>(2 * a).norm();
      std::vector<nsb::Index> segment(static_cast<std::size_t>(slaves));
      for (nsb::Index k = 0; k < slaves; ++k) segment[static_cast<std::size_t>(k)] = b.segment_contact(b.initial_state().u, k).segment;
      long changes = 0;
      double worst = 0.0, between = 0.0, friction = 0.0;
      nsb::RunOptions options{dt, t_end, 1, false};
      const auto r = nsb::run(b, *integ, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
        const Eigen::Vector2d dP = b.linear_momentum(it.state().v) - b.linear_momentum(v_prev);
        const Eigen::Vector2d floor(it.tangential_impulses().head(pf).sum(), it.impulses().head(pf).sum());
        worst = std::max(worst, (dP - floor).norm());
        between += it.impulses().tail(slaves).sum();
        friction += it.tangential_impulses().tail(slaves).cwiseAbs().sum();
        for (nsb::Index k = 0; k < slaves; ++k) {
          const nsb::Index now = b.segment_contact(it.state().u, k).segment;
          changes += now != segment[static_cast<std::size_t>(k)];
          segment[static_cast<std::size_t>(k)] = now;
        }
        v_prev = it.state().v;
      });
      INFO(r.message << "; " << changes << " segment changes, worst |dP - floor impulses| " << worst << " of " << p_scale);
      REQUIRE(r.status == nsb::RunStatus::Ok);
      REQUIRE(between > 1.0);   // the upper block did land on the lower one
      REQUIRE(friction > 0.1);  // and slid on it under friction
      REQUIRE(changes >= 4);    // while its nodes changed segment
      CHECK(worst <= 1e-12 * p_scale);
    }
  }
}

TEST_CASE("impulse-contact: the LCP path (H not diagonal) agrees with the closed forms where both apply",
          "[integrators][bodies][lcp]") {
  const nsb::LcpOptions options{1e-14, 100000};
  nsb::StepInfo info;
  nsb::WorkCounters work;
  SECTION("closed contacts that share no dof: the per-contact closed form") {
    // Balls 1-2 and 3-4 touching and closing, 2-3 apart: H is tridiagonal, but the closed
    // contacts' block is diagonal.
    const auto c = chain({{"n", "4"}, {"gap", "0"}, {"e", "0.5"}});
    const nsb::Vec minv = nsb::Vec::Ones(4);
    nsb::ImpulseContact impulses(c, minv, options);
    nsb::Vec u(4), v_prev(4), v(4), lambda(3), tangential(3);
    u << 0.0, -0.01, 0.02, 0.015;  // g = (-0.01, 0.03, -0.005)
    v_prev << 1.0, 0.2, 0.1, -0.3;
    v = v_prev + nsb::Vec::Constant(4, 0.01);
    const nsb::Vec v_free = v;
    // 1: the general path (the diagonal one returns 0), its LCP diagonal, solved in one pass.
    CHECK(impulses.apply(u, v_prev, v, lambda, tangential, info, work) == 1);
    const double h = 2.0;  // (L M^{-1} L^T)_ii
    const auto closed_form = [&](int a, int b) {
      return std::max(0.0, -((v_free[b] - v_free[a]) + 0.5 * (v_prev[b] - v_prev[a])) / h);
    };
    CHECK(lambda[0] == Approx(closed_form(0, 1)).epsilon(1e-14));
    CHECK(lambda[1] == 0.0);
    CHECK(lambda[2] == Approx(closed_form(2, 3)).epsilon(1e-14));
    CHECK(lambda[0] > 0.0);
    CHECK(lambda[2] > 0.0);
  }
  SECTION("the touching chain: projected Gauss-Seidel reaches Moreau's exact impulses") {
    for (int n = 3; n <= 6; ++n) {
      INFO("n = " << n);
      const auto c = chain({{"n", std::to_string(n)}, {"gap", "0"}, {"e", "1"}, {"v0", "2"}});
      nsb::ImpulseContact impulses(c, nsb::Vec::Ones(n), options);
      const nsb::Vec v_prev = c.initial_state().v;
      nsb::Vec u = nsb::Vec::Zero(n), v = v_prev, lambda(n - 1), tangential(n - 1);
      u[0] = 1e-3;  // ball 1 has moved into ball 2: every contact closed (g_1 < 0, the rest 0)
      const long iterations = impulses.apply(u, v_prev, v, lambda, tangential, info, work);
      CHECK(iterations > 1);  // the general path, iterating
      CHECK((lambda - c.simultaneous_impulses()).cwiseAbs().maxCoeff() <= 1e-12);
      CHECK((v - c.simultaneous_outcome()).cwiseAbs().maxCoeff() <= 1e-12);
    }
  }
  CHECK(work.lcp_unconverged == 0);
}
