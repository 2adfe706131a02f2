#include "problems/rocking_block_exact.hpp"
#include "core/deterministic_math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

#include "problems/extrapolation_ode.hpp"
#include "problems/input_check.hpp"

namespace nsb {

namespace {

constexpr double kForever = std::numeric_limits<double>::infinity();
constexpr std::size_t kMaxImpactsMarched = 200000;        // march cap (a very slender block)
constexpr std::size_t max_periodic_impacts = 10000;  // |ratio| = 1: marched this far
constexpr double horizon_periods = 1e4;             // first-phase search horizon, in 1 / p

// psi'' = p^2 sin(psi) as a first-order system in (psi, psi').
struct Pendulum {
  double p2;
  extrapolation::Vec<2> operator()(double, const extrapolation::Vec<2>& y) const {
    return {y(1), p2 * nsb::dmath::sin(y(0))};
  }
};

}  // namespace

BlockCorners block_corners(double b, double h, const Eigen::Vector3d& U) {
  return {body_point_contact(b, -h, U), body_point_contact(-b, -h, U)};
}

double housner_ratio(double alpha) {
  const double s = nsb::dmath::sin(alpha);
  return 1.0 - 1.5 * s * s;
}

CornerImpact moreau_impact(double b, double h, double m, double e, double mu, int pivot, double omega_minus) {
  const double sigma = pivot > 0 ? 1.0 : -1.0;
  if (!(sigma * omega_minus < 0.0))
    throw std::invalid_argument("moreau_impact: pivot * omega_minus must be < 0 (the other corner approaching)");
  const double R2 = b * b + h * h;
  const Eigen::Vector3d Minv(1.0 / m, 1.0 / m, 3.0 / (m * R2));
  Eigen::Matrix3d G;  // rows: new corner's L, old corner's L, common T (theta = 0)
  G << 0.0, 1.0, sigma * b, 0.0, 1.0, -sigma * b, 1.0, 0.0, h;
  const Eigen::Vector3d v_minus(-h * omega_minus, sigma * b * omega_minus, omega_minus);
  const Eigen::Matrix3d W = G * Minv.asDiagonal() * G.transpose();
  const Eigen::Vector3d c_minus = G * v_minus;  // (2 sigma b omega-, 0, 0)

  const double impulse_scale = m * std::abs(omega_minus) * std::sqrt(R2);
  const double velocity_scale = std::abs(omega_minus) * std::sqrt(R2);
  const double tol = 1e-12;
  CornerImpact best;
  std::vector<Eigen::Vector3d> found;
  // Normal states: bit 0 new corner closed, bit 1 old corner closed; tangential: 0 stick,
  // +1 / -1 slipping forward / back (u_T+ of that sign, Lambda_T = -d mu sum Lambda_N).
  for (int closed = 0; closed < 4; ++closed) {
    for (int d : {0, 1, -1}) {
      if (closed == 0 && d != 0) continue;
      if (d != 0 && !std::isfinite(mu)) continue;
      Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
      Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
      for (int i = 0; i < 2; ++i) {
        if (closed & (1 << i)) {
          A.row(i) = W.row(i);
          rhs(i) = -(1.0 + e) * c_minus(i);
        } else {
          A(i, i) = 1.0;
        }
      }
      if (closed == 0) {
        A(2, 2) = 1.0;
      } else if (d == 0) {
        A.row(2) = W.row(2);
        rhs(2) = -c_minus(2);
      } else {
        A(2, 0) = A(2, 1) = d * mu;
        A(2, 2) = 1.0;
      }
      const Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
      if (!lu.isInvertible()) continue;
      const Eigen::Vector3d z = lu.solve(rhs);
      const Eigen::Vector3d c_plus = c_minus + W * z;
      bool ok = z(0) >= -tol * impulse_scale && z(1) >= -tol * impulse_scale;
      for (int i = 0; i < 2; ++i)
        if (!(closed & (1 << i))) ok = ok && c_plus(i) + e * c_minus(i) >= -tol * velocity_scale;
      if (closed != 0 && d == 0) ok = ok && std::abs(z(2)) <= mu * (z(0) + z(1)) + tol * impulse_scale;
      if (d != 0) ok = ok && d * c_plus(2) >= -tol * velocity_scale;
      if (!ok) continue;
      const bool seen = std::any_of(found.begin(), found.end(), [&](const Eigen::Vector3d& f) {
        return (f - z).norm() <= 1e-9 * impulse_scale;
      });
      if (seen) continue;
      found.push_back(z);
      if (found.size() > 1) continue;  // the first found in this order is reported
      best.Lambda_new = z(0);
      best.Lambda_old = z(1);
      best.Lambda_T = z(2);
      best.velocity_before = v_minus;
      best.velocity_after = v_minus + Minv.asDiagonal() * (G.transpose() * z);
      best.normal_velocity_after = c_plus;
    }
  }
  best.solutions = static_cast<int>(found.size());
  if (found.empty()) return best;
  best.ratio = best.velocity_after(2) / omega_minus;
  const Eigen::Vector3d& c = best.normal_velocity_after;
  const double vtol = 1e-12 * velocity_scale;
  const bool new_still = std::abs(c(0)) <= vtol, old_still = std::abs(c(1)) <= vtol;
  if (std::abs(c(2)) > vtol)
    best.kind = CornerImpact::Kind::slip;
  else if (new_still && old_still)
    best.kind = CornerImpact::Kind::rest;
  else if (new_still)
    best.kind = CornerImpact::Kind::rocks_on_new_corner;
  else if (old_still)
    best.kind = CornerImpact::Kind::rocks_on_old_corner;
  else
    best.kind = CornerImpact::Kind::flight;
  return best;
}

RockingBlockExact::RockingBlockExact(const RockingBlockSpec& spec)
    : b_(spec.b), h_(spec.h), m_(spec.m), g_(spec.g), theta0_(spec.theta0), omega0_(spec.omega0),
      mu_(spec.mu), e_(spec.e), law_(spec.law), t_rest_(kForever), t_end_(kForever) {
  const std::string alpha_range = "(0, inf): the slenderness alpha = atan(b / h) must lie in (0, 90) degrees";
  require_input(b_ > 0.0 && std::isfinite(b_), "rocking-block", "b", b_, alpha_range);
  require_input(h_ > 0.0 && std::isfinite(h_), "rocking-block", "h", h_, alpha_range);
  require_input(m_ > 0.0 && std::isfinite(m_), "rocking-block", "m", m_, "(0, inf)");
  require_input(g_ > 0.0 && std::isfinite(g_), "rocking-block", "g", g_, "(0, inf)");
  require_input(mu_ >= 0.0, "rocking-block", "mu", mu_, "[0, inf)");
  require_input(e_ >= 0.0 && e_ <= 1.0, "rocking-block", "e", e_, "[0, 1]");
  require_input(std::abs(theta0_) < std::numbers::pi / 2, "rocking-block", "theta0", theta0_,
                "(-pi/2, pi/2) rad (beyond it an upper corner starts in the floor)");
  require_input(std::isfinite(omega0_), "rocking-block", "omega0", omega0_, "(-inf, inf)");
  R_ = nsb::dmath::hypot(b_, h_);
  alpha_ = nsb::dmath::atan2(b_, h_);
  p_ = std::sqrt(0.75 * g_ / R_);
  first_phase();
}

double RockingBlockExact::rise_time(double w) const {
  if (topples_from_upright(w)) return kForever;
  const double half = nsb::dmath::sin(0.5 * alpha_);
  const double sin_half_m = std::sqrt(half * half - w * w / (4.0 * p_ * p_));
  const double k = std::sqrt(1.0 - sin_half_m * sin_half_m);
  const double gamma = nsb::dmath::atan2(w, 2.0 * p_ * sin_half_m * nsb::dmath::cos(0.5 * alpha_));
  return std::ellint_1(k, gamma) / p_;
}

double RockingBlockExact::amplitude(double w) const {
  if (topples_from_upright(w)) return kForever;
  // alpha - psi_m = 2 (asin A - asin B), A = sin(alpha / 2), B = sin(psi_m / 2) = sqrt(A^2 - q),
  // q = w^2 / (4 p^2), written without the cancellation: asin A - asin B = asin(q / (A cos(psi_m / 2)
  // + B cos(alpha / 2))).
  const double A = nsb::dmath::sin(0.5 * alpha_), q = w * w / (4.0 * p_ * p_);
  const double B = std::sqrt(A * A - q);
  return 2.0 * nsb::dmath::asin(q / (A * std::sqrt(1.0 - B * B) + B * nsb::dmath::cos(0.5 * alpha_)));
}

bool RockingBlockExact::topples_from_upright(double w) const {
  const double half = nsb::dmath::sin(0.5 * alpha_);
  return w * w >= 4.0 * p_ * p_ * half * half;
}

void RockingBlockExact::first_phase() {
  const int sigma = theta0_ > 0.0 ? 1 : theta0_ < 0.0 ? -1 : omega0_ > 0.0 ? 1 : omega0_ < 0.0 ? -1 : 0;
  if (sigma == 0) {  // upright at rest
    phases_.push_back({0.0, 1, alpha_, 0.0});
    t_rest_ = 0.0;
    return;
  }
  x_mid_ = h_ * nsb::dmath::sin(theta0_) - sigma * b_ * (nsb::dmath::cos(theta0_) - 1.0);
  const Phase start{0.0, sigma, alpha_ - sigma * theta0_, -sigma * omega0_};
  phases_.push_back(start);
  const Pendulum f{p_ * p_};
  const double half_pi = std::numbers::pi / 2;
  // Inside the phase both are positive: sigma theta = alpha - psi (0 at the impact) and
  // 90 degrees - sigma theta (0 on its side). From theta0 = 0 only the second.
  const bool upright = theta0_ == 0.0;
  const auto event = [&](double, const extrapolation::Vec<2>& y) {
    const double side = half_pi - alpha_ + y(0);
    return upright ? side : std::min(alpha_ - y(0), side);
  };
  if (upright && !topples_from_upright(std::abs(omega0_))) {
    march_impacts(2.0 * rise_time(std::abs(omega0_)), sigma, -omega0_);
    return;
  }
  const double horizon = horizon_periods / p_;
  const auto hit = extrapolation::find_event<2>(f, event, 0.0, {start.psi, start.psi_dot}, horizon, 0.1 / p_);
  if (!hit.found) {
    ending_ = Ending::balances;
    t_end_ = horizon;
  } else if (!upright && std::abs(alpha_ - hit.y(0)) < std::abs(half_pi - alpha_ + hit.y(0))) {
    march_impacts(hit.t, sigma, -sigma * hit.y(1));
  } else {
    ending_ = Ending::topples;
    t_end_ = hit.t;
  }
}

double RockingBlockExact::impact_law_ratio(int sigma, double omega_minus) {
  if (law_ == RockingImpactLaw::housner) return std::max(0.0, housner_ratio(alpha_));
  first_outcome_ = moreau_impact(b_, h_, m_, e_, mu_, sigma, omega_minus);
  const auto kind = first_outcome_->kind;
  if (first_outcome_->solutions == 0 || kind == CornerImpact::Kind::flight || kind == CornerImpact::Kind::slip)
    return std::numeric_limits<double>::quiet_NaN();
  return kind == CornerImpact::Kind::rest ? 0.0 : first_outcome_->ratio;
}

void RockingBlockExact::march_impacts(double t, int sigma, double omega_minus) {
  ratio_ = impact_law_ratio(sigma, omega_minus);
  if (std::isnan(ratio_)) {  // flight or slip: the rocking solution ends at this impact
    impacts_.push_back({t, omega_minus, first_outcome_->velocity_after(2), kForever});
    ending_ = Ending::leaves_rocking;
    t_end_ = t;
    return;
  }
  const double decay = std::abs(ratio_);
  const Pendulum f{p_ * p_};
  double lost = 0.0;
  for (;;) {
    const double omega_plus = ratio_ * omega_minus;
    const double w = std::abs(omega_plus);
    const int next_sigma = ratio_ > 0.0 ? -sigma : sigma;
    impacts_.push_back({t, omega_minus, omega_plus, amplitude(w)});
    if (w == 0.0) {
      t_rest_ = t;
      return;
    }
    const Phase phase{t, next_sigma, alpha_, -w};
    phases_.push_back(phase);
    if (topples_from_upright(w)) {
      const auto side = [&](double, const extrapolation::Vec<2>& y) { return std::numbers::pi / 2 - alpha_ + y(0); };
      const auto hit = extrapolation::find_event<2>(f, side, t, {alpha_, -w}, t + horizon_periods / p_, 0.1 / p_);
      ending_ = hit.found ? Ending::topples : Ending::balances;
      t_end_ = hit.t;
      return;
    }
    // Compensated summation of the phases: `lost` is what t lacks of their exact sum.
    const double step = 2.0 * rise_time(w) + lost;
    const double t_next = t + step;
    if (decay == 1.0 && impacts_.size() >= max_periodic_impacts) {
      ending_ = Ending::rocks_forever;
      t_end_ = t_next;
      return;
    }
    if (decay < 1.0) {
      // Stop once the phases no longer advance t: what remains is below its rounding.
      const double tail = 2.0 * w / (p_ * p_ * nsb::dmath::sin(alpha_) * (1.0 - decay));
      if (t_next == t || t + (tail + lost) == t || impacts_.size() >= kMaxImpactsMarched) {
        t_rest_ = t + (tail + lost);
        if (impacts_.size() >= kMaxImpactsMarched) t_end_ = t_next;  // nothing marched beyond it
        return;
      }
    }
    lost = step - (t_next - t);
    t = t_next;
    sigma = next_sigma;
    omega_minus = -next_sigma * w;
  }
}

RockingBlockExact::State RockingBlockExact::state_in_phase(const Phase& phase, double t) const {
  double h = 0.1 / p_;
  const Pendulum f{p_ * p_};
  const auto y = extrapolation::integrate_to<2>(f, phase.t, {phase.psi, phase.psi_dot}, t, h);
  const double sigma = phase.sigma;
  State s;
  s.theta = sigma * (alpha_ - y(0));
  s.omega = -sigma * y(1);
  const double c = nsb::dmath::cos(s.theta), sn = nsb::dmath::sin(s.theta);
  s.x = x_mid_ - h_ * sn + sigma * b_ * (c - 1.0);
  s.y = h_ * c + sigma * b_ * sn;
  s.vx = (-h_ * c - sigma * b_ * sn) * s.omega;
  s.vy = (-h_ * sn + sigma * b_ * c) * s.omega;
  return s;
}

std::optional<RockingBlockExact::State> RockingBlockExact::state(double t) const {
  if (!(t >= 0.0)) return std::nullopt;
  if (t >= t_rest_) {
    State rest;
    rest.x = x_mid_;
    rest.y = h_;
    return rest;
  }
  if (t > t_end_) return std::nullopt;  // the solution ended, or the march stopped at its cap
  const auto after = std::upper_bound(phases_.begin(), phases_.end(), t,
                                      [](double time, const Phase& ph) { return time < ph.t; });
  return state_in_phase(*std::prev(after), t);
}

Eigen::Vector2d RockingBlockExact::pivot_force(double theta, double omega) const {
  const double sigma = theta > 0.0 ? 1.0 : theta < 0.0 ? -1.0 : omega >= 0.0 ? 1.0 : -1.0;
  const double psi = alpha_ - sigma * theta, rate2 = omega * omega, p2 = p_ * p_;
  return {sigma * m_ * R_ * nsb::dmath::sin(psi) * (p2 * nsb::dmath::cos(psi) - rate2),
          m_ * g_ - m_ * R_ * (p2 * nsb::dmath::sin(psi) * nsb::dmath::sin(psi) + rate2 * nsb::dmath::cos(psi))};
}

double RockingBlockExact::energy(const State& s) const {
  return 0.5 * m_ * (s.vx * s.vx + s.vy * s.vy) + 0.5 * (m_ * R_ * R_ / 3.0) * s.omega * s.omega + m_ * g_ * s.y;
}

}  // namespace nsb
