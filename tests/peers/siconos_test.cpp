// The Siconos peers (peers/siconos/): built only with NSBENCH_SICONOS (tests/CMakeLists.txt
// reports the test as skipped otherwise).
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <map>
#include <memory>
#include <thread>

#include "integrators/registry.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/registry.hpp"
#include "problems/sphere.hpp"
#include "tests/problems/forwarding_problem.hpp"

namespace {

const char* const kPeers[] = {"siconos-moreau-jean", "siconos-schatzman-paoli", "siconos-d1-minus-linear"};

// Moving at 30 degrees down a slope; mu 0.3 < tan 30 slides on, mu 0.8 stops (at t = 1.06
// from v0 = 2) and sticks.
std::unique_ptr<nsb::Problem> siconos_sliding_mass(const std::string& mu, const std::string& v0) {
  return nsb::make_problem("sliding-mass", {{"alpha", "30"}, {"mu", mu}, {"v0", v0}});
}

// A registered problem on a belt: its contacts' obstacle moves at w along +T.
class OnBelt final : public ForwardingProblem {
 public:
  OnBelt(std::unique_ptr<nsb::Problem> problem, double w) : ForwardingProblem(std::move(problem)), contacts_(held().contacts()) {
    contacts_.tangent_velocity.setConstant(w);
  }
  const nsb::Contacts& contacts() const override { return contacts_; }

