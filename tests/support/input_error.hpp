#pragma once
// The one-line text of the InputError that constructing T from `spec` throws ("" if none).
#include <string>

#include "core/parameters.hpp"

namespace nsb::test {

template <class T, class Spec>
std::string input_error_text(const Spec& spec) {
  try {
    const T made(spec);
  } catch (const InputError& err) {
    return err.what();
  }
  return "";
}

// The one-line text of the InputError that call() throws ("" if none).
template <class Call>
std::string input_error_text_of(const Call& call) {
  try {
    call();
  } catch (const InputError& err) {
    return err.what();
  }
  return "";
}

}  // namespace nsb::test
