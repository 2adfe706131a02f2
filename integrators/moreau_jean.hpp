#pragma once
// Moreau–Jean time-stepping, theta-method (M. Jean, CMAME 1999; V. Acary and B. Brogliato,
// Numerical Methods for Nonsmooth Dynamical Systems, Springer 2008, ch. 10; Siconos'
// MoreauJeanOSI). docs/method.md section 2:
//
//     M (V_{k+1} - V_k) = h [theta F_{k+1} + (1 - theta) F_k] + L^T Lambda,  F = F_ext - F_int
//     U_{k+1}           = U_k + h [theta V_{k+1} + (1 - theta) V_k]
//
// F_int linearised at U_k (exact for linear problems):
//     W (V_free - V_k) = h [theta F_ext,k+1 + (1 - theta) F_ext,k - F_int(U_k)] - h^2 theta K V_k
//     W = M + h^2 theta^2 K      (sparse Cholesky, CHOLMOD; factorised once when K is constant)
// Contacts with forecast gap g_k + gamma h g'_k <= 0 are active (Siconos'
// MoreauJeanOSI::addInteractionInIndexSet); on them the Newton impact law at velocity level
//     0 <= Lambda  _|_  g'_{k+1} + e g'_k >= 0,   g'_{k+1} = L V_free + D Lambda,  D = L W^{-1} L^T
// (diagonal D: closed form; otherwise projected Gauss-Seidel to lcp_tol, see lcp.hpp), then
//     V_{k+1} = V_free + W^{-1} L^T Lambda.
// theta in [1/2, 1]; first order with impacts; dissipative for theta > 1/2.
// gamma in [0, 1], unset: 1 - theta, the weight of the known V_k in the position update
// U_{k+1} = U_k + h [theta V_{k+1} + (1 - theta) V_k], i.e. the gap the step would reach
// without V_{k+1}'s share. Siconos' MoreauJeanOSI(theta, gamma) takes gamma = 1/2 when
// unset, whatever theta: at theta = 1 the unset values differ (0 here), and the two schemes
// activate contacts a step apart; with the same gamma they agree to round-off
// (tests/peers/siconos_test.cpp). gamma = 0: a contact acts only once g_k <= 0, i.e. once
// penetrated; a larger gamma forecasts further ahead.
// Moving contacts (Problem::contacts_move): the gaps and rows are evaluated once per step at
// U_k, the state at the step's start: the forecast g(U_k) + gamma h L(U_k) V_k <= 0 selects
// the active set, and L(U_k), T(U_k) carry g'_k, g'_{k+1} = L(U_k) V_{k+1}, the Delassus
// matrix and the impulses (their responses W^{-1} L_i^T recomputed every step). These are the
// rows Siconos' LagrangianScleronomousR uses: computeJach evaluates dh/dq at the interaction's
// q, which MoreauJeanOSI::prepareNewtonIteration refreshes before the first Newton iterate,
// i.e. at q_k (this scheme's one linearly implicit iterate; Siconos re-evaluates at each
// further Newton iterate). projection = position is refused with moving contacts (it
// projects onto the linear gap).
// Coulomb friction (docs/method.md section 6; Jean 1999): on the active contacts the 2D
// Moreau–Coulomb law with the local velocities U_N = g'_{k+1} + e g'_k, U_T = T V_{k+1} - w
// and the Delassus matrix of the interleaved rows [L_i; T_i] W^{-1} [L_j; T_j]^T, solved by
// nonsmooth Gauss–Seidel over contacts (coulomb.hpp: closed form per contact when they share
// no dof of W^{-1}, i.e. W diagonal), then V_{k+1} = V_free + W^{-1} (L^T Lambda_N + T^T Lambda_T).
// 3D contacts (Contacts::has_cone, capability "3D friction cone"; docs/three_d.md): the cone
//     0 <= Lambda_N _|_ U_N >= 0,  |Lambda_T| <= mu Lambda_N,  U_T = 0 inside,
//     Lambda_T = -mu Lambda_N U_T / |U_T| on the boundary (maximal dissipation),
// U_T = (T, T2) V_{k+1} - (w, w2), with the 3x3 blocks of [L_i; T_i; T2_i] W^{-1} [L_j; T_j;
// T2_j]^T, by the same nonsmooth Gauss–Seidel over contacts (solve_coulomb_cone) until a sweep
// changes no impulse by more than lcp_tol (relative, velocity units); its local solver is
// neither a projection iteration, Alart–Curnier nor Fischer–Burmeister but the exact solve of
// coulomb_cone.hpp: the projection onto the disk where the block is diagonal with equal
// tangent entries, else the tangential trust-region step (Moré–Sorensen secular equation,
// Newton to round-off) inside an Illinois iteration on Lambda_N to 1e-15 relative (its
// Alart–Curnier residual is the tests' measure of the law). Then
// V_{k+1} = V_free + W^{-1} (L^T Lambda_N + T^T Lambda_T1 + T2^T Lambda_T2).
// Massless dofs (the singular-mass bar's contact node): their rows of W are algebraic, and
// theta = 1/2 only carries an algebraic error over from step to step with factor -1 (the
// trapezoidal rule is not stiffly accurate): on the singular-mass bar bouncing under gravity
// theta = 1/2 lets the node's velocity flip sign each step after a release and the bar passes
// through the wall, theta > 1/2 damps the alternation (docs/measurements.md has the run and
// its numbers). Not fixed here: the studies run the default theta = 1/2 and show it.
//
// Nonlinear F_int (e.g. block-2d): linearised, not Newton. Each step assembles K(U_k) into
// its fixed pattern, refactorises W (CHOLMOD keeps the symbolic analysis) and solves once:
// a linearly implicit (Rosenbrock-type) theta step. Why: F_int(U_{k+1}) - F_int(U_k) -
// K dU = O(|dU|^2) = O(h^2), a local velocity error O(h^3), so theta = 1/2 stays second
// order in smooth phases and the scheme is first order with impacts anyway; Newton would
// cost several factorisations per step for no gain in order. The price: no exact
// discrete energy or angular momentum balance (the block study measures both).
// W = M + h^2 theta^2 K is symmetric but can be indefinite when K is (compressed
// hyperelastic material, large h): when CHOLMOD's Cholesky fails, the step falls back to
// a sparse LU with partial pivoting (Eigen's SparseLU; counted as "lu_fallbacks"). The
// largest LCP residual over the run is reported as "lcp_max_residual" next to the LCP
// iteration counts.
// No BLAS: CHOLMOD is held to its simplicial LL^T (its automatic mode takes the supernodal
// one, which calls dgemm/dsyrk/dtrsm/dpotrf, from about 2000 dofs on the block) and the
// fallback LU is Eigen's (UMFPACK calls BLAS too). Debian's serial OpenBLAS keeps its work
// buffers in one process-wide table taken without a lock, so two studies' cases factorising
// at once wrote into each other's buffers and changed each other's results; and the BLAS
// kernel picked for the CPU changes the rounding from one machine to the next. The price in
// CPU time per step on the block, measured against the supernodal factor: docs/measurements.md.
// tests/integrators/moreau_jean_concurrency_test.cpp guards the race.
//
// projection = position (Acary, CMAME 256, 2013; Siconos' MoreauJeanDirectProjectionOSI):
// after the step, U_{k+1} <- U_{k+1} + W^{-1} L^T nu, 0 <= nu _|_ g(U_{k+1}) >= 0 (an LCP on
// positions, implicit_contact.hpp): no penetration at the step's end. Along W^{-1} L^T, not
// M^{-1} L^T (equal to O(h^2) on massive dofs; W stays regular for massless dofs). V is
// left as the velocity step made it, so energy and momentum are not changed by nu directly;
// the position shift is O(h * penetration speed) per step, the scheme stays first order
// with impacts and of the theta-method's order in smooth phases (no correction there).
#include "integrators/contact_responses.hpp"
#include "solvers/coulomb.hpp"
#include "integrators/implicit_contact.hpp"
#include "integrators/integrator.hpp"
#include "solvers/lcp.hpp"
#include "solvers/sparse_cholesky.hpp"

