#pragma once
// Nonsmooth generalised-alpha with position and velocity levels enforced (Brüls, Acary,
// Cardona, "Simultaneous enforcement of constraints at position and velocity levels in the
// nonsmooth generalized-alpha scheme", CMAME 281, 2014; after Chen, Acary, Virlez, Brüls,
// IJNME 96, 2013). docs/method.md "The field's schemes". The velocity is a smooth part plus a
// jump, the position a smooth part plus a correction:
//
//   smooth (generalised-alpha, Arnold-Brüls form, Chung-Hulbert parameters from rho_inf):
//     M a_{k+1} + F_int(Q_{k+1}) = F_ext,k+1
//     (1 - alpha_m) abar_{k+1} + alpha_m abar_k = (1 - alpha_f) a_{k+1} + alpha_f a_k
//     Q_{k+1} = U_k + h V_k + h^2 [(1/2 - beta) abar_k + beta abar_{k+1}]
//     W_{k+1} = V_k + h [(1 - gamma) abar_k + gamma abar_{k+1}]
//     alpha_m = (2 rho_inf - 1)/(rho_inf + 1), alpha_f = rho_inf/(rho_inf + 1),
//     gamma = 1/2 + alpha_f - alpha_m, beta = (gamma + 1/2)^2 / 4
//   position correction (no penetration at the step's end):
//     U_{k+1} = Q_{k+1} + S^{-1} L^T nu,        0 <= nu  _|_  g(U_{k+1}) >= 0
//   velocity jump, Newton impact law on the contacts the smooth step closes (g(Q_{k+1}) <= 0):
//     V_{k+1} = W_{k+1} + S^{-1} L^T Lambda,    0 <= Lambda  _|_  L V_{k+1} + e L V_k >= 0
//   S = M + c K,  c = beta h^2 (1 - alpha_f) / (1 - alpha_m)  (the smooth step's iteration matrix)
//
// rho_inf = 1: alpha_m = alpha_f = 1/2, the trapezoidal rule (energy conserving on linear
// problems); rho_inf < 1 damps the modes with omega h >> 1 towards a spectral radius rho_inf
// and leaves omega h << 1 nearly untouched. Second order in smooth phases (a_k, abar_k are
// smooth accelerations: the contact terms never enter them, as in Brüls et al.), first order
// with impacts.
// Differences from Brüls et al. 2014, stated: (i) the three problems are solved one after
// the other (smooth step, then the position LCP, then the velocity LCP), not as one coupled
// system; with constant L this only changes the order in which the linear corrections
// enter; (ii) the corrections go along S^{-1} L^T instead of M^{-1} L^T (equal to O(h^2)
// on massive dofs), which keeps them defined for massless dofs (singular mass): there M is
// not invertible but S is, and the massless rows of the smooth step are quasi-static
// (F_int = F_ext); (iii) the persistent-contact force is carried by the per-step impulses
// (as in Moreau-Jean), not by a separate smooth multiplier.
// Coulomb friction (docs/method.md section 6), at the velocity level only, in the spirit of the
// frictional NSGA of Capobianco, Harsch, Eugster, Leine ("A nonsmooth generalized-alpha
// method for mechanical systems with frictional contact", IJNME 122, 2021): the velocity
// jump takes (Lambda_N, Lambda_T) from the 2D Moreau–Coulomb law with U_N = L V_{k+1} +
// e L V_k, U_T = T V_{k+1} - w (implicit_contact.hpp's frictional correction),
// V_{k+1} = W_{k+1} + S^{-1} (L^T Lambda_N + T^T Lambda_T); the position correction stays
// normal (no tangential constraint on positions). Differences from Capobianco et al.: their
// scheme carries separate contact forces and percussions, each with its own friction law,
// and solves the stages as one system; here, as in (iii) above, the per-step impulse carries
// the persistent friction force too. The price: the friction force never enters the smooth
// accelerations, so a stuck contact still moves with the smooth step's tangential load,
// h^2/2 a_T per step: creep at about h a_T / 2 under a static load (a_T = g sin(alpha) on the
// sliding mass; tests/integrators/friction_test.cpp holds nsga to that rate), which
// Capobianco et al.'s smooth friction force removes.
// 3D contacts (Contacts::has_cone, capability "3D friction cone"; docs/three_d.md): the same
// velocity jump with the Coulomb cone, U_T = (T, T2) V_{k+1} - (w, w2),
//     0 <= Lambda_N _|_ U_N >= 0,  |Lambda_T| <= mu Lambda_N,  U_T = 0 inside,
//     Lambda_T = -mu Lambda_N U_T / |U_T| on the boundary (maximal dissipation),
//     V_{k+1} = W_{k+1} + S^{-1} (L^T Lambda_N + T^T Lambda_T1 + T2^T Lambda_T2),
// on the 3x3 blocks of [L_i; T_i; T2_i] S^{-1} [L_j; T_j; T2_j]^T: Moreau–Jean's solve, shared
// (implicit_contact.hpp's frictional correction): nonsmooth Gauss–Seidel over contacts
// (solve_coulomb_cone) until a sweep changes no impulse by more than lcp_tol (relative,
// velocity units), each contact by the exact local solve of coulomb_cone.hpp (the projection
// onto the disk where its block is diagonal with equal tangent entries, else the Moré–Sorensen
// trust-region step inside an Illinois iteration on Lambda_N to 1e-15 relative); neither a
// projection iteration, Alart–Curnier nor Fischer–Burmeister. The creep above holds in 3D too.
// Nonlinear F_int: the smooth step is solved by Newton (newton_tol on the increment, see
// implicit_contact.hpp), refactorising S each iteration; the corrections use the last S.
// impulses() = Lambda, the velocity jump's impulse (nu is a position correction, no momentum).
// Cost of the position level (bouncing mass, e = 1): the correction lifts the smooth step's
// penetration back to g = 0 while the impact law restores the pre-step speed |g'_k|, so each
// impact loses m g_grav g_k (g_k in [0, h |g'_k|], the height at the start of the step): O(h)
// per impact, a loss Moreau-Jean (which leaves U at g_k) does not have. The energy so lost on
// the hard study's bouncing mass: docs/measurements.md.
// Moving contacts (Problem::contacts_move; capability "moving contacts"): g and its rows at
// the positions where each level is enforced, as Chen, Acary, Virlez and Brüls (IJNME 96,
// 2013: g(q_{n+1}) and g_q(q_{n+1}) inside their Newton iteration) and Capobianco et al.
// (g_N(q_{n+1}), W_N(q_{n+1})) do:
//     closing set:  g_i(Q_{k+1}) <= 0;
//     position:     U_{k+1} = Q_{k+1} + S^{-1} L(U_{k+1})^T nu,  0 <= nu _|_ g(U_{k+1}) >= 0,
//                   by Newton (Josephy) on the rows: from x_0 = Q_{k+1},
//                   x_{j+1} = Q_{k+1} + S^{-1} L(x_j)^T nu_j,
//                   0 <= nu_j _|_ g(x_j) + L(x_j) (x_{j+1} - x_j) >= 0   (one LCP per iterate),
//                   stopped when |x_{j+1} - x_j|_inf <= newton_tol |x_{j+1} - Q_{k+1}|_inf
//                   + 100 eps |x_{j+1}|_inf (the smooth step's test), at most newton_max_iter
//                   iterates (then the step reports unconverged, counted in
//                   work().extra["position_newton_unconverged"]);
//     velocity:     rows L(U_{k+1}), T(U_{k+1}) for the jump, U_N = L(U_{k+1}) V_{k+1}
//                   + e L(U_k) V_k (each rate at its own position, as Capobianco et al.'s
//                   xi_N = gamma_N(q_{n+1}, u_{n+1}) + e gamma_N(q_n, u_n)).
// The three problems stay sequential (difference (i) above). Constant kinematics: the rows of
// the construction and one LCP for the position, as before.
#include "integrators/implicit_contact.hpp"

namespace nsb {

class Nsga final : public Integrator {
 public:
  explicit Nsga(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;

 private:
  StepInfo advance(double dt_requested) override;
  // Moving contacts: the position correction by Newton on the rows (formula block above),
  // q_ in: the smooth step's Q, out: U_{k+1}.
  void correct_positions_on_moving_rows(StepInfo& info);
  double alpha_m_, alpha_f_, gamma_, beta_;
  NewtonOptions newton_;
  ImplicitContact implicit_;
  bool moving_ = false;
  Vec a_, abar_, abar_next_, u_pred_, u_hat_, q_, w_, nu_, f_ext_, b_;
  Vec q_smooth_, q_previous_, offset_, restitution_rate_;  // moving contacts
  std::vector<Index> closing_;
};

}  // namespace nsb
