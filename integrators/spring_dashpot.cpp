#include "integrators/spring_dashpot.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

namespace nsb {

double spring_dashpot_restitution(double zeta) {
  if (zeta == 0.0) return 1.0;
  if (zeta < 1.0) {
    const double wd = std::sqrt(1.0 - zeta * zeta);
    const double t = (std::numbers::pi - std::atan2(2.0 * zeta * wd, 1.0 - 2.0 * zeta * zeta)) / wd;
    return std::exp(-zeta * t) * std::abs(std::cos(wd * t) - zeta / wd * std::sin(wd * t));
  }
  if (zeta == 1.0) return std::exp(-2.0);  // critical: x = t e^-t, force zero at t* = 2
  const double s = std::sqrt(zeta * zeta - 1.0), r1 = -zeta + s, r2 = -zeta - s;
  const double t = std::log((1.0 + 2.0 * zeta * r2) / (1.0 + 2.0 * zeta * r1)) / (r1 - r2);
  return std::abs((r1 * std::exp(r1 * t) - r2 * std::exp(r2 * t)) / (r1 - r2));
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

}  // namespace nsb
