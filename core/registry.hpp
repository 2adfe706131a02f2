#pragma once
// Lookup shared by the explicit registries (problems, integrators): an entry has a `name`,
// its `parameters()` and a `make(Params)` factory.
#include <fmt/format.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/parameters.hpp"

namespace nsb {

// Factory of a registry line: builds T from its validated parameters.
template <class Base, class T>
std::unique_ptr<Base> make_from_params(const Params& p) {
  return std::make_unique<T>(p);
}

// Throws InputError naming the option and the valid names when `name` is unknown.
template <class Entry>
const Entry& find_entry(const std::vector<Entry>& entries, const std::string& name, const std::string& option,
                        const std::string& kind) {
  std::vector<std::string> names;
  for (const auto& e : entries) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw InputError(fmt::format("{} '{}': unknown {} (valid: {})", option, name, kind, fmt::join(names, ", ")));
}

template <class Entry>
auto make_entry(const Entry& entry, const std::map<std::string, std::string>& overrides) {
  return entry.make(Params(entry.parameters(), overrides));
}

}  // namespace nsb
