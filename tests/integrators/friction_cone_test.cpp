// The 3D Coulomb cone in the schemes that declare "3D friction cone" (cd-lagrange, moreau-jean,
// nsga, d1-minus-linear; integrators/capabilities.hpp), per contact and step (docs/three_d.md):
// the law's Alart–Curnier residual at the step's local velocities, stick inside the cone (the
// slip after the step is zero), slip on its boundary opposite to the slip velocity, no energy
// gain; the sphere's roll-onset time against its exact value; every other scheme declines the
// cone in one line. The penalty schemes (cd-penalty, penalty-bdf) with the regularised cone:
// the law's implicit form, the bound, the direction and the energy per step; the band's entry
// against the exact roll onset and the creep.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>

#include "integrators/registry.hpp"
#include "integrators/spring_dashpot.hpp"
#include "problems/registry.hpp"
#include "problems/rigid_problem.hpp"
#include "problems/sphere.hpp"
#include "run/run.hpp"
#include "solvers/coulomb_cone.hpp"

using nsb::Index;
using nsb::Vec;

namespace {

// A body of three dofs with unequal masses on a plane whose rows are not aligned with the dofs:
// its contact's Delassus block is full (W_NT != 0), the local solve's case, not the closed form.
class SkewContact final : public nsb::RigidProblem {
 public:
  SkewContact(double mu, const Eigen::Vector3d& v0) : v0_(v0) {
    mass_ = Vec(3);
    mass_ << 1.0, 2.0, 0.5;
    load_ = Vec(3);
    load_ << 0.3, 0.2, -5.0;
    const auto row = [](double a, double b, double c) {
      nsb::SpMat r(1, 3);
      r.insert(0, 0) = a;
      r.insert(0, 1) = b;
      r.insert(0, 2) = c;
      return r;
    };
    contacts_.normal = row(0.1, 0.2, 1.0);
    contacts_.gap_offset = Vec::Zero(1);
    contacts_.set_cone(row(1.0, 0.0, -0.1), row(-0.05, 1.0, -0.2), mu);
  }
  std::string name() const override { return "skew-contact"; }
  const nsb::Params& parameters() const override { return params_; }
  nsb::State initial_state() const override { return {0.0, Vec::Zero(3), Vec(v0_)}; }

 private:
  nsb::Params params_{nsb::ParamSpecs{}, {}};
  Eigen::Vector3d v0_;
};

struct ConeChecks {
  double worst_residual = 0.0;     // the cone law's residual (coulomb_cone.hpp), relative
  double worst_stick_slip = 0.0;   // |U_T| / |q| after a sticking step
  double worst_alignment = 0.0;    // 1 + cos(Lambda_T, U_T) on slipping steps (0: opposite)
  double worst_impulse_work = 0.0;  // Lambda . (q + U) / 2 per contact, relative to W-energy of q
  double worst_energy_gain = 0.0;   // max(0, E_{k+1} - E_k) / E scale
  long stick_steps = 0, slip_steps = 0;
};

// Per step and contact: U = C v after the step (e = 0), W = C M^{-1} C^T with C = [L; T; T2],
// q = U - W Lambda the local velocity before the impulse.
ConeChecks check_cone(const nsb::Problem& p, nsb::Integrator& integ, double dt, double t_end) {
  ConeChecks c;
  const nsb::Contacts& k = p.contacts();
  const Vec minv = p.mass_matrix().diagonal().cwiseInverse();
  double energy = std::numeric_limits<double>::quiet_NaN(), scale = 0.0;
  integ.init(p, p.initial_state());
  nsb::run(p, integ, {dt, t_end, 1, false}, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
    const Vec& v = it.state().v;
    for (Index i = 0; i < k.size(); ++i) {
      const double n = it.impulses()[i];
      if (n == 0.0) continue;
      Eigen::MatrixXd C(3, p.ndof());
      C.row(0) = Eigen::MatrixXd(k.normal.row(i));
      C.row(1) = Eigen::MatrixXd(k.tangent.row(i));
      C.row(2) = Eigen::MatrixXd(k.tangent2.row(i));
      const Eigen::Matrix3d W = C * minv.asDiagonal() * C.transpose();
      const Eigen::Vector3d lambda(n, it.tangential_impulses()[i], it.tangential_impulses2()[i]);
      const Eigen::Vector3d U = C * v, q = U - W * lambda;
      const nsb::ConeImpulse impulse{n, lambda.tail<2>()};
      c.worst_residual = std::max(c.worst_residual, nsb::cone_law_residual(W, q, k.mu[i], impulse));
      // The impulse's kinetic energy change in local terms (e = 0: q before, U after).
      const double scale_q = q.dot(W.ldlt().solve(q));
      c.worst_impulse_work = std::max(c.worst_impulse_work, 0.5 * lambda.dot(q + U) / scale_q);
      const double bound = k.mu[i] * n, length = lambda.tail<2>().norm();
      if (length < bound * (1.0 - 1e-9)) {
        ++c.stick_steps;
        c.worst_stick_slip = std::max(c.worst_stick_slip, U.tail<2>().norm() / q.norm());
      } else if (U.tail<2>().norm() > 1e-9 * q.norm()) {
        ++c.slip_steps;
        c.worst_alignment = std::max(c.worst_alignment, 1.0 + lambda.tail<2>().dot(U.tail<2>()) / (length * U.tail<2>().norm()));
      }
    }
    const double e = it.energy().total();
    scale = std::max(scale, std::abs(e));
    if (!std::isnan(energy)) c.worst_energy_gain = std::max(c.worst_energy_gain, e - energy);
    energy = e;
  });
  c.worst_energy_gain /= scale;
  return c;
}

