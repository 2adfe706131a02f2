#include "problems/lumped_gravity.hpp"

namespace nsb {

SpMat diagonal_mass_matrix(const Vec& m) {
  const Index n = m.size();
  SpMat M(n, n);
  M.reserve(Eigen::VectorXi::Ones(n));
  for (Index i = 0; i < n; ++i) M.insert(i, i) = m[i];
  M.makeCompressed();
  return M;
}

void lumped_gravity_force(const Vec& m, int dofs_per_node, double g, VecRef f) {
  f.setZero();
  for (Index q = dofs_per_node - 1; q < m.size(); q += dofs_per_node) f[q] = -m[q] * g;
}

double lumped_gravity_potential(const Vec& m, const Eigen::Ref<const Eigen::MatrixXd>& X, ConstVecRef u, double g) {
  const Index D = X.rows(), up = D - 1;
  double V = 0.0;
  for (Index a = 0; a < X.cols(); ++a) V += m[D * a + up] * g * (X(up, a) + u[D * a + up]);
  return V;
}

}  // namespace nsb
