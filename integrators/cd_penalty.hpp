#pragma once
// Explicit central difference with penalty contact (the industrial explicit codes' choice:
// P. Wriggers, Computational Contact Mechanics, 2nd ed., Springer 2006, ch. 6 and 10;
// J. O. Hallquist et al., CMAME 51, 1985, and LS-DYNA's soft-constraint penalty, whose
// stiffness scales with the nodal mass over the step squared; friction regularised after
// J. T. Oden and J. A. C. Martins, CMAME 52, 1985, see spring_dashpot.hpp). CD-Lagrange's
// staggered update (cd_lagrange.hpp) with the contact as a force instead of an impulse law:
//
//     U_{k+1}   = U_k + tau v_{k+1/2}
//     v_free    = v_{k+1/2} + tau M^{-1} (F_ext(t_{k+1}) - F_int(U_{k+1}))
//     on each contact with g_i = g_i(U_{k+1}) < 0 (in turn, v updated after each):
//         f_i   = max(0, -kappa_i g_i - c_i g'_i),   g'_i = L_i v_{k+3/2}   (dashpot implicit)
//               = max(0, (-kappa_i g_i - c_i L_i v) / (1 + c_i tau H_ii)),  H = L M^{-1} L^T
//         v    <- v + tau M^{-1} L_i^T f_i
//         with friction (mu_i > 0), then on the same contact, implicit in the slip:
//         Lambda_T,i = -mu_i tau f_i phi((T_i v - w_i) / (v_reg + h_T,i mu_i tau f_i)),
//                                                        h_T = T M^{-1} T^T, phi = clamp(., -1, 1)
//         v    <- v + M^{-1} T_i^T Lambda_T,i
//     v_{k+3/2} = v
//
// Penalty stiffness: kappa_i = penalty_factor * m_i / tau^2, m_i = 1 / H_ii the contact's
// effective mass. The contact dof's own stiffness scale is taken as the stiffness its mass
// resolves at the step (the LS-DYNA soft-constraint scale), not its elastic K_ii: a rigid
// body (the bouncing mass) has none, and with a step-scaled kappa the penalty solution
// converges to Signorini's as tau -> 0 (penetration F tau^2 / (penalty_factor m_i) = O(tau^2)
// under a force F, contact duration O(tau): the phase error per impact is pi tau /
// (2 asin(sqrt(penalty_factor) / 2)), i.e. 2 steps at penalty_factor = 2). A fixed kappa would
// instead converge to the penalty problem, never to the contact law.
// Damping: the clamped spring-dashpot (Kelvin-Voigt) of penalty-bdf, c_i = 2 zeta sqrt(kappa_i
// m_i), zeta from the problem's e through spring_dashpot.hpp (the same map as penalty-bdf, so
// both converge to the same law; capped at zeta = 1e3, e = 2.5e-7: the implicit dashpot is
// stable for any c). This differs from the textbook "damping only while closing"
// c max(0, -g') [g < 0], whose restitution map is another function.
// Stable step with the contact springs: by Weyl's inequality the largest eigenvalue of
// M^{-1} (K + sum kappa_i L_i^T L_i) is at most omega_max^2 + penalty_factor / tau^2 (diagonal
// H; the dashpot, implicit, adds no limit), so the step is stable when
//     tau <= tau_stable = stable_step() sqrt(1 - penalty_factor / 4),   penalty_factor < 4
// (a sufficient bound: 0.71 tau_CFL at the default 2). stable_step_with_contacts() returns it
// and work().extra["stable_step_with_contacts"] records it when finite.
// Impulses: tau f_i, the contact impulse of the step (>= 0; non-zero only while g_i < 0).
// Energy: CD-Lagrange's discrete energy plus the springs kappa_i g_i(U_k) g_i(U_{k+1}) / 2
// where both are closed: the leapfrog invariant while a spring stays on. Across the on/off
// switches no discrete invariant holds: within a contact resolved in ~2 steps the energy so
// measured swings by up to 50% of the impact's kinetic energy at penalty_factor 2 (25% at 1;
// g_{k+1}^2 in place of g_k g_{k+1} doubles it), the price of a coarse penalty.
// Friction (docs/method.md section 6): the regularised Coulomb law of spring_dashpot.hpp,
// F_T = -mu F_N phi(u_T / v_reg), v_reg = `friction_velocity`, F_N = f_i the spring-dashpot
// force of the step, in its implicit form: the slip after the kick, u_T(+) = T_i v_{k+3/2} -
// w_i, is the one the law sees. Why implicit: the viscous branch is a damper of coefficient
// c_T = mu F_N / v_reg, explicitly stable only for tau < 2 m / c_T; resting under its weight
// (F_N = m g) that is tau < 2 v_reg / (mu g), 0.4 ms at v_reg = 1 mm/s, mu = 0.5, far below
// the step of a stiff body, and the limit moves with F_N (impacts). The implicit form is a
// closed form per contact (a scalar clamp), stable for any tau, and never reverses the slip
// in one step. The normal force comes first (Gauss-Seidel on the contact's two rows): exact
// when T_i M^{-1} L_i^T = 0, as for every contact on a rigid floor or slope in this suite
// (normal and tangent rows on different dofs); otherwise the tangential impulse moves g' by
// (T_i M^{-1} L_i^T) Lambda_T after the dashpot saw it. Creep, the regularisation's error:
// under a tangential load F < mu F_N the contact slides at u_T = v_reg F / (mu F_N), also in
// the discrete steady state (the implicit law's fixed point is the continuous one). mu = 0
// on every contact (a frictionless problem) runs the frictionless step, bit for bit.
// Tangential impulses: Lambda_T,i above (|Lambda_T,i| <= mu_i tau f_i, = when sliding).
// Start: the half kick of cd_lagrange.hpp. Declines (InputError): a non-diagonal mass or a
// massless dof (M^{-1} in the update; CD-Lagrange's quasi-static treatment of massless dofs
// is an impulse law, not a penalty).
#include "integrators/central_difference.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

class CdPenalty final : public Integrator {
 public:
  explicit CdPenalty(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "cd-penalty"; }
  void init(const Problem& problem, const State& initial) override;
  StepInfo step(double dt_requested) override;
  // Explicit, and its stable step is below the problem's (stable_step_with_contacts).
  bool conditionally_stable() const override { return true; }
  bool treats_friction() const override { return true; }
  Energy energy() const override;
  // The contact lasts n_c = pi / (2 asin(sqrt(penalty_factor) / 2)) steps (the discrete
  // spring's half period) plus the entry step; its restitution depends on the impact's
  // phase for e < 1 (see the header).
  ImpactAccuracy impact_accuracy() const override;

  // The stable-step bound above (infinite when the problem's own is).
  double stable_step_with_contacts() const;

 private:
  double factor_;
  double zeta_ = 0.0;
  CentralDifference cd_;
  Vec h_diag_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_;
  Vec gap_, gap_prev_;  // gaps at U_{k+1}, U_k
  double tau_ = 0.0;    // last step (the springs' stiffness depends on it)
  double v_reg_;
  bool friction_ = false;
  Eigen::SparseMatrix<double, Eigen::RowMajor> T_;
  Vec mu_, w_, ht_diag_;
};

}  // namespace nsb
