// The field mesh contract (problems/problem.hpp, FieldMesh) on every registered problem:
// each describes its bodies (points, dofs and cells consistently with ndof, every point in a
// cell) and writes its elements' stresses and its bodies' arrays without allocating.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "problems/registry.hpp"
#include "tests/support/allocation_counter.hpp"

TEST_CASE("field mesh: points, dofs and cells agree with ndof; stress and body arrays written without allocating",
          "[problems][field-mesh]") {
  for (const auto& entry : nsb::problem_registry()) {
    const auto p = nsb::make_problem(entry.name);
    const auto mesh = p->field_mesh();
    INFO(entry.name);
    REQUIRE(mesh.has_value());  // every built-in problem can be watched
    const int dim = mesh->dimension;
    REQUIRE((dim >= 1 && dim <= 3));
    REQUIRE(mesh->points.cols() == (dim == 3 ? 3 : 2));
    REQUIRE(mesh->point_dofs.rows() == mesh->npoints());
    REQUIRE(mesh->point_dofs.cols() == dim);
    REQUIRE(mesh->cell_body.size() == static_cast<std::size_t>(mesh->ncells()));
    REQUIRE(mesh->ncells() > 0);
    // Stress components exactly when there are elements (1: a bar's or spring's; 3: plane; 6: solid).
    if (mesh->nelements() > 0) REQUIRE(mesh->stress_components.size() == (dim == 1 ? 1u : dim == 2 ? 3u : 6u));
    // Every dof at most once, within [0, ndof); 1D meshes lie on y = 0.
    std::set<int> dofs;
    for (nsb::Index a = 0; a < mesh->npoints(); ++a)
      for (int k = 0; k < dim; ++k) {
        const int d = mesh->point_dofs(a, k);
        if (d < 0) continue;
        CHECK(d < p->ndof());
        CHECK(dofs.insert(d).second);
      }
    if (dim == 1) CHECK(mesh->points.col(1).isZero(0.0));
    // Cells: 1, 2, 4 or 8 valid points then -1 padding; lines along +x, quads counter-clockwise
    // (positive signed area), hexahedra in VTK's order (edges 0-1, 0-3, 0-4 right-handed); a
    // quad only in 2D, a hexahedron only in 3D; every point in some cell (else invisible).
    std::vector<bool> used(static_cast<std::size_t>(mesh->npoints()), false);
    for (nsb::Index c = 0; c < mesh->ncells(); ++c) {
      const int n = mesh->cell_size(c);
      REQUIRE((n == 1 || n == 2 || (n == 4 && dim == 2) || (n == 8 && dim == 3)));
      for (int k = 0; k < mesh->cells.cols(); ++k) {
        const int a = mesh->cells(c, k);
        if (k >= n) {
          CHECK(a == -1);
          continue;
        }
        REQUIRE((a >= 0 && a < mesh->npoints()));
        used[static_cast<std::size_t>(a)] = true;
      }
      double area = 0.0;
      if (n == 2) {
        area = mesh->points(mesh->cells(c, 1), 0) - mesh->points(mesh->cells(c, 0), 0);
      } else if (n == 4) {
        for (int k = 0; k < 4; ++k) {
          const auto a = mesh->points.row(mesh->cells(c, k)), b = mesh->points.row(mesh->cells(c, (k + 1) % 4));
          area += 0.5 * (a.x() * b.y() - b.x() * a.y());
        }
      } else if (n == 8) {
        const auto corner = [&](int k) { return Eigen::Vector3d(mesh->points.row(mesh->cells(c, k)).transpose()); };
        area = (corner(1) - corner(0)).cross(corner(3) - corner(0)).dot(corner(4) - corner(0));
      }
      if (n > 1) CHECK(area > 0.0);
    }
    CHECK(std::count(used.begin(), used.end(), false) == 0);
    // A state with every dof set: cell_stress and body_data fill every entry (NaN
    // beforehand), allocating nothing.
    nsb::State s;
    s.u = 1e-3 * nsb::Vec::LinSpaced(p->ndof(), -1.0, 1.0);
    s.v = nsb::Vec::LinSpaced(p->ndof(), 1.0, 2.0);
    Eigen::MatrixXd sigma = Eigen::MatrixXd::Constant(mesh->nelements(), static_cast<nsb::Index>(mesh->stress_components.size()),
                                                      std::nan(""));
    Eigen::MatrixXd body = Eigen::MatrixXd::Constant(mesh->nbodies(), mesh->body_columns(), std::nan(""));
    long allocations = 0;
    {
      nsb::test::CountAllocations count;
      if (sigma.size() > 0) p->cell_stress(s.u, sigma);
      if (body.size() > 0) p->body_data(s, body);
      allocations = count.count();
    }
    CHECK(allocations == 0);
    CHECK(sigma.allFinite());
    CHECK(body.allFinite());
  }
}

