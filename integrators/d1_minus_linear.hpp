#pragma once
// D1MinusLinear, half-explicit on velocity level (T. Schindler and V. Acary, "Timestepping
// schemes for nonsmooth dynamics based on discontinuous Galerkin methods: definition and
// outlook", Math. Comput. Simul. 95, 2014, 180-199; Siconos' D1MinusLinearOSI, type
// halfexplicit_velocity_level, read to learn). Velocities piecewise linear in time and
// discontinuous at the nodes (impacts only at t_k), positions continuous:
//
//     F_k = F_ext(t_k) - F_int(U_k)          (F_{k+1} of the previous step: one F_int per step)
//     (the contact stages below are skipped when no contact is closed: the free step is
//     velocity Verlet in three passes over the dofs)
//     left   V_{k,1}  = V_k + h M^{-1} F_k + M^{-1} L^T P_1,
//                       0 <= P_1 _|_ L_i V_{k,1} >= 0  on the contacts closed at U_k (g_i <= 0)
//            U_{k+1}  = U_k + h/2 (V_k + V_{k,1})
//     right  impact in the step <=> some contact with g_i(U_{k+1}) <= 0 has L_i V_{k,1} < 0:
//              yes: V^- = V_k + h/2 M^{-1} (F_k + F_{k+1})      (the impulse replaces the forces)
//              no:  V^- = V_k + h/2 M^{-1} (F_k + F_{k+1}) + 1/2 M^{-1} L^T P_1 + M^{-1} L^T P_2,
//                   0 <= P_2 _|_ L_i V^- >= 0  on the contacts closed at U_k
//     impact at t_{k+1}, on the contacts closed at U_{k+1} (Newton):
//            V_{k+1}  = V^- + M^{-1} L^T Lambda,   0 <= Lambda _|_ L V_{k+1} + e L V^- >= 0
// P_1 = h lambda_k^+ and P_2 = h/2 lambda_{k+1}^- are the non-impulsive contact forces at both
// ends of the step (solved at velocity level: the half-explicit choice), Lambda the impact.
// In smooth phases this is velocity Verlet: second order, explicit. Impulse of the step:
// Lambda + P_1/2 + P_2 (no impact) or Lambda (impact), >= 0. The LCPs: closed form for a
// diagonal H = L M^{-1} L^T, else projected Gauss-Seidel (impulse_contact.hpp).
// Coulomb friction: every stage's contact solve takes (P_N, P_T) from the 2D Moreau–Coulomb
// law (impulse_contact.hpp) at its own velocity, slip U_T = T V - w, and the tangential
// impulses join the normal ones in every update (M^{-1} (L^T P_N + T^T P_T)); the step's
// tangential impulse is summed like the normal one, so it stays in the cone.
// 3D contacts (Contacts::has_cone, capability "3D friction cone"; docs/three_d.md): every stage's
// contact solve takes (P_N, P_T1, P_T2) from the Coulomb cone at its own velocity,
//     0 <= P_N _|_ U_N >= 0,  |P_T| <= mu P_N,  U_T = 0 inside,
//     P_T = -mu P_N U_T / |U_T| on the boundary (maximal dissipation),  U_T = (T, T2) V - (w, w2),
// by CD-Lagrange's explicit cone solve (cone_contact.hpp, with e = 0 for P_1, P_2): per contact
// where no two contacts share a dof, the projection onto the disk where the contact's block
// [L; T; T2] M^{-1} [L; T; T2]^T is diagonal with equal tangent entries (a node of a lumped
// mesh, a rigid sphere), else the exact local solve of coulomb_cone.hpp (Moré–Sorensen
// trust-region step inside an Illinois iteration on P_N, to 1e-15 relative); nonsmooth
// Gauss–Seidel over the closed contacts (solve_coulomb_cone, to lcp_tol) where they share a
// dof; and M^{-1} (L^T P_N + T^T P_T1 + T2^T P_T2) in every update. The step's impulse sums
// the stages' like the 2D one; a sum of impulses in a convex cone stays in it.
// Reported state: (U_{k+1}, V_{k+1}) at t_{k+1}; energy V^T M V / 2 + V(U).
// Declines (InputError): a non-diagonal mass or a massless dof (M^{-1} in every stage).
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): Schindler and Acary evaluate the
// rows at the midpoint and end positions of the step; not implemented here.
#include "integrators/cone_contact.hpp"
#include "integrators/impulse_contact.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

class D1MinusLinear final : public Integrator {
 public:
  explicit D1MinusLinear(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;

 private:
  StepInfo advance(double dt_requested) override;
  // The impulses of one contact stage: normal, along T, along T2 (3D contacts).
  struct StageImpulses {
    Vec normal, tangential, tangential2;
    void reset(Index p);
  };
  // v += scale M^{-1} (L^T normal + T^T tangential + T2^T tangential2)
  void add_impulses(const StageImpulses& p, double scale, VecRef v) const;
  // The stage's contact solve (impulse_contact.hpp, or cone_contact.hpp for 3D contacts)
  // at the new position u with restitution e: v in, the free velocity, out, after p.
  long solve_stage(ConstVecRef u, ConstVecRef v_prev, VecRef v, StageImpulses& p, StepInfo& info, double e);
  // f(j) for each dof j of the contact rows (normal and tangent): the only velocities the
  // contact solves read.
  template <class F>
  void for_contact_dofs(F&& f) const {
    for (Index i = 0; i < L_.rows(); ++i) {
      for (decltype(L_)::InnerIterator it(L_, i); it; ++it) f(it.col());
      if (friction_)
        for (decltype(T_)::InnerIterator it(T_, i); it; ++it) f(it.col());
      if (cone_)
        for (decltype(T2_)::InnerIterator it(T2_, i); it; ++it) f(it.col());
    }
  }

  LcpOptions lcp_;
  ImpulseContact contact_;
  bool cone_ = false;  // 3D contacts with friction: cone_contact_ instead of contact_
  ConeContact cone_contact_;
  Vec minv_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_;
  Vec f_ext_, a_now_, a_next_, f_int_, v1_, v_minus_, u_start_, gap_;
  StageImpulses p1_, p2_, impact_;
  bool friction_ = false;
  Eigen::SparseMatrix<double, Eigen::RowMajor> T_, T2_;
  bool started_ = false;
  bool closed_start_ = false;  // some contact closed at U_k (g <= 0)
};

}  // namespace nsb
