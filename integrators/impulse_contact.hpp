#pragma once
// Contact impulses of an explicit step with a diagonal mass (CD-Lagrange family):
//
//     on contacts closed at the new position (g_i <= 0):
//     0 <= Lambda  _|_  g'_free + H Lambda + e g'_prev >= 0,   H = L M^{-1} L^T
//     v  <-  v_free + M^{-1} L^T Lambda
//
// H diagonal (node-to-rigid contacts on distinct dofs): closed form per contact,
// Lambda_i = max(0, -(g'_free,i + e g'_prev,i) / H_ii), no allocation. Otherwise an LCP on
// the closed contacts (projected Gauss-Seidel, lcp.hpp).
// A contact with H_ii = 0 acts on massless dofs only (minv zero there): it has no impulse
// law and is skipped here; the caller solves it quasi-statically (cd_lagrange.hpp).
#include "integrators/integrator.hpp"
#include "integrators/lcp.hpp"

namespace nsb {

class ImpulseContact {
 public:
  ImpulseContact() = default;
  ImpulseContact(const Problem& problem, const Vec& minv, LcpOptions lcp);

  // u: new position; v_prev: velocity before the step (for restitution); v: in, the free
  // velocity, out, the velocity after the impulses; impulses: out (size p). Returns the LCP
  // iterations (0 for a diagonal H); counts unconverged LCPs in `work`.
  long apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, StepInfo& info,
             WorkCounters& work);
  // The same with restitution e instead of the problem's (e = 0: the velocity-level
  // constraint g' >= 0 of a closed contact, as d1_minus_linear.hpp needs).
  long apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, StepInfo& info,
             WorkCounters& work, double e);

 private:
  const Problem* problem_ = nullptr;
  Vec minv_;
  LcpOptions lcp_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_;
  Vec gap_;
  Vec h_diag_;
  bool h_is_diagonal_ = true;
  Eigen::MatrixXd h_full_;  // H, when it is not diagonal
};

}  // namespace nsb
