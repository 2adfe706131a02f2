#include "problems/registry.hpp"

#include "core/registry.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/spring_chain.hpp"

namespace nsb {

const std::vector<ProblemEntry>& problem_registry() {
  static const std::vector<ProblemEntry> entries = {
      {"bouncing-mass", "point mass bouncing on a rigid floor under gravity (exact solution)", &BouncingMass::parameters_spec, &make_from_params<Problem, BouncingMass>},
      {"spring-chain", "masses joined by linear springs, no external force, optional rigid wall (momentum and energy test bed)", &SpringChain::parameters_spec, &make_from_params<Problem, SpringChain>},
  };
  return entries;
}

const ProblemEntry& find_problem(const std::string& name) {
  return find_entry(problem_registry(), name, "--problem", "problem");
}

std::unique_ptr<Problem> make_problem(const std::string& name, const std::map<std::string, std::string>& overrides) {
  return make_entry(find_problem(name), overrides);
}

}  // namespace nsb