namespace nsb {

class MoreauJean final : public Integrator {
 public:
  explicit MoreauJean(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;

 private:
  StepInfo advance(double dt_requested) override;
  void factorize(double h);
  const Vec& contact_response(Index contact);  // W^{-1} L_i^T, cached while W is unchanged
  const Vec& tangent_response(Index contact);  // W^{-1} T_i^T, likewise
  const Vec& tangent2_response(Index contact);  // W^{-1} T2_i^T (3D contacts), likewise
  LcpResult solve_frictionless(Index a, double e);
  LcpResult solve_with_friction();  // on active_, b = e g'_k (restitution_rate_)

  double theta_;
  double gamma_;  // activation forecast weight
  bool project_positions_;
  LcpOptions lcp_;
  SpMat K_;
  SparseSum W_;         // M + h^2 theta^2 K, refilled in place
  SparseCholesky chol_;  // its factorisation (sparse_cholesky.hpp)
  double h_factored_ = 0.0;
  bool moving_ = false;   // Problem::contacts_move
  ContactGeometry rows_;  // L, T (and g(U_k) for moving contacts)
  ContactResponses responses_;  // W^{-1} L_i^T
  bool friction_ = false;
  ContactResponses tangent_responses_;  // W^{-1} T_i^T
  bool cone_ = false;                    // 3D contacts with friction (Contacts::has_cone)
  ContactResponses tangent2_responses_;  // W^{-1} T2_i^T
  Vec mu_active_, restitution_rate_;
  Vec f_int_, f_ext_now_, f_ext_next_, rhs_, v_next_, gap_, gdot_, nu_;
  LcpStorage lcp_storage_;  // the LCP on the active set
  double* lcp_max_residual_ = nullptr;  // work_.extra's entry, once created
  std::vector<Index> active_;
  CorrectionBuffers correction_;  // projection = position
};

}  // namespace nsb
