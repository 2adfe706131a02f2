// The field mesh contract (problems/problem.hpp, FieldMesh) on every registered problem: a
// problem with a body mesh describes points, dofs and cells consistently with ndof and
// writes its stresses without allocating; one without (point masses, rigid bodies) has none.
#include <catch2/catch.hpp>
#include <set>

#include "problems/registry.hpp"
#include "tests/support/allocation_counter.hpp"

namespace {

// The built-in problems built from a body mesh, and those without one (a point mass, rigid
// bodies, a spring chain).
const std::set<std::string> kMeshed = {"signorini-bar", "signorini-bar-steel", "bouncing-bar", "two-bars",
                                       "mass-on-bar",   "block-2d",            "two-blocks"};
const std::set<std::string> kUnmeshed = {"bouncing-mass", "ball-chain", "sliding-mass", "rolling-disk", "spring-chain"};

}  // namespace

TEST_CASE("field mesh: points, dofs and cells agree with ndof; stress written without allocating",
          "[problems][field-mesh]") {
  for (const auto& entry : nsb::problem_registry()) {
    const auto p = nsb::make_problem(entry.name);
    const auto mesh = p->field_mesh();
    INFO(entry.name);
    if (kUnmeshed.contains(entry.name)) CHECK_FALSE(mesh.has_value());
    if (kMeshed.contains(entry.name)) REQUIRE(mesh.has_value());
    if (!mesh) continue;
    const int dim = mesh->dimension;
    REQUIRE((dim == 1 || dim == 2));
    REQUIRE(mesh->points.cols() == 2);
    REQUIRE(mesh->point_dofs.rows() == mesh->npoints());
    REQUIRE(mesh->point_dofs.cols() == dim);
    REQUIRE(mesh->cells.cols() == (dim == 1 ? 2 : 4));
    REQUIRE(mesh->cell_body.size() == static_cast<std::size_t>(mesh->ncells()));
    REQUIRE(mesh->stress_components.size() == (dim == 1 ? 1u : 3u));
    // Every dof at most once, within [0, ndof); bars lie on y = 0.
    std::set<int> dofs;
    for (nsb::Index a = 0; a < mesh->npoints(); ++a)
      for (int k = 0; k < dim; ++k) {
        const int d = mesh->point_dofs(a, k);
        if (d < 0) continue;
        CHECK(d < p->ndof());
        CHECK(dofs.insert(d).second);
      }
    if (dim == 1) CHECK(mesh->points.col(1).isZero(0.0));
    // Cells: valid points; lines along +x, quads counter-clockwise (positive signed area).
    for (nsb::Index c = 0; c < mesh->ncells(); ++c) {
      for (int k = 0; k < mesh->cells.cols(); ++k) REQUIRE((mesh->cells(c, k) >= 0 && mesh->cells(c, k) < mesh->npoints()));
      double area = 0.0;
      if (dim == 1) {
        area = mesh->points(mesh->cells(c, 1), 0) - mesh->points(mesh->cells(c, 0), 0);
      } else {
        for (int k = 0; k < 4; ++k) {
          const auto a = mesh->points.row(mesh->cells(c, k)), b = mesh->points.row(mesh->cells(c, (k + 1) % 4));
          area += 0.5 * (a.x() * b.y() - b.x() * a.y());
        }
      }
      CHECK(area > 0.0);
    }
    // A state with every dof set: cell_stress fills every entry (NaN beforehand), allocating nothing.
    const nsb::Vec u = 1e-3 * nsb::Vec::LinSpaced(p->ndof(), -1.0, 1.0);
    Eigen::MatrixXd sigma = Eigen::MatrixXd::Constant(mesh->ncells(), dim == 1 ? 1 : 3, std::nan(""));
    long allocations = 0;
    {
      nsb::test::CountAllocations count;
      p->cell_stress(u, sigma);
      allocations = count.count();
    }
    CHECK(allocations == 0);
    CHECK(sigma.allFinite());
  }
}

TEST_CASE("field mesh: append shifts points and dofs, keeps fixed components fixed, sets the body",
          "[problems][field-mesh]") {
  nsb::FieldMesh a, b;
  a.dimension = b.dimension = 1;
  a.points = Eigen::MatrixXd::Zero(2, 2);
  a.points(1, 0) = 1.0;
  a.point_dofs = Eigen::MatrixXi::Zero(2, 1);
  a.point_dofs(1, 0) = 1;
  a.cells = Eigen::MatrixXi(1, 2);
  a.cells << 0, 1;
  a.cell_body = {0};
  b = a;
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
