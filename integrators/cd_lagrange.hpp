#pragma once
// CD-Lagrange, fixed step: explicit variational integrator for non-smooth dynamics
// (A. Gravouil, talk at GdR GDM 2022; Fekak, Brun, Gravouil, Depale, CMAME 2017;
// Di Stasio, Dureisseix, Gravouil et al. 2019). Impulse form of DESIGN.md section 2:
//
//     U_{k+1}   = U_k + tau M^{-1} P_{k+1/2}
//     P_free    = P_{k+1/2} + tau (F_ext(t_{k+1}) - F_int(U_{k+1}))
//     Lambda_i  = 0 where g_i(U_{k+1}) > 0; on the others
//                 0 <= Lambda  _|_  g'_free + H Lambda + e g'_{k+1/2} >= 0,  H = L M^{-1} L^T
//                 (H diagonal: Lambda_i = max(0, -(g'_free,i + e g'_{k+1/2,i}) / H_ii))
//     P_{k+3/2} = P_free + L^T Lambda
//
// Lambda is the impulse of the step. The talk's cumulative form L^T(Lambda_{k+3/2} -
// Lambda_{k+1/2}) with Lambda reset to 0 when the gap opens is adhesive (DESIGN.md); the
// impulse form is not.
//
// Start: P_{1/2} = M v0 + tau/2 (F_ext(0) - F_int(U_0)) (half kick, second order in
// smooth phases). Needs a diagonal mass with positive entries.
//
// Reported state after a step: t = t_{k+1}, u = U_{k+1}, v = M^{-1} P_{k+3/2} (the velocity
// of the coming step). Reported energy: the scheme's discrete energy
//     E_{k+1/2} = 1/2 P_{k+1/2}^T M^{-1} P_{k+1/2} + 1/2 (V(U_k) + V(U_{k+1})),
// which is constant in free flight under a constant force.
#include "integrators/integrator.hpp"
#include "integrators/impulse_contact.hpp"

namespace nsb {

class CdLagrange final : public Integrator {
 public:
  explicit CdLagrange(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "cd-lagrange"; }
  void init(const Problem& problem, const State& initial) override;
  StepInfo step(double dt_requested) override;
  Energy energy() const override;

 private:
  LcpOptions lcp_;
  ImpulseContact contact_;
  Vec m_, minv_;
  Vec u_prev_, v_prev_;   // U_k and M^{-1} P_{k+1/2}
  Vec f_int_, f_ext_;
  bool started_ = false;
};

}  // namespace nsb
