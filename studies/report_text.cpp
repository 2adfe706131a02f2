#include "studies/report_text.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace nsb {

std::string escape_controls(const std::string& s, std::string_view kept) {
  std::string out;
  for (const char ch : s) {
    const auto byte = static_cast<unsigned char>(ch);
    if ((byte < 0x20 || byte == 0x7f) && kept.find(ch) == std::string_view::npos)
      out += fmt::format("\\x{:02x}", byte);
    else
      out += ch;
  }
  return out;
}

std::string one_line(const std::string& s) {
  std::string out = escape_controls(s, "\t\n\r");
  std::replace_if(out.begin(), out.end(), [](char ch) { return ch == '\t' || ch == '\n' || ch == '\r'; }, ' ');
  return out;
}

}  // namespace nsb
