#include "problems/sphere_incline_exact.hpp"
#include "core/deterministic_math.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "problems/input_check.hpp"

namespace nsb {

namespace {

// G(q) = int_0^lambda e^{-q l} dl = (1 - e^{-q lambda}) / q (lambda for q = 0), to round-off
// for small q lambda; lambda = +inf gives 1 / q (q > 0) or +inf.
double decay_integral(double q, double lambda) {
  if (q == 0.0) return lambda;
  return -nsb::dmath::expm1(-q * lambda) / q;
}

// coef * G(q): zero when coef is (a term absent, even where G is infinite).
double term(double coef, double q, double lambda) { return coef == 0.0 ? 0.0 : coef * decay_integral(q, lambda); }

}  // namespace

SphereInclineExact::SphereInclineExact(const SphereInclineSpec& spec)
    : R_(spec.R), m_(spec.m), g_(spec.g), alpha_(spec.alpha * std::numbers::pi / 180.0), mu_(spec.mu) {
  const char* problem = "sphere";
  require_input(R_ > 0.0 && std::isfinite(R_), problem, "R", R_, "(0, inf)");
  require_input(spec.alpha >= 0.0 && spec.alpha < 90.0, problem, "alpha", spec.alpha, "[0, 90) degrees");
  require_input(mu_ >= 0.0 && std::isfinite(mu_), problem, "mu", mu_, "[0, inf)");
  require_input(m_ > 0.0 && std::isfinite(m_), problem, "m", m_, "(0, inf)");
  require_input(g_ > 0.0 && std::isfinite(g_), problem, "g", g_, "(0, inf)");
  const char* names[] = {"vx0", "vy0", "wx0", "wy0", "wz0"};
  const double values[] = {spec.vx0, spec.vy0, spec.wx0, spec.wy0, spec.wz0};
  for (int i = 0; i < 5; ++i) require_input(std::isfinite(values[i]), problem, names[i], values[i], "(-inf, inf)");

  a_ = g_ * nsb::dmath::sin(alpha_);
  b_ = 3.5 * mu_ * g_ * nsb::dmath::cos(alpha_);
  k_ = a_ > 0.0 ? b_ / a_ : inf_;
  v0_ = {spec.vx0, spec.vy0};
  omega0_ = {spec.wx0, spec.wy0, spec.wz0};
  w0_ = {v0_.x() - R_ * omega0_.y(), v0_.y() + R_ * omega0_.x()};
  const double speed = w0_.norm();
  A_ = 0.5 * (speed + w0_.x());
  B_ = 0.5 * (speed - w0_.x());
  rolls_ = b_ >= a_;  // friction can hold rolling: (2/7) m a <= mu m g cos(alpha)
  if (speed == 0.0) {
    t1_ = 0.0;
  } else if (a_ == 0.0) {
    t1_ = b_ > 0.0 ? speed / b_ : inf_;
  } else {
    t1_ = turning_time(inf_);
  }
  if (!std::isfinite(t1_)) return;
  if (a_ > 0.0) {
    at_t1_ = turning_phase(inf_);
  } else {  // level floor: the slip fell linearly to zero
    at_t1_.path = 0.5 * t1_ * w0_;
    at_t1_.length = 0.5 * t1_ * speed;
  }
}

double SphereInclineExact::turning_time(double lambda) const {
  return (term(A_, k_ - 1.0, lambda) + term(B_, k_ + 1.0, lambda)) / a_;
}

SphereInclineExact::SlipIntegrals SphereInclineExact::turning_phase(double lambda) const {
  const double k = k_;
  SlipIntegrals r;
  const double ea = A_ == 0.0 ? 0.0 : A_ * nsb::dmath::exp(-(k - 1.0) * lambda);
  const double eb = B_ == 0.0 ? 0.0 : B_ * nsb::dmath::exp(-(k + 1.0) * lambda);
  r.w = {ea - eb, w0_.y() == 0.0 ? 0.0 : w0_.y() * nsb::dmath::exp(-k * lambda)};
  r.path = {(term(A_ * A_, 2.0 * k - 2.0, lambda) - term(B_ * B_, 2.0 * k + 2.0, lambda)) / a_,
            w0_.y() * (term(A_, 2.0 * k - 1.0, lambda) + term(B_, 2.0 * k + 1.0, lambda)) / a_};
  r.length = (term(A_ * A_, 2.0 * k - 2.0, lambda) + term(2.0 * A_ * B_, 2.0 * k, lambda) +
              term(B_ * B_, 2.0 * k + 2.0, lambda)) / a_;
  return r;
}

double SphereInclineExact::lambda_at(double t) const {
  // t(lambda) rises from 0 to t_1 with slope |w| / a: bracket, then Newton kept inside it.
  double lo = 0.0, hi = 1.0;
  while (turning_time(hi) < t && hi < 1e300) lo = hi, hi *= 2.0;
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 200 && hi - lo > 2e-16 * hi; ++it) {
    const double f = turning_time(x) - t;
    if (f == 0.0) return x;
    (f < 0.0 ? lo : hi) = x;
    const double speed = (A_ == 0.0 ? 0.0 : A_ * nsb::dmath::exp(-(k_ - 1.0) * x)) +
                         (B_ == 0.0 ? 0.0 : B_ * nsb::dmath::exp(-(k_ + 1.0) * x));
    double next = x - f * a_ / speed;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - x) <= 1e-16 * x) return next;
    x = next;
  }
  return x;
}

