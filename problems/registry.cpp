#include "problems/registry.hpp"

#include "core/registry.hpp"
#include "problems/block_2d.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/signorini_bar.hpp"
#include "problems/spring_chain.hpp"

namespace nsb {

const std::vector<ProblemEntry>& problem_registry() {
  static const std::vector<ProblemEntry> entries = {
      {"bouncing-mass", "point mass bouncing on a rigid floor under gravity (exact solution)", &BouncingMass::parameters_spec, &make_from_params<Problem, BouncingMass>},
      {"signorini-bar", "1D elastic bar hitting a rigid wall, nondimensional; mass lumped|consistent|singular (exact d'Alembert solution)", &SignoriniBar::parameters_spec, &make_from_params<Problem, SignoriniBar>},
      {"signorini-bar-steel", "the Signorini bar with steel defaults (L 1 m, E 210 GPa, rho 7800, A 3.14e-4 m^2, v0 0.1 m/s, g0 5e-5 m)", &SignoriniBar::steel_parameters_spec, &SignoriniBar::make_steel},
      {"bouncing-bar", "Doyen-Ern-Piperno bouncing bar: the Signorini bar (L 10, E 900, rho 1) dropped from rest 5 m above the wall, g 10 (exact solution, period 16 L/c)", &SignoriniBar::bouncing_parameters_spec, &SignoriniBar::make_bouncing},
      {"spring-chain", "masses joined by linear springs, no external force, optional rigid wall (momentum and energy test bed)", &SpringChain::parameters_spec, &make_from_params<Problem, SpringChain>},
      {"block-2d", "hyperelastic Q4 block (plane strain) dropped tilted on a rigid frictionless floor", &Block2d::parameters_spec, &make_from_params<Problem, Block2d>},
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
