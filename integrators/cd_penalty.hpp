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
// Damping: a clamped spring-dashpot (Kelvin-Voigt), c_i = 2 zeta_i sqrt(kappa_i m_i), with
// zeta_i chosen per impact so that the scheme's own discrete restitution is e. Why not the
// continuous map of spring_dashpot.hpp (penalty-bdf's, right for an ODE solved accurately):
// the scheme resolves the contact in a few steps and its rebound depends on where in a step
// the impact falls: with the continuous zeta the restitution of the bouncing mass varies with
// the impact's phase within the step, by more than any zeta chosen once per problem can
// correct (docs/measurements.md).
// The discrete map. One contact, its effective mass m_i alone (H diagonal, no elastic
// coupling, the external force negligible over the contact, O(n_c tau) of the impulse), in
// step units x = g_i(U_k), s = tau g'_i(v_{k+1/2}), p = penalty_factor = kappa_i tau^2 / m_i,
// beta = c_i tau / m_i = 2 zeta_i sqrt(p): the update above is
//     x_{k+1} = x_k + s_k,
//     s_{k+1} = max(s_k, (s_k - p x_{k+1}) / (1 + beta))   while x_{k+1} < 0
// (the max is the clamp f >= 0), a linear 2x2 recurrence [[1, 1], [-p, 1 - p]] / (1 + beta)
// on its second row (det 1 / (1 + beta): the implicit dashpot damps at any beta > 0), with no
// step size in it: p is fixed by the scheme, so the map is the same at every tau. The
// impact enters with s_0 < 0 from x_0 >= 0 and closes the gap at x_1 = x_0 + s_0 < 0; its
// phase phi = -x_1 / |s_0| in (0, 1] is known at that step (the gaps at U_k and U_{k+1}).
// The contact opens at the first x_n >= 0 and leaves with s_{n-1} (no force on that step):
//     e_d(phi, p, zeta) = s_{n-1} / |s_0|,   the rebound speed over the impact speed,
// measured as the velocity after the contact's last forced step over the one before its
// first, nothing to choose at the exit. By homogeneity e_d depends on phi, p and zeta only;
// it decreases towards 0 as zeta grows. Undamped, e_d(phi, p, 0) = 1 at every phase when
// the discrete half period n_c = pi / (2 asin(sqrt(p) / 2)) is a whole number of steps (p = 2,
// the default: x_1 = -phi, s_1 = 2 phi - 1, x_2 = phi - 1, s_2 = 1, x_3 = phi); between
// whole numbers the switches gain or lose energy with the phase: e_d(., p, 0) spans
// 0.966..1.036 at p = 0.3 (5.7 steps), 0.995..1.005 at p = 0.1 (9.9 steps), 0.9989..1.0011 at
// p = 0.001 (99 steps). At the step that closes contact i, zeta_i solves
// e_d(phi, p, zeta_i) = e (cd_penalty_damping_ratio; once per impact, kept until the contact
// opens): bisection in log zeta when e_d(phi, p, 0) > e; when the switch lost more than
// 1 - e at this phase (e near 1 between whole half periods), a negative dashpot,
// -1 / (2 sqrt(p)) < zeta_i < 0 (1 + beta > 0: the implicit update stays defined), returns
// the energy the switch lost, bisection on that interval; zeta_i = 0 when e_d(phi, p, 0) is
// e to 1e-12. So the isolated contact rebounds at e to round-off at every phase and every
// p, 2 steps per contact included, e = 1 too. What remains: the external force over the
// contact (the weight's impulse m g n_c tau, relative g n_c tau / |v_in|) and, on an elastic
// body, the coupling of the contact dof to its neighbours, which the map does not see. A
// contact closed from the start (no impact) takes zeta at phi = 1. e = 0 needs zeta -> inf:
// zeta is capped at 1e3 (the implicit dashpot is stable for any c >= 0), a residual rebound
// e_d(phi, p, 1e3) of about 1e-3 or less at p <= 2; a contact still closed after 1e7 steps
// of the recurrence counts as absorbed (e_d = 0). This differs from the textbook "damping
// only while closing" c max(0, -g') [g < 0], whose restitution map is another function.
// Stable step with the contact springs: by Weyl's inequality the largest eigenvalue of
// M^{-1} (K + sum kappa_i L_i^T L_i) is at most omega_max^2 + penalty_factor / tau^2 (diagonal
// H; the dashpot, implicit, adds no limit), so the step is stable when
//     tau <= tau_stable = stable_step() sqrt(1 - penalty_factor / 4),   penalty_factor < 4
// (a sufficient bound: 0.71 tau_CFL at the default 2). stable_step_with_contacts() returns it
// and work().extra["stable_step_with_contacts"] records it when finite.
// Impulses: tau f_i, the contact impulse of the step (>= 0; non-zero only while g_i < 0).
// Energy: CD-Lagrange's discrete energy (kinetic at v_{k+1/2}, potential the mean over U_k and
// U_{k+1}) plus what the penalty springs store: the work the spring force of contact i,
// f_s = kappa_i max(0, -g_i), has taken from the body since the contact closed, summed as the
// kinetic energy sees it, S_i += f_s(U_k) (g_i(U_{k+1}) - g_i(U_{k-1})) / 2 (the kick at U_k
// changes 1/2 m v^2 by its impulse times the mean of v_{k-1/2} and v_{k+1/2}), and 0 once
// the contact is open. While a spring stays on this is the leapfrog invariant kappa_i g_k
// g_{k+1} / 2 plus a constant; its first term alone (the earlier choice) left out the work of
// the closing step, and the energy fell by up to half the impact's kinetic energy on it
// (9.81 -> 4.92 J, the bouncing mass with e = 1 at dt = 1e-3). So the reported energy is
// continuous through a contact, and what it changes by when the contact opens is the switch's
// own defect (e_d(phi, p, 0) != 1 between whole half periods) and the weight's impulse over
// the contact (2.1e-3 J there); the dashpot's work and friction's are dissipated, not stored.
// Moving contacts: g_i(U_{k+1}) - g_i(U_{k-1}) in place of L_i(U_k) (U_{k+1} - U_{k-1}), equal
// to second order in the step.
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
// 3D contacts (Contacts::has_cone, capability "3D friction cone"; docs/three_d.md): the
// regularised cone of spring_dashpot.hpp, the same implicit law with the interval become the
// disk, after the same normal force:
//     s_i = (T_i v - w_i, T2_i v - w2_i),   H_T,i = [T_i; T2_i] M^{-1} [T_i; T2_i]^T,
//     Lambda_T,i = -mu_i tau f_i phi(u_T(+) / v_reg),  phi(x) = x / max(1, |x|),
//                  u_T(+) = s_i + H_T,i Lambda_T,i
//     v    <- v + M^{-1} (T_i^T Lambda_T1,i + T2_i^T Lambda_T2,i)
// in closed form where H_T,i = h I (a node of a lumped mesh, a rigid sphere:
// Lambda_T = -mu tau f phi(s / (v_reg + h mu tau f))), else by bisection on the sliding
// branch's scalar equation to 1e-15 relative (spring_dashpot.hpp); |Lambda_T,i| <= mu_i tau
// f_i, = when sliding, opposite to u_T(+), which keeps the direction of (I + c H_T) ^{-1} s_i.
// Start: the half kick of cd_lagrange.hpp. Declines (InputError): a non-diagonal mass or a
// massless dof (M^{-1} in the update; CD-Lagrange's quasi-static treatment of massless dofs
// is an impulse law, not a penalty).
// Moving contacts (Problem::contacts_move; capability "moving contacts"): CD-Lagrange's
// evaluation (cd_lagrange.hpp, its step 3) with the penalty in place of the impulse law. After
// the drift, g(U_{k+1}), L(U_{k+1}), T(U_{k+1}) (and T2) are evaluated once per step; each
// contact with g_i(U_{k+1}) < 0 takes H_ii = L_i(U_{k+1}) M^{-1} L_i(U_{k+1})^T (so m_i and
// kappa_i follow the configuration), the force above along L_i(U_{k+1}) with the gap
// g_i(U_{k+1}) and g'_i = L_i(U_{k+1}) v, and the friction above along T_i(U_{k+1}) with
// h_T,i from it. The impact's phase uses g_i(U_k) (the previous step's evaluation) and
// g_i(U_{k+1}); the spring energy uses H_ii at U_{k+1}. On a rigid body the normal and tangent
// rows share the rotation (W_nt = L_i M^{-1} T_i^T != 0), where the Gauss-Seidel order above
// (normal first) lets the tangential impulse move g' after the dashpot saw it, which gains
// energy (the rocking block's pivot, mu = 1); so with 2D friction a moving contact solves its
// two impulses together, by sweeps until Lambda_T changes by at most 1e-13 relative (at most
// 200):
//     f_i = max(0, (-kappa_i g_i - c_i (L_i v + W_nt Lambda_T)) / (1 + c_i tau H_ii)),
//     Lambda_T = -mu_i tau f_i phi((T_i v + W_nt tau f_i - w_i) / (v_reg + h_T,i mu_i tau f_i)),
// v the velocity before the contact, then v <- v + M^{-1} (L_i^T tau f_i + T_i^T Lambda_T).
// 3D contacts keep the order above (normal, then the cone).
// Constant kinematics: the rows of the construction and g0 + L U, as before.
#include <Eigen/Core>
#include <vector>