const char* const kConeSchemes[] = {"cd-lagrange", "moreau-jean", "nsga", "d1-minus-linear"};

}  // namespace

TEST_CASE("friction cone: a full Delassus block (local solve), stick and slip, for every scheme with the cone",
          "[integrators][friction_cone]") {
  for (const char* name : kConeSchemes) {
    INFO(name);
    // Sliding (mu 0.3: the load's tangential part cannot hold it, it slips throughout) ...
    const SkewContact sliding(0.3, {1.0, 0.5, -0.2});  // L v0 = 0: starts sliding on the plane
    auto a = nsb::make_integrator(name, {});
    const ConeChecks s = check_cone(sliding, *a, 1e-3, 0.2);
    CHECK(s.slip_steps > 150);
    CHECK(s.worst_residual < 1e-12);
    CHECK(s.worst_alignment < 1e-12);
    CHECK(s.worst_impulse_work <= 1e-14);
    // ... and held (mu 2: it stops, then sticks under the load).
    const SkewContact held(2.0, {0.2, -0.1, 0.0});
    auto b = nsb::make_integrator(name, {});
    const ConeChecks h = check_cone(held, *b, 1e-3, 0.2);
    CHECK(h.stick_steps > 150);
    CHECK(h.worst_residual < 1e-12);
    CHECK(h.worst_stick_slip < 1e-12);
    CHECK(h.worst_impulse_work <= 1e-14);
    // No step-to-step energy statement here: with W_NT != 0 the balance of the step (for
    // moreau-jean Lambda . C (v_k + v_{k+1}) / 2 at theta 1/2) is not the impulse's alone.
  }
}

TEST_CASE("friction cone: the sphere's contact (closed form), slip then rolling, no energy gain",
          "[integrators][friction_cone]") {
  const auto sphere = nsb::make_problem("sphere", {{"alpha", "0"}});  // level floor: energy can only fall
  for (const char* name : kConeSchemes) {
    INFO(name);
    auto integ = nsb::make_integrator(name, {});
    const ConeChecks c = check_cone(*sphere, *integ, 1e-3, 0.2);
    CHECK(c.slip_steps > 10);
    CHECK(c.stick_steps > 10);
    CHECK(c.worst_residual < 1e-12);
    CHECK(c.worst_alignment < 1e-12);
    CHECK(c.worst_stick_slip < 1e-12);
    CHECK(c.worst_impulse_work <= 1e-14);
    CHECK(c.worst_energy_gain <= 1e-14);
  }
}