 private:
  nsb::Contacts contacts_;
};

using Strings = std::map<std::string, std::string>;

struct Agreement {
  double du = 0.0, dv = 0.0;  // max over the run of the max-norm differences, over ours' largest |u|, |v| (if > 0)
  double dimpulse = 0.0;      // normal and tangential impulses' differences, over ours' largest impulse
  double impulse = 0.0;       // sum of ours' normal impulses: a contact did act
  double slip_impulse = 0.0;  // sum of ours' |Lambda_T|: friction did act
  double slip2_impulse = 0.0; // sum of ours' |Lambda_T2|: friction along the second tangent (3D contacts)
  double dslip = 0.0;         // slip speed |(T v, T2 v)| (3D contacts), over ours' largest
  long peer_iterations = 0;   // the peer's friction-solver sweeps (0: no FrictionContact problem solved)
  double peer_roll_onset = 0.0;  // 3D contacts: the end of the peer's last step with a slip above 1e-9 (its last step: still slipping)
  double v_end = 0.0;         // ours' max |v| at the end
  int first_ours = -1, first_peer = -1;  // the first step with a normal impulse, each
};

// siconos-moreau-jean against moreau-jean in lockstep.
Agreement agreement(const nsb::Problem& problem, const Strings& ours_params, const Strings& peer_params, double dt, int steps) {
  auto ours = nsb::make_integrator("moreau-jean", ours_params);
  auto peer = nsb::make_integrator("siconos-moreau-jean", peer_params);
  ours->init(problem, problem.initial_state());
  peer->init(problem, problem.initial_state());
  Agreement a;
  double u_scale = 0.0, v_scale = 0.0, impulse_scale = 0.0, dimpulse = 0.0, slip_scale = 0.0;
  const nsb::Contacts& contacts = problem.contacts();
  const auto slip = [&](const nsb::Vec& v) -> nsb::Vec {
    return contacts.has_cone() ? ((contacts.tangent * v).cwiseAbs2() + (contacts.tangent2 * v).cwiseAbs2()).cwiseSqrt() : nsb::Vec();
  };
  for (int k = 0; k < steps; ++k) {
    ours->step(dt);
    const nsb::StepInfo info = peer->step(dt);
    REQUIRE(info.converged);
    a.peer_iterations += info.iterations;
    const nsb::State &x = ours->state(), &y = peer->state();
    a.du = std::max(a.du, (x.u - y.u).lpNorm<Eigen::Infinity>());
    a.dv = std::max(a.dv, (x.v - y.v).lpNorm<Eigen::Infinity>());
    u_scale = std::max(u_scale, x.u.lpNorm<Eigen::Infinity>());
    v_scale = std::max(v_scale, x.v.lpNorm<Eigen::Infinity>());
    dimpulse = std::max({dimpulse, (ours->impulses() - peer->impulses()).lpNorm<Eigen::Infinity>(),
                         (ours->tangential_impulses() - peer->tangential_impulses()).lpNorm<Eigen::Infinity>(),
                         (ours->tangential_impulses2() - peer->tangential_impulses2()).lpNorm<Eigen::Infinity>()});
    impulse_scale = std::max({impulse_scale, ours->impulses().lpNorm<Eigen::Infinity>(),
                              ours->tangential_impulses().lpNorm<Eigen::Infinity>(), ours->tangential_impulses2().lpNorm<Eigen::Infinity>()});
    a.impulse += ours->impulses().sum();
    a.slip_impulse += ours->tangential_impulses().cwiseAbs().sum();
    a.slip2_impulse += ours->tangential_impulses2().cwiseAbs().sum();
    if (contacts.has_cone()) {
      if (slip(y.v).maxCoeff() > 1e-9) a.peer_roll_onset = y.t;
      a.dslip = std::max(a.dslip, (slip(x.v) - slip(y.v)).lpNorm<Eigen::Infinity>());
      slip_scale = std::max(slip_scale, slip(x.v).lpNorm<Eigen::Infinity>());
    }
    if (a.first_ours < 0 && ours->impulses().sum() > 0.0) a.first_ours = k;
    if (a.first_peer < 0 && peer->impulses().sum() > 0.0) a.first_peer = k;
  }
  const auto relative = [](double d, double scale) { return scale > 0.0 ? d / scale : d; };  // at rest: absolute
  a.du = relative(a.du, u_scale);
  a.dv = relative(a.dv, v_scale);
  a.dimpulse = relative(dimpulse, impulse_scale);
  a.dslip = relative(a.dslip, slip_scale);
  a.v_end = ours->state().v.lpNorm<Eigen::Infinity>();
  return a;
}

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

TEST_CASE("siconos peers: siconos-moreau-jean agrees with moreau-jean under Coulomb friction to 1e-10", "[peers][siconos][friction]") {
  // theta = 1 too where the contact stays closed (g = g' = 0): there the two active-set
  // forecasts agree whatever gamma (unset: ours 1 - theta = 0, Siconos' 1/2).
  struct Case {
    const char* label;
    std::string problem;
    Strings params;
    std::vector<const char*> thetas;
  };
  const Case cases[] = {
      {"sliding mass, mu 0.3: slides on, accelerating", "sliding-mass", {{"alpha", "30"}, {"mu", "0.3"}, {"v0", "2"}}, {"0.5", "1"}},
      {"sliding mass, mu 0.8: slows down, then sticks", "sliding-mass", {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "2"}}, {"0.5", "1"}},
      {"sliding mass, mu 0.8, at rest: sticks throughout", "sliding-mass", {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "0"}}, {"0.5", "1"}},
      {"rolling disk on the floor, v0 1, mu 0.3: slips, then rolls", "rolling-disk", {{"v0", "1"}, {"omega0", "0"}, {"mu", "0.3"}}, {"0.5", "1"}},
      {"rolling disk dropped from 0.05, omega0 20, e 0.5, mu 0.3", "rolling-disk", {{"h0", "0.05"}, {"omega0", "20"}, {"e", "0.5"}, {"mu", "0.3"}}, {"0.5"}},
  };
  for (const Case& c : cases) {
    for (const char* theta : c.thetas) {
      DYNAMIC_SECTION(c.label << ", theta = " << theta) {
        auto problem = nsb::make_problem(c.problem, c.params);
        const Agreement a = agreement(*problem, {{"theta", theta}}, {{"theta", theta}}, 1e-3, 2000);
        CAPTURE(a.du, a.dv, a.dimpulse);
        CHECK(a.slip_impulse > 0.0);  // friction acted
        CHECK(a.du <= 1e-10);
        CHECK(a.dv <= 1e-10);
        CHECK(a.dimpulse <= 1e-10);
      }
    }
  }
}

