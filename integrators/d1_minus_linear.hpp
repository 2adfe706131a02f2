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
// Moving contacts (Problem::contacts_move; capability "moving contacts"): each contact force
// acts along the rows of the node it belongs to (the discontinuous Galerkin scheme's
// quadrature at the element's ends t_k^+ and t_{k+1}^-, with W(q_k) and W(q_{k+1})):
//     P_1 (t_k^+):   active set g_i(U_k) <= 0, rows L(U_k), T(U_k) (solve, the kick of
//                    V_{k,1}, and its share h/2 M^{-1} L(U_k)^T P_1 of U_{k+1} and of V^-);
//     impact test and Lambda (t_{k+1}): g(U_{k+1}), rows L(U_{k+1}), T(U_{k+1});
//     P_2:           active set of U_k (as above) and its rows L(U_k), T(U_k).
// U_{k+1} is the scheme's only new position (no midpoint stage exists in the half-explicit
// velocity-level scheme), so these are the rows at the step's two nodes; P_2's rows at U_k
// instead of U_{k+1} differ by O(h) in a force term of weight h/2, O(h^2) per step, within
// the scheme's first order at impacts. The rows at U_{k+1} are kept for the next step's U_k
// (one evaluation of g, L, T per step here; the contact solves evaluate their own).
// Constant kinematics: the rows of the construction and g0 + L U, as before.
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
    for (Index i = 0; i < rows_.normal.rows(); ++i) {
      for (RowSpMat::InnerIterator it(rows_.normal, i); it; ++it) f(it.col());
      if (friction_)
        for (RowSpMat::InnerIterator it(rows_.tangent, i); it; ++it) f(it.col());
      if (cone_)
        for (RowSpMat::InnerIterator it(rows_.tangent2, i); it; ++it) f(it.col());
    }
  }

  LcpOptions lcp_;
  ImpulseContact contact_;
  bool cone_ = false;  // 3D contacts with friction: cone_contact_ instead of contact_
  ConeContact cone_contact_;
  Vec minv_;
  bool moving_ = false;
  // L, T, T2 at U_k (the construction's for constant kinematics; with moving contacts
  // evaluated at U_k: the rows P_1 acts along) and at U_{k+1} (the impact test's).
  ContactGeometry rows_, rows_next_;
  // gap_ = g(u), and rows at u for moving contacts (g0 + L u otherwise).
  void evaluate_gaps(ConstVecRef u, ContactGeometry& rows);
  Vec f_ext_, a_now_, a_next_, f_int_, v1_, v_minus_, u_start_, gap_;
  StageImpulses p1_, p2_, impact_;
  bool friction_ = false;
  bool started_ = false;
  bool closed_start_ = false;  // some contact closed at U_k (g <= 0)
};

}  // namespace nsb