namespace {

// The time of the first step from which the slip stays below kStopped to the end, NaN if none.
double measured_roll_time(const nsb::Problem& sphere, const char* scheme, double dt, double t_end) {
  constexpr double kStopped = 1e-9;
  auto integ = nsb::make_integrator(scheme, {});
  const nsb::Contacts& c = sphere.contacts();
  double onset = std::numeric_limits<double>::quiet_NaN();
  integ->init(sphere, sphere.initial_state());
  nsb::run(sphere, *integ, {dt, t_end, 1, false}, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
    const double slip = std::hypot((c.tangent * it.state().v)(0), (c.tangent2 * it.state().v)(0));
    if (slip > kStopped) onset = std::numeric_limits<double>::quiet_NaN();
    else if (std::isnan(onset)) onset = it.state().t;
  });
  return onset;
}

}  // namespace

TEST_CASE("friction cone: the sphere's roll onset within O(dt) of the exact time", "[integrators][friction_cone]") {
  const auto problem = nsb::make_problem("sphere", {});
  const double exact = dynamic_cast<const nsb::Sphere&>(*problem).roll_time();
  for (const char* name : kConeSchemes) {
    INFO(name);
    // Measured (printed below): the onset falls within one step of the exact time at each dt,
    // quantised to the step grid, so the error is O(dt) without a clean ratio between two dt.
    for (const double dt : {2e-3, 1e-3, 5e-4}) {
      const double error = measured_roll_time(*problem, name, dt, 0.4) - exact;
      std::printf("%s: roll-onset error %.3e s at dt %.0e (exact %.6f s)\n", name, error, dt, exact);
      CHECK(std::abs(error) <= dt);
    }
  }
}

TEST_CASE("friction cone: every scheme without the capability declines the cone in one line", "[integrators][friction_cone]") {
  const auto sphere = nsb::make_problem("sphere", {});
  for (const auto& entry : nsb::integrator_registry()) {
    auto integ = nsb::make_integrator(entry.name, {});
    if (integ->capabilities().friction_cone) continue;
    INFO(entry.name);
    std::string what;
    try {
      integ->init(*sphere, sphere->initial_state());
    } catch (const nsb::InputError& e) {
      what = e.what();
    }
    CHECK_THAT(what, Catch::StartsWith("integrator " + entry.name));  // " with theta = 0" may follow
    CHECK_THAT(what, Catch::Contains(" needs 2D contacts (one tangent row: the Coulomb interval) or mu = 0; problem sphere has 3D contacts "
                      "with friction (two tangent rows: the Coulomb cone, mu = 0.3) (valid: a problem with 2D contacts or "
                      "mu = 0, or an integrator `nsbench list` marks as treating the 3D friction cone)"));
  }
}

// The regularised cone of the penalty schemes (cd-penalty, penalty-bdf; integrators/
// spring_dashpot.hpp): F_T = -mu F_N u_T / max(v_reg, |u_T|), v_reg = friction_velocity
// (1e-3 m/s, both schemes' default).
namespace {

const char* const kRegularisedConeSchemes[] = {"cd-penalty", "penalty-bdf"};
constexpr double kRegularisedConeVelocity = 1e-3;

// The law's residual of the implicit form, |Lambda_T + a phi((s + H Lambda_T) / v_reg)| / a.
double regularised_cone_residual(double a, const Eigen::Vector2d& s, const Eigen::Matrix2d& H, const Eigen::Vector2d& lambda) {
  const Eigen::Vector2d u = s + H * lambda;
  return (lambda + a * u / std::max(kRegularisedConeVelocity, u.norm())).norm() / a;
}

}  // namespace

