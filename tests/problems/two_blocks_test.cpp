// two-blocks: the contact rows (floor and node-to-segment) are what the header says, a
// rigid translation of both blocks leaves the inter-body gaps unchanged, the assembled
// operators are the blocks' (F_int sums to zero, K is the gradient of F_int), the
// observables total both blocks, and bad placements and meshes are refused. Large sliding:
// g, L, T against central differences (check/conformance.cpp's test), the rows at the flat
// placement are small sliding's, a node changing segment keeps its gap and shifts its row's
// pattern, the evaluation allocates nothing.
#include <catch2/catch.hpp>
#include <cmath>

#include "check/conformance.hpp"
#include "problems/registry.hpp"
#include "problems/two_blocks.hpp"
#include "tests/support/allocation_counter.hpp"

using Catch::Detail::Approx;

namespace {

nsb::TwoBlocks blocks(std::map<std::string, std::string> overrides = {}) {
  return nsb::TwoBlocks(nsb::Params(nsb::TwoBlocks::parameters_spec(), overrides));
}

nsb::Vec noise(nsb::Index n, double amplitude, unsigned seed) {
  std::srand(seed);
  return amplitude * nsb::Vec::Random(n);
}

// The rows of the node-to-segment contacts.
nsb::Vec between_gaps(const nsb::TwoBlocks& b, const nsb::Vec& u) {
  const nsb::Vec g = b.gap_offset() + b.gap_operator() * u;
  return g.tail(b.ncontacts() - b.floor_contacts());
}

}  // namespace

TEST_CASE("two-blocks: contact rows: the floors as block-2d, node-to-segment rows interpolate the lower top edge",
          "[problems][two-blocks]") {
  const auto b = blocks({{"upper_gap", "0.05"}, {"lower_height", "0.02"}});
  const nsb::Index nl = b.lower_dofs();
  REQUIRE(b.ndof() == b.lower().ndof() + b.upper().ndof());
  REQUIRE(b.floor_contacts() == b.lower().ncontacts() + b.upper().ncontacts());
  const nsb::Index nts = b.upper().parameters().integer("nx") + 1;
  REQUIRE(b.ncontacts() == b.floor_contacts() + nts);
  const nsb::Vec u0 = nsb::Vec::Zero(b.ndof());
  // At t = 0 every node-to-segment gap is upper_gap (flat faces).
  CHECK((between_gaps(b, u0).array() - 0.05).abs().maxCoeff() <= 1e-14);
  // Each row: +1 on one upper y dof, weights summing to -1 on lower y dofs of one top segment,
  // interpolating the reference abscissa.
  const Eigen::MatrixXd L(b.gap_operator());
  for (nsb::Index r = b.floor_contacts(); r < b.ncontacts(); ++r) {
    double upper_sum = 0.0, lower_sum = 0.0, x_interp = 0.0, x_node = 0.0;
    int lower_entries = 0;
    for (nsb::Index j = 0; j < b.ndof(); ++j) {
      if (L(r, j) == 0.0) continue;
      REQUIRE(j % 2 == 1);  // y dofs only
      if (j >= nl) {
        upper_sum += L(r, j);
        x_node = b.upper().reference_position((j - nl) / 2).x();
      } else {
        lower_sum += L(r, j);
        x_interp -= L(r, j) * b.lower().reference_position(j / 2).x();
        ++lower_entries;
        CHECK(b.lower().reference_position(j / 2).y() == Approx(0.32));  // the top edge
      }
    }
    CHECK(upper_sum == 1.0);
    CHECK(lower_sum == Approx(-1.0).epsilon(1e-15));
    CHECK(lower_entries >= 1);
    CHECK(lower_entries <= 2);
    CHECK(x_interp == Approx(x_node).margin(1e-14));
  }
  // Floor rows: g0 = reference height of the node.
  CHECK(b.gap_offset().head(b.lower().ncontacts()).minCoeff() == Approx(0.02));
}

