// ContactGaps (problems/contact_gaps.hpp): g0 + L U for constant kinematics, the problem's
// own g(U) where contacts move, +inf as the least gap without contacts.
#include <catch2/catch.hpp>

#include <limits>

#include "problems/contact_gaps.hpp"
#include "problems/registry.hpp"

TEST_CASE("contact gaps: g0 + L u, the moving gaps themselves, none without contacts", "[problems][contacts]") {
  const auto bar = nsb::make_problem("signorini-bar", {{"N", "8"}});
  nsb::ContactGaps bar_gaps(*bar);
  const nsb::Vec u = nsb::Vec::LinSpaced(bar->ndof(), -0.3, 0.2);
  const nsb::Vec expected = bar->gap_offset() + bar->gap_operator() * u;
  CHECK(bar_gaps.at(u) == expected);
  CHECK(bar_gaps.min_at(u) == expected.minCoeff());

  const auto block = nsb::make_problem("rocking-block");
  REQUIRE(block->contacts_move());
  nsb::ContactGaps block_gaps(*block);
  nsb::Vec q = block->initial_state().u;
  q[2] += 0.3;  // turned: the linearisation at U0 is no longer the gap
  nsb::ContactGeometry geometry = block->contact_geometry();
  block->evaluate_contacts(q, geometry);
  CHECK(block_gaps.at(q) == geometry.gap);
  CHECK(block_gaps.min_at(q) != Approx((block->gap_offset() + block->gap_operator() * q).minCoeff()));

  const auto chain = nsb::make_problem("spring-chain", {{"wall", "none"}});
  REQUIRE(chain->ncontacts() == 0);
  CHECK(nsb::ContactGaps(*chain).min_at(chain->initial_state().u) == std::numeric_limits<double>::infinity());
}