TEST_CASE("regularised cone: the implicit law solved, isotropic (closed form) and full H_T (bisection)",
          "[integrators][friction_cone]") {
  const double mu = 0.4, normal = 0.5, a = mu * normal;
  Eigen::Matrix2d full;
  full << 2.0, 0.7, 0.7, 0.5;
  for (const Eigen::Matrix2d& H : {Eigen::Matrix2d(1.3 * Eigen::Matrix2d::Identity()), full}) {
    for (const Eigen::Vector2d& s : {Eigen::Vector2d(3.0, -1.0), Eigen::Vector2d(0.05, 0.02), Eigen::Vector2d(1e-4, -2e-4)}) {
      INFO("H = " << H(0, 0) << " " << H(0, 1) << " " << H(1, 1) << ", s = " << s.transpose());
      const Eigen::Vector2d lambda = nsb::implicit_regularised_cone_friction(mu, normal, s, H, kRegularisedConeVelocity);
      CHECK(regularised_cone_residual(a, s, H, lambda) < 1e-12);
      CHECK(lambda.norm() <= a * (1.0 + 1e-15));
      CHECK(lambda.dot(s) < 0.0);  // dissipative: against the slip
    }
  }
  // The 1D law is its one-row case: a slip along one axis with H diagonal gives the 2D impulse.
  const Eigen::Matrix2d diagonal = Eigen::Vector2d(0.8, 0.8).asDiagonal();
  for (const double s : {3.0, 2e-4, -0.5})
    CHECK(nsb::implicit_regularised_cone_friction(mu, normal, {s, 0.0}, diagonal, kRegularisedConeVelocity)[0] ==
          Approx(nsb::implicit_regularised_friction(mu, normal, s, 0.8, kRegularisedConeVelocity)).epsilon(1e-15));
}

TEST_CASE("regularised cone: the force law's slopes (penalty-bdf's Jacobian) against central differences",
          "[integrators][friction_cone]") {
  const double mu = 0.4, normal = 2.0, step = 1e-7;
  // Inside the band (viscous) and outside (sliding, the force turning with the slip).
  for (const Eigen::Vector2d& slip : {Eigen::Vector2d(3e-4, -4e-4), Eigen::Vector2d(0.3, -0.2)}) {
    INFO("slip " << slip.transpose());
    const double h = step * std::max(slip.norm(), kRegularisedConeVelocity);
    const nsb::RegularisedConeFriction law = nsb::regularised_cone_friction(mu, normal, slip, kRegularisedConeVelocity);
    for (int l = 0; l < 2; ++l) {
      const Eigen::Vector2d e = Eigen::Vector2d::Unit(l) * h;
      const Eigen::Vector2d fd = (nsb::regularised_cone_friction(mu, normal, slip + e, kRegularisedConeVelocity).force -
                                  nsb::regularised_cone_friction(mu, normal, slip - e, kRegularisedConeVelocity).force) /
                                 (2.0 * h);
      CHECK((fd - law.d_slip.col(l)).norm() <= 1e-6 * mu * normal / kRegularisedConeVelocity);
    }
    const Eigen::Vector2d fd_normal = (nsb::regularised_cone_friction(mu, normal + 1e-6, slip, kRegularisedConeVelocity).force -
                                       nsb::regularised_cone_friction(mu, normal - 1e-6, slip, kRegularisedConeVelocity).force) /
                                      2e-6;
    CHECK((fd_normal - law.d_normal).norm() <= 1e-8);
    CHECK(law.force.norm() <= mu * normal * (1.0 + 1e-15));
  }
}

