#include "solvers/lcp.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace nsb {

namespace {

// w = D x + q into `w` (Eigen's product, as D * x + q), then the residual of the header.
double residual(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, const Eigen::VectorXd& x,
                Eigen::Map<Eigen::VectorXd> w) {
  w.noalias() = D * x;
  w += q;
  double r = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i)
    r = std::max(r, std::abs(std::min(D(i, i) * x[i], w[i])));
  const double scale = std::max(q.cwiseAbs().maxCoeff(), 1e-300);
  return r / scale;
}

// Storage for w kept per thread and only grown: the schemes' steps allocate nothing.
Eigen::Map<Eigen::VectorXd> workspace(Eigen::Index n) {
  thread_local std::vector<double> w;
  if (w.size() < static_cast<std::size_t>(n)) w.resize(static_cast<std::size_t>(n));
  return {w.data(), n};
}

}  // namespace

double lcp_residual(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, const Eigen::VectorXd& x) {
  return residual(D, q, x, workspace(q.size()));
}

LcpResult solve_lcp(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, Eigen::VectorXd& x,
                    const LcpOptions& options) {
  const Eigen::Index n = q.size();
  if (x.size() != n) x = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(D(i, i) > 0.0)) throw std::runtime_error("LCP: Delassus operator has a non-positive diagonal");

  bool diagonal = true;
  for (Eigen::Index j = 0; j < n && diagonal; ++j)
    for (Eigen::Index i = 0; i < n; ++i)
      if (i == j ? !std::isfinite(D(i, i)) : !(D(i, j) == 0.0)) {
        diagonal = false;
        break;
      }
  const auto w = workspace(n);
  if (diagonal) {
    for (Eigen::Index i = 0; i < n; ++i) x[i] = std::max(0.0, -q[i] / D(i, i));
    return {1, residual(D, q, x, w), true};
  }
  LcpResult result;
  for (result.iterations = 1; result.iterations <= options.max_iterations; ++result.iterations) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double wi = D.row(i).dot(x) + q[i];
      x[i] = std::max(0.0, x[i] - wi / D(i, i));
    }
    result.residual = residual(D, q, x, w);
    if (result.residual <= options.tolerance) return result;
  }
  result.iterations = options.max_iterations;
  result.converged = false;
  return result;
}

ParamSpecs lcp_parameter_specs() {
  return {
      ParamSpec::real("lcp_tol", 1e-12, 0.0, 1e-2,
                      "LCP tolerance (relative natural-map residual; unused when the Delassus operator is diagonal)", true),
      ParamSpec::integer("lcp_max_iter", 10000, 1, 100000000, "LCP iteration cap"),
  };
}

LcpOptions lcp_options(const Params& params) { return {params.real("lcp_tol"), params.integer("lcp_max_iter")}; }

}  // namespace nsb