#include "integrators/central_difference.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

// The discrete restitution e_d(phi, p, zeta) of the header: impact phase phi in (0, 1],
// p = penalty_factor, damping ratio zeta >= 0.
double cd_penalty_restitution(double phase, double penalty_factor, double zeta);
// The zeta with e_d(phi, p, zeta) = e, e in [0, 1]: 0 when e_d(phi, p, 0) = e to 1e-12,
// negative (above -1 / (2 sqrt(p))) when e_d(phi, p, 0) < e, the cap 1e3 when e is below
// e_d(phi, p, 1e3).
double cd_penalty_damping_ratio(double phase, double penalty_factor, double e);

class CdPenalty final : public Integrator {
 public:
  explicit CdPenalty(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;
  // Explicit, and its stable step is below the problem's (stable_step_with_contacts).
  Energy energy() const override;
  // The contact lasts n_c = pi / (2 asin(sqrt(penalty_factor) / 2)) steps (the discrete
  // spring's half period) plus the entry step; its restitution is e for an isolated contact
  // (the discrete map above), not on an elastic body's contact dof (coupled): not exact.
  ImpactAccuracy impact_accuracy() const override;

  // The stable-step bound above (infinite when the problem's own is).
  double stable_step_with_contacts() const;

 private:
  StepInfo advance(double dt_requested) override;
  // The regularised cone's tangential impulse of contact i after its normal impulse.
  void apply_cone_friction(Index i);
  // Moving contacts with 2D friction: contact i's normal force and tangential impulse solved
  // together (header), from its kappa, c and g'_i before it.
  void apply_coupled_contact(Index i, double kappa, double c, double gdot, double tau);
  double factor_;
  double e_ = 1.0;
  Vec zeta_;  // per contact, set when it closes
  CentralDifference cd_;
  // H_ii, h_T,i and H_T,i of contact i from the rows in rows_.
  void contact_masses(Index i);
  bool moving_ = false;
  // L, T, T2 (the construction's, or at U_{k+1} for moving contacts) and g(U_{k+1}) (moving).
  ContactGeometry rows_;
  Vec h_diag_;
  Vec gap_, gap_prev_, gap_prev2_;  // gaps at U_{k+1}, U_k, U_{k-1}
  // Per contact: the spring force f_s applied at U_k (0 where none), and the energy S_i its
  // spring stores (Energy above).
  Vec spring_force_, stored_;
  // Adds the work of the spring forces at U_k to stored_ (U_{k+1} known), empties the open.
  void store_spring_work();
  double v_reg_;
  bool friction_ = false;
  Vec mu_, w_, ht_diag_;
  bool cone_ = false;  // 3D contacts with friction
  Vec w2_;
  std::vector<Eigen::Matrix2d> ht_blocks_;  // H_T,i per contact (3D contacts)
};

}  // namespace nsb
