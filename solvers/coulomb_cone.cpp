#include "solvers/coulomb_cone.hpp"
#include "solvers/coulomb.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace nsb {

namespace {

// The tangential impulse of Lambda_N = n: argmin over |x| <= radius of x^T S x / 2 + c^T x.
Eigen::Vector2d disk_minimiser(const Eigen::Matrix2d& S, const Eigen::Vector2d& c, double radius,
                               const ConeOptions& options) {
  if (radius <= 0.0) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d stick = -S.ldlt().solve(c);
  if (stick.norm() <= radius) return stick;
  // |x(nu)|^2 = sum_i ct_i^2 / (s_i + nu)^2 in the eigenbasis; Newton on phi(nu) = 1/radius - 1/|x(nu)|,
  // convex and decreasing, converges monotonically from nu = 0 (where phi > 0): no step overshoots.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(S);
  const Eigen::Vector2d s = eig.eigenvalues();
  const Eigen::Vector2d ct = eig.eigenvectors().transpose() * c;
  double nu = 0.0;
  for (int it = 0; it < options.max_iterations; ++it) {
    const Eigen::Vector2d xt = -(ct.array() / (s.array() + nu)).matrix();
    const double norm = xt.norm();
    // d|x|/dnu = -sum x_i^2 / (s_i + nu) / |x|
    const double dnorm = -(xt.array().square() / (s.array() + nu)).sum() / norm;
    const double phi = 1.0 / radius - 1.0 / norm;
    const double step = -phi * norm * norm / dnorm;  // phi' = dnorm / norm^2
    nu += step;
    if (std::abs(step) <= 1e-16 * nu) break;
  }
  const Eigen::Vector2d x = -eig.eigenvectors() * (ct.array() / (s.array() + nu)).matrix();
  return x * (radius / x.norm());  // on the circle to round-off
}

}  // namespace

ConeImpulse solve_cone_isotropic(double w, const Eigen::Vector3d& q, double mu) { return solve_cone_decoupled(w, w, q, mu); }

ConeImpulse solve_cone_decoupled(double w_n, double w_t, const Eigen::Vector3d& q, double mu) {
  if (q.x() >= 0.0) return {};
  ConeImpulse r;
  r.normal = -q.x() / w_n;
  r.tangential = -q.tail<2>() / w_t;
  const double bound = mu * r.normal, length = r.tangential.norm();
  if (length > bound) r.tangential *= bound / length;
  return r;
}

ConeSolve solve_cone(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, const ConeOptions& options) {
  const bool decoupled = W(0, 1) == 0.0 && W(0, 2) == 0.0 && W(1, 2) == 0.0 && W(1, 0) == 0.0 && W(2, 0) == 0.0 &&
                         W(2, 1) == 0.0 && W(1, 1) == W(2, 2);
  if (decoupled) return {solve_cone_decoupled(W(0, 0), W(1, 1), q, mu), 0, true};
  return solve_cone_local(W, q, mu, options);
}

LcpResult solve_coulomb_cone(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, Eigen::Ref<const Eigen::VectorXd> mu,
                             Eigen::VectorXd& x, const LcpOptions& options) {
  const Eigen::Index a = mu.size();
  if (x.size() != 3 * a) x = Eigen::VectorXd::Zero(3 * a);
  const bool coupled = couples_blocks(D, 3);
  const double scale = std::max(q.cwiseAbs().maxCoeff(), 1e-300);
  LcpResult result;
  const long cap = coupled ? options.max_iterations : 1;
  for (result.iterations = 1; result.iterations <= cap; ++result.iterations) {
    double change = 0.0;
    for (Eigen::Index i = 0; i < a; ++i) {
      const Eigen::Index n = 3 * i;
      const Eigen::Matrix3d W = D.block<3, 3>(n, n);
      Eigen::Vector3d local = q.segment<3>(n);
      // The others' impulses enter as a shift of the local free velocities.
      if (coupled) local += D.middleRows<3>(n) * x - W * x.segment<3>(n);
      const ConeSolve r = solve_cone(W, local, mu[i]);
      if (!r.converged) result.converged = false;
      const Eigen::Vector3d next(r.impulse.normal, r.impulse.tangential.x(), r.impulse.tangential.y());
      change = std::max(change, (W.diagonal().array() * (next - x.segment<3>(n)).array().abs()).maxCoeff());
      x.segment<3>(n) = next;
    }
    result.residual = coupled ? change / scale : 0.0;  // uncoupled: one sweep is exact
    if (result.residual <= options.tolerance) return result;
  }
  result.iterations = options.max_iterations;
  result.converged = false;
  return result;
}

ConeSolve solve_cone_local(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, const ConeOptions& options) {
  ConeSolve out;
  if (q.x() >= 0.0) return out;
  const Eigen::Matrix2d S = W.bottomRightCorner<2, 2>();
  const Eigen::Vector2d coupling = W.block<2, 1>(1, 0);  // W_TN
  const auto tangential = [&](double n) { return disk_minimiser(S, q.tail<2>() + coupling * n, mu * n, options); };
  const auto h = [&](double n, Eigen::Vector2d& x) {
    x = tangential(n);
    return n - std::max(0.0, -(q.x() + coupling.dot(x)) / W(0, 0));
  };
  Eigen::Vector2d x_lo, x_hi;
  double lo = 0.0, h_lo = h(lo, x_lo);  // -(-q_N / W_NN) < 0
  double hi = -q.x() / W(0, 0), h_hi = h(hi, x_hi);
  for (int it = 0; h_hi < 0.0; ++it) {
    if (it == options.max_iterations) {
      out.converged = false;
      return out;
    }
    lo = hi, h_lo = h_hi, x_lo = x_hi;
    hi *= 2.0;
    h_hi = h(hi, x_hi);
  }
  // Illinois on [lo, hi] (h_lo < 0 <= h_hi).
  int kept = 0;
  for (out.iterations = 1; h_hi != 0.0 && hi - lo > options.tolerance * hi; ++out.iterations) {
    if (out.iterations > options.max_iterations) {
      out.converged = false;
      break;
    }
    const double c = std::clamp(hi - h_hi * (hi - lo) / (h_hi - h_lo), lo, hi);
    Eigen::Vector2d x_c;
    const double h_c = h(c, x_c);
    if (h_c >= 0.0) {
      hi = c, h_hi = h_c, x_hi = x_c;
      if (kept == -1) h_lo *= 0.5;
      kept = -1;
    } else {
      lo = c, h_lo = h_c, x_lo = x_c;
      if (kept == 1) h_hi *= 0.5;
      kept = 1;
    }
  }
  out.impulse.normal = hi;
  out.impulse.tangential = x_hi;
  return out;
}

double cone_law_residual(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, const ConeImpulse& impulse) {
  const Eigen::Vector3d lambda(impulse.normal, impulse.tangential.x(), impulse.tangential.y());
  const Eigen::Vector3d U = q + W * lambda;
  const double rho = 3.0 / W.trace();
  const double n = impulse.normal;
  Eigen::Vector2d trial = impulse.tangential - rho * U.tail<2>();
  const double radius = mu * std::max(n, 0.0), length = trial.norm();
  if (length > radius) trial *= length > 0.0 ? radius / length : 0.0;
  const Eigen::Vector3d map(n - std::max(0.0, n - rho * U.x()), impulse.tangential.x() - trial.x(),
                            impulse.tangential.y() - trial.y());
  return map.norm() / (rho * std::max(q.cwiseAbs().maxCoeff(), 1e-300));
}

}  // namespace nsb