namespace {

// One bar element from x = 0 (dof 0) to x = 1 (dof 1), body 0.
nsb::FieldMesh one_element_bar() {
  nsb::FieldMesh bar;
  bar.dimension = 1;
  bar.points = Eigen::MatrixXd::Zero(2, 2);
  bar.points(1, 0) = 1.0;
  bar.point_dofs = Eigen::MatrixXi::Zero(2, 1);
  bar.point_dofs(1, 0) = 1;
  bar.cells = Eigen::MatrixXi(1, 2);
  bar.cells << 0, 1;
  bar.cell_body = {0};
  return bar;
}

}  // namespace

TEST_CASE("field mesh: append shifts points and dofs, keeps fixed components fixed, sets the body",
          "[problems][field-mesh]") {
  nsb::FieldMesh a = one_element_bar(), b = a;
  b.point_dofs(1, 0) = -1;
  a.append(b, 5, 3);
  CHECK(a.npoints() == 4);
  CHECK(a.ncells() == 2);
  CHECK(a.point_dofs(2, 0) == 5);
  CHECK(a.point_dofs(3, 0) == -1);
  CHECK(a.cells(1, 0) == 2);
  CHECK(a.cells(1, 1) == 3);
  CHECK(a.cell_body == std::vector<int>{0, 3});
}

TEST_CASE("field mesh: append carries the turning bodies' rotation dofs, shifted, -1 for the bodies that do not turn",
          "[problems][field-mesh]") {
  // A 3D body's centre: one vertex, its translation on dofs 0..2 and its rotation dofs from 3 (or none).
  const auto centre = [](std::vector<int> rotation_dofs) {
    nsb::FieldMesh m;
    m.dimension = 3;
    m.points = Eigen::RowVector3d(0.0, 0.0, 1.0);
    m.point_dofs = Eigen::RowVector3i(0, 1, 2);
    m.cells = Eigen::MatrixXi::Zero(1, 1);
    m.cell_body = {0};
    m.body_rotation_dofs = std::move(rotation_dofs);
    return m;
  };
  nsb::FieldMesh turning = centre({3});
  turning.append(centre({3}), 6, 1);
  CHECK(turning.body_rotation_dofs == std::vector<int>{3, 9});
  turning.append(centre({}), 12, 2);
  CHECK(turning.body_rotation_dofs == std::vector<int>{3, 9, -1});
  nsb::FieldMesh still = centre({});
  still.append(centre({3}), 3, 1);
  CHECK(still.body_rotation_dofs == std::vector<int>{-1, 6});
  nsb::FieldMesh none = centre({});
  none.append(centre({}), 3, 1);
  CHECK(none.body_rotation_dofs.empty());
}

TEST_CASE("field mesh: cells of mixed sizes are padded with -1; a vertex appended to lines, lines to a vertex",
          "[problems][field-mesh]") {
  nsb::FieldMesh m;
  m.dimension = 1;
  m.add_vertex(-1.0, 0.0, {4}, 2);
  CHECK(m.cells.cols() == 1);
  m.append(one_element_bar(), 0, 0);  // widens the vertex's row
  m.add_vertex(3.0, 0.0, {-1}, 1);
  REQUIRE(m.ncells() == 3);
  REQUIRE(m.cells.cols() == 2);
  CHECK(m.cells.row(0) == Eigen::RowVector2i(0, -1));
  CHECK(m.cells.row(1) == Eigen::RowVector2i(1, 2));
  CHECK(m.cells.row(2) == Eigen::RowVector2i(3, -1));
  CHECK(m.cell_size(0) == 1);
  CHECK(m.cell_size(1) == 2);
  CHECK(m.nelements() == 1);
  CHECK(m.nbodies() == 2);
  CHECK(m.point_dofs(0, 0) == 4);
  CHECK(m.point_dofs(3, 0) == -1);
  CHECK(m.cell_body == std::vector<int>{2, 0, 1});
  m.body_arrays = {{"a", 1}, {"b", 3}};
  CHECK(m.body_columns() == 4);
  CHECK_THROWS_AS(m.add_vertex(0.0, 0.0, {0, 1}, 0), std::logic_error);  // 2 dofs in a 1D mesh
}
