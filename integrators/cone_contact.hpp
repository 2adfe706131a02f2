#pragma once
// Contact impulses of an explicit step with a diagonal mass on 3D contacts (the Coulomb cone,
// Contacts::has_cone; docs/three_d.md): ImpulseContact's law (impulse_contact.hpp) with the
// tangential interval become a disk. On the contacts closed at the new position (g_i <= 0)
// and with a mass to act on (W_NN,i > 0):
//
//     q_i = (L_i v_free + e L_i v_prev,  T_i v_free - w_i,  T2_i v_free - w2_i)
//     W_ij = [L_i; T_i; T2_i] M^{-1} [L_j; T_j; T2_j]^T           (3x3 blocks)
//     Lambda_i = (Lambda_N, Lambda_T) from the cone law (coulomb_cone.hpp) with U = q + W Lambda
//     v  <-  v_free + M^{-1} (L^T Lambda_N + T^T Lambda_T1 + T2^T Lambda_T2)
//
// Contacts that share no dof (W block diagonal): each contact on its own, by solve_cone:
// closed form where its block is diagonal with equal tangent entries (W = w I_3, the talk's
// "diagonal and spherical per node", or diag(w_n, w_t, w_t), a rigid sphere: projection of
// -q_T / w_t onto the disk of radius mu Lambda_N), the exact local solve otherwise
// (trust-region disk step and Illinois on Lambda_N, to 1e-15 relative). Contacts that share a
// dof: nonsmooth Gauss–Seidel over the closed contacts (solve_coulomb_cone, to lcp_tol). The
// blocks are formed at each step from the rows (a few sparse products per closed contact), so
// moving contacts (Problem::contacts_move) take their rows at the new position u, as
// ImpulseContact does; which contacts share a dof is decided once from the rows' pattern.
// No tangential restitution.
#include <vector>

#include "integrators/impulse_contact.hpp"
#include "integrators/integrator.hpp"
#include "solvers/coulomb_cone.hpp"
#include "solvers/lcp.hpp"

namespace nsb {

class ConeContact {
 public:
  ConeContact() = default;
  ConeContact(const Problem& problem, const Vec& minv, LcpOptions lcp);

  // u: new position; v_prev: velocity before the step (restitution); v: in, the free velocity,
  // out, the velocity after the impulses; normal, tangential, tangential2: out (size p).
  // Returns the Gauss–Seidel sweeps (0 for contacts that share no dof); counts an unconverged
  // solve in `work` and info.
  long apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef normal, VecRef tangential, VecRef tangential2,
             StepInfo& info, WorkCounters& work);
  // The same with restitution e instead of the problem's (e = 0: the velocity-level
  // constraint g' >= 0 of a closed contact, as d1_minus_linear.hpp needs).
  long apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef normal, VecRef tangential, VecRef tangential2,
             StepInfo& info, WorkCounters& work, double e);

 private:
  // Row k (0: L, 1: T, 2: T2) of contact i.
  const RowSpMat& rows_of(int k) const { return k == 0 ? rows_.normal : k == 1 ? rows_.tangent : rows_.tangent2; }
  double row_dot(int k, Index i, ConstVecRef x) const;
  double weighted_dot(int k, Index i, int l, Index j) const;  // row k of i . M^{-1} row l of j
  Eigen::Matrix3d block(Index i, Index j) const;
  Eigen::Vector3d free_velocity(Index i, ConstVecRef v_prev, ConstVecRef v, double e) const;
  void add_impulse(Index i, const Eigen::Vector3d& lambda, VecRef v) const;

  const Problem* problem_ = nullptr;
  Vec minv_;
  LcpOptions lcp_;
  bool moving_ = false;
  bool coupled_ = false;  // two contacts share a dof
  double e_ = 0.0;
  ContactGeometry rows_;
  Vec offset_, mu_, w1_, w2_, mu_closed_;
  std::vector<Index> closed_;
  LcpStorage storage_;  // D, q, x of the coupled contacts, per size
};

}  // namespace nsb