TEST_CASE("two-blocks: a rigid translation of both blocks leaves the inter-body gaps unchanged; a relative one "
          "changes them by it",
          "[problems][two-blocks]") {
  const auto b = blocks();
  const nsb::Vec u = noise(b.ndof(), 1e-3, 3);
  nsb::Vec shifted = u, lifted = u;
  for (nsb::Index a = 0; a < b.ndof() / 2; ++a) {
    shifted[2 * a] += 0.01;
    shifted[2 * a + 1] += -0.7;
  }
  for (nsb::Index j = b.lower_dofs() + 1; j < b.ndof(); j += 2) lifted[j] += 0.03;
  CHECK((between_gaps(b, shifted) - between_gaps(b, u)).cwiseAbs().maxCoeff() <= 1e-15);
  CHECK((between_gaps(b, lifted) - between_gaps(b, u)).array().abs().isApproxToConstant(0.03, 1e-12));
}

TEST_CASE("two-blocks: F_int sums to zero over each direction and K is its gradient (central differences)",
          "[problems][two-blocks]") {
  for (const char* material : {"svk", "neo-hookean"}) {
    SECTION(material) {
      const auto b = blocks({{"lower_material", material}, {"upper_material", material}, {"upper_nx", "4"},
                             {"lower_nx", "3"}, {"upper_W", "0.6"}});
      const nsb::Vec u = noise(b.ndof(), 4e-3, 5);
      nsb::Vec f(b.ndof());
      b.internal_force(u, f);
      const double scale = f.cwiseAbs().maxCoeff();
      REQUIRE(scale > 1e2);
      double fx = 0.0, fy = 0.0;
      for (nsb::Index a = 0; a < b.ndof() / 2; ++a) {
        fx += f[2 * a];
        fy += f[2 * a + 1];
      }
      CHECK(std::abs(fx) <= 1e-12 * scale * b.ndof());
      CHECK(std::abs(fy) <= 1e-12 * scale * b.ndof());
      // The blocks' own forces, each on its own dofs.
      nsb::Vec fl(b.lower_dofs());
      b.lower().internal_force(u.head(b.lower_dofs()), fl);
      CHECK(f.head(b.lower_dofs()) == fl);

      nsb::SpMat K;
      b.tangent_stiffness(u, K);
      REQUIRE(K.rows() == b.ndof());
      const Eigen::MatrixXd Kd(K);
      // Truncation (eps/l)^2 |K| and rounding eps_mach |f| / eps, as block_2d_test.cpp.
      const double eps = 1e-6;
      double worst = 0.0;
      for (nsb::Index j = 0; j < b.ndof(); ++j) {
        nsb::Vec up = u, um = u, fp(b.ndof()), fm(b.ndof());
        up[j] += eps;
        um[j] -= eps;
        b.internal_force(up, fp);
        b.internal_force(um, fm);
        worst = std::max(worst, ((fp - fm) / (2 * eps) - Kd.col(j)).cwiseAbs().maxCoeff());
      }
      CHECK(worst <= 1e-5 * Kd.cwiseAbs().maxCoeff());
      // No coupling between the blocks in K.
      CHECK(Kd.topRightCorner(b.lower_dofs(), b.ndof() - b.lower_dofs()).cwiseAbs().maxCoeff() == 0.0);
      // A refill keeps the pattern and gives the same values.
      const nsb::Vec u2 = noise(b.ndof(), 4e-3, 6);
      const auto* values = K.valuePtr();
      b.tangent_stiffness(u2, K);
      CHECK(K.valuePtr() == values);
      nsb::SpMat K2;
      b.tangent_stiffness(u2, K2);
      CHECK(Eigen::MatrixXd(K) == Eigen::MatrixXd(K2));
    }
  }
}

TEST_CASE("two-blocks: energies, mass and observables total both blocks", "[problems][two-blocks]") {
  const auto b = blocks({{"upper_vx", "0.3"}, {"lower_spin", "0.5"}});
  const nsb::State s0 = b.initial_state();
  const nsb::Vec u = noise(b.ndof(), 1e-3, 7);
  const nsb::Index nl = b.lower_dofs(), nu = b.ndof() - nl;
  CHECK(b.strain_energy(u) == Approx(b.lower().strain_energy(u.head(nl)) + b.upper().strain_energy(u.tail(nu))));
  CHECK(b.load_potential(u) == Approx(b.lower().load_potential(u.head(nl)) + b.upper().load_potential(u.tail(nu))));
  CHECK(b.stable_step() == std::min(b.lower().stable_step(), b.upper().stable_step()));
  const auto names = b.observable_names();
  REQUIRE(names == std::vector<std::string>{"strain_energy", "gravity_energy", "px", "py", "angular_momentum",
                                            "closed_contacts", "closed_between"});
  std::vector<double> out(names.size());
  b.observe(s0, nsb::Vec(), 0.0, out);
  const double mu_total = b.upper().lumped_mass().sum() / 2;
  CHECK(out[2] == Approx(0.3 * mu_total));
  CHECK(out[3] == Approx(-1.0 * mu_total));
  // The lower block rests on the floor: its bottom nodes (lower_nx + 1) touch; nothing else.
  CHECK(out[5] == b.lower().parameters().integer("nx") + 1);
  CHECK(out[6] == 0.0);
  // Upper block pressed onto the lower top: every node-to-segment contact closed.
  nsb::State s = s0;
  for (nsb::Index j = nl + 1; j < b.ndof(); j += 2) s.u[j] = -0.06;
  b.observe(s, nsb::Vec(), 0.0, out);
  CHECK(out[6] == b.upper().parameters().integer("nx") + 1);
}

