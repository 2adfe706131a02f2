// The rocking-block problem (problems/rocking_block.hpp): its moving contacts against finite
// differences, its initial state and exact solution, its bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "check/conformance.hpp"
#include "problems/registry.hpp"
#include "problems/rocking_block.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::Params;
using nsb::RockingBlock;

namespace {

RockingBlock make_rocking_block(const std::map<std::string, std::string>& set = {}) {
  return RockingBlock(Params(RockingBlock::parameters_spec(), set));
}

}  // namespace

TEST_CASE("rocking-block: g, L and T against central differences at random configurations", "[problems][rocking_block]") {
  const RockingBlock p = make_rocking_block();
  REQUIRE(p.contacts_move());
  nsb::ContactGeometry at = p.contact_geometry();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-1.4, 1.4), coordinate(-1.0, 1.0);
  for (int k = 0; k < 50; ++k) {
    const nsb::Vec u = nsb::Vec::NullaryExpr(3, [&] { return coordinate(rng); }) + nsb::Vec::Unit(3, 2) * angle(rng);
    p.evaluate_contacts(u, at);
    // The gap is the corner's height, independent of the problem's own formulas.
    const double c = std::cos(u[2]), s = std::sin(u[2]);
    CHECK(at.gap[0] == Approx(u[1] + 0.2 * s - 1.0 * c).margin(1e-15));
    CHECK(at.gap[1] == Approx(u[1] - 0.2 * s - 1.0 * c).margin(1e-15));
  }
  // L and T by nsbench check's test, around tilts across (-1.4, 1.4) rad, the block high
  // enough (y = 2) that every random configuration near it is admissible.
  for (const double theta : {-1.4, -0.7, 0.0, 0.3, 1.1, 1.4}) {
    const nsb::Vec u0 = (nsb::Vec(3) << 0.4, 2.0, theta).finished();
    const nsb::CheckVerdict v = nsb::check_contact_rows(p, u0);
    INFO("theta " << theta << ": " << v.figure);
    CHECK(v.outcome == nsb::CheckVerdict::Outcome::Pass);
    CHECK_THAT(v.figure, Catch::Contains("moving, 6 configurations"));
  }
}

TEST_CASE("rocking-block: contacts evaluated without allocating, in the pattern of contacts()", "[problems][rocking_block][allocation]") {
  const RockingBlock p = make_rocking_block();
  nsb::ContactGeometry at = p.contact_geometry();
  const nsb::Vec u = nsb::Vec::LinSpaced(3, 0.1, 0.4);
  const auto nonzeros = at.normal.nonZeros() + at.tangent.nonZeros();
  long allocations = 0;
  {
    nsb::test::CountAllocations count;
    p.evaluate_contacts(u, at);
    allocations = count.count();
  }
  CHECK(allocations == 0);
  CHECK(at.normal.nonZeros() + at.tangent.nonZeros() == nonzeros);
}

TEST_CASE("rocking-block: starts on its pivot, the linearised gap at U0 is g(U0), the exact solution starts there", "[problems][rocking_block]") {
  for (const char* theta0 : {"0.1", "-0.1"}) {
    const RockingBlock p = make_rocking_block({{"theta0", theta0}});
    const nsb::State s0 = p.initial_state();
    nsb::ContactGeometry at = p.contact_geometry();
    p.evaluate_contacts(s0.u, at);
    const double pivot = std::min(at.gap[0], at.gap[1]), other = std::max(at.gap[0], at.gap[1]);
    CHECK(std::abs(pivot) <= 1e-15);
    CHECK(other == Approx(2 * 0.2 * std::sin(0.1)).epsilon(1e-13));
    const nsb::Vec linear = p.contacts().gap_offset + p.contacts().normal * s0.u;
    CHECK((linear - at.gap).cwiseAbs().maxCoeff() <= 1e-15);
    // The exact solution: pivot's velocity zero at t = 0 (no slip, no lift-off).
    CHECK((at.normal * s0.v).cwiseAbs().minCoeff() <= 1e-15);
    CHECK(p.impact_times(10.0).size() > 3);
    const auto ex = p.state(p.impact_times(10.0).front());
    REQUIRE(ex);
    CHECK(std::abs(ex->u[2]) <= 1e-12);  // the first impact at theta = 0
  }
}

TEST_CASE("rocking-block: observables theta, omega, omega_exact", "[problems][rocking_block]") {
  const RockingBlock p = make_rocking_block();
  REQUIRE(p.observable_names() == std::vector<std::string>{"theta", "omega", "omega_exact"});
  const nsb::State s = *p.state(0.3);
  double out[3];
  p.observe(s, nsb::Vec(), 0.0, out);
  CHECK(out[0] == s.u[2]);
  CHECK(out[1] == s.v[2]);
  CHECK(out[2] == s.v[2]);
  CHECK(out[1] < 0.0);  // falling back toward theta = 0
}

TEST_CASE("rocking-block: bad input, one line naming the parameter and its range", "[problems][rocking_block]") {
  using nsb::test::input_error_text_of;
  const auto error = [](const std::map<std::string, std::string>& set) {
    return input_error_text_of([&] { nsb::make_problem("rocking-block", set); });
  };
  CHECK_THAT(error({{"b", "0"}}), Catch::Contains("b") && Catch::Contains("(0, inf)"));
  CHECK_THAT(error({{"h", "-1"}}), Catch::Contains("h") && Catch::Contains("(0, inf)"));
  CHECK_THAT(error({{"mu", "-0.1"}}), Catch::Contains("mu") && Catch::Contains("[0, inf)"));
  CHECK_THAT(error({{"theta0", "1.6"}}), Catch::Contains("theta0"));  // a corner in the floor
  CHECK_THAT(error({{"e", "1.5"}}), Catch::Contains("e") && Catch::Contains("[0, 1]"));
  for (const char* key : {"b", "mu", "theta0"}) {
    const std::string why = error({{key, std::string(key) == "theta0" ? "1.6" : "-0.1"}});
    CHECK(!why.empty());
    CHECK(why.find('\n') == std::string::npos);
  }
}
