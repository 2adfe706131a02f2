#pragma once
// Siconos' time-stepping schemes run as nsbench integrators: the peers of docs/method.md section 2,
// "Peers run side by side" (Siconos 4.4 kernel, Debian libsiconos-kernel-dev). A linear
// Problem is handed to Siconos (siconos_model.hpp) as
//
//     LagrangianLinearTIDS      M q'' + K q = F_ext          (dense M, K; constant F_ext)
//     LagrangianLinearTIR       y_i = L_i q + g0_i           (one Interaction per contact)
//     NewtonImpactNSL(e)        0 <= Lambda _|_ y'(+) + e y'(-) >= 0
//     LCP one-step NS problem   Lemke pivoting (SICONOS_LCP_LEMKE), tolerance `lcp_tol`
//
// with one of Siconos' one-step integrators:
//   siconos-moreau-jean      MoreauJeanOSI(theta, gamma), TimeStepping; velocity-level LCP on
//                            the contacts with y_k + gamma h y'_k <= 0 (MoreauJeanOSI::
//                            addInteractionInIndexSet). gamma defaults to 1/2, Siconos' own
//                            value when none is given: the same bits (without gamma its
//                            _useGamma only picks a literal 1/2 instead). impulses() =
//                            lambda(1), the impulse of the step, and tangential_impulses()
//                            its tangential component with friction
//   siconos-schatzman-paoli  SchatzmanPaoliOSI(theta), TimeStepping; position-level LCP
//                              W (q_{k+1} - q_k) = M (q_k - q_{k-1}) + h^2 (F_ext - K q_k) + L^T R,
//                              W = M + h^2 theta^2 K,  0 <= R _|_ g0 + L q_{k+1} + e (g0 + L q_{k-1}) >= 0;
//                            Siconos starts from q_{-1} = q_0, q_0 <- q_0 + h v_0 (one step ahead)
//                            and reports v = (q_{k+1} - q_{k-1}) / 2h; impulses() = R / h.
//                            theta = 0 is the explicit central difference (Paoli & Schatzman 2002);
//                            theta > 0 is Siconos' own linearly implicit variant, not ours (schatzman_paoli.hpp)
//                            K (theta q_{k+1} + (1 - 2 theta) q_k + theta q_{k-1}).
//   siconos-d1-minus-linear  D1MinusLinearOSI (half-explicit, acceleration level),
//                            TimeSteppingD1Minus with an impact LCP and a contact-force LCP
//                            (Schindler & Acary, Math. Comput. Simul. 95, 2014);
//                            impulses() = lambda(1) + h lambda(2).
//
// For a problem with Coulomb friction (some mu_i > 0; siconos-moreau-jean only), every
// contact is one 2D interaction instead:
//
//     LagrangianLinearTIR       y_i = [L_i; T_i] q + (g0_i, 0)    (gap, slip position)
//     NewtonImpactFrictionNSL   (e, e_t = 0, mu_i): Newton on the normal, Coulomb on the
//                               tangent; Siconos' tangential lambda acts along +T_i (p = C^T
//                               lambda) and opposes y'_T, as our Lambda_T and u_T = T v
//     FrictionContact(2)        2D nonsmooth Gauss-Seidel (SICONOS_FRICTION_2D_NSGS: exact
//                               local solve per contact), tolerance `friction_tol` (1e-12,
//                               Siconos' residual |q + W r - u| / |q|), at most
//                               `friction_max_iter` sweeps; iterations and convergence are
//                               reported as the LCP's (lcp_iterations, lcp_unconverged)
//
// A frictionless problem (mu = 0 everywhere) takes the LCP model above unchanged.
// The Schatzman-Paoli and D1MinusLinear peers decline friction (bind(): mu named).
// D1MinusLinearOSI has no NewtonImpactFrictionNSL case in its free-output visitor (only
// NewtonImpactNSL: Siconos throws "you must define a visit function"). SchatzmanPaoliOSI has
// one (a position-level FrictionContact), but our schatzman-paoli treats no friction to
// compare it with.
// References: V. Acary, B. Brogliato, Numerical Methods for Nonsmooth Dynamical Systems,
// Springer 2008; the Siconos kernel sources (MoreauJeanOSI.cpp, SchatzmanPaoliOSI.cpp,
// D1MinusLinearOSI*.cpp, FrictionContact.cpp, numerics' fc2d_nsgs.c), read, not copied;
// M. Jean, The non-smooth contact dynamics method, CMAME 177, 1999 (friction).
//
// Declared capabilities (the registry entries; refused when the problem binds): linear only
// (Siconos' LagrangianDS would need plugins for a nonlinear F_int; a constant F_ext), no
// massless dofs (LagrangianDS inverts M), at most `max_dofs` dofs (dense matrices). Declined
// by init() with an InputError: with friction an obstacle moving along a contact (w != 0, e.g.
// block-2d's floor_velocity): LagrangianLinearTIR has no velocity offset (y' = C v), and
// Siconos' time-dependent relation (LagrangianRheonomousR) takes h, its Jacobian and hDot
// only as plugins loaded from a shared library by path. The step is fixed at the first call
// of step() (Siconos' TimeDiscretisation); a later different step is refused.
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): the model passes the constant
// rows as a LagrangianLinearTIR; a LagrangianScleronomousR with g(U) and its Jacobian is not
// built.
#include <memory>

#include "integrators/integrator.hpp"
#include "peers/siconos/siconos_model.hpp"

namespace nsb {

class SiconosIntegrator : public Integrator {
 public:
  SiconosIntegrator(const Params& params, siconos::Scheme scheme);
  ~SiconosIntegrator() override;
  // Parameters of a scheme (theta only where Siconos' OSI has one).
  static ParamSpecs parameters_spec(siconos::Scheme scheme);

  void init(const Problem& problem, const State& initial) override;

 private:
  StepInfo advance(double dt_requested) override;
  void build(double h);  // the Siconos model, once h is known

  siconos::Scheme scheme_;
  std::unique_ptr<siconos::Model> model_;
  double h_ = 0.0;
};

template <siconos::Scheme S>
class SiconosPeer final : public SiconosIntegrator {
 public:
  explicit SiconosPeer(const Params& params) : SiconosIntegrator(params, S) {}
  static ParamSpecs parameters_spec() { return SiconosIntegrator::parameters_spec(S); }
};

// The Debian version of the Siconos kernel built against (e.g. "4.4.0+dfsg-2").
std::string siconos_version();

}  // namespace nsb
