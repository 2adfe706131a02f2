#pragma once
// Range checks of the exact solutions' inputs: one line naming the problem, the parameter, its
// value and the valid range (InputError, as Params' own checks).
#include <fmt/format.h>

#include <string>

#include "core/parameters.hpp"

namespace nsb {

inline void require_input(bool ok, const std::string& problem, const std::string& name, double value,
                          const std::string& range) {
  if (!ok) throw InputError(fmt::format("{}: {} = {} is outside {}", problem, name, value, range));
}

}  // namespace nsb
