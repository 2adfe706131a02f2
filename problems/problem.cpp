#include "problems/problem.hpp"

#include <fmt/format.h>

#include <cmath>

namespace nsb {

std::optional<Vec> diagonal_mass(const SpMat& M) {
  Vec d = Vec::Zero(M.rows());
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SpMat::InnerIterator it(M, j); it; ++it) {
      if (it.row() != it.col()) {
        if (it.value() != 0.0) return std::nullopt;
      } else {
        d[it.row()] = it.value();
      }
    }
  return d;
}

void FieldMesh::append(const FieldMesh& part, Index dof_offset, int body) {
  const Index p0 = npoints(), c0 = ncells();
  points.conservativeResize(p0 + part.npoints(), 2);
  points.bottomRows(part.npoints()) = part.points;
  point_dofs.conservativeResize(p0 + part.npoints(), dimension);
  point_dofs.bottomRows(part.npoints()) =
      (part.point_dofs.array() < 0).select(-1, part.point_dofs.array() + static_cast<int>(dof_offset));
  cells.conservativeResize(c0 + part.ncells(), part.cells.cols());
  cells.bottomRows(part.ncells()) = part.cells.array() + static_cast<int>(p0);
  cell_body.resize(static_cast<std::size_t>(c0 + part.ncells()), body);
}

void Contacts::set_friction(SpMat tangent_rows, double mu_all, double w_all) {
  tangent = std::move(tangent_rows);
  tangent.makeCompressed();
  mu = Vec::Constant(tangent.rows(), mu_all);
  tangent_velocity = Vec::Constant(tangent.rows(), w_all);
}

void check_contacts(const Contacts& c, Index ndof, const std::string& problem) {
  const auto fail = [&](const std::string& why) { throw InputError(fmt::format("problem {}: contacts: {}", problem, why)); };
  const Index p = c.normal.rows();
  if (c.normal.cols() != ndof) fail(fmt::format("L has {} columns, expected ndof = {}", c.normal.cols(), ndof));
  if (c.gap_offset.size() != p) fail(fmt::format("g0 has {} entries, expected one per contact ({})", c.gap_offset.size(), p));
  if (!(c.restitution >= 0.0 && c.restitution <= 1.0)) fail(fmt::format("restitution {} outside [0, 1]", c.restitution));
  const bool frictionless = c.tangent.rows() == 0 && c.mu.size() == 0 && c.tangent_velocity.size() == 0;
  if (frictionless) return;
  if (c.tangent.rows() != p || c.tangent.cols() != ndof)
    fail(fmt::format("T is {} x {}, expected {} x {} (one tangent row per contact)", c.tangent.rows(), c.tangent.cols(), p, ndof));
  if (c.mu.size() != p || c.tangent_velocity.size() != p)
    fail(fmt::format("mu and w need one entry per contact ({}); they have {} and {}", p, c.mu.size(), c.tangent_velocity.size()));
  for (Index i = 0; i < p; ++i) {
    if (!(c.mu[i] >= 0.0) || !std::isfinite(c.mu[i])) fail(fmt::format("mu of contact {} is {}; valid: finite, >= 0", i, c.mu[i]));
    if (!std::isfinite(c.tangent_velocity[i])) fail(fmt::format("w of contact {} is {}; valid: finite", i, c.tangent_velocity[i]));
  }
}

}  // namespace nsb
