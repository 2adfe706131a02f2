#pragma once
// The 3D Moreau–Coulomb contact law of one contact at velocity level: the cone (derivations in
// docs/three_d.md; J.J. Moreau, "Unilateral contact and dry friction in finite freedom
// dynamics", 1988; M. Jean, "The non-smooth contact dynamics method", CMAME 177, 1999; V. Acary
// and B. Brogliato, Numerical Methods for Nonsmooth Dynamical Systems, Springer 2008, ch. 12).
//
// One contact, normal row L and two tangent rows T1, T2; local Delassus block
// W = [L; T1; T2] S^{-1} [L; T1; T2]^T (3x3, symmetric positive definite), impulse
// Lambda = (Lambda_N, Lambda_T) with Lambda_T in R^2, local velocities after it
//     U = q + W Lambda      (q_N = g'_free + e g'_prev, q_T = T v_free - w_obstacle),
// and the law (the 2D one of solvers/coulomb.hpp with the interval become a disk)
//     0 <= Lambda_N  _|_  U_N >= 0,   |Lambda_T| <= mu Lambda_N,
//     |Lambda_T| < mu Lambda_N => U_T = 0,
//     |Lambda_T| = mu Lambda_N => Lambda_T = -mu Lambda_N U_T / |U_T|  (maximal dissipation).
// As for 2D, a contact with q_N >= 0 takes no impulse.
//
// solve_cone_isotropic: W = w I_3 (a node of equal mass in x, y, z on a flat obstacle: "diagonal
// and spherical per node"), closed form:
//     Lambda_N = -q_N / w,   Lambda_T = -q_T / w scaled onto the disk of radius mu Lambda_N
//     when longer (then U_T = q_T + w Lambda_T is -q_T's multiple, opposite to Lambda_T).
//
// solve_cone_local: any SPD W, to round-off. For a given Lambda_N = n the tangential law is the
// optimality condition of the convex problem
//     min_{|x| <= mu n}  x^T W_TT x / 2 + c^T x,      c = q_T + W_TN n,
// solved exactly: the unconstrained minimiser -W_TT^{-1} c if inside the disk (stick), else
// x(nu) = -(W_TT + nu I)^{-1} c with |x(nu)| = mu n, nu > 0 (then U_T = -nu x: slip opposite to
// Lambda_T), the secular equation 1 / |x(nu)| = 1 / (mu n) solved by Newton's method in the
// eigenbasis of W_TT (monotone convergence from nu = 0; Moré and Sorensen, "Computing a trust
// region step", SIAM J. Sci. Stat. Comput. 4, 1983). The normal impulse is the root of the
// scalar equation
//     h(n) = n - max(0, -(q_N + W_NT . x(n)) / W_NN) = 0
// located by the Illinois method on a bracket [0, n_hi] (h(0) < 0; h grows at least like
// (1 - mu |W_NT| / W_NN) n, so a root exists where mu |W_NT| < W_NN, as for 2D), to
// |n_hi - n_lo| <= tolerance n; both loops are capped (ConeOptions), allocation-free and
// fixed-size. Beyond mu |W_NT| < W_NN the law may have several solutions; the first bracketed
// is returned, converged = false when no bracket is found.
//
// solve_cone_decoupled: W = diag(w_n, w_t, w_t) (W_NT = 0, the tangent block isotropic: a
// rigid sphere on a plane, whose tangent rows carry the rotation), the same closed form with
// Lambda_N = -q_N / w_n and the trial -q_T / w_t; solve_cone_isotropic is its w_n = w_t case.
// solve_cone: one contact of any SPD block, the closed form where W has that shape (exactly:
// zero off-diagonal entries and equal tangent diagonal), solve_cone_local otherwise.
//
// solve_coulomb_cone: many contacts coupled through a full Delassus matrix D (3a x 3a, rows and
// columns ordered N_1, T1_1, T2_1, N_2, ...): nonsmooth Gauss–Seidel over contacts (Jean 1999),
// each contact solved by solve_cone against the others' latest impulses, warm-started from x,
// until a sweep changes no impulse by more than
//     r = max_i max(W_NN,i |dLambda_N,i|, W_T1T1,i |dLambda_T1,i|, W_T2T2,i |dLambda_T2,i|)
//         / max(max |q|, tiny)  <= tolerance
// (velocity units, relative: the 2D solve_coulomb's rule, coulomb.hpp). D block diagonal: one
// sweep is exact. A local solve that does not converge marks the result unconverged.
//
// cone_law_residual: the Alart–Curnier natural map, in velocity units relative to max |q|,
//     r = |(Lambda_N - max(0, Lambda_N - rho U_N),
//           Lambda_T - proj_{|.| <= mu Lambda_N}(Lambda_T - rho U_T))| / (rho max(|q|, tiny)),
// rho = 3 / trace(W): zero exactly when Lambda satisfies the law (for any rho > 0).
#include <Eigen/Core>

#include "solvers/lcp.hpp"

namespace nsb {

struct ConeImpulse {
  double normal = 0.0;
  Eigen::Vector2d tangential = Eigen::Vector2d::Zero();
};

struct ConeOptions {
  double tolerance = 1e-15;  // relative width of the bracket on Lambda_N
  int max_iterations = 200;  // each of the two loops
};

struct ConeSolve {
  ConeImpulse impulse;
  int iterations = 0;  // of the outer (normal) loop
  bool converged = true;
};

ConeImpulse solve_cone_isotropic(double w, const Eigen::Vector3d& q, double mu);
ConeImpulse solve_cone_decoupled(double w_n, double w_t, const Eigen::Vector3d& q, double mu);
ConeSolve solve_cone(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, const ConeOptions& options = {});

// D: 3a x 3a, q: 3a, mu: a; x (3a, interleaved N, T1, T2) in: warm start, out: the impulses.
LcpResult solve_coulomb_cone(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, Eigen::Ref<const Eigen::VectorXd> mu,
                             Eigen::VectorXd& x, const LcpOptions& options);

ConeSolve solve_cone_local(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu,
                           const ConeOptions& options = {});

double cone_law_residual(const Eigen::Matrix3d& W, const Eigen::Vector3d& q, double mu, const ConeImpulse& impulse);

}  // namespace nsb