TEST_CASE("siconos peers: a stuck body stays stuck in both", "[peers][siconos][friction]") {
  for (const char* v0 : {"2", "0"}) {
    auto problem = siconos_sliding_mass("0.8", v0);
    auto peer = nsb::make_integrator("siconos-moreau-jean");
    peer->init(*problem, problem->initial_state());
    for (int k = 0; k < 2000; ++k) peer->step(1e-3);
    CHECK(peer->state().v.lpNorm<Eigen::Infinity>() <= 1e-12);
    CHECK(peer->work().lcp_iterations >= 2000);  // the friction solver's sweeps, one step or more each
    CHECK(peer->work().lcp_unconverged == 0);
    CHECK(agreement(*problem, {{"theta", "0.5"}}, {{"theta", "0.5"}}, 1e-3, 2000).v_end <= 1e-12);
  }
}

TEST_CASE("siconos peers: friction declined where Siconos cannot treat it, with the reason", "[peers][siconos][friction]") {
  const auto input_error = [](nsb::Integrator& integrator, const nsb::Problem& problem) -> std::string {
    try {
      integrator.init(problem, problem.initial_state());
    } catch (const nsb::InputError& e) {
      return e.what();
    }
    return "no InputError";
  };
  for (const char* name : {"siconos-schatzman-paoli", "siconos-d1-minus-linear"}) {
    auto integrator = nsb::make_integrator(name);
    CHECK_FALSE(integrator->treats_friction());
    CHECK_THAT(input_error(*integrator, *siconos_sliding_mass("0.3", "2")), Catch::Contains("mu = 0.3"));
    CHECK_THAT(input_error(*integrator, *nsb::make_problem("rolling-disk")), Catch::Contains("mu = 0.3"));
  }
  // A moving floor: LagrangianLinearTIR has no velocity offset.
  auto peer = nsb::make_integrator("siconos-moreau-jean");
  CHECK(peer->treats_friction());
  CHECK_THAT(input_error(*peer, OnBelt(siconos_sliding_mass("0.3", "2"), 1.0)), Catch::Contains("floor_velocity") && Catch::Contains("tangent_velocity"));
  // Without friction the obstacle's tangential velocity plays no part.
  CHECK(input_error(*peer, OnBelt(siconos_sliding_mass("0", "2"), 1.0)) == "no InputError");
}

// The activation forecast g_k + gamma h g'_k <= 0: gamma unset is 1 - theta in ours, 1/2 in
// Siconos' MoreauJeanOSI. Given the same theta and gamma, the two are the same scheme.
TEST_CASE("siconos peers: siconos-moreau-jean agrees with moreau-jean step for step at the same theta and gamma", "[peers][siconos][gamma]") {
  struct Case {
    const char* label;
    std::string problem;
    Strings params;
    double dt;
    int steps;
  };
  // The bar with consistent mass too (W not diagonal); singular mass is declined by the peer.
  const Case cases[] = {
      {"bouncing mass, e = 0.9", "bouncing-mass", {{"e", "0.9"}}, 1e-3, 3000},
      {"Signorini bar, lumped", "signorini-bar", {{"N", "100"}, {"mass", "lumped"}, {"g0", "0.4937"}}, 2e-3, 1750},
      {"Signorini bar, consistent", "signorini-bar", {{"N", "100"}, {"mass", "consistent"}, {"g0", "0.4937"}}, 2e-3, 1750},
  };
  for (const Case& c : cases) {
    for (const char* theta : {"0.5", "1"}) {
      for (const char* gamma : {"0", "0.5"}) {
        DYNAMIC_SECTION(c.label << ", theta = " << theta << ", gamma = " << gamma) {
          auto problem = nsb::make_problem(c.problem, c.params);
          const Strings params = {{"theta", theta}, {"gamma", gamma}};
          const Agreement a = agreement(*problem, params, params, c.dt, c.steps);
          // Catch prints doubles fixed to 10 decimals: round-off would read 0.0.
          INFO(fmt::format("du {:.2e}, dv {:.2e}, dimpulse {:.2e}, first impulse at step {} / {}", a.du, a.dv, a.dimpulse,
                           a.first_ours, a.first_peer));
          CHECK(a.impulse > 0.0);  // the contact acted
          CHECK(a.first_ours == a.first_peer);
          CHECK(a.du <= 1e-10);
          CHECK(a.dv <= 1e-10);
          CHECK(a.dimpulse <= 1e-10);
        }
      }
    }
  }
}

