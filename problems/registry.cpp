#include "problems/registry.hpp"

#include <fmt/format.h>

#include "problems/block_2d.hpp"
#include "problems/bouncing_mass.hpp"

namespace nsb {

namespace {
template <class P>
std::unique_ptr<Problem> make(const Params& p) {
  return std::make_unique<P>(p);
}
}  // namespace

const std::vector<ProblemEntry>& problem_registry() {
  static const std::vector<ProblemEntry> entries = {
      {"bouncing-mass", "point mass bouncing on a rigid floor under gravity (exact solution)", &BouncingMass::parameters_spec, &make<BouncingMass>},
      {"block-2d", "hyperelastic Q4 block (plane strain) dropped tilted on a rigid frictionless floor", &Block2d::parameters_spec, &make<Block2d>},
  };
  return entries;
}

const ProblemEntry& find_problem(const std::string& name) {
  std::vector<std::string> names;
  for (const auto& e : problem_registry()) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw InputError(fmt::format("--problem '{}': unknown problem (valid: {})", name, fmt::join(names, ", ")));
}

std::unique_ptr<Problem> make_problem(const std::string& name,
                                      const std::map<std::string, std::string>& overrides) {
  const auto& entry = find_problem(name);
  return entry.make(Params(entry.parameters(), overrides));
}

}  // namespace nsb
