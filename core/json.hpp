#pragma once
// JSON read from files the suite does not control (a reference cache, shards): parsed only
// when its nesting is bounded. An array nested 100,000 deep parses, but recursive walks
// over it (dump(), comparisons, destruction) overflow the stack; no file the suite writes
// nests deeper than a dozen levels.
#include <algorithm>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string_view>

namespace nsb {

inline constexpr std::size_t kMaxJsonDepth = 64;

// The deepest nesting of arrays and objects in `text` (brackets inside strings not counted),
// scanning no further than max_depth + 1.
inline std::size_t json_nesting(std::string_view text, std::size_t max_depth = kMaxJsonDepth) {
  std::size_t depth = 0, deepest = 0;
  bool in_string = false, escaped = false;
  for (const char c : text) {
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      deepest = std::max(deepest, ++depth);
      if (deepest > max_depth) break;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

// The JSON value of `text`, or a discarded value (is_discarded()) when it is malformed or
// nested deeper than max_depth.
inline nlohmann::json parse_json_bounded(std::string_view text, std::size_t max_depth = kMaxJsonDepth) {
  if (json_nesting(text, max_depth) > max_depth) return nlohmann::json(nlohmann::json::value_t::discarded);
  return nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
}

}  // namespace nsb