TEST_CASE("siconos peers: at theta = 1 the unset gammas (ours 0, Siconos' 1/2) activate a step apart, and only they differ", "[peers][siconos][gamma]") {
  // Bouncing mass dropped from h0 = 1, h = 1e-3, theta = 1: u_k = h0 - h^2 g k (k + 1)/2, v_k = -k h g
  // (moreau_jean_test.cpp); gamma = 0 activates at k (k + 1) >= 2 h0 / (h^2 g) = 203873.6,
  // k = 452; gamma = 1/2 at k^2 + 2 k >= 203873.6, k = 451: Siconos impacts a step earlier.
  CHECK_FALSE(nsb::Params(nsb::find_integrator("moreau-jean").parameters()).optional_real("gamma"));
  CHECK(nsb::Params(nsb::find_integrator("siconos-moreau-jean").parameters()).real("gamma") == 0.5);
  auto problem = nsb::make_problem("bouncing-mass", {{"e", "0.9"}});
  const Agreement unset = agreement(*problem, {{"theta", "1"}}, {{"theta", "1"}}, 1e-3, 3000);
  CHECK(unset.first_ours == 452);
  CHECK(unset.first_peer == 451);
  CHECK(unset.dv > 0.1);  // the rebounds then differ by O(1) in the velocities
  // Ours given Siconos' 1/2, Siconos given ours' 0: the same numbers.
  for (const auto& [ours, peer] : {std::pair<Strings, Strings>{{{"theta", "1"}, {"gamma", "0.5"}}, {{"theta", "1"}}},
                                   std::pair<Strings, Strings>{{{"theta", "1"}}, {{"theta", "1"}, {"gamma", "0"}}}}) {
    const Agreement a = agreement(*problem, ours, peer, 1e-3, 3000);
    INFO(fmt::format("du {:.2e}, dv {:.2e}, dimpulse {:.2e}, first impulse at step {} / {}", a.du, a.dv, a.dimpulse,
                     a.first_ours, a.first_peer));
    CHECK(a.first_ours == a.first_peer);
    CHECK(a.du <= 1e-10);
    CHECK(a.dv <= 1e-10);
    CHECK(a.dimpulse <= 1e-10);
  }
}

// FrictionContact(3) with Siconos' 3D NSGS (the cone): the sphere's contact rows are constant,
// so Siconos' LagrangianLinearTIDS + LagrangianLinearTIR is the problem itself, and with the
// same theta and dt MoreauJeanOSI is our moreau-jean; ours solves the cone exactly
// (coulomb_cone.hpp), Siconos' NSGS to friction_tol = 1e-12. Measured: the slip speeds agree
// to 4e-16 of the largest (theta = 1/2, dt = 1e-3).
TEST_CASE("siconos peers: FrictionContact(3) on the sphere agrees with moreau-jean to round-off, roll onset within a step of the exact time",
          "[peers][siconos][friction_cone]") {
  CHECK(nsb::make_integrator("siconos-moreau-jean")->capabilities().friction_cone);
  for (const char* mu : {"0.3", "0.05"}) {
    auto problem = nsb::make_problem("sphere", {{"mu", mu}});
    const double t_roll = dynamic_cast<const nsb::Sphere&>(*problem).roll_time();
    for (const char* theta : {"0.5", "1"}) {
      for (const double dt : {2e-3, 1e-3, 5e-4}) {
        DYNAMIC_SECTION("mu = " << mu << ", theta = " << theta << ", dt = " << dt) {
          const Strings params = {{"theta", theta}, {"gamma", "0.5"}};
          const Agreement a = agreement(*problem, params, params, dt, static_cast<int>(std::lround(0.5 / dt)));
          INFO(fmt::format("du {:.2e}, dv {:.2e}, dimpulse {:.2e}, dslip {:.2e}, roll onset {:.6f} (exact {:.6f})", a.du, a.dv, a.dimpulse,
                           a.dslip, a.peer_roll_onset, t_roll));
          CHECK(a.slip_impulse > 0.0);   // friction acted along both tangents
          CHECK(a.slip2_impulse > 0.0);
          CHECK(a.peer_iterations > 0);  // Siconos solved a FrictionContact problem
          CHECK(a.dslip <= 1e-12);
          CHECK(a.du <= 1e-10);
          CHECK(a.dv <= 1e-10);
          CHECK(a.dimpulse <= 1e-10);
          if (std::isfinite(t_roll))  // mu = 0.3 > (2/7) tan 20 deg: rolls from t_roll on
            CHECK(std::abs(a.peer_roll_onset - t_roll) <= dt);
          else  // mu = 0.05: slides for ever
            CHECK(a.peer_roll_onset == Approx(0.5));
        }
      }
    }
  }
}

