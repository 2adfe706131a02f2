#pragma once
// The 2D Moreau–Coulomb contact law at velocity level (docs/method.md section 6; J.J. Moreau,
// "Unilateral contact and dry friction in finite freedom dynamics", 1988; M. Jean, "The
// non-smooth contact dynamics method", CMAME 177, 1999; V. Acary and B. Brogliato,
// Numerical Methods for Nonsmooth Dynamical Systems, Springer 2008, ch. 3 and 12).
//
// One contact, local Delassus operator W = [L; T] S^{-1} [L; T]^T (2x2, S the scheme's
// iteration matrix), local velocities after the impulse (Lambda_N, Lambda_T)
//
//     U_N = q_N + W_NN Lambda_N + W_NT Lambda_T     (q_N = g'_free + e g'_prev)
//     U_T = q_T + W_NT Lambda_N + W_TT Lambda_T     (q_T = T v_free - w)
//
//     0 <= Lambda_N  _|_  U_N >= 0,   |Lambda_T| <= mu Lambda_N,
//     |Lambda_T| < mu Lambda_N => U_T = 0,   |Lambda_T| = mu Lambda_N => U_T Lambda_T <= 0.
//
// solve_coulomb_local: the exact solution, by enumeration of the four cases (separate,
// stick, slip with U_T > 0, slip with U_T < 0), first the one that holds. Decoupled
// (W_NT = 0: a lumped node on a rigid obstacle, a disk on a floor) this is the closed form
//     Lambda_N = max(0, -q_N / W_NN),  Lambda_T = clamp(-q_T / W_TT, -mu Lambda_N, mu Lambda_N).
// For W_NT != 0 and mu |W_NT| < W_NN (always so for the moderate mu of a positive definite W:
// |W_NT| < sqrt(W_NN W_TT)) exactly one slip case is consistent with the sign tests; beyond,
// the law can have several solutions and the first found is returned.
//
// solve_coulomb: many contacts coupled through a full Delassus matrix D (rows and columns
// ordered N_1, T_1, N_2, T_2, ...): nonsmooth Gauss–Seidel over contacts (Jean 1999), each
// contact solved exactly by solve_coulomb_local against the others' latest impulses,
// warm-started from x, until a sweep changes no impulse by more than
//     r = max_i max(W_NN,i |dLambda_N,i|, W_TT,i |dLambda_T,i|) / max(max |q|, tiny)
// (velocity units, relative, as the frictionless LCP's residual in lcp.hpp) <= tolerance.
#include <Eigen/Core>

#include "solvers/lcp.hpp"

namespace nsb {

struct CoulombImpulse {
  double normal = 0.0;
  double tangential = 0.0;
};

// True when D has a nonzero entry outside its diagonal blocks of size `block` (the contacts
// are coupled: Gauss–Seidel sweeps until they settle; otherwise one sweep is exact).
bool couples_blocks(const Eigen::MatrixXd& D, Eigen::Index block);

CoulombImpulse solve_coulomb_local(double w_nn, double w_nt, double w_tt, double q_n, double q_t, double mu);

// D: 2a x 2a, q: 2a, mu: a; x (2a, interleaved N, T) in: warm start, out: the impulses.
LcpResult solve_coulomb(const Eigen::MatrixXd& D, const Eigen::VectorXd& q, Eigen::Ref<const Eigen::VectorXd> mu,
                        Eigen::VectorXd& x, const LcpOptions& options);

}  // namespace nsb
