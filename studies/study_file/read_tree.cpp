// A study file's text as one JSON tree: TOML and JSON both read into it, with the line of each
// key path, so that both formats give the same errors ("FILE:LINE: key.path: what; valid: ...").
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <memory>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace nsb::study_files {

namespace {

void toml_to_json(const toml::node& node, const std::string& path, Json& out, Lines& lines) {
  if (node.source().begin.line) lines.emplace(path, node.source().begin.line);
  if (const auto* t = node.as_table()) {
    out = Json::object();
    for (const auto& [k, v] : *t) {
      const std::string p = child(path, std::string(k.str()));
      if (k.source().begin.line) lines[p] = k.source().begin.line;
      toml_to_json(v, p, out[std::string(k.str())], lines);
    }
  } else if (const auto* a = node.as_array()) {
    out = Json::array();
    for (std::size_t i = 0; i < a->size(); ++i) toml_to_json((*a)[i], element(path, i), out[i], lines);
  } else if (const auto* s = node.as_string()) {
    out = s->get();
  } else if (const auto* i = node.as_integer()) {
    out = i->get();
  } else if (const auto* f = node.as_floating_point()) {
    out = f->get();
  } else if (const auto* b = node.as_boolean()) {
    out = b->get();
  } else {
    out = Json::object({{"<date or time>", true}});  // no such value in the schema: a wrong type
  }
}

// JSON allows a key twice in one object (the last wins); TOML does not, and neither does a
// study file: a parser callback that fails on the second occurrence.
Json::parser_callback_t duplicate_key_check(const std::string& text, const std::string& file) {
  auto open = std::make_shared<std::vector<std::set<std::string>>>();
  return [open, &text, &file](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) open->emplace_back();
    if (event == Json::parse_event_t::object_end) open->pop_back();
    if (event == Json::parse_event_t::key && !open->empty() && !open->back().insert(parsed.get<std::string>()).second) {
      const std::string key = parsed.get<std::string>(), quoted = Json(key).dump();
      const std::size_t first = text.find(quoted), second = first == std::string::npos ? first : text.find(quoted, first + 1);
      const long line = second == std::string::npos ? 0 : 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(second), '\n'));
      throw InputError(fmt::format("{}:{}: key '{}' given twice in one table; valid: each key once", file, line, key));
    }
    return true;
  };
}

}  // namespace

// JSON gives no positions: the line of a key path is found by looking for each of its keys
// in turn, from where the previous one was found.
long json_line(const std::string& text, const std::string& path) {
  std::size_t pos = 0;
  std::stringstream parts(path);
  for (std::string part; std::getline(parts, part, '.');) {
    const std::string key = part.substr(0, part.find('['));
    const std::size_t at = text.find("\"" + key + "\"", pos);
    if (at != std::string::npos) pos = at;
  }
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

std::string type_name(const Json& j) {
  if (j.is_object()) return "a table";
  if (j.is_array()) return "an array";
  if (j.is_string()) return "a string";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number_integer()) return "an integer";
  return "a number";
}

Json read_tree(const std::string& text, const std::string& file, bool json, Lines& lines) {
  Json root;
  if (json) {
    try {
      root = Json::parse(text, duplicate_key_check(text, file));
    } catch (const Json::parse_error& e) {
      throw InputError(fmt::format("{}: not valid JSON: {}", file, e.what()));
    } catch (const Json::out_of_range& e) {  // a number beyond a double's range (406)
      throw InputError(fmt::format("{}: a number beyond the range of a double (1.8e308): {}", file, e.what()));
    }
  } else {
    try {
      toml_to_json(toml::parse(text, file), "", root, lines);
    } catch (const toml::parse_error& e) {
      throw InputError(fmt::format("{}:{}: not valid TOML: {}", file, e.source().begin.line, e.description()));
    }
  }
  return root;
}

}  // namespace nsb::study_files
