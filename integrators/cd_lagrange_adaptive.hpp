#pragma once
// CD-Lagrange with an adaptive, energy-consistent step (docs/method.md section 2). Sources:
// A. Gravouil, talk at GdR GDM 2022 ("pas de temps adaptatif", the horizontal generator of
// the discrete action); Kane, Marsden, Ortiz, West, "Variational integrators and the
// Newmark algorithm for conservative and dissipative mechanical systems", IJNME 49 (2000)
// 1295-1325 (KMOW: variable-step variational integrators, the step from the discrete
// energy); Fekak, Brun, Gravouil, Depale, CMAME 2017 (CD-Lagrange).
//
// tau_{k+1} = t_{k+1} - t_k. A step advances U_k -> U_{k+1} with the step tau_{k+1} chosen
// by the previous one, then chooses tau_{k+2}:
//
//   U_{k+1}   = U_k + tau_{k+1} M^{-1} P_{k+1/2},      F_{k+1} = F_ext(t_{k+1}) - F_int(U_{k+1})
//   momentum = variational (KMOW, the discrete Euler-Lagrange equation of the trapezoidal
//              discrete Lagrangian with variable steps):
//       P_free = P_{k+1/2} + (tau_{k+1} + tau_{k+2})/2 F_{k+1}
//   momentum = talk (the talk's literal weighting):
//       w_{k+3/2} P_free = w_{k+1/2} P_{k+1/2} + tau_{k+1} F_{k+1},  w_{k+1/2} = (tau_k + tau_{k+1}) / (2 tau_{k+1})
//   Lambda    = impulse of the contacts closed at U_{k+1}, Newton restitution against
//               g'_{k+1/2} = L M^{-1} P_{k+1/2} (ImpulseContact, as the fixed-step scheme)
//   P_{k+3/2} = P_free + L^T Lambda,                   U_{k+2} = U_{k+1} + tau_{k+2} M^{-1} P_{k+3/2}
//
// tau_{k+2} is the root of the discrete energy balance (the talk's equation for delta t):
//
//   r(tau_{k+2}) = E_{k+3/2} - E_{k+1/2} - W_ext - W_Lambda = 0
//   E_{k+1/2} = 1/2 P_{k+1/2}^T M^{-1} P_{k+1/2} + 1/2 (V(U_k) + V(U_{k+1})),  V = strain + load potential
//   W_ext     = 1/2 F_ext(t_{k+1})^T (U_{k+2} - U_k) + 1/2 (V_load(U_{k+2}) - V_load(U_k))
//               (trapezoidal work of the part of F_ext not in V_load; 0 to round-off for
//               gravity, where F_ext = -grad V_load is constant)
//   W_Lambda  = 0                                 energy_target = no-work (the talk: impulses
//                                                 do no work, Lambda^T g'_{k+3/2} = 0)
//             = (1 - e)/2 Lambda^T g'_{k+1/2}     energy_target = impact-law: the work
//               1/2 Lambda^T (g'+ + g'-) of a Newton impact, g'+ = -e g'-, g'- = g'_{k+1/2};
//               0 for e = 1, -(1 - e^2)/2 m (g'-)^2 for an isolated mass m.
//
// Why the step must move: E_{k+3/2} - E_{k+1/2} = 1/2 (P_{k+3/2} - P_{k+1/2})^T (v_{k+3/2} +
// v_{k+1/2}) + 1/2 (V(U_{k+2}) - V(U_k)). Without contact, with the variational update and
// a linear V (constant force F, mass m) this is F^2 (tau_{k+1}^2 - tau_{k+2}^2) / (8 m): the
// root is tau_{k+2} = tau_{k+1} (free flight keeps the step). With a quadratic V the fixed
// step leaves the trapezoidal-rule defect F^T (U_{k+2} - U_k)/2 + (V(U_{k+2}) - V(U_k))/2,
// which the step absorbs when a root exists. On the bouncing mass the root is tau_{k+1}
// also at impacts (e = 1, or any e with impact-law), so there the scheme is the fixed one.
//
// step_rule = talk: tau_{k+2} by the talk's own update instead of the root above. A. Gravouil,
// "CD-Lagrange" talk (GdR GDM 2022), the slides "Formulation variationnelle discrétisée en
// espace et en temps pour l'élastodynamique non-régulière" with adaptive step: the
// Euler-Lagrange equation of its variable-step action for the step, i.e. the derivative of the
// action in tau_{k+1} set to 0, solved for the tau_{k+2} of the term P_{k+3/2}^T (U_{k+2} -
// U_{k+1}) / (2 tau_{k+2}):
//
//   tau_{k+2} = [1/2 P_{k+3/2}^T (U_{k+2} - U_{k+1})] / D,
//   D = tau_k / (2 tau_{k+1}^2) P_{k+1/2}^T (U_{k+1} - U_k) + F_int,k+1^T U_{k+1} - Psi*(F_int,k+1)
//       + 1/2 (T(P_{k+3/2}) + T(P_{k+1/2})) - F_ext,k+1^T U_{k+1}
//       + 1/2 (Lambda_{k+3/2}^T gN'_{k+3/2} + Lambda_{k+1/2}^T gN'_{k+1/2})
//
// P = M v, T(P) = 1/2 P^T M^{-1} P; Psi* is the complementary strain energy, so F_int^T U -
// Psi*(F_int(U)) = Psi(U), the strain energy (Legendre); the talk's gap rate gN' = -L M^{-1} P
// is -g' here, so its Lambda^T gN' is -Lambda^T g' with this suite's impulses (0 for a closed
// contact with e = 0, complementarity). The update is implicit (U_{k+2} and P_{k+3/2} depend
// on tau_{k+2}); the talk's algorithm iterates it: predictor tau_{k+2} = tau_{k+1}, then the
// trial (P_free, Lambda, P_{k+3/2}, U_{k+2}) of that tau, the update, again until tau_{k+2}
// stops changing (here: |change| <= energy_tol x tau, at most max_iter updates), each update
// clamped to [tau_min, tau_up]. Note that U_{k+2} - U_{k+1} = tau_{k+2} M^{-1} P_{k+3/2} makes
// the numerator tau_{k+2} T(P_{k+3/2}): a fixed point is a step where T(P_{k+3/2}) = D, which
// the momentum update reaches only through P_{k+3/2}'s dependence on tau_{k+2}; and D holds
// F_ext^T U and Psi at U_{k+1}, not differences, so the rule depends on where U = 0 is. The
// energy-balance root r(tau) above is still evaluated for the step taken (max_rel_residual):
// how far the talk's step is from the discrete energy balance. Counters with this rule:
// no_root_steps counts the steps the update drove to tau_min (collapse), cfl_capped_steps those
// held at tau_up, unconverged_steps those still moving after max_iter updates.
//
// Momentum: the variational update gives sum_i P_{k+3/2} - P_{1/2} = sum_j (tau_j +
// tau_{j+1})/2 F_j + L^T Lambda_j, so with zero net force the linear momentum changes only
// by the impulses, for any step sequence. The talk's update conserves w P instead: P is
// rescaled by w_{k+1/2} / w_{k+3/2} whenever the step changes.
//
// Root finder (per step, at most max_iter residual evaluations): predictor tau_{k+1}
// clamped to [tau_min, tau_up], tau_up = min(tau_max, cfl_fraction * stable step at
// U_{k+1}); accepted if |r| <= energy_tol * S, S = 1/2 P^T M^{-1} P + (|V(U_k)| +
// |V(U_{k+1})|)/2 (the size of the terms, so the tolerance is relative). Else bracketing:
// probes at tau_pred (1 + d)^{+-1}, d = 1e-3, 4e-3, ... up to the bounds, the first sign
// change nearest (in ratio) to the predictor; then Illinois (safeguarded secant) to the
// tolerance. No sign change in [tau_min, tau_up]: the probe of least |r| is taken and the
// step counted in no_root_steps. The first step is the requested dt (clamped to tau_up)
// with the fixed scheme's half kick P_{1/2} = M v0 + tau_1/2 F_0: with tau_0 = 0 the balance
// would force tau_1 = 0 (E_{1/2} = E_0 - F^2 tau_1^2/(8 m) in free flight), so E_{1/2}, not
// the continuous E_0, is the balanced quantity. tau_min = tau_min_ratio * dt,
// tau_max = tau_max_ratio * dt (dt: the first requested step; later requests are ignored).
//
// Coulomb friction (either target): the closed contacts' tangential impulses do the work
//   W_T = 1/2 Lambda_T^T T (v_{k+3/2} + v_{k+1/2})    (the exact work of an impulse on the body,
//   <= 0 on a fixed obstacle), added to W_Lambda: friction is dissipation the balance must
//   allow, whatever the normal impulses' target.
//
// Counters (work().extra): energy_iterations (residual evaluations), no_root_steps,
// cfl_capped_steps (the step was held at tau_up: predictor above it, or no root and the
// least residual there; tau_up is the CFL bound or the user cap tau_max, whichever is
// smaller), unconverged_steps (bracketed but max_iter reached), max_rel_residual
// (max |r| / S over the steps taken, no-root steps included).
//
// Reported like the fixed scheme: after a step t = t_{k+1}, u = U_{k+1}, v = M^{-1} P_{k+3/2},
// energy E_{k+1/2}, dt = tau_{k+1}; so with a constant step the two schemes report the same.
// Needs a diagonal mass with positive entries.
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): its step control predicts the
// impact time from the linear gap g0 + L U; a nonlinear prediction is not implemented.
#include "integrators/impulse_contact.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

