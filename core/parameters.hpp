#pragma once
// Named, typed, range-checked parameters shared by problems, integrators and the CLI.
// Every problem and integrator declares its parameters as a list of ParamSpec; user input
// ("key=value" strings) is validated against that list, so a bad value fails with one
// line that names the parameter and its valid range.
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace nsb {

// Bad user input: unknown name, malformed number, value out of range. The CLI prints
// what() on one line and exits non-zero.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ParamSpec {
  enum class Kind { Real, Integer, Choice };

  std::string name;
  std::string description;
  Kind kind = Kind::Real;
  std::string default_value;
  double lower = -1e308;
  double upper = 1e308;
  bool lower_open = false;  // true: value must be > lower, not >=
  bool upper_open = false;
  std::vector<std::string> choices;

  static ParamSpec real(std::string name, double default_value, double lower, double upper,
                        std::string description, bool lower_open = false, bool upper_open = false);
  static ParamSpec integer(std::string name, long default_value, long lower, long upper,
                           std::string description);
  static ParamSpec choice(std::string name, std::string default_value,
                          std::vector<std::string> choices, std::string description);
  // A real without a default value: unset unless given (an empty default_value), for a
  // parameter whose absence means something no constant can say (e.g. moreau-jean's gamma,
  // 1 - theta when unset). Read with Params::optional_real; the description says what
  // unset means.
  static ParamSpec optional_real(std::string name, double lower, double upper, std::string description);

  // "[0, 1]", "(0, inf)", "{lumped, consistent}" ...
  std::string range_text() const;
  // Throws InputError naming the parameter and the range when text is not valid.
  void validate(const std::string& text) const;
};

using ParamSpecs = std::vector<ParamSpec>;

// Validated values (as canonical text) of one problem's or integrator's parameters.
class Params {
 public:
  Params() = default;
  // Applies overrides on top of the defaults; throws InputError on an unknown key or bad value.
  Params(const ParamSpecs& specs, const std::map<std::string, std::string>& overrides = {});

  double real(const std::string& name) const;  // a logic_error on an unset optional real
  std::optional<double> optional_real(const std::string& name) const;  // nullopt when unset
  long integer(const std::string& name) const;
  const std::string& choice(const std::string& name) const;
  // Every declared parameter; an unset optional real holds an empty text.
  const std::map<std::string, std::string>& values() const { return values_; }

 private:
  const std::string& text(const std::string& name) const;
  std::map<std::string, std::string> values_;
};

// Parses a floating-point number in full; throws InputError naming `what` otherwise.
double parse_real(const std::string& text, const std::string& what);

// The name of `valid` nearest to `word` (Levenshtein distance; the first of equals), for
// "unknown X (nearest: Y)" messages of the CLI and the study files; "" when `valid` is empty.
std::string nearest_name(const std::string& word, const std::vector<std::string>& valid);

// Splits "key=value"; throws InputError on a malformed item.
std::pair<std::string, std::string> split_assignment(const std::string& item);

}  // namespace nsb

namespace nsb {

// "--set key=value" items split between a problem's and an integrator's parameters. A key
// goes to whichever declares it; "problem.key" or "integrator.key" picks one explicitly
// (needed only when both declare the key). Throws InputError on unknown or ambiguous keys
// and on a key given twice (also as e and problem.e).
struct RoutedOverrides {
  std::map<std::string, std::string> problem;
  std::map<std::string, std::string> integrator;
};
RoutedOverrides route_overrides(const std::vector<std::string>& items, const ParamSpecs& problem,
                                const ParamSpecs& integrator);

}  // namespace nsb
