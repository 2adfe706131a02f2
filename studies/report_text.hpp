#pragma once
// Report text from labels and titles a user (a study file, a plugin) chose, made safe for the
// report formats: each control byte (below 0x20, and 0x7f) not in `kept` is written as the
// text \xHH (a NUL or an ESC would end a string or drive a terminal); one_line also turns
// tabs, newlines and carriage returns into spaces, so that a label cannot split a Markdown
// row, start a heading, end a comment line or put a paragraph break into a TeX table. The
// table writers (studies/table.hpp) and index.md pass every such text through them.
#include <string>
#include <string_view>

namespace nsb {

std::string escape_controls(const std::string& s, std::string_view kept);
std::string one_line(const std::string& s);

}  // namespace nsb
