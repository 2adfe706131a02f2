#pragma once
// CD-Lagrange, fixed step: explicit variational integrator for non-smooth dynamics
// (A. Gravouil, talk at GdR GDM 2022; Fekak, Brun, Gravouil, Depale, CMAME 2017;
// Di Stasio, Dureisseix, Gravouil et al. 2019). Impulse form of docs/method.md section 2:
//
//     U_{k+1}   = U_k + tau M^{-1} P_{k+1/2}
//     P_free    = P_{k+1/2} + tau (F_ext(t_{k+1}) - F_int(U_{k+1}))
//     Lambda_i  = 0 where g_i(U_{k+1}) > 0; on the others
//                 0 <= Lambda  _|_  g'_free + H Lambda + e g'_{k+1/2} >= 0,  H = L M^{-1} L^T
//                 (H diagonal: Lambda_i = max(0, -(g'_free,i + e g'_{k+1/2,i}) / H_ii))
//     P_{k+3/2} = P_free + L^T Lambda
//
// Lambda is the impulse of the step. The talk's cumulative form L^T(Lambda_{k+3/2} -
// Lambda_{k+1/2}) with Lambda reset to 0 when the gap opens is adhesive (docs/method.md); the
// impulse form is not.
//
// Coulomb friction (docs/method.md section 6): the closed contacts take (Lambda_N, Lambda_T) from
// the 2D Moreau–Coulomb law, P_{k+3/2} = P_free + L^T Lambda_N + T^T Lambda_T, in closed form
// per contact where no two contacts share a dof (impulse_contact.hpp); no tangential
// restitution.
//
// 3D contacts (Contacts::has_cone, capability "3D friction cone"; docs/three_d.md): the
// closed contacts take (Lambda_N, Lambda_T1, Lambda_T2) from the cone law
//     0 <= Lambda_N _|_ U_N >= 0,  |Lambda_T| <= mu Lambda_N,  stick U_T = 0 inside,
//     Lambda_T = -mu Lambda_N U_T / |U_T| on the boundary (maximal dissipation),
// U = q + W Lambda, W_i = [L_i; T_i; T2_i] M^{-1} [L_i; T_i; T2_i]^T (3x3), and
// P_{k+3/2} = P_free + L^T Lambda_N + T^T Lambda_T1 + T2^T Lambda_T2 (cone_contact.hpp): per
// contact in closed form where W_i is diagonal with equal tangent entries (W_i = w I_3, a node
// of equal mass in x, y, z on a flat obstacle, the talk's "diagonal and spherical": Lambda_N =
// -q_N / w, Lambda_T = -q_T / w projected onto the disk of radius mu Lambda_N; a rigid sphere's
// diag(w_n, w_t, w_t) likewise), the exact local solve of coulomb_cone.hpp otherwise
// (trust-region disk step, Illinois on Lambda_N to 1e-15 relative), nonsmooth Gauss–Seidel
// over the closed contacts where contacts share a dof (to lcp_tol). The step stays explicit.
//
// Moving contacts (Problem::contacts_move; the talk's step 3): the gaps and rows are
// evaluated at the new position, g(U_{k+1}), L(U_{k+1}), T(U_{k+1}), and every quantity of
// the impulse law above uses them: the active set g_i(U_{k+1}) <= 0, g'_free = L(U_{k+1})
// M^{-1} P_free, the restitution term e L(U_{k+1}) M^{-1} P_{k+1/2}, H = L M^{-1} L^T and
// P_{k+3/2} = P_free + L(U_{k+1})^T Lambda_N + T(U_{k+1})^T Lambda_T. The update stays
// explicit (one evaluation of the contacts per step). Not with massless dofs (their
// quasi-static solve below uses g0 + l u_i): init() refuses that pairing.
//
// Start: P_{1/2} = M v0 + tau/2 (F_ext(0) - F_int(U_0)) (half kick, second order in
// smooth phases). Needs a diagonal mass.
//
// Massless dofs (zero diagonal mass, e.g. the singular mass of signorini_bar.hpp) have no
// momentum: each is quasi-static, its position from its own equilibrium with its contact
// at t_{k+1}, after the massive dofs have moved (Khenous, Laborde, Renard 2008):
//     r_i   = F_int,i(U_{k+1}) - F_ext,i(t_{k+1}),   u_i <- u_i - r_i / K_ii   (free equilibrium)
//     if its contact c would be closed, g_c = g0_c + l u_i < 0:  u_i <- u_i - g_c / l
//     F_int <- F_int + K(:, i) du_i   (exact: the problem is linear)
//     Lambda_c = tau (F_int,i - F_ext,i) / l >= 0   (its internal force: no impulse law, no e)
// Conditions, checked by init() (InputError otherwise): the problem is linear, K_ii > 0, no
// two massless dofs are coupled by K (the massless tangent block is diagonal), and a contact
// touching a massless dof touches only that dof (row l e_i), at most one per dof. The
// momentum identity P_end - P_start = sum L^T Lambda + int F_ext still holds to round-off:
// the massive dofs receive -tau F_int,i = -Lambda_c l - tau F_ext,i through K's zero column
// sums. The reported v_i of a massless dof is its rate (U_{k+1,i} - U_{k,i}) / tau.
//
// Reported state after a step: t = t_{k+1}, u = U_{k+1}, v = M^{-1} P_{k+3/2} (the velocity
// of the coming step). Reported energy: the scheme's discrete energy
//     E_{k+1/2} = 1/2 P_{k+1/2}^T M^{-1} P_{k+1/2} + 1/2 (V(U_k) + V(U_{k+1})),
// which is constant in free flight under a constant force.
#include "integrators/central_difference.hpp"
#include "integrators/cone_contact.hpp"
#include "integrators/integrator.hpp"
#include "integrators/impulse_contact.hpp"

namespace nsb {

class CdLagrange final : public Integrator {
 public:
  explicit CdLagrange(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;
  Energy energy() const override;

 private:
  StepInfo advance(double dt_requested) override;
  LcpOptions lcp_;
  ImpulseContact contact_;
  bool cone_ = false;        // 3D contacts with friction: cone_contact_ instead of contact_
  ConeContact cone_contact_;
  CentralDifference cd_;

  // Quasi-static (massless) dofs; K's column i is stored as entries [begin, end) of
  // column_rows_/column_values_, so the update touches only i's neighbours.
  struct MasslessDof {
    Index dof, contact;  // contact = -1: none
    double k_ii, l;
    std::size_t begin, end;
  };
  void solve_massless(double tau);
  std::vector<MasslessDof> massless_;
  std::vector<Index> column_rows_;
  std::vector<double> column_values_;
  Vec massless_impulse_;  // per massless dof, this step
};

}  // namespace nsb