namespace {

// Contact force history (the step's impulses over dt) and the impulse in all, of one integrator.
struct ForceHistory {
  std::vector<double> force;
  double impulse = 0.0;
};

ForceHistory siconos_force_history(const nsb::Problem& problem, const std::string& name, const Strings& params, double dt, int steps) {
  auto integrator = nsb::make_integrator(name, params);
  integrator->init(problem, problem.initial_state());
  ForceHistory h;
  for (int k = 0; k < steps; ++k) {
    integrator->step(dt);
    h.force.push_back(integrator->impulses().sum() / dt);
    h.impulse += integrator->impulses().sum();
  }
  return h;
}

}  // namespace

// bar-3d with one_step_problem = fc3d: one FrictionContact(3) contact per wall-face node, mu = 0
// and zero tangent rows (the problem is frictionless): the same numbers as moreau-jean (and as
// Siconos' own LCP on the same problem); against cd-lagrange, another scheme, the impulse in all
// (the momentum the wall reverses; exact 2 rho A L v0 = 2 with the sides held) and the contact
// force history, which differ by the two schemes' own errors on these coarse meshes (dt = 0.9
// of the stable step): measured, impulse 1.854 against 1.930 (held, N = 6, N_side = 2) and 1.563
// against 1.651 (free, N = 4), rms force difference 9 % and 15 % of the peak.
TEST_CASE("siconos peers: FrictionContact(3) on a small bar-3d agrees with moreau-jean to round-off and with cd-lagrange's contact force",
          "[peers][siconos][friction_cone]") {
  const Strings fc3d = {{"one_step_problem", "fc3d"}};
  for (const Strings& bar : {Strings{{"N", "6"}, {"N_side", "2"}, {"lateral", "held"}}, Strings{{"N", "4"}, {"N_side", "1"}, {"lateral", "free"}}}) {
    DYNAMIC_SECTION("lateral = " << bar.at("lateral")) {
      auto problem = nsb::make_problem("bar-3d", bar);
      const double dt = 0.9 * problem->stable_step();
      const int steps = static_cast<int>(2.5 / dt);  // the contact phase, 2 L / c_p = 1.7 at nu = 0.3, and the rebound
      const Agreement a = agreement(*problem, {}, fc3d, dt, steps);
      INFO(fmt::format("du {:.2e}, dv {:.2e}, dimpulse {:.2e}", a.du, a.dv, a.dimpulse));
      CHECK(a.impulse > 0.0);
      CHECK(a.peer_iterations > 0);  // FrictionContact(3), not the LCP
      CHECK(a.du <= 1e-10);
      CHECK(a.dv <= 1e-10);
      CHECK(a.dimpulse <= 1e-10);
      CHECK(agreement(*problem, {}, {}, dt, steps).peer_iterations == 0);  // auto: Lemke's LCP
      const ForceHistory peer = siconos_force_history(*problem, "siconos-moreau-jean", fc3d, dt, steps);
      const ForceHistory cd = siconos_force_history(*problem, "cd-lagrange", {}, dt, steps);
      double l2 = 0.0, scale = 0.0;
      for (int k = 0; k < steps; ++k) {
        l2 += (peer.force[k] - cd.force[k]) * (peer.force[k] - cd.force[k]);
        scale = std::max(scale, std::abs(cd.force[k]));
      }
      const double force_difference = std::sqrt(l2 / steps) / scale;
      std::printf("bar-3d, lateral = %s: FC3D against cd-lagrange: impulse %.6f / %.6f, rms force difference %.3e of the peak\n",
                  bar.at("lateral").c_str(), peer.impulse, cd.impulse, force_difference);
      CHECK(peer.impulse == Approx(cd.impulse).epsilon(0.1));
      CHECK(force_difference <= 0.25);
    }
  }
}
