// Snapshots of a deformed mesh: corners moved by the displacement, the contact impulses as
// vectors at the contact nodes, and the four instants in time order.
#include <catch2/catch.hpp>

#include "problems/block_2d.hpp"
#include "studies/snapshots.hpp"

TEST_CASE("snapshots: deformed corners, impulses at the nodes, instants", "[studies][snapshots]") {
  const nsb::Block2d block(nsb::Params(nsb::Block2d::parameters_spec(), {{"nx", "2"}, {"ny", "1"}}));
  const nsb::FieldMesh mesh = block.field_mesh().value();
  nsb::MeshSnapshots pictures(block, "sigma_yy");
  nsb::State s = block.initial_state();
  pictures.add(s, nsb::Vec(), nsb::Vec());
  // A rigid translation by (0.1, -0.2): no stress; then one contact impulse of 3 N s.
  for (nsb::Index a = 0; a < mesh.npoints(); ++a) {
    s.u[mesh.point_dofs(a, 0)] += 0.1;
    s.u[mesh.point_dofs(a, 1)] -= 0.2;
  }
  s.t = 0.5;
  nsb::Vec normal = nsb::Vec::Zero(block.contacts().size());
  pictures.add(s, normal, nsb::Vec());
  normal[0] = 3.0;
  s.t = 1.0;
  pictures.add(s, normal, nsb::Vec());
  const nsb::Json all = pictures.finish();
  // In time order; no strain energy ever (a translation): the largest is the first step's.
  REQUIRE(all.size() == 4);
  CHECK(all[0]["instant"] == "initial");
  CHECK(all[1]["instant"] == "largest compression");
  CHECK(all[1]["t"] == 0.5);
  CHECK(all[2]["instant"] == "first contact");
  CHECK(all[2]["t"] == 1.0);
  CHECK(all[3]["instant"] == "end");
  const nsb::Json& end = all[3];
  REQUIRE(end["corners"].size() == 8 * static_cast<std::size_t>(mesh.ncells()));
  for (nsb::Index e = 0; e < mesh.ncells(); ++e)
    for (nsb::Index j = 0; j < 4; ++j) {
      const nsb::Index a = mesh.cells(e, j);
      CHECK(end["corners"][8 * e + 2 * j].get<double>() == Approx(mesh.points(a, 0) + 0.1));
      CHECK(end["corners"][8 * e + 2 * j + 1].get<double>() == Approx(mesh.points(a, 1) - 0.2));
      CHECK(std::abs(end["stress"][e].get<double>()) < 1e-6);
    }
  // One arrow, at the node of contact 0 (deformed position), the 3 N s upwards (the block's
  // normal rows are +1 on a node's y dof).
  const nsb::Vec f = block.contacts().normal.transpose() * normal;
  REQUIRE(end["arrows"].size() == 4);
  int found = 0;
  for (nsb::Index a = 0; a < mesh.npoints(); ++a)
    if (f[mesh.point_dofs(a, 1)] != 0.0) {
      ++found;
      CHECK(end["arrows"][0].get<double>() == Approx(mesh.points(a, 0) + 0.1));
      CHECK(end["arrows"][1].get<double>() == Approx(mesh.points(a, 1) - 0.2));
    }
  CHECK(found == 1);
  CHECK(end["arrows"][2].get<double>() == 0.0);
  CHECK(end["arrows"][3].get<double>() == 3.0);
  CHECK(all[0]["arrows"].empty());
  CHECK_THROWS_AS(nsb::MeshSnapshots(block, "no-such-component"), std::logic_error);
}