class CdLagrangeAdaptive final : public Integrator {
 public:
  explicit CdLagrangeAdaptive(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;
  Energy energy() const override;

  // The step the next call of step() will take (tau_{k+2}).
  double next_step() const { return tau_next_; }

 private:
  StepInfo advance(double dt_requested) override;
  void start(double dt);
  void load_force(double t);
  double residual(double tau, StepInfo& info);
  double step_bound() const;
  void choose_next_step(StepInfo& info);
  void choose_by_talk_update(StepInfo& info);
  double talk_update() const;

  bool talk_momentum_, no_work_, talk_step_;
  double energy_tol_, tau_min_ratio_, tau_max_ratio_, cfl_fraction_;
  long max_iter_;
  LcpOptions lcp_;
  ImpulseContact contact_;
  Vec m_, minv_;
  Vec u_prev_, u_next_, v_next_;  // U_k; trial U_{k+2}, M^{-1} P_{k+3/2}
  Vec f_int_, f_ext_, acc_, gdot_prev_;  // F_int, F_ext, M^{-1} F at U_{k+1}; L M^{-1} P_{k+1/2}
  bool friction_ = false;
  Eigen::SparseMatrix<double, Eigen::RowMajor> T_;
  Vec tdot_prev_, tdot_next_;  // T M^{-1} P_{k+1/2}, T v of the trial
  double e_ = 1.0;
  double tau_prev_ = 0, tau_ = 0, tau_next_ = 0;  // tau_k, tau_{k+1}, tau_{k+2}
  double tau_min_ = 0, tau_max_ = 0, cfl_ = 0;
  double kinetic_ = 0, pot_prev_ = 0, pot_cur_ = 0, pot_next_ = 0;  // T_{k+1/2}, V(U_k), V(U_{k+1}), V(trial)
  double load_prev_ = 0, load_cur_ = 0, load_next_ = 0;            // V_load of the same
  double energy_ = 0, scale_ = 0, fext_u_prev_ = 0;                // E_{k+1/2}, S, F_ext^T U_k
  double impulse_rate_prev_ = 0;                                   // Lambda_{k+1/2}^T g'_{k+1/2}
  bool started_ = false;
  // Counters in work_.extra (map nodes are stable; set in init()).
  double *iterations_ = nullptr, *no_root_ = nullptr, *capped_ = nullptr, *unconverged_ = nullptr,
         *max_residual_ = nullptr;
};

}  // namespace nsb
