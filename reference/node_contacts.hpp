#pragma once
// The contacts of a problem read as node-to-rigid contacts, as the event-driven references
// need them: each row i of the gap operator acts on a single dof d,
//     g_i = g0_i + a_i u_d = a_i (u_d - position_i),   position_i = -g0_i / a_i,
// and no two contacts act on one dof.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "problems/problem.hpp"

namespace nsb {

struct NodeContact {
  Index dof;
  double a;         // g = a (u_dof - position)
  double position;  // of the dof on the obstacle
};

// InputError, naming `integrator`, for a row of L on several dofs (or none) and for two rows
// on one dof.
inline std::vector<NodeContact> node_contacts(const Problem& problem, const std::string& integrator) {
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const RowMajor L = problem.gap_operator();
  const Vec& g0 = problem.gap_offset();
  std::vector<NodeContact> contacts;
  std::vector<char> used(static_cast<std::size_t>(problem.ndof()), 0);
  for (Index i = 0; i < L.rows(); ++i) {
    RowMajor::InnerIterator it(L, i);
    if (!it || it.value() == 0.0 || (++RowMajor::InnerIterator(it)))
      throw InputError(fmt::format("{}: contact {} must act on exactly one dof (node-to-rigid contact)", integrator, i));
    if (used[it.col()]++)
      throw InputError(fmt::format("{}: contacts share dof {}; valid: one contact per dof", integrator, it.col()));
    contacts.push_back({it.col(), it.value(), -g0[i] / it.value()});
  }
  return contacts;
}

}  // namespace nsb
