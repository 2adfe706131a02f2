#pragma once
// Linear complementarity problem of a contact step:
//
//     0 <= x  _|_  w = D x + q >= 0
//
// D is a Delassus operator L W^{-1} L^T (symmetric, positive diagonal). A diagonal D is
// solved in closed form, x_i = max(0, -q_i / D_ii). Otherwise projected Gauss-Seidel
// (Jean & Moreau 1992; Acary & Brogliato 2008, sec. 12.4), warm-started from x, stopped on
// the natural-map residual
//
//     r = max_i |min(D_ii x_i, w_i)| / max(max_i |q_i|, tiny)     (velocity units, relative)
//
// being below the tolerance.
#include <Eigen/Core>
#include <vector>

#include "core/parameters.hpp"

namespace nsb {

struct LcpOptions {
  double tolerance = 1e-12;
  long max_iterations = 10000;
};

struct LcpResult {
  long iterations = 0;
  double residual = 0.0;
  bool converged = true;
};

LcpResult solve_lcp(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, Eigen::VectorXd& x,
                    const LcpOptions& options);

// Storage for the LCPs a scheme solves step after step: one D, q, x per size, made the first
// time that size occurs, so that a step whose active set has a size seen before allocates
// nothing (an Eigen matrix reallocates whenever its size changes). x comes zeroed.
class LcpStorage {
 public:
  struct Arrays {
    Eigen::MatrixXd D;
    Eigen::VectorXd q, x;
  };
  Arrays& of_size(Eigen::Index a) {
    if (static_cast<std::size_t>(a) >= by_size_.size()) by_size_.resize(static_cast<std::size_t>(a) + 1);
    Arrays& s = by_size_[static_cast<std::size_t>(a)];
    if (s.q.size() != a) {
      s.D.resize(a, a);
      s.q.resize(a);
    }
    s.x.setZero(a);
    return s;
  }

 private:
  std::vector<Arrays> by_size_;
};

// The relative natural-map residual above, for checks and reports.
double lcp_residual(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, const Eigen::VectorXd& x);

// The parameters lcp_tol and lcp_max_iter of every scheme that solves contact LCPs, and the
// options they set.
ParamSpecs lcp_parameter_specs();
LcpOptions lcp_options(const Params& params);

}  // namespace nsb
