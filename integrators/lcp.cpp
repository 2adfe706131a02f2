#include "integrators/lcp.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nsb {

double lcp_residual(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, const Eigen::VectorXd& x) {
  const Eigen::VectorXd w = D * x + q;
  double r = 0.0;
  for (Eigen::Index i = 0; i < q.size(); ++i)
    r = std::max(r, std::abs(std::min(D(i, i) * x[i], w[i])));
  const double scale = std::max(q.cwiseAbs().maxCoeff(), 1e-300);
  return r / scale;
}

LcpResult solve_lcp(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, Eigen::VectorXd& x,
                    const LcpOptions& options) {
  const Eigen::Index n = q.size();
  if (x.size() != n) x = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i)
    if (!(D(i, i) > 0.0)) throw std::runtime_error("LCP: Delassus operator has a non-positive diagonal");

  const bool diagonal = (D - Eigen::MatrixXd(D.diagonal().asDiagonal())).cwiseAbs().maxCoeff() == 0.0;
  if (diagonal) {
    for (Eigen::Index i = 0; i < n; ++i) x[i] = std::max(0.0, -q[i] / D(i, i));
    return {1, lcp_residual(D, q, x), true};
  }
  LcpResult result;
  for (result.iterations = 1; result.iterations <= options.max_iterations; ++result.iterations) {
    for (Eigen::Index i = 0; i < n; ++i) {
      const double wi = D.row(i).dot(x) + q[i];
      x[i] = std::max(0.0, x[i] - wi / D(i, i));
    }
    result.residual = lcp_residual(D, q, x);
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
