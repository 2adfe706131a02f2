#pragma once
// Contact impulses of an explicit step with a diagonal mass (CD-Lagrange family):
//
//     on contacts closed at the new position (g_i <= 0):
//     0 <= Lambda  _|_  g'_free + H Lambda + e g'_prev >= 0,   H = L M^{-1} L^T
//     v  <-  v_free + M^{-1} L^T Lambda
//
// H diagonal (node-to-rigid contacts on distinct dofs): closed form per contact,
// Lambda_i = max(0, -(g'_free,i + e g'_prev,i) / H_ii), no allocation. Otherwise an LCP on
// the closed contacts (projected Gauss-Seidel, lcp.hpp).
// A contact with H_ii = 0 acts on massless dofs only (minv zero there): it has no impulse
// law and is skipped here; the caller solves it quasi-statically (cd_lagrange.hpp).
//
// With Coulomb friction (Contacts::mu > 0 somewhere, docs/method.md section 6) each closed
// contact takes (Lambda_N, Lambda_T) from the 2D Moreau–Coulomb law (coulomb.hpp) with
// q_N = g'_free + e g'_prev, q_T = T v_free - w and W = [L; T] M^{-1} [L; T]^T:
//     v  <-  v_free + M^{-1} (L^T Lambda_N + T^T Lambda_T).
// Contacts that share no dof with another (W block diagonal): each in closed form, still
// explicit and allocation-free; otherwise nonsmooth Gauss–Seidel over the closed contacts.
// The frictionless path is the one above, untouched.
//
// Moving contacts (Problem::contacts_move): apply() evaluates the gaps and rows at the new
// position u (g(u), L(u), T(u): CD-Lagrange's step 3, contacts at U_{k+1}) and H, W from
// those rows, then the same laws: g'_free, g'_prev, the slip and the impulses all along the
// rows at u. Which contacts may be coupled is decided from the rows' pattern (the worst case
// over configurations); the products are formed only where the step reads them: the diagonal
// blocks of the contacts closed at u, and the pairs of closed contacts whose rows' nonzero
// entries share a dof (each row's nonzeros gathered once per step, on storage sized once);
// with friction the closed contacts' rates and impulses also run over those nonzeros.
// Constant kinematics: the rows and H of the construction, as before.
#include "solvers/coulomb.hpp"
#include "integrators/integrator.hpp"
#include "solvers/lcp.hpp"

namespace nsb {

// A_i M^{-1} B_j^T for rows i of A and j of B (row-major, sorted columns), M^{-1} = diag(minv).
double weighted_row_dot(const RowSpMat& A, Index i, const RowSpMat& B, Index j, const Vec& minv);

class ImpulseContact {
 public:
  ImpulseContact() = default;
  ImpulseContact(const Problem& problem, const Vec& minv, LcpOptions lcp);

  // u: new position; v_prev: velocity before the step (for restitution); v: in, the free
  // velocity, out, the velocity after the impulses; impulses, tangential: out (size p; the
  // tangential ones stay zero without friction). Returns the LCP iterations (0 for a
  // diagonal H); counts unconverged LCPs in `work`.
  long apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, VecRef tangential, StepInfo& info,
             WorkCounters& work);
  // The same with restitution e instead of the problem's (e = 0: the velocity-level
  // constraint g' >= 0 of a closed contact, as d1_minus_linear.hpp needs).
  long apply(ConstVecRef u, ConstVecRef v_prev, VecRef v, VecRef impulses, VecRef tangential, StepInfo& info,
             WorkCounters& work, double e);

 private:
  long apply_with_friction(ConstVecRef v_prev, VecRef v, VecRef impulses, VecRef tangential, StepInfo& info,
                           WorkCounters& work, double e);
  // v += M^{-1} (L_i^T n + T_i^T t)
  void add_impulse(Index i, double n, double t, VecRef v) const;
  // Contact i is closed at the new position and has a mass to act on (a contact on massless
  // dofs only carries no impulse: the quasi-static treatment holds it).
  bool is_closed(Index i) const { return offset_[i] + rows_.gap[i] <= 0.0 && h_diag_[i] != 0.0; }
  // Fills closed_ with the closed contacts, in order; returns how many.
  Index collect_closed();
  // Moving contacts: rows_ at u, and h_diag_, w_nt_, w_tt_ of the contacts closed at u.
  void evaluate_at(ConstVecRef u);
  // Moving contacts: h_full_ (w_full_) between the closed contacts of closed_.
  void couple_closed();
  // Row i's nonzero L and T entries at u, gathered into entries_ (moving contacts).
  void gather(Index i);
  // L_i M^{-1} L_j^T, L_i M^{-1} T_j^T, T_i M^{-1} L_j^T, T_i M^{-1} T_j^T from the gathered rows.
  struct Products {
    double nn = 0.0, nt = 0.0, tn = 0.0, tt = 0.0;
  };
  Products products(Index i, Index j) const;

  const Problem* problem_ = nullptr;
  Vec minv_;
  LcpOptions lcp_;
  bool moving_ = false;
  // L (normal), T (tangent) and the gap at the new position: L u (constant kinematics, the
  // offset g0 apart) or g(u) (moving contacts, offset 0).
  ContactGeometry rows_;
  Vec offset_;
  Vec h_diag_;
  bool h_is_diagonal_ = true;
  Eigen::MatrixXd h_full_;  // H, when it is not diagonal
  std::vector<Index> closed_;  // the closed contacts of the step, when H is not diagonal
  LcpStorage storage_;         // D, q, x per size (friction: 2 rows per contact)

  // Friction: T, mu, w, the local 2x2 blocks (w_nn = h_diag_), and the full interleaved
  // [L; T] M^{-1} [L; T]^T when contacts share dofs.
  bool friction_ = false;
  bool friction_coupled_ = false;
  Vec mu_, w_, w_nt_, w_tt_;
  Eigen::MatrixXd w_full_;
  Vec mu_closed_;

  // Moving contacts: row i's nonzero (column, L value, T value) at u, in column order, in
  // entries_[entries_begin_[i], entries_end_[i]); capacity the row's pattern in L and T.
  struct RowEntry {
    Index col;
    double l, t;
  };
  std::vector<RowEntry> entries_;
  std::vector<Index> entries_begin_, entries_end_;
  const RowEntry* gathered_begin(Index i) const { return entries_.data() + entries_begin_[static_cast<std::size_t>(i)]; }
  const RowEntry* gathered_end(Index i) const { return entries_.data() + entries_end_[static_cast<std::size_t>(i)]; }
};

}  // namespace nsb
