// The painleve-rod problem (problems/painleve_rod.hpp): its moving contact against finite
// differences, its initial state on the floor, its bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <random>
#include <string>

#include "check/conformance.hpp"
#include "problems/painleve_rod.hpp"
#include "problems/registry.hpp"
#include "tests/support/allocation_counter.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::PainleveRod;
using nsb::Params;

TEST_CASE("painleve-rod: g, L and T against central differences at random configurations", "[problems][painleve_rod]") {
  const PainleveRod p(Params(PainleveRod::parameters_spec()));
  REQUIRE(p.contacts_move());
  nsb::ContactGeometry at = p.contact_geometry();
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> coordinate(-1.5, 1.5);
  for (int k = 0; k < 50; ++k) {
    const nsb::Vec u = nsb::Vec::NullaryExpr(3, [&] { return coordinate(rng); });
    p.evaluate_contacts(u, at);
    CHECK(at.gap[0] == Approx(u[1] - std::sin(u[2])).margin(1e-15));  // A's height, s = 1
  }
  // L and T by nsbench check's test, around angles across (-1.5, 1.5) rad, the rod high
  // enough (y = 1.5) that every random configuration near it is admissible.
  for (const double phi : {-1.5, -0.6, 0.0, 0.54, 1.2, 1.5}) {
    const nsb::Vec u0 = (nsb::Vec(3) << -0.3, 1.5, phi).finished();
    const nsb::CheckVerdict v = nsb::check_contact_rows(p, u0);
    INFO("phi " << phi << ": " << v.figure);
    CHECK(v.outcome == nsb::CheckVerdict::Outcome::Pass);
    CHECK_THAT(v.figure, Catch::Contains("moving, 6 configurations"));
  }
  const nsb::Vec u = nsb::Vec::Constant(3, 0.3);
  long allocations = 0;
  {
    nsb::test::CountAllocations count;
    p.evaluate_contacts(u, at);
    allocations = count.count();
  }
  CHECK(allocations == 0);
}

TEST_CASE("painleve-rod: starts sliding with A on the floor; the exact phase ends in the jam at 0.8145 s", "[problems][painleve_rod]") {
  const PainleveRod p(Params(PainleveRod::parameters_spec()));
  const nsb::State s0 = p.initial_state();
  nsb::ContactGeometry at = p.contact_geometry();
  p.evaluate_contacts(s0.u, at);
  CHECK(std::abs(at.gap[0]) <= 1e-15);
  CHECK(s0.u[2] == Approx(31.0 * std::acos(-1.0) / 180.0).epsilon(1e-15));
  CHECK(s0.v[0] == 30.0);
  CHECK((p.contacts().gap_offset + p.contacts().normal * s0.u - at.gap).cwiseAbs().maxCoeff() <= 1e-15);
  CHECK(p.closed_form().ending() == nsb::PainleveRodExact::Ending::jam);
  CHECK(p.closed_form().end_time() == Approx(0.814549658670072).epsilon(1e-12));
  CHECK_FALSE(p.state(0.83));  // nothing after the jam
  double out[4];
  p.observe(*p.state(0.4), nsb::Vec(), 0.0, out);
  CHECK(out[3] == Approx(10.349291121638).epsilon(1e-9));  // docs/rigid_bodies.md section 3
  CHECK(out[1] == Approx(11.511835856683).epsilon(1e-9));
}

TEST_CASE("painleve-rod: bad input, one line naming the parameter", "[problems][painleve_rod]") {
  const auto error = [](const std::map<std::string, std::string>& set) {
    return nsb::test::input_error_text_of([&] { nsb::make_problem("painleve-rod", set); });
  };
  CHECK_THAT(error({{"s", "0"}}), Catch::Contains("s") && Catch::Contains("(0, inf)"));
  CHECK_THAT(error({{"mu", "-1"}}), Catch::Contains("mu") && Catch::Contains("[0, inf)"));
  CHECK_THAT(error({{"phi0", "95"}}), Catch::Contains("phi0"));
  CHECK_THAT(error({{"v0", "0"}}), Catch::Contains("v0"));
  CHECK_THAT(error({{"phi0", "50"}}), Catch::Contains("phi0"));  // D(phi0) < 0: the paradox at the start
  for (const char* key : {"s", "phi0", "v0"}) {
    const std::string why = error({{key, std::string(key) == "phi0" ? "50" : "0"}});
    CHECK(!why.empty());
    CHECK(why.find('\n') == std::string::npos);
  }
}
