#include "problems/problem.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

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

int FieldMesh::cell_size(Index c) const {
  int k = 0;
  while (k < cells.cols() && cells(c, k) >= 0) ++k;
  return k;
}

Index FieldMesh::nelements() const {
  Index n = 0;
  for (Index c = 0; c < ncells(); ++c) n += cell_size(c) >= 2;
  return n;
}

int FieldMesh::body_columns() const {
  int n = 0;
  for (const FieldArray& a : body_arrays) n += a.components;
  return n;
}

void FieldMesh::append(const FieldMesh& part, Index dof_offset, int body) {
  if (!body_rotation_dofs.empty() || !part.body_rotation_dofs.empty()) {  // -1 for the bodies that do not turn
    body_rotation_dofs.resize(static_cast<std::size_t>(nbodies()), -1);
    for (Index b = 0; b < part.nbodies(); ++b) {
      const int r = part.body_rotation_dofs.empty() ? -1 : part.body_rotation_dofs[static_cast<std::size_t>(b)];
      body_rotation_dofs.push_back(r < 0 ? -1 : r + static_cast<int>(dof_offset));
    }
  }
  const Index p0 = npoints(), c0 = ncells(), width = std::max(cells.cols(), part.cells.cols());
  points.conservativeResize(p0 + part.npoints(), part.points.cols());
  points.bottomRows(part.npoints()) = part.points;
  point_dofs.conservativeResize(p0 + part.npoints(), dimension);
  point_dofs.bottomRows(part.npoints()) =
      (part.point_dofs.array() < 0).select(-1, part.point_dofs.array() + static_cast<int>(dof_offset));
  // Widening pads the earlier cells with -1 (conservativeResize leaves new entries unset).
  const Index old_width = cells.cols();
  cells.conservativeResize(c0 + part.ncells(), width);
  cells.topRightCorner(c0, width - old_width).setConstant(-1);
  cells.bottomRows(part.ncells()).setConstant(-1);
  cells.bottomLeftCorner(part.ncells(), part.cells.cols()) =
      (part.cells.array() < 0).select(-1, part.cells.array() + static_cast<int>(p0));
  cell_body.resize(static_cast<std::size_t>(c0 + part.ncells()), body);
}

void FieldMesh::add_vertex(double x, double y, std::initializer_list<int> dofs, int body) {
  if (static_cast<int>(dofs.size()) != dimension)
    throw std::logic_error(fmt::format("FieldMesh::add_vertex: {} dofs for a mesh of dimension {}", dofs.size(), dimension));
  FieldMesh vertex;
  vertex.dimension = dimension;
  vertex.points = Eigen::RowVector2d(x, y);
  vertex.point_dofs = Eigen::Map<const Eigen::RowVectorXi>(dofs.begin(), static_cast<Index>(dofs.size()));
  vertex.cells = Eigen::MatrixXi::Zero(1, 1);
  append(vertex, 0, body);
}

void Contacts::set_friction(SpMat tangent_rows, double mu_all, double w_all) {
  tangent = std::move(tangent_rows);
  tangent.makeCompressed();
  mu = Vec::Constant(tangent.rows(), mu_all);
  tangent_velocity = Vec::Constant(tangent.rows(), w_all);
}

void Contacts::set_cone(SpMat tangent_rows, SpMat tangent2_rows, double mu_all) {
  set_friction(std::move(tangent_rows), mu_all, 0.0);
  tangent2 = std::move(tangent2_rows);
  tangent2.makeCompressed();
  tangent2_velocity = Vec::Zero(tangent2.rows());
}

void Problem::evaluate_contacts(ConstVecRef u, ContactGeometry& out) const {
  const Contacts& c = contacts();
  out.gap.noalias() = c.normal * u;
  out.gap += c.gap_offset;
}

void Problem::contact_slide(ConstVecRef u, VecRef s) const { s.noalias() = contacts().tangent * u; }
void Problem::contact_slide2(ConstVecRef u, VecRef s2) const { s2.noalias() = contacts().tangent2 * u; }

ContactGeometry Problem::contact_geometry() const {
  const Contacts& c = contacts();
  ContactGeometry out{c.gap_offset, c.normal, c.tangent, c.tangent2};
  out.normal.makeCompressed();
  out.tangent.makeCompressed();
  out.tangent2.makeCompressed();
  return out;
}

