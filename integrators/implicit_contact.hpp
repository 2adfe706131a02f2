#pragma once
// Shared parts of the implicit Newmark-type schemes with contact (nsga, newmark-lm):
//
//     M (U - U_hat) + c (F_int(U) - F_ext) = L^T mu    [0 <= mu _|_ g(U) >= 0, or mu = 0]
//
// solved for U by Newton from U_hat: S = M + c K(U_i),
//     U_{i+1} = U_i - S^{-1} R(U_i)   (R without the contact term), then corrected below,
// with the contact a Josephy-Newton (sequential LCP) iteration: each iterate solves the
// linearised step with its LCP. Stopped when |U_{i+1} - U_i|_inf <= newton_tol
// |U_{i+1} - U_hat|_inf + 100 eps |U_{i+1}|_inf (the second term: round-off of U, which
// |U - U_hat| = O(h^2) can be far below, and without which a step near rest can run to the
// iteration cap: docs/measurements.md); a linear K takes one iteration and one factorisation per c.
//
//     S = M + c K                          iteration matrix (c = beta h^2 for Newmark,
//                                          beta h^2 (1 - alpha_f) / (1 - alpha_m) for gen.-alpha)
//     x <- x + S^{-1} L_A^T mu,   0 <= mu  _|_  b_A + L_A x >= 0        (contact correction)
//
// S is factorised by CHOLMOD's simplicial LL^T (sparse_cholesky.hpp: pattern analysed at
// bind(), where a factor too large for the memory is refused; no BLAS, see moreau_jean.hpp),
// with Eigen's sparse LU as the fallback when S is indefinite; the responses S^{-1} L_i^T are
// cached per contact while S is unchanged. S is regular for a singular (massless-dof) M when K
// holds those dofs, which is why the corrections go along S^{-1} L^T and not M^{-1} L^T
// (the two agree to O(c) on massive dofs).
// The correction is one LCP on the contact set A with Delassus D = L_A S^{-1} L_A^T (see
// lcp.hpp). With grow = true, A starts as the violated rows (b + L x < 0) and contacts that
// the correction pushes into violation are added until none is left (position level:
// no penetration at the step's end beyond the LCP tolerance).
#include <functional>
#include <vector>

#include "integrators/contact_responses.hpp"
#include "solvers/coulomb.hpp"
#include "solvers/coulomb_cone.hpp"
#include "integrators/integrator.hpp"
#include "solvers/lcp.hpp"
#include "solvers/sparse_cholesky.hpp"