TEST_CASE("two-blocks: friction rows: the x components with the same weights", "[problems][two-blocks]") {
  const auto b = blocks({{"mu", "0.3"}});
  const auto& c = b.contacts();
  REQUIRE(c.has_friction());
  REQUIRE(c.tangent.rows() == b.ncontacts());
  const Eigen::MatrixXd L(c.normal), T(c.tangent);
  for (nsb::Index r = 0; r < b.ncontacts(); ++r)
    for (nsb::Index a = 0; a < b.ndof() / 2; ++a) {
      CHECK(T(r, 2 * a) == L(r, 2 * a + 1));
      CHECK(T(r, 2 * a + 1) == 0.0);
    }
  CHECK(c.mu.isConstant(0.3));
  CHECK(!blocks().contacts().has_friction());
}

TEST_CASE("two-blocks: bad input names the parameter and its range", "[problems][two-blocks][bad-input]") {
  CHECK_THROWS_WITH(nsb::make_problem("two-blocks", {{"upper_gap", "-0.01"}}), Catch::Contains("upper_gap"));
  CHECK_THROWS_WITH(nsb::make_problem("two-blocks", {{"upper_W", "1.5"}}),
                    Catch::Contains("upper_W") && Catch::Contains("(0, lower_W = 1]"));
  CHECK_THROWS_WITH(nsb::make_problem("two-blocks", {{"upper_nx", "2"}}),
                    Catch::Contains("upper_nx") && Catch::Contains("upper_nx >= 3"));
  CHECK_THROWS_AS(nsb::make_problem("two-blocks", {{"lower_height", "-1"}}), nsb::InputError);
  CHECK_NOTHROW(nsb::make_problem("two-blocks", {{"upper_nx", "3"}}));
}

TEST_CASE("two-blocks: field mesh is the lower block's then the upper block's (dofs shifted), stress per block",
          "[problems][two-blocks][field-mesh]") {
  const auto p = blocks();
  const auto mesh = p.field_mesh();
  const auto lower = p.lower().field_mesh(), upper = p.upper().field_mesh();
  REQUIRE(mesh.has_value());
  REQUIRE(mesh->npoints() == lower->npoints() + upper->npoints());
  REQUIRE(mesh->ncells() == lower->ncells() + upper->ncells());
  const nsb::Index pl = lower->npoints(), cl = lower->ncells();
  CHECK(mesh->point_dofs.topRows(pl) == lower->point_dofs);
  CHECK(mesh->point_dofs.bottomRows(upper->npoints()) == (upper->point_dofs.array() + int(p.lower_dofs())).matrix());
  CHECK(mesh->cells.bottomRows(upper->ncells()) == (upper->cells.array() + int(pl)).matrix());
  CHECK(mesh->points.bottomRows(upper->npoints()) == upper->points);
  for (nsb::Index c = 0; c < mesh->ncells(); ++c) CHECK(mesh->cell_body[c] == (c < cl ? 0 : 1));
  // Each block's part of the stress is that block's own cell stress.
  const nsb::Vec u = 1e-3 * nsb::Vec::LinSpaced(p.ndof(), -1.0, 2.0);
  Eigen::MatrixXd sigma(mesh->ncells(), 3), sl(cl, 3), su(upper->ncells(), 3);
  p.cell_stress(u, sigma);
  p.lower().cell_stress(u.head(p.lower_dofs()), sl);
  p.upper().cell_stress(u.tail(p.ndof() - p.lower_dofs()), su);
  CHECK(sigma.topRows(cl) == sl);
  CHECK(sigma.bottomRows(su.rows()) == su);
  CHECK(sl.cwiseAbs().maxCoeff() > 0.0);
}

