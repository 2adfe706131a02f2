#include "integrators/spring_dashpot.hpp"
#include "core/deterministic_math.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

namespace nsb {

double spring_dashpot_restitution(double zeta) {
  if (zeta == 0.0) return 1.0;
  if (zeta < 1.0) {
    const double wd = std::sqrt(1.0 - zeta * zeta);
    const double t = (std::numbers::pi - nsb::dmath::atan2(2.0 * zeta * wd, 1.0 - 2.0 * zeta * zeta)) / wd;
    return nsb::dmath::exp(-zeta * t) * std::abs(nsb::dmath::cos(wd * t) - zeta / wd * nsb::dmath::sin(wd * t));
  }
  if (zeta == 1.0) return nsb::dmath::exp(-2.0);  // critical: x = t e^-t, force zero at t* = 2
  const double s = std::sqrt(zeta * zeta - 1.0), r1 = -zeta + s, r2 = -zeta - s;
  const double t = nsb::dmath::log((1.0 + 2.0 * zeta * r2) / (1.0 + 2.0 * zeta * r1)) / (r1 - r2);
  return std::abs((r1 * nsb::dmath::exp(r1 * t) - r2 * nsb::dmath::exp(r2 * t)) / (r1 - r2));
}

double damping_ratio_for_restitution(double e, double max_ratio, const std::function<double(double)>& restitution) {
  // restitution(zeta) decreases towards 0 as zeta grows: bisection in log zeta.
  double lo = 1e-12, hi = max_ratio;
  if (restitution(hi) >= e) return hi;
  for (int it = 0; it < 200 && hi / lo > 1.0 + 1e-15; ++it) {
    const double mid = std::sqrt(lo * hi);
    (restitution(mid) > e ? lo : hi) = mid;
  }
  return std::sqrt(lo * hi);
}

double spring_dashpot_damping_ratio(double e, double max_ratio) {
  if (e >= 1.0) return 0.0;
  return damping_ratio_for_restitution(e, max_ratio, spring_dashpot_restitution);
}

RegularisedFriction regularised_friction(double mu, double normal, double slip, double v_reg) {
  const double x = slip / v_reg;
  // -mu normal times phi, in this order: saturated, the force is -mu normal to the bit.
  const double phi = std::clamp(x, -1.0, 1.0);
  return {-mu * normal * phi, std::abs(x) < 1.0 ? -mu * normal / v_reg : 0.0, -mu * phi};
}

double implicit_regularised_friction(double mu, double normal, double slip, double h_tangent, double v_reg) {
  return regularised_friction(mu, normal, slip, v_reg + h_tangent * mu * normal).force;
}

RegularisedConeFriction regularised_cone_friction(double mu, double normal, const Eigen::Vector2d& slip, double v_reg) {
  const double length = slip.norm();
  const double a = mu * normal;
  if (length < v_reg) return {-a / v_reg * slip, -a / v_reg * Eigen::Matrix2d::Identity(), -mu / v_reg * slip};
  const Eigen::Vector2d direction = slip / length;
  return {-a * direction, -a / length * (Eigen::Matrix2d::Identity() - direction * direction.transpose()), -mu * direction};
}

Eigen::Vector2d implicit_regularised_cone_friction(double mu, double normal, const Eigen::Vector2d& slip,
                                                   const Eigen::Matrix2d& h_tangent, double v_reg) {
  const double a = mu * normal;
  if (a == 0.0 || slip.isZero(0.0)) return Eigen::Vector2d::Zero();
  if (h_tangent(0, 1) == 0.0 && h_tangent(1, 0) == 0.0 && h_tangent(0, 0) == h_tangent(1, 1))
    return regularised_cone_friction(mu, normal, slip, v_reg + h_tangent(0, 0) * a).force;
  const auto slip_after = [&](double r) -> Eigen::Vector2d {
    return (Eigen::Matrix2d::Identity() + (a / r) * h_tangent).inverse() * slip;
  };
  const Eigen::Vector2d viscous = slip_after(v_reg);
  if (viscous.norm() <= v_reg) return -a / v_reg * viscous;
  double lo = v_reg, hi = slip.norm();
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const double mid = 0.5 * (lo + hi);
    (slip_after(mid).norm() > mid ? lo : hi) = mid;
  }
  const Eigen::Vector2d u = slip_after(hi);
  return -a * u / u.norm();
}

}  // namespace nsb
