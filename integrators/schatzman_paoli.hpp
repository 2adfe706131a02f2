#pragma once
// Schatzman–Paoli scheme: two-step (central difference), contact at position level
// (M. Schatzman, Nonlinear Anal. 2, 1978; L. Paoli and M. Schatzman, SIAM J. Numer. Anal. 40,
// 2002, 702-733 and 734-768; Siconos' SchatzmanPaoliOSI). docs/method.md "The field's schemes":
//
//     M (U_{k+1} - 2 U_k + U_{k-1}) = h^2 (F_ext(t_k) - F_int,theta) + L^T R
//     0 <= R  _|_  g0 + L (U_{k+1} + e U_{k-1}) / (1 + e) >= 0
//     F_int,theta = F_int(U_k)                                   theta = 0 (explicit)
//                 = K (theta U_{k+1} + (1 - 2 theta) U_k + theta U_{k-1})   theta > 0 (linear K)
// With W = M + theta h^2 K and U_free = W^{-1} [M (2 U_k - U_{k-1}) + h^2 (F_ext,k - F_int,theta
// without its U_{k+1} part)], U_{k+1} = U_free + W^{-1} L^T R and the position-level LCP is
//     0 <= R  _|_  D R + q >= 0,   D = L W^{-1} L^T,   q = (1 + e) g0 + L (U_free + e U_{k-1})
// (the constraint times 1 + e), in closed form R_i = max(0, -q_i / D_ii) when D is diagonal
// (theta = 0, lumped mass, node-to-rigid contacts); otherwise projected Gauss-Seidel on the
// contacts with q_i <= 0 (lcp.hpp). theta = 0 is explicit (diagonal M, CFL-limited step,
// nonlinear F_int allowed); theta = 1/4 is unconditionally stable on a linear K (the Newmark
// average-acceleration displacement form), theta = 1/2 too, with a larger period error.
// Written in increments, one F_int (or K U_k) per step for every theta:
//     U_free = 2 U_k - U_{k-1} + h^2 W^{-1} (F_ext(t_k) - F_int(U_k))
// W is factorised once per step size (CHOLMOD), as in moreau_jean.hpp.
//
// theta = 0 and e = 0 is the forward-increment Lagrange multiplier method of N. J. Carpenter,
// R. L. Taylor and M. G. Katona (IJNME 32, 1991, 103-128), the usual explicit-dynamics contact:
// the predicted central-difference position is projected onto g >= 0 along M^{-1} L^T.
//
// Impulse of the step: R / h (M (V_{k+1/2} - V_{k-1/2}) = h F + L^T R / h), >= 0.
// Start (first step): U_{-1} = U_0 - h v_0 and the force term halved,
//     U_free = U_0 + h v_0 + h^2/2 W^{-1} (F_ext(0) - F_int(U_0)),
// the Taylor start U_0 + h v_0 + h^2/2 M^{-1} F_0 + O(h^4) without forming M^{-1}; its
// reported velocity is the trapezoidal 2 (U_1 - U_0) / h - v_0.
// Reported velocity at t_{k+1}: the second-order backward difference
// (3 U_{k+1} - 4 U_k + U_{k-1}) / 2h (no M^{-1} needed); in and after a step with an
// impulse, (U_{k+1} - U_k) / h (BDF2 would extrapolate the jump: on the bouncing mass with e = 1 it
// reported energies 2.3 E0). Energy: v^T M v / 2 + V(u) at that state.
// Declines (InputError): theta = 0 with a non-diagonal mass or a massless dof (M^{-1});
// theta > 0 on a nonlinear problem (K is factorised once). Massless dofs (the singular-mass
// bar) are allowed for theta > 0: their rows of W are theta h^2 K, i.e. they follow the
// equilibrium of the theta-weighted position theta U_{k+1} + (1 - 2 theta) U_k + theta U_{k-1},
// which, like the trapezoidal rule (moreau_jean.hpp), leaves a (-1)^k mode undamped there.
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): its impact law is written on positions,
// g(U_{k+1}) + e g(U_{k-1}) >= 0 with L constant, and Paoli and Schatzman's treatment of a
// nonlinear g (a projection onto {g(U) >= 0} in the kinetic metric, a nonlinear problem per
// step) is not implemented.
#include "integrators/contact_responses.hpp"
#include "integrators/integrator.hpp"
#include "solvers/lcp.hpp"
#include "solvers/sparse_cholesky.hpp"

namespace nsb {

class SchatzmanPaoli final : public Integrator {
 public:
  explicit SchatzmanPaoli(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;
  // With e > 0 the law spans U_{k-1}..U_{k+1}: the discrete motion rebounds from up to two
  // steps of travel past the obstacle (U_{k+1} = -U_{k-1} for e = 1), one step more than a
  // one-step law.
  ImpactAccuracy impact_accuracy() const override { return {problem_->restitution() > 0.0 ? 3.0 : 2.0, true}; }

 private:
  StepInfo advance(double dt_requested) override;
  bool explicit_() const { return theta_ == 0.0; }
  void factorize(double h);
  void solve_in_place(Vec& x);                 // x <- W^{-1} x
  const Vec& contact_response(Index contact);  // W^{-1} L_i^T, cached while W is unchanged
  void solve_contacts(double h, StepInfo& info);  // R; u_next_ += W^{-1} L^T R

  double theta_;
  LcpOptions lcp_;
  Vec minv_;                        // theta = 0
  SpMat K_;                         // theta > 0
  SparseSum W_;
  SparseCholesky chol_;
  double h_factored_ = 0.0;
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_;
  Vec h_diag_;                      // diag(L W^{-1} L^T) when D is known to be diagonal
  bool d_diagonal_ = false;
  ContactResponses responses_;  // W^{-1} L_i^T
  Vec u_prev_, u_next_, f_int_, f_ext_, rhs_;
  LcpStorage lcp_storage_;  // the LCP on the active set
  std::vector<Index> active_;
  bool started_ = false;
  bool impulse_before_ = false;  // the previous step had an impulse
};

}  // namespace nsb
