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
// Reported state: (U_{k+1}, V_{k+1}) at t_{k+1}; energy V^T M V / 2 + V(U).
// Declines (InputError): a non-diagonal mass or a massless dof (M^{-1} in every stage).
#include "integrators/impulse_contact.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

class D1MinusLinear final : public Integrator {
 public:
  explicit D1MinusLinear(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "d1-minus-linear"; }
  void init(const Problem& problem, const State& initial) override;
  StepInfo step(double dt_requested) override;
  bool conditionally_stable() const override { return true; }  // explicit in the smooth forces

 private:
  void add_impulses(const Vec& impulse, double scale, VecRef v) const;  // v += scale M^{-1} L^T impulse

  LcpOptions lcp_;
  ImpulseContact contact_;
  Vec minv_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_;
  Vec f_ext_, a_now_, a_next_, f_int_, v1_, v_minus_, u_start_, p1_, p2_, impact_, gap_;
  bool started_ = false;
  bool closed_start_ = false;  // some contact closed at U_k (g <= 0)
};

}  // namespace nsb
