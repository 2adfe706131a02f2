#include "problems/registry.hpp"

namespace nsb {

namespace {

struct ByName {
  bool operator()(const ProblemEntry& a, const ProblemEntry& b) const { return a.name < b.name; }
};

Registry<ProblemEntry, ByName>& problems() {
  static Registry<ProblemEntry, ByName> registry;
  return registry;
}

}  // namespace

bool register_problem(const ProblemEntry& entry, int abi) { return problems().add(entry, abi, "problem"); }

const std::vector<ProblemEntry>& problem_registry() { return problems().entries(); }

const ProblemEntry& find_problem(const std::string& name) {
  return find_entry(problem_registry(), name, "--problem", "problem");
}

std::unique_ptr<Problem> make_problem(const std::string& name, const std::map<std::string, std::string>& overrides) {
  return make_entry(find_problem(name), overrides);
}

}  // namespace nsb
