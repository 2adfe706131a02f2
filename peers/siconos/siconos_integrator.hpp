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
// 3D contacts with friction (Contacts::has_cone: two tangent rows, capability "3D friction
// cone"; siconos-moreau-jean only), and with one_step_problem = fc3d every contact of any
// problem, are one 3D interaction each:
//
//     LagrangianLinearTIR       y_i = [L_i; T_i; T2_i] q + (g0_i, 0, 0)   (gap, two slip
//                               positions; a tangent row zero where the problem has none)
//     NewtonImpactFrictionNSL   (e, e_t = 0, mu_i, 3): Newton on the normal, the Coulomb cone
//                               |lambda_T| <= mu_i lambda_N with maximal dissipation on the
//                               tangents (mu_i = 0 where the problem has no friction: the
//                               cone is the normal ray, lambda_T = 0); Siconos' lambda(1) =
//                               (normal, along +T_i, along +T2_i): impulses(),
//                               tangential_impulses(), tangential_impulses2()
//     FrictionContact(3)        3D nonsmooth Gauss-Seidel over the contacts
//                               (SICONOS_FRICTION_3D_NSGS), tolerance `friction_tol` (1e-12)
//                               on Siconos' residual (fc3d_compute_error: the natural-map
//                               residual of the cone complementarity, over |q|; evaluated
//                               per sweep by the increment, fully at the end: Siconos'
//                               "light with full final"), at most `friction_max_iter`
//                               sweeps; local solver per contact Siconos 4.4's default
//                               (solver_options_create(SICONOS_FRICTION_3D_NSGS)):
//                               SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID, a nonsmooth
//                               Newton on the Alart-Curnier function (Goldstein-Price line
//                               search) alternating with a projection on the cone, local
//                               tolerance 1e-14, at most 10 iterations
//
// theta and gamma as above; the scheme is MoreauJeanOSI's whatever the one-step problem.
// Sphere (problems/sphere.hpp) is linear time-invariant in these terms: its dofs are the
// centre's displacement and the integral of omega (theta' = omega), M = diag(m, m, m, I, I,
// I), constant rows L = e_z, T = (1, 0, 0, 0, -R, 0), T2 = (0, 1, 0, R, 0, 0), a constant
// F_ext: exactly LagrangianLinearTIDS (K = 0) with one LagrangianLinearTIR.
// A frictionless problem (mu = 0 everywhere) takes the LCP model above unchanged unless
// one_step_problem = fc3d (bar-3d: one 3D contact per wall-face node, mu = 0).
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
// by init() with an InputError: with friction an obstacle moving along a contact (w or w2 != 0, e.g.
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
