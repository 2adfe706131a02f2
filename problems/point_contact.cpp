#include "problems/point_contact.hpp"
#include "core/deterministic_math.hpp"

#include <cmath>

namespace nsb {

PointContact body_point_contact(double px, double py, const Eigen::Vector3d& U) {
  const double c = nsb::dmath::cos(U(2)), s = nsb::dmath::sin(U(2));
  PointContact k;
  k.gap = U(1) + px * s + py * c;
  k.normal_row << 0.0, 1.0, px * c - py * s;
  k.tangent_row << 1.0, 0.0, -px * s - py * c;
  return k;
}

}  // namespace nsb
