#include <catch2/catch.hpp>

#include "core/parameters.hpp"

using nsb::InputError;
using nsb::ParamSpec;
using nsb::Params;

namespace {
const nsb::ParamSpecs specs = {
    ParamSpec::real("e", 0.5, 0.0, 1.0, "restitution"),
    ParamSpec::real("dt", 1e-3, 0.0, 1e308, "step", true),
    ParamSpec::integer("n", 10, 1, 1000, "elements"),
    ParamSpec::choice("mass", "lumped", {"lumped", "singular"}, "mass model"),
};

std::string error_of(const std::map<std::string, std::string>& overrides) {
  try {
    Params p(specs, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST_CASE("parameters: defaults and overrides are read back typed", "[core]") {
  Params p(specs, {{"e", "0.25"}, {"n", "20"}, {"mass", "singular"}});
  CHECK(p.real("e") == 0.25);
  CHECK(p.real("dt") == 1e-3);
  CHECK(p.integer("n") == 20);
  CHECK(p.choice("mass") == "singular");
}

TEST_CASE("parameters: bad values name the parameter and the valid range", "[core][bad-input]") {
  CHECK(error_of({{"e", "1.5"}}) == "parameter 'e' = 1.5 is outside its valid range [0, 1]");
  CHECK(error_of({{"dt", "0"}}) == "parameter 'dt' = 0 is outside its valid range (0, inf)");
  CHECK(error_of({{"e", "abc"}}) == "parameter 'e' = 'abc' is not a finite number; valid: [0, 1]");
  CHECK(error_of({{"e", "nan"}}) == "parameter 'e' = 'nan' is not a finite number; valid: [0, 1]");
  CHECK(error_of({{"e", "0.5x"}}) == "parameter 'e' = '0.5x' is not a finite number; valid: [0, 1]");
  // Issue 20: an underflow is not "not a finite number".
  CHECK(error_of({{"e", "5e-324"}}) ==
        "parameter 'e' = '5e-324' is subnormal (below 2.2e-308, the smallest normal double: too small to compute with); valid: [0, 1]");
  CHECK(error_of({{"e", "1e-400"}}) == "parameter 'e' = '1e-400' underflows to 0 (below the smallest double, 4.9e-324); valid: [0, 1]");
  CHECK(error_of({{"e", "1e400"}}) == "parameter 'e' = '1e400' is beyond the largest double (1.8e308); valid: [0, 1]");
  CHECK_THROWS_WITH(nsb::parse_real("5e-324", "--dt"), "--dt: '5e-324' is subnormal (below 2.2e-308, the smallest normal "
                                                       "double: too small to compute with)");
  CHECK(error_of({{"n", "2.5"}}) == "parameter 'n' = 2.5 is not an integer; valid: integer in [1, 1000]");
  CHECK(error_of({{"mass", "heavy"}}) == "parameter 'mass' = 'heavy' is not one of {lumped, singular}");
  CHECK(error_of({{"zz", "1"}}) == "unknown parameter 'zz' (nearest: e; valid: e, dt, n, mass)");
}

TEST_CASE("parameters: --set items are routed to the problem or the integrator", "[core]") {
  const nsb::ParamSpecs integ = {ParamSpec::real("theta", 0.5, 0.5, 1.0, "theta"),
                                 ParamSpec::real("e", 0.5, 0.0, 1.0, "clash")};
  const auto r = nsb::route_overrides({"n=3", "theta=0.7", "problem.e=0.1", "integrator.e=0.2"}, specs, integ);
  CHECK(r.problem.at("n") == "3");
  CHECK(r.problem.at("e") == "0.1");
  CHECK(r.integrator.at("theta") == "0.7");
  CHECK(r.integrator.at("e") == "0.2");
  CHECK_THROWS_WITH(nsb::route_overrides({"e=0.1"}, specs, integ), Catch::Contains("both the problem and the integrator"));
  CHECK_THROWS_WITH(nsb::route_overrides({"foo=1"}, specs, integ), Catch::Contains("unknown parameter 'foo'"));
  CHECK_THROWS_WITH(nsb::route_overrides({"novalue"}, specs, integ), Catch::Contains("expected key=value"));
}

TEST_CASE("parameters: an optional real is unset unless given, and range-checked when given", "[core]") {
  const nsb::ParamSpecs with_optional = {ParamSpec::real("theta", 0.5, 0.5, 1.0, "theta"),
                                         ParamSpec::optional_real("gamma", 0.0, 1.0, "unset: 1 - theta")};
  CHECK(with_optional[1].default_value.empty());
  const Params unset(with_optional);
  CHECK_FALSE(unset.optional_real("gamma").has_value());
  CHECK(unset.values().at("gamma").empty());
  CHECK_THROWS_AS(unset.real("gamma"), std::logic_error);  // a programming error, not bad input
  const Params given(with_optional, {{"gamma", "0"}});
  CHECK(given.optional_real("gamma") == 0.0);
  CHECK(given.real("gamma") == 0.0);
  CHECK_THROWS_WITH(Params(with_optional, {{"gamma", "1.5"}}), "parameter 'gamma' = 1.5 is outside its valid range [0, 1]");
  CHECK_THROWS_WITH(Params(with_optional, {{"gamma", ""}}), "parameter 'gamma' = '' is not a finite number; valid: [0, 1]");
}
