#pragma once
// One contact point of a rigid body against the floor y = 0, at a configuration U: its gap,
// normal row L = dg/dU and tangent row T (the point's horizontal velocity is T U'). The exact
// solutions of docs/rigid_bodies.md give theirs as functions of U, for the problems to reuse.
#include <Eigen/Dense>

namespace nsb {

struct PointContact {
  double gap = 0.0;
  Eigen::RowVector3d normal_row = Eigen::RowVector3d::Zero();
  Eigen::RowVector3d tangent_row = Eigen::RowVector3d::Zero();
};

// A point fixed in a planar rigid body U = (x, y, theta): body coordinates (p_x, p_y) about the
// centre (x, y), theta counter-clockwise. World height y + p_x sin theta + p_y cos theta, so
//     L = (0, 1, p_x cos theta - p_y sin theta),   T = (1, 0, -p_x sin theta - p_y cos theta).
PointContact body_point_contact(double px, double py, const Eigen::Vector3d& U);

}  // namespace nsb
