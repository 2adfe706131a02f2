#pragma once
// The built-in study of that name, for the study tests (a missing registration fails the test).
#include <stdexcept>
#include <string>

#include "studies/study.hpp"

namespace nsb::test {

inline const StudyEntry& registered_study(const std::string& name) {
  for (const auto& s : study_registry())
    if (s.name == name) return s;
  throw std::logic_error("study " + name + " not registered");
}

}  // namespace nsb::test
