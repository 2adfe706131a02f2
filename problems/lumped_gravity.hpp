#pragma once
// The lumped (diagonal) mass and the gravity of the solid blocks (block_2d.hpp, block_3d.hpp):
// nodes of D dofs each (D = 2 or 3), node a on dofs D a .. D a + D - 1, the last of them
// vertical; m the mass per dof, X (D x nodes) the reference positions. Gravity g (0: off)
// along the vertical's minus direction:
//     F_ext on node a's vertical dof = -m g,   V_load = sum_a m g (X_a,vertical + u_a,vertical).
#include <Eigen/Core>

#include "problems/problem.hpp"

namespace nsb {

// M = diag(m), compressed.
SpMat diagonal_mass_matrix(const Vec& m);
// f = F_ext (written whole).
void lumped_gravity_force(const Vec& m, int dofs_per_node, double g, VecRef f);
double lumped_gravity_potential(const Vec& m, const Eigen::Ref<const Eigen::MatrixXd>& X, ConstVecRef u, double g);

}  // namespace nsb
