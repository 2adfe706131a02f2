#pragma once
// The problems, by name. Each registers itself in its own .cpp (built-in or plugin):
//
//   NSBENCH_PROBLEM({"name", "one-line description", &T::parameters_spec,
//                    &make_from_params<Problem, T>});
//
// at namespace scope (inside or outside namespace nsb; outside, qualify nsb::). The listing
// is sorted by name.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "problems/problem.hpp"

namespace nsb {

struct ProblemEntry {
  std::string name;
  std::string description;
  ParamSpecs (*parameters)();
  std::unique_ptr<Problem> (*make)(const Params&);
};

// What NSBENCH_PROBLEM calls (`abi`: the caller's NSBENCH_PLUGIN_ABI).
bool register_problem(const ProblemEntry& entry, int abi);
const std::vector<ProblemEntry>& problem_registry();
// Throws InputError listing the valid names when `name` is unknown.
const ProblemEntry& find_problem(const std::string& name);
std::unique_ptr<Problem> make_problem(const std::string& name,
                                      const std::map<std::string, std::string>& overrides = {});

}  // namespace nsb

#define NSBENCH_PROBLEM(...)                                  \
  [[maybe_unused]] static const bool NSBENCH_UNIQUE(nsbench_problem_) = \
      ::nsb::register_problem(::nsb::ProblemEntry __VA_ARGS__, NSBENCH_PLUGIN_ABI)
