#pragma once
// The contacts of a problem read as node-to-rigid contacts, as the event-driven references
// need them: each row i of the gap operator acts on a single dof d,
//     g_i = g0_i + a_i u_d = a_i (u_d - position_i),   position_i = -g0_i / a_i,
// and no two contacts act on one dof.
#include <vector>

#include "core/parameters.hpp"
#include "problems/problem.hpp"

namespace nsb {

struct NodeContact {
  Index dof;
  double a;         // g = a (u_dof - position)
  double position;  // of the dof on the obstacle
};

// The node contacts of a problem whose contacts are node-to-rigid (checked when the integrator
// binds the problem: Capabilities::node_to_rigid_only).
inline std::vector<NodeContact> node_contacts(const Problem& problem) {
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const RowMajor L = problem.gap_operator();
  const Vec& g0 = problem.gap_offset();
  std::vector<NodeContact> contacts;
  for (Index i = 0; i < L.rows(); ++i) {
    RowMajor::InnerIterator it(L, i);
    while (it.value() == 0.0) ++it;  // node-to-rigid: one non-zero in the row
    contacts.push_back({it.col(), it.value(), -g0[i] / it.value()});
  }
  return contacts;
}

}  // namespace nsb
