#include "solvers/coulomb.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nsb {

CoulombImpulse solve_coulomb_local(double w_nn, double w_nt, double w_tt, double q_n, double q_t, double mu) {
  if (q_n >= 0.0) return {};  // separating (or grazing): no impulse satisfies the law
  if (w_nt == 0.0) {
    const double n = -q_n / w_nn;
    const double bound = mu * n;
    return {n, std::clamp(-q_t / w_tt, -bound, bound)};
  }
  // Stick: U_N = U_T = 0.
  const double det = w_nn * w_tt - w_nt * w_nt;
  if (det > 0.0) {
    const double n = (-q_n * w_tt + q_t * w_nt) / det;
    const double t = (-q_t * w_nn + q_n * w_nt) / det;
    if (n >= 0.0 && std::abs(t) <= mu * n) return {n, t};
  }
  // Slip: Lambda_T = s mu Lambda_N with s = -sign(U_T), U_N = 0.
  CoulombImpulse best{};
  double best_violation = INFINITY;
  for (const double s : {-1.0, 1.0}) {
    const double a = w_nn + s * mu * w_nt;
    if (!(a > 0.0)) continue;
    const double n = -q_n / a;
    const double u_t = q_t + (w_nt + s * mu * w_tt) * n;
    const double violation = std::max(0.0, s * u_t);  // the slip must oppose the impulse
    if (violation == 0.0) return {n, s * mu * n};
    if (violation < best_violation) {
      best_violation = violation;
      best = {n, s * mu * n};
    }
  }
  return best;  // only reached through round-off at the stick/slip boundary
}

bool couples_blocks(const Eigen::MatrixXd& D, Eigen::Index block) {
  for (Eigen::Index c = 0; c < D.cols(); ++c)
    for (Eigen::Index r = 0; r < D.rows(); ++r)
      if (r / block != c / block && D(r, c) != 0.0) return true;
  return false;
}

LcpResult solve_coulomb(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, Eigen::Ref<const Eigen::VectorXd> mu,
                        Eigen::VectorXd& x, const LcpOptions& options) {
  const Eigen::Index a = mu.size();
  if (x.size() != 2 * a) x = Eigen::VectorXd::Zero(2 * a);
  for (Eigen::Index i = 0; i < 2 * a; ++i)
    if (!(D(i, i) > 0.0)) throw std::runtime_error("Coulomb contact: Delassus operator has a non-positive diagonal");
  const bool coupled = couples_blocks(D, 2);
  const double scale = std::max(q.cwiseAbs().maxCoeff(), 1e-300);
  LcpResult result;
  const long cap = coupled ? options.max_iterations : 1;
  for (result.iterations = 1; result.iterations <= cap; ++result.iterations) {
    double change = 0.0;
    for (Eigen::Index i = 0; i < a; ++i) {
      const Eigen::Index n = 2 * i, t = n + 1;
      // The others' impulses enter as a shift of the local free velocities.
      double q_n = q[n], q_t = q[t];
      if (coupled) {
        q_n += D.row(n).dot(x) - D(n, n) * x[n] - D(n, t) * x[t];
        q_t += D.row(t).dot(x) - D(t, n) * x[n] - D(t, t) * x[t];
      }
      const CoulombImpulse r = solve_coulomb_local(D(n, n), D(n, t), D(t, t), q_n, q_t, mu[i]);
      change = std::max({change, D(n, n) * std::abs(r.normal - x[n]), D(t, t) * std::abs(r.tangential - x[t])});
      x[n] = r.normal;
      x[t] = r.tangential;
    }
    result.residual = coupled ? change / scale : 0.0;  // uncoupled: one sweep is exact
    if (result.residual <= options.tolerance) return result;
  }
  result.iterations = options.max_iterations;
  result.converged = false;
  return result;
}

}  // namespace nsb