SphereInclineExact::SlipIntegrals SphereInclineExact::integrals(double t) const {
  if (t < t1_) {
    if (a_ > 0.0) return turning_phase(lambda_at(t));
    // Level floor: the slip shrinks along its own direction at the rate b.
    const double shrink = std::isfinite(t1_) ? t / t1_ : 0.0;
    SlipIntegrals r;
    r.w = w0_ * (1.0 - shrink);
    r.path = w0_ * (t - 0.5 * shrink * t);
    r.length = w0_.norm() * (t - 0.5 * shrink * t);
    return r;
  }
  SlipIntegrals r = at_t1_;
  if (rolls_) {
    r.w.setZero();
    return r;
  }
  // Sliding from zero slip straight down the slope.
  const double tau = t - t1_, rate = a_ - b_;
  r.w = {rate * tau, 0.0};
  r.path.x() += 0.5 * rate * tau * tau;
  r.length += 0.5 * rate * tau * tau;
  return r;
}

Eigen::Vector2d SphereInclineExact::slip(double t) const { return integrals(t).w; }

double SphereInclineExact::slip_path_length(double t) const { return integrals(t).length; }

SphereInclineExact::State SphereInclineExact::state(double t) const {
  const SlipIntegrals r = integrals(t);
  const Eigen::Vector2d dw = r.w - w0_;
  const double c = 5.0 / (7.0 * R_);
  State s;
  s.velocity = {v0_.x() + (5.0 / 7.0) * a_ * t + (2.0 / 7.0) * dw.x(), v0_.y() + (2.0 / 7.0) * dw.y(), 0.0};
  s.omega = {omega0_.x() + c * dw.y(), omega0_.y() - c * (dw.x() - a_ * t), omega0_.z()};
  const Eigen::Vector2d drift = r.path - w0_ * t;
  s.position = {v0_.x() * t + (5.0 / 14.0) * a_ * t * t + (2.0 / 7.0) * drift.x(),
                v0_.y() * t + (2.0 / 7.0) * drift.y(), R_};
  s.rotation = {omega0_.x() * t + c * drift.y(), omega0_.y() * t - c * (drift.x() - 0.5 * a_ * t * t), omega0_.z() * t};
  return s;
}

Eigen::Vector3d SphereInclineExact::contact_angular_momentum(const State& s) const {
  const double I = 0.4 * m_ * R_ * R_;
  return {I * s.omega.x() - m_ * R_ * s.velocity.y(), I * s.omega.y() + m_ * R_ * s.velocity.x(), I * s.omega.z()};
}

double SphereInclineExact::energy(const State& s) const {
  const double I = 0.4 * m_ * R_ * R_;
  return 0.5 * m_ * s.velocity.squaredNorm() + 0.5 * I * s.omega.squaredNorm() - m_ * a_ * s.position.x();
}

}  // namespace nsb
