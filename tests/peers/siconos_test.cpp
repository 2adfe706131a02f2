// The Siconos peers (peers/siconos/): built only with NSBENCH_SICONOS (tests/CMakeLists.txt
// reports the test as skipped otherwise).
#include <catch2/catch.hpp>

#include <cmath>
#include <thread>

#include "integrators/registry.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/registry.hpp"

namespace {

const char* const kPeers[] = {"siconos-moreau-jean", "siconos-schatzman-paoli", "siconos-d1-minus-linear"};

}  // namespace

TEST_CASE("siconos peers: the bouncing mass' impact times within O(dt)", "[peers][siconos]") {
  auto problem = nsb::make_problem("bouncing-mass", {{"e", "0.9"}});
  const auto& bm = dynamic_cast<const nsb::BouncingMass&>(*problem);
  for (const char* name : kPeers) {
    for (double dt : {1e-3, 1e-4}) {
    DYNAMIC_SECTION(name << ", dt = " << dt) {
      auto integrator = nsb::make_integrator(name);
      integrator->init(*problem, problem->initial_state());
      std::vector<double> impacts;
      double last = -1.0;
      while (integrator->state().t < 3.0) {
        integrator->step(dt);
        const double t = integrator->state().t;
        CHECK(integrator->impulses()[0] >= 0.0);
        // A new impact: an impulse after a flight (Schatzman-Paoli spreads one over two steps).
        if (integrator->impulses()[0] > 0.0) {
          if (t - last > 10 * dt) impacts.push_back(t);
          last = t;
        }
      }
      REQUIRE(impacts.size() >= 3);
      // As tests/integrators/contact_law_test.cpp: the impact is seen at the end of the step
      // that closes the gap and the rebound may cost one more step, so each impact adds at
      // most 2 dt of phase.
      for (int i = 1; i <= 3; ++i) {
        CAPTURE(i, impacts[i - 1] - bm.impact_time(i));
        CHECK(std::abs(impacts[i - 1] - bm.impact_time(i)) <= 2 * i * dt);
      }
    }
    }
  }
}

TEST_CASE("siconos peers: siconos-moreau-jean agrees with moreau-jean on the lumped bar to 1e-10", "[peers][siconos]") {
  auto problem = nsb::make_problem("signorini-bar", {{"N", "100"}, {"mass", "lumped"}, {"g0", "0.4937"}});
  auto ours = nsb::make_integrator("moreau-jean");
  auto peer = nsb::make_integrator("siconos-moreau-jean");
  ours->init(*problem, problem->initial_state());
  peer->init(*problem, problem->initial_state());
  const nsb::SpMat& L = problem->gap_operator();
  const double E0 = ours->energy().total();
  double u_scale = 0.0, du = 0.0, dE = 0.0, impulses = 0.0;
  for (int k = 0; k < 1750; ++k) {  // to t = 3.5: the whole contact phase and the rebound
    ours->step(2e-3);
    peer->step(2e-3);
    const double u = L.row(0).dot(ours->state().u), u_peer = L.row(0).dot(peer->state().u);
    u_scale = std::max(u_scale, std::abs(u));
    du = std::max(du, std::abs(u - u_peer));
    dE = std::max(dE, std::abs(ours->energy().total() - peer->energy().total()) / E0);
    impulses += ours->impulses().sum();
  }
  REQUIRE(impulses > 0.0);  // the bar did hit the wall
  CHECK(du / u_scale <= 1e-10);
  CHECK(dE <= 1e-10);
}

TEST_CASE("siconos peers: nonlinear problems, massless dofs and big problems are declined", "[peers][siconos]") {
  for (const char* name : kPeers) {
    auto integrator = nsb::make_integrator(name);
    auto block = nsb::make_problem("block-2d");
    CHECK_THROWS_AS(integrator->init(*block, block->initial_state()), nsb::InputError);
    auto singular = nsb::make_problem("signorini-bar", {{"mass", "singular"}});
    CHECK_THROWS_AS(integrator->init(*singular, singular->initial_state()), nsb::InputError);
    auto big = nsb::make_problem("signorini-bar", {{"N", "200"}});  // 201 dofs > max_dofs = 128
    CHECK_THROWS_AS(integrator->init(*big, big->initial_state()), nsb::InputError);
  }
}

TEST_CASE("siconos peers: registered and marked as peers", "[peers][siconos]") {
  for (const char* name : kPeers) {
    const auto& entry = nsb::find_integrator(name);
    CHECK(entry.peer);
    CHECK_FALSE(entry.reference);
  }
  CHECK(nsb::peer_versions().find("Siconos") != std::string::npos);
}

// Siconos calls BLAS, which Debian's serial OpenBLAS does not make safe for two threads at
// once: the adapter holds one lock around every model (peers/siconos/siconos_integrator.cpp).
// Two runs at once must give the bits of a run alone. A weak guard: without the lock this
// test still passed 5 times out of 5 (the bar's BLAS calls are small, the window narrow);
// the evidence for the lock is ThreadSanitizer, which found the race in dgemm_oncopy under
// SiconosIntegrator::step in the peers study with 2 jobs, and none with the lock.
TEST_CASE("siconos peers: two runs at once give the bits of a run alone", "[peers][siconos][threads]") {
  auto problem = nsb::make_problem("signorini-bar", {{"N", "100"}, {"mass", "lumped"}});
  const double dt = 0.9 * problem->stable_step();
  const auto run = [&] {
    auto integrator = nsb::make_integrator("siconos-moreau-jean");
    integrator->init(*problem, problem->initial_state());
    for (int k = 0; k < 400; ++k) integrator->step(dt);
    nsb::Vec out(2 * problem->ndof());
    out << integrator->state().u, integrator->state().v;
    return out;
  };
  const nsb::Vec alone = run();
  for (int pair = 0; pair < 3; ++pair) {
    nsb::Vec a, b;
    std::thread first([&] { a = run(); });
    std::thread second([&] { b = run(); });
    first.join();
    second.join();
    CHECK(a == alone);
    CHECK(b == alone);
  }
}