namespace nsb {

using ContactRows = Eigen::SparseMatrix<double, Eigen::RowMajor>;

// The correction's storage, kept by the caller from step to step (no allocation per step).
struct CorrectionBuffers {
  std::vector<Index> active;
  Vec x0;
  LcpStorage lcp;
};

// The correction above for any iteration matrix: response(i) = S^{-1} L_i^T (cached by the
// caller). Adds the LCP iterations to work (and an unconverged LCP to lcp_unconverged).
LcpResult contact_correction(const ContactRows& L, const Vec& b, Vec& x, Vec& mu, const std::vector<Index>& active, bool grow,
                             const std::function<const Vec&(Index)>& response, const LcpOptions& lcp,
                             WorkCounters& work, CorrectionBuffers& buffers);

// The frictional velocity correction of an implicit scheme (docs/method.md section 6), on the
// contact set `active`, S the iteration matrix:
//     x <- x + S^{-1} (L^T Lambda_N + T^T Lambda_T),
//     2D Moreau–Coulomb law (coulomb.hpp) with U_N = b_i + L_i x, U_T = T_i x - w_i,
// Delassus blocks [L_i; T_i] S^{-1} [L_j; T_j]^T from the cached responses S^{-1} L_j^T and
// S^{-1} T_j^T. normal, tangential (size p) get the impulses, zero off the set. The caller
// counts the iterations.
// 3D contacts (T2 set: Contacts::has_cone): the rows [L_i; T_i; T2_i], U_T2 = T2_i x - w2_i,
// the 3x3 blocks from S^{-1} T2_j^T too, the cone law solved by nonsmooth Gauss–Seidel over
// contacts with each contact's exact local solve (solve_coulomb_cone, coulomb_cone.hpp), and
// x <- x + S^{-1} (L^T Lambda_N + T^T Lambda_T1 + T2^T Lambda_T2), Lambda_T2 into *tangential2.
struct FrictionalCorrection {
  const ContactRows& L;
  const ContactRows& T;
  const Contacts& contacts;  // mu and w (w2)
  std::function<const Vec&(Index)> normal_response, tangent_response;
  const ContactRows* T2;  // null: 2D contacts (the interval law)
  std::function<const Vec&(Index)> tangent2_response;
  Vec* tangential2;  // the impulses along T2 (size p), with T2
};
LcpResult frictional_correction(const FrictionalCorrection& c, const Vec& b, Vec& x, Vec& normal, Vec& tangential,
                                const std::vector<Index>& active, const LcpOptions& lcp, LcpStorage& storage,
                                Vec& mu_active);

struct NewtonOptions {
  double tolerance = 1e-10;
  long max_iterations = 25;
};

class ImplicitContact {
 public:
  // M must outlive this object (the integrator's mass_).
  void bind(const Problem& problem, const SpMat& M, const Vec& u0, WorkCounters& work, const LcpOptions& lcp,
            const NewtonOptions& newton, const char* who);
  // The step equation above; with_contact selects the LCP inside the Newton iteration
  // (mu, size p, is returned; zero without contact). info gets iterations and convergence.
  void solve_step(const Vec& u_hat, const Vec& f_ext, double c, bool with_contact, Vec& u, Vec& mu, StepInfo& info);
  // Corrects x on the contact set (fixed `active`, or grown from the violated rows when
  // `grow`): x += S^{-1} L^T mu, mu (size p, zero off the set) returned in `mu`.
  LcpResult correct(const Vec& b, Vec& x, Vec& mu, const std::vector<Index>& active, bool grow);
  // The frictional correction above on the fixed set `active` (the problem has friction),
  // iterations counted in work. 3D contacts (Contacts::has_cone): the cone law, Lambda_T2
  // into `tangential2` (size p), which 2D contacts leave untouched.
  LcpResult correct_with_friction(const Vec& b, Vec& x, Vec& normal, Vec& tangential, Vec& tangential2,
                                  const std::vector<Index>& active);
  // Moving contacts (Problem::contacts_move): the rows L, T, T2 the corrections use become
  // L(u), T(u), T2(u) (values refilled in their pattern, the cached responses dropped);
  // returns g(u). Only for a problem whose contacts move.
  const Vec& evaluate_contacts_at(ConstVecRef u);
  // The normal rows the corrections use (the construction's, or the last evaluate_contacts_at).
  const ContactRows& normal_rows() const { return L_; }

 private:
  const Vec& response(Index contact);
  const Vec& tangent_response(Index contact);
  const Vec& tangent2_response(Index contact);
  void factorize(double c);

  const Problem* problem_ = nullptr;
  const SpMat* M_ = nullptr;
  WorkCounters* work_ = nullptr;
  const char* who_ = "";
  LcpOptions lcp_;
  NewtonOptions newton_;
  SpMat K_;
  double c_factored_ = 0.0;
  Vec f_int_, r_, du_;
  ContactRows L_;
  SparseSum S_;
  SparseCholesky chol_;
  ContactResponses responses_;  // S^{-1} L_i^T
  CorrectionBuffers buffers_;
  ContactRows T_;                       // with friction
  ContactResponses tangent_responses_;  // S^{-1} T_i^T
  bool cone_ = false;                    // 3D contacts with friction
  ContactRows T2_;
  ContactResponses tangent2_responses_;  // S^{-1} T2_i^T
  Vec mu_active_;
  ContactGeometry geometry_;  // moving contacts: g, L, T, T2 at the last evaluate_contacts_at
};

// The Newton and LCP parameters (newton_tol, newton_max_iter, lcp_tol, lcp_max_iter) shared
// by the schemes, appended to their specs, and read back.
void add_implicit_contact_specs(ParamSpecs& specs);
NewtonOptions newton_options(const Params& params);

// Initial acceleration M A_0 = F_ext(t_0) - F_int(U_0) on the massive dofs; massless dofs
// (zero diagonal of a diagonal M) get 0: their acceleration never enters the schemes'
// equations, which see M A only. A non-diagonal M must be positive definite (InputError).
Vec initial_acceleration(const Problem& problem, const State& s, const SpMat& M, const char* who);

}  // namespace nsb