namespace {

// The upper block translated by (dx, dy) on top of u.
nsb::Vec upper_moved(const nsb::TwoBlocks& b, nsb::Vec u, double dx, double dy) {
  for (nsb::Index j = b.lower_dofs(); j < b.ndof(); j += 2) {
    u[j] += dx;
    u[j + 1] += dy;
  }
  return u;
}

// First node of the lower block's top edge.
nsb::Index top_edge(const nsb::TwoBlocks& b) {
  return (b.lower().parameters().integer("nx") + 1) * b.lower().parameters().integer("ny");
}

// The columns of row r holding a nonzero value.
std::vector<nsb::Index> nonzero_columns(const nsb::RowSpMat& rows, nsb::Index r) {
  std::vector<nsb::Index> cols;
  for (nsb::RowSpMat::InnerIterator it(rows, r); it; ++it)
    if (it.value() != 0.0) cols.push_back(it.col());
  return cols;
}

}  // namespace

TEST_CASE("two-blocks, large sliding: g, L and T against central differences (nsbench check's test), over the edge "
          "and past its end",
          "[problems][two-blocks][large-sliding]") {
  // Blocks apart, so that check_contact_rows' random configurations (every dof moved by up
  // to 0.05 (1 + max|u0|)) are admissible: they kink the top edge and move every node.
  const auto b = blocks({{"sliding", "large"}, {"mu", "0.3"}, {"lower_height", "0.2"}, {"upper_gap", "0.15"}});
  REQUIRE(b.contacts_move());
  // 0.3: the upper block's last bottom node (x = 0.55) past the lower block's end (x = 0.5).
  for (const double shift : {0.0, 0.13, 0.3}) {
    const nsb::Vec u0 = upper_moved(b, nsb::Vec::Zero(b.ndof()), shift, 0.0);
    const nsb::CheckVerdict v = nsb::check_contact_rows(b, u0);
    INFO("upper block shifted by " << shift << ": " << v.figure);
    CHECK(v.outcome == nsb::CheckVerdict::Outcome::Pass);
    CHECK_THAT(v.figure, Catch::Contains("moving, 6 configurations"));
  }
  const nsb::Index last = b.upper().parameters().integer("nx");
  const auto past = b.segment_contact(upper_moved(b, nsb::Vec::Zero(b.ndof()), 0.3, 0.0), last);
  CHECK(past.xi > 1.0);
  CHECK(past.gap == Approx(std::hypot(0.05, 0.15)).epsilon(1e-14));  // the distance to the corner (0.5, 0.3 + 0.2)
}

TEST_CASE("two-blocks, large sliding: at the flat placement the rows and gaps are small sliding's",
          "[problems][two-blocks][large-sliding]") {
  const std::map<std::string, std::string> set = {{"mu", "0.3"}, {"upper_gap", "0"}};
  auto with_large = set;
  with_large["sliding"] = "large";
  const auto small = blocks(set), large = blocks(with_large);
  CHECK(!small.contacts_move());
  CHECK(nsb::TwoBlocks::parameters_spec().back().default_value == "small");
  const Eigen::MatrixXd dL = Eigen::MatrixXd(small.gap_operator()) - Eigen::MatrixXd(large.gap_operator());
  const Eigen::MatrixXd dT = Eigen::MatrixXd(small.contacts().tangent) - Eigen::MatrixXd(large.contacts().tangent);
  CHECK(dL.cwiseAbs().maxCoeff() <= 1e-15);
  CHECK(dT.cwiseAbs().maxCoeff() <= 1e-15);
  CHECK((small.gap_offset() - large.gap_offset()).cwiseAbs().maxCoeff() <= 1e-15);
  // Away from it, small sliding is its linear rows and large sliding is not.
  const nsb::Vec u = upper_moved(small, noise(small.ndof(), 1e-3, 5), 0.15, 0.0);
  nsb::ContactGeometry gs = small.contact_geometry(), gl = large.contact_geometry();
  small.evaluate_contacts(u, gs);
  large.evaluate_contacts(u, gl);
  CHECK((gs.gap - (small.gap_offset() + small.gap_operator() * u)).cwiseAbs().maxCoeff() <= 1e-15);
  CHECK((gl.gap - gs.gap).head(large.floor_contacts()).cwiseAbs().maxCoeff() <= 1e-15);
  CHECK((gl.gap - gs.gap).tail(large.ncontacts() - large.floor_contacts()).cwiseAbs().maxCoeff() >= 1e-4);
}

