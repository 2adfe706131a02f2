// Bad --set values, systematically: every parameter of every registered problem and
// integrator against garbage, non-finite, out-of-range and mutated values. Each is either
// accepted (then it lies in the declared range) or rejected with an InputError naming the
// parameter and its valid range; nothing else (no crash, no other exception).
#include <catch2/catch.hpp>
#include <cmath>

#include "core/parameters.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"

namespace {

void fuzz(const nsb::ParamSpecs& specs) {
  const std::vector<std::string> values = {"", " ", "nan", "NaN", "inf", "-inf", "1e400", "-1e400", "1e-400", "-1",
                                           "0", "-0", "1e308", "0x10", "1,5", "1.5.2", "abc", "1e", "--1", "+",
                                           "9223372036854775808", "2.5", "1 ", "\t3", "\xff\xfe", "lumped;rm"};
  for (const auto& spec : specs) {
    std::vector<std::string> tried = values;
    tried.push_back(spec.default_value + "x");  // a mutated default
    tried.push_back("-" + spec.default_value);
    for (const auto& value : tried) {
      CAPTURE(spec.name, value);
      try {
        const nsb::Params p(specs, {{spec.name, value}});
        if (spec.kind != nsb::ParamSpec::Kind::Choice) CHECK(std::isfinite(p.real(spec.name)));
      } catch (const nsb::InputError& e) {
        const std::string m = e.what();
        CHECK_THAT(m, Catch::Contains("'" + spec.name + "'") && Catch::Contains(spec.range_text()));
      }
    }
  }
}

}  // namespace

TEST_CASE("bad input: every --set parameter against garbage values is rejected naming it and its range",
          "[core][bad-input][fuzz]") {
  for (const auto& e : nsb::problem_registry()) fuzz(e.parameters());
  for (const auto& e : nsb::integrator_registry()) fuzz(e.parameters());
}
