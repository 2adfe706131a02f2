#include "core/parameters.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace nsb {

ParamSpec ParamSpec::real(std::string name, double default_value, double lower, double upper,
                          std::string description, bool lower_open, bool upper_open) {
  ParamSpec s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.kind = Kind::Real;
  s.default_value = fmt::format("{}", default_value);
  s.lower = lower;
  s.upper = upper;
  s.lower_open = lower_open;
  s.upper_open = upper_open;
  return s;
}

ParamSpec ParamSpec::integer(std::string name, long default_value, long lower, long upper,
                             std::string description) {
  ParamSpec s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.kind = Kind::Integer;
  s.default_value = fmt::format("{}", default_value);
  s.lower = static_cast<double>(lower);
  s.upper = static_cast<double>(upper);
  return s;
}

ParamSpec ParamSpec::choice(std::string name, std::string default_value,
                            std::vector<std::string> choices, std::string description) {
  ParamSpec s;
  s.name = std::move(name);
  s.description = std::move(description);
  s.kind = Kind::Choice;
  s.default_value = std::move(default_value);
  s.choices = std::move(choices);
  return s;
}

ParamSpec ParamSpec::optional_real(std::string name, double lower, double upper, std::string description) {
  ParamSpec s = real(std::move(name), 0.0, lower, upper, std::move(description));
  s.default_value.clear();
  return s;
}

static std::string bound_text(double v) {
  if (v <= -1e308) return "-inf";
  if (v >= 1e308) return "inf";
  return fmt::format("{}", v);
}

std::string ParamSpec::range_text() const {
  if (kind == Kind::Choice) return fmt::format("{{{}}}", fmt::join(choices, ", "));
  const bool lo_open = lower_open || lower <= -1e308;
  const bool hi_open = upper_open || upper >= 1e308;
  std::string r = fmt::format("{}{}, {}{}", lo_open ? "(" : "[", bound_text(lower),
                              bound_text(upper), hi_open ? ")" : "]");
  return kind == Kind::Integer ? "integer in " + r : r;
}

namespace {

// Why `text` is no usable real number ("" when it is one, its value in v).
std::string real_defect(const std::string& text, double& v) {
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  v = std::strtod(begin, &end);
  if (text.empty() || end != begin + text.size() || (!std::isfinite(v) && errno != ERANGE)) return "is not a finite number";
  if (errno == ERANGE && std::isinf(v)) return "is beyond the largest double (1.8e308)";
  // strtod flags an underflow; a subnormal or zero result has lost its precision.
  if (errno == ERANGE && std::abs(v) < std::numeric_limits<double>::min())
    return v == 0.0 ? "underflows to 0 (below the smallest double, 4.9e-324)"
                    : "is subnormal (below 2.2e-308, the smallest normal double: too small to compute with)";
  return "";
}

}  // namespace

double parse_real(const std::string& text, const std::string& what) {
  double v = 0.0;
  if (const std::string defect = real_defect(text, v); !defect.empty())
    throw InputError(fmt::format("{}: '{}' {}", what, text, defect));
  return v;
}

void ParamSpec::validate(const std::string& text) const {
  if (kind == Kind::Choice) {
    for (const auto& c : choices)
      if (c == text) return;
    throw InputError(fmt::format("parameter '{}' = '{}' is not one of {}", name, text, range_text()));
  }
  double v = 0.0;
  if (const std::string defect = real_defect(text, v); !defect.empty())
    throw InputError(fmt::format("parameter '{}' = '{}' {}; valid: {}", name, text, defect, range_text()));
  if (kind == Kind::Integer && v != std::floor(v))
    throw InputError(fmt::format("parameter '{}' = {} is not an integer; valid: {}", name, text,
                                 range_text()));
  const bool below = lower_open ? !(v > lower) : !(v >= lower);
  const bool above = upper_open ? !(v < upper) : !(v <= upper);
  if (below || above)
    throw InputError(fmt::format("parameter '{}' = {} is outside its valid range {}", name, text,
                                 range_text()));
}