TEST_CASE("regularised cone: the sphere on a level floor, per contact and step, for every penalty scheme",
          "[integrators][friction_cone]") {
  const auto sphere = nsb::make_problem("sphere", {{"alpha", "0"}});
  const nsb::Contacts& k = sphere->contacts();
  const Vec minv = sphere->mass_matrix().diagonal().cwiseInverse();
  Eigen::MatrixXd C(2, sphere->ndof());
  C.row(0) = Eigen::MatrixXd(k.tangent.row(0));
  C.row(1) = Eigen::MatrixXd(k.tangent2.row(0));
  const Eigen::Matrix2d H = C * minv.asDiagonal() * C.transpose();
  for (const char* name : kRegularisedConeSchemes) {
    INFO(name);
    const bool implicit_law = std::string(name) == "cd-penalty";  // its impulse is the law's at the step's end
    auto integ = nsb::make_integrator(name, {});
    integ->init(*sphere, sphere->initial_state());
    const double e0 = integ->energy().total();
    double worst_bound = 0.0, worst_alignment = 0.0, worst_law = 0.0, energy = e0, worst_gain = 0.0;
    long sliding = 0, viscous = 0;
    nsb::run(*sphere, *integ, {1e-3, 0.3, 1, false}, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
      const double n = it.impulses()[0];
      const Eigen::Vector2d lambda(it.tangential_impulses()[0], it.tangential_impulses2()[0]);
      const Eigen::Vector2d u = C * it.state().v;  // the slip after the step (w = 0)
      if (n > 0.0 && lambda.norm() > 0.0) {
        worst_bound = std::max(worst_bound, lambda.norm() / (k.mu[0] * n) - 1.0);
        if (u.norm() >= kRegularisedConeVelocity) {
          ++sliding;
          worst_alignment = std::max(worst_alignment, 1.0 + lambda.dot(u) / (lambda.norm() * u.norm()));
        } else {
          ++viscous;
        }
        // cd-penalty: s = u - H Lambda_T, the slip before the tangential impulse.
        if (implicit_law) worst_law = std::max(worst_law, regularised_cone_residual(k.mu[0] * n, u - H * lambda, H, lambda));
      }
      const double e = it.energy().total();
      worst_gain = std::max(worst_gain, (e - energy) / e0);
      energy = e;
    });
    CHECK(sliding > 50);  // the slip phase (about 0.07 s at mu = 0.3 on the level floor)
    CHECK(viscous > 0);   // then the band, where the viscous law damps the slip out
    CHECK(worst_bound <= 1e-12);  // |Lambda_T| <= mu Lambda_N
    CHECK(worst_alignment < 1e-9);  // opposite to the slip (it does not turn on a level floor)
    CHECK(worst_law < 1e-12);
    CHECK(worst_gain <= 1e-12);
  }
}

TEST_CASE("regularised cone: the sphere enters the band at the exact roll onset, then creeps at the law's rate",
          "[integrators][friction_cone]") {
  const auto problem = nsb::make_problem("sphere", {});
  const auto& sphere = dynamic_cast<const nsb::Sphere&>(*problem);
  const nsb::Contacts& c = problem->contacts();
  const double exact = sphere.roll_time();
  // Creep: rolling needs the static friction (2/7) m g sin(alpha); the law gives it at
  // |u_T| = v_reg (2/7) tan(alpha) / mu.
  const double mu = c.mu[0], alpha = problem->parameters().real("alpha") * std::numbers::pi / 180.0;
  const double creep = kRegularisedConeVelocity * (2.0 / 7.0) * std::tan(alpha) / mu;
  for (const char* name : kRegularisedConeSchemes) {
    INFO(name);
    for (const double dt : {2e-3, 1e-3, 5e-4}) {
      auto integ = nsb::make_integrator(name, {});
      integ->init(*problem, problem->initial_state());
      double band = std::numeric_limits<double>::quiet_NaN(), slip = 0.0;
      nsb::run(*problem, *integ, {dt, 0.4, 1, false}, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
        slip = std::hypot((c.tangent * it.state().v)(0), (c.tangent2 * it.state().v)(0));
        if (std::isnan(band) && slip < kRegularisedConeVelocity) band = it.state().t;
      });
      // The band is entered v_reg / |a_slip| before the exact onset (a_slip = 7 mu g cos(alpha)
      // / 2 - ..., about 6 m/s^2 here: 1.6e-4 s), quantised to the step.
      std::printf("%s: band entry - exact roll onset %.3e s at dt %.0e; creep %.6e (law %.6e)\n", name, band - exact, dt,
                  slip, creep);
      CHECK(std::abs(band - exact) <= dt + 2e-4);
      CHECK(slip == Approx(creep).epsilon(1e-3));
    }
  }
}