TEST_CASE("two-blocks, large sliding: a node crossing a segment boundary keeps its gap while its row's pattern "
          "shifts by one node",
          "[problems][two-blocks][large-sliding]") {
  const auto b = blocks({{"sliding", "large"}, {"mu", "0.3"}});
  const nsb::Index top0 = top_edge(b), k = 3, r = b.floor_contacts() + k;
  // A kink at the top edge's node 2 (x = -0.1): node 3 raised by 0.05, so the boundary
  // between segments 1 and 2 is the bisector there, leaning left, not the vertical.
  nsb::Vec kinked = nsb::Vec::Zero(b.ndof());
  kinked[2 * (top0 + 3) + 1] = 0.05;
  // Node 3 of the upper block (x = -0.036) on segment 2; moved left, it crosses onto segment 1.
  double lo = 0.0, hi = 0.15;
  REQUIRE(b.segment_contact(upper_moved(b, kinked, -lo, 0.0), k).segment == 2);
  REQUIRE(b.segment_contact(upper_moved(b, kinked, -hi, 0.0), k).segment == 1);
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (b.segment_contact(upper_moved(b, kinked, -mid, 0.0), k).segment == 2 ? lo : hi) = mid;
  }
  const nsb::Vec before = upper_moved(b, kinked, -lo, 0.0), after = upper_moved(b, kinked, -hi, 0.0);
  nsb::ContactGeometry at_before = b.contact_geometry(), at_after = b.contact_geometry();
  b.evaluate_contacts(before, at_before);
  b.evaluate_contacts(after, at_after);
  INFO("boundary crossed at dx = " << -lo << ", gaps " << at_before.gap[r] << " and " << at_after.gap[r]);
  CHECK(lo > 0.068);  // past the vertical through the vertex (dx = -0.064): the bisector leans
  CHECK(std::abs(at_before.gap[r] - at_after.gap[r]) <= 1e-14);
  // The lower block's nodes in the row: segment 2's ends (2, 3) before, segment 1's (1, 2) after.
  const auto lower_nodes = [&](const nsb::RowSpMat& rows) {
    std::vector<nsb::Index> nodes;
    for (const nsb::Index col : nonzero_columns(rows, r))
      if (col < b.lower_dofs() && (nodes.empty() || nodes.back() != col / 2)) nodes.push_back(col / 2);
    return nodes;
  };
  CHECK(lower_nodes(at_before.normal) == std::vector<nsb::Index>{top0 + 2, top0 + 3});
  CHECK(lower_nodes(at_after.normal) == std::vector<nsb::Index>{top0 + 1, top0 + 2});
  CHECK(lower_nodes(at_before.tangent) == std::vector<nsb::Index>{top0 + 2, top0 + 3});
  CHECK(lower_nodes(at_after.tangent) == std::vector<nsb::Index>{top0 + 1, top0 + 2});
  // The storage keeps its pattern: every top-edge node and the node, in both.
  CHECK(at_before.normal.nonZeros() == b.contact_geometry().normal.nonZeros());
  CHECK(at_after.tangent.nonZeros() == b.contact_geometry().tangent.nonZeros());
}

TEST_CASE("two-blocks, large sliding: contacts evaluated without allocating", "[problems][two-blocks][large-sliding][allocation]") {
  const auto b = blocks({{"sliding", "large"}, {"mu", "0.3"}});
  nsb::ContactGeometry at = b.contact_geometry();
  const nsb::Vec u = upper_moved(b, noise(b.ndof(), 1e-3, 9), 0.2, -0.05);
  long allocations = 0;
  {
    nsb::test::CountAllocations count;
    b.evaluate_contacts(u, at);
    allocations = count.count();
  }
  CHECK(allocations == 0);
  CHECK(at.gap.tail(b.ncontacts() - b.floor_contacts()).minCoeff() < 0.0);  // moved into the lower block
}