Params::Params(const ParamSpecs& specs, const std::map<std::string, std::string>& overrides) {
  for (const auto& s : specs) values_[s.name] = s.default_value;
  for (const auto& [key, value] : overrides) {
    const ParamSpec* spec = nullptr;
    for (const auto& s : specs)
      if (s.name == key) spec = &s;
    if (!spec) {
      std::vector<std::string> names;
      for (const auto& s : specs) names.push_back(s.name);
      throw InputError(names.empty() ? fmt::format("unknown parameter '{}' (valid: none)", key)
                                     : fmt::format("unknown parameter '{}' (nearest: {}; valid: {})", key,
                                                   nearest_name(key, names), fmt::join(names, ", ")));
    }
    spec->validate(value);
    values_[key] = value;
  }
}

const std::string& Params::text(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw std::logic_error("undeclared parameter read: " + name);
  return it->second;
}

double Params::real(const std::string& name) const {
  const std::string& t = text(name);
  if (t.empty()) throw std::logic_error("unset optional parameter read with real(): " + name + " (optional_real)");
  return parse_real(t, name);
}

std::optional<double> Params::optional_real(const std::string& name) const {
  const std::string& t = text(name);
  if (t.empty()) return std::nullopt;
  return parse_real(t, name);
}

long Params::integer(const std::string& name) const {
  return static_cast<long>(parse_real(text(name), name));
}

const std::string& Params::choice(const std::string& name) const { return text(name); }

static std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string nearest_name(const std::string& word, const std::vector<std::string>& valid) {
  std::string best;
  std::size_t d = std::string::npos;
  for (const auto& v : valid)
    if (const std::size_t dv = edit_distance(word, v); dv < d) {
      d = dv;
      best = v;
    }
  return best;
}

std::pair<std::string, std::string> split_assignment(const std::string& item) {
  const auto eq = item.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == item.size())
    throw InputError(fmt::format("--set '{}': expected key=value", item));
  return {item.substr(0, eq), item.substr(eq + 1)};
}

}  // namespace nsb

namespace nsb {

static bool declares(const ParamSpecs& specs, const std::string& key) {
  for (const auto& s : specs)
    if (s.name == key) return true;
  return false;
}

static std::vector<std::string> names_of(const ParamSpecs& specs) {
  std::vector<std::string> names;
  for (const auto& s : specs) names.push_back(s.name);
  return names;
}

static std::string listed(const std::vector<std::string>& names) {
  return names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "));
}

RoutedOverrides route_overrides(const std::vector<std::string>& items, const ParamSpecs& problem,
                                const ParamSpecs& integrator) {
  RoutedOverrides routed;
  std::map<std::pair<const void*, std::string>, std::string> given;  // (destination, key) -> the --set that gave it
  // A repeated key is refused, as a repeated --dt is: the last one silently winning hides a typo.
  const auto assign = [&](std::map<std::string, std::string>& to, const std::string& key, const std::string& value, const std::string& item) {
    const auto [at, fresh] = given.emplace(std::pair<const void*, std::string>{&to, key}, item);
    if (!fresh)
      throw InputError(fmt::format("--set {}: parameter '{}' is already set by --set {}; valid: each parameter once", item,
                                   key, at->second));
    to[key] = value;
  };
  for (const auto& item : items) {
    auto [key, value] = split_assignment(item);
    if (key.rfind("problem.", 0) == 0) {
      assign(routed.problem, key.substr(8), value, item);  // validated when the problem is built
      continue;
    }
    if (key.rfind("integrator.", 0) == 0) {
      assign(routed.integrator, key.substr(11), value, item);
      continue;
    }
    const bool p = declares(problem, key), i = declares(integrator, key);
    if (p && i)
      throw InputError(fmt::format("--set {}: both the problem and the integrator take '{}'; write problem.{} or integrator.{}",
                                   item, key, key, key));
    if (!p && !i) {
      std::vector<std::string> both = names_of(problem), ints = names_of(integrator);
      both.insert(both.end(), ints.begin(), ints.end());
      throw InputError(fmt::format("--set {}: unknown parameter '{}' (nearest: {}; problem takes: {}; integrator takes: {})",
                                   item, key, both.empty() ? "none" : nearest_name(key, both), listed(names_of(problem)),
                                   listed(ints)));
    }
    assign(p ? routed.problem : routed.integrator, key, value, item);
  }
  return routed;
}

}  // namespace nsb
