#pragma once
// Newmark with position-level Lagrange multipliers (Newmark, ASCE J. Eng. Mech. 85, 1959;
// with contact: Carpenter, Taylor, Katona, IJNME 32, 1991; Laursen, Computational Contact
// and Impact Mechanics, Springer 2002, ch. 8). docs/method.md "The field's schemes":
//
//     M A_{k+1} + F_int(U_{k+1}) = F_ext,k+1 + L^T lambda_{k+1}
//     0 <= lambda_{k+1}  _|_  g(U_{k+1}) = g0 + L U_{k+1} >= 0
//     U_{k+1} = U_k + h V_k + h^2 [(1/2 - beta) A_k + beta A_{k+1}]
//     V_{k+1} = V_k + h [(1 - gamma) A_k + gamma A_{k+1}]          beta = 1/4, gamma = 1/2
//
// Solved for U_{k+1} (displacement form): with U_pred = U_k + h V_k + h^2 (1/2 - beta) A_k,
//     M (U - U_pred) + beta h^2 (F_int(U) - F_ext,k+1) = L^T mu,   mu = beta h^2 lambda,
// by Newton on U where each iterate solves the linearised step with its contact LCP
// (a Josephy-Newton / sequential-LCP iteration, S = M + beta h^2 K(U_i)), stopped on the
// increment (newton_tol, implicit_contact.hpp); linear K: one iteration, S factorised once
// per step size.
// A_{k+1} = (U_{k+1} - U_pred) / (beta h^2). Impulse of the step (impulses()):
// h [(1 - gamma) lambda_k + gamma lambda_{k+1}], the momentum the multipliers transfer.
//
// Mass models. Only M A enters the equations, so a massless dof (zero diagonal of M) is
// quasi-static: its row is F_int = F_ext + L^T lambda, solvable because S = M + beta h^2 K
// is regular; its A and V are the Newmark differences of its positions (no kinetic energy).
// With the singular bar (massless contact node) this is the mass-redistribution method of
// Khenous, Laborde, Renard (Eur. J. Mech. A/Solids 27, 2008) / the modified mass of Doyen,
// Ern, Piperno (SISC 33, 2011): the contact is a Lipschitz unilateral spring of the massive
// dofs and beta = 1/4, gamma = 1/2 nearly conserve the energy. With a lumped or consistent
// mass the contact dof has inertia and no impact law: the classic failing control
// (contact-force chatter, energy jumps at impacts and releases).
// Declines (InputError): a restitution e > 0 on a contact acting on a massive dof, through the
// capability "e = 0 on contacts with mass" (Capabilities::inelastic_only, refused in the same
// line as any other capability the problem misses): the scheme has no velocity-level impact
// law, so the rebound speed would depend on where in the step the contact closes, anything in
// [-v, v]; a non-diagonal singular mass.
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): its multipliers hold the linear
// constraint g0 + L U >= 0 at the step's end; not extended to g(U).
#include "integrators/implicit_contact.hpp"

namespace nsb {

class NewmarkLm final : public Integrator {
 public:
  explicit NewmarkLm(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;

 private:
  StepInfo advance(double dt_requested) override;
  double beta_, gamma_;
  ImplicitContact implicit_;
  Vec a_, a_next_, lambda_, mu_, u_pred_, u_next_, f_ext_;
};

}  // namespace nsb