void check_contacts(const Contacts& c, Index ndof, const std::string& problem) {
  const auto fail = [&](const std::string& why) { throw InputError(fmt::format("problem {}: contacts: {}", problem, why)); };
  const Index p = c.normal.rows();
  if (c.normal.cols() != ndof) fail(fmt::format("L has {} columns, expected ndof = {}", c.normal.cols(), ndof));
  if (c.gap_offset.size() != p) fail(fmt::format("g0 has {} entries, expected one per contact ({})", c.gap_offset.size(), p));
  if (!(c.restitution >= 0.0 && c.restitution <= 1.0)) fail(fmt::format("restitution {} outside [0, 1]", c.restitution));
  const bool frictionless = c.tangent.rows() == 0 && c.mu.size() == 0 && c.tangent_velocity.size() == 0;
  if (frictionless) {
    if (c.tangent2.rows() > 0 || c.tangent2_velocity.size() > 0) fail("T2 given without T, mu and w (a 3D contact has both tangent rows)");
    return;
  }
  if (c.tangent.rows() != p || c.tangent.cols() != ndof)
    fail(fmt::format("T is {} x {}, expected {} x {} (one tangent row per contact)", c.tangent.rows(), c.tangent.cols(), p, ndof));
  if (c.mu.size() != p || c.tangent_velocity.size() != p)
    fail(fmt::format("mu and w need one entry per contact ({}); they have {} and {}", p, c.mu.size(), c.tangent_velocity.size()));
  for (Index i = 0; i < p; ++i) {
    if (!(c.mu[i] >= 0.0) || !std::isfinite(c.mu[i])) fail(fmt::format("mu of contact {} is {}; valid: finite, >= 0", i, c.mu[i]));
    if (!std::isfinite(c.tangent_velocity[i])) fail(fmt::format("w of contact {} is {}; valid: finite", i, c.tangent_velocity[i]));
  }
  if (c.tangent2.rows() == 0 && c.tangent2_velocity.size() == 0) return;
  if (c.tangent2.rows() != p || c.tangent2.cols() != ndof)
    fail(fmt::format("T2 is {} x {}, expected {} x {} (3D contacts: a second tangent row per contact)", c.tangent2.rows(),
                     c.tangent2.cols(), p, ndof));
  if (c.tangent2_velocity.size() != p)
    fail(fmt::format("w2 needs one entry per contact ({}); it has {}", p, c.tangent2_velocity.size()));
  for (Index i = 0; i < p; ++i)
    if (!std::isfinite(c.tangent2_velocity[i])) fail(fmt::format("w2 of contact {} is {}; valid: finite", i, c.tangent2_velocity[i]));
}

void check_problem_contract(const Problem& problem, const SpMat& mass, const State& initial) {
  const auto fail = [&](const std::string& why, const std::string& valid) {
    throw InputError(fmt::format("problem {}: {}; valid: {} (the problem contract, problems/problem.hpp)", problem.name(), why, valid));
  };
  const double largest = mass.nonZeros() ? Eigen::Map<const Vec>(mass.valuePtr(), mass.nonZeros()).cwiseAbs().maxCoeff() : 0.0;
  for (Index i = 0; i < mass.rows() && i < mass.cols(); ++i)
    if (const double d = mass.coeff(i, i); !(d >= 0.0) || !std::isfinite(d))
      fail(fmt::format("mass_matrix() has {} on its diagonal at dof {}", d, i), "finite, >= 0 (0: a massless dof)");
  const SpMat asymmetry = mass - SpMat(mass.transpose());
  if (asymmetry.nonZeros() &&
      Eigen::Map<const Vec>(asymmetry.valuePtr(), asymmetry.nonZeros()).cwiseAbs().maxCoeff() > 1e-12 * largest)
    fail("mass_matrix() is not symmetric", "M = M^T");
  ContactGeometry at = problem.contact_geometry();
  if (at.gap.size() == 0 || initial.u.size() != problem.ndof()) return;
  problem.evaluate_contacts(initial.u, at);
  const Vec& g0 = problem.gap_offset();
  for (Index i = 0; i < at.gap.size(); ++i)
    if (!(at.gap[i] >= -1e-9 * (1.0 + std::abs(g0[i]))))
      fail(fmt::format("contact {} is closed at the initial state (gap {:g})", i, at.gap[i]), "initial gaps >= 0");
}

}  // namespace nsb
