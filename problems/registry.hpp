#pragma once
// Explicit list of the problems, by name (problems/registry.cpp, one line each).
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "problems/problem.hpp"

namespace nsb {

struct ProblemEntry {
  std::string name;
  std::string description;
  ParamSpecs (*parameters)();
  std::unique_ptr<Problem> (*make)(const Params&);
};

const std::vector<ProblemEntry>& problem_registry();
// Throws InputError listing the valid names when `name` is unknown.
const ProblemEntry& find_problem(const std::string& name);
std::unique_ptr<Problem> make_problem(const std::string& name,
                                      const std::map<std::string, std::string>& overrides = {});

}  // namespace nsb
