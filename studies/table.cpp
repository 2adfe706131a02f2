#include "studies/table.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "core/build_info.hpp"
#include "core/output.hpp"

#include <nlohmann/json.hpp>

namespace nsb {

void Table::add_row(std::vector<Cell> row) {
  if (row.size() != columns.size())
    throw std::logic_error(fmt::format("table {}: row of {} cells for {} columns", id, row.size(), columns.size()));
  rows.push_back(std::move(row));
}

std::string header_text(const Column& c) { return c.unit.empty() ? c.name : fmt::format("{} [{}]", c.name, c.unit); }

namespace {

std::vector<std::pair<std::string, std::string>> stamp(const Table& t) {
  const BuildInfo& b = build_info();
  auto s = t.metadata;
  s.emplace_back("git_revision", b.git_revision);
  s.emplace_back("build_type", b.build_type);
  s.emplace_back("compiler", b.compiler);
  return s;
}

// Text of a cell; `format` applies to numbers (empty: shortest round-trip).
std::string cell_text(const Cell& c, const std::string& format) {
  struct Visitor {
    const std::string& format;
    std::string operator()(std::monostate) const { return "n/a"; }
    std::string operator()(double v) const {
      if (std::isnan(v)) return "n/a";
      if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
      return format.empty() ? fmt::format("{}", v) : fmt::format(fmt::runtime(format), v);
    }
    std::string operator()(long v) const { return fmt::format("{}", v); }
    std::string operator()(const std::string& s) const { return s; }
  };
  return std::visit(Visitor{format}, c);
}

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char ch : s) out += (ch == '"') ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

std::string latex_escape(const std::string& s) {
  std::string out;
  for (char ch : s) {
    switch (ch) {
      case '_': case '%': case '&': case '#': case '$': case '{': case '}':
        out += '\\';
        out += ch;
        break;
      case '^': out += "\\^{}"; break;
      case '~': out += "\\~{}"; break;
      default: out += ch;
    }
  }
  return out;
}

}  // namespace

std::string to_csv(const Table& t) {
  std::string out;
  for (const auto& [k, v] : stamp(t)) out += fmt::format("# {}: {}\n", k, v);
  std::vector<std::string> head;
  for (const auto& c : t.columns) head.push_back(csv_escape(header_text(c)));
  out += fmt::format("{}\n", fmt::join(head, ","));
  for (const auto& row : t.rows) {
    std::vector<std::string> cells;
    for (const auto& c : row) cells.push_back(csv_escape(cell_text(c, "")));
    out += fmt::format("{}\n", fmt::join(cells, ","));
  }
  return out;
}

std::string to_markdown(const Table& t) {
  std::string out = fmt::format("## {}\n\n{}\n\n", t.title, t.caption);
  std::vector<std::string> head, rule;
  for (const auto& c : t.columns) {
    head.push_back(header_text(c));
    rule.push_back("---");
  }
  out += fmt::format("| {} |\n| {} |\n", fmt::join(head, " | "), fmt::join(rule, " | "));
  for (const auto& row : t.rows) {
    std::vector<std::string> cells;
    for (std::size_t i = 0; i < row.size(); ++i) cells.push_back(cell_text(row[i], t.columns[i].format));
    out += fmt::format("| {} |\n", fmt::join(cells, " | "));
  }
  out += "\n";
  for (const auto& c : t.columns)
    if (!c.description.empty()) out += fmt::format("- `{}`: {}\n", c.name, c.description);
  out += "\n";
  std::vector<std::string> meta;
  for (const auto& [k, v] : stamp(t)) meta.push_back(fmt::format("{} = {}", k, v));
  out += fmt::format("<sub>{}</sub>\n", fmt::join(meta, "; "));
  return out;
}

std::string to_latex(const Table& t) {
  std::string out;
  for (const auto& [k, v] : stamp(t)) out += fmt::format("% {}: {}\n", k, v);
  out += "% needs \\usepackage{booktabs}\n\\begin{table}\n\\centering\n\\small\n";
  out += fmt::format("\\caption{{{} {}}}\n\\label{{tab:{}}}\n", latex_escape(t.title), latex_escape(t.caption), t.id);
  out += fmt::format("\\begin{{tabular}}{{{}}}\n\\toprule\n", std::string(t.columns.size(), 'l'));
  std::vector<std::string> head;
  for (const auto& c : t.columns) head.push_back(latex_escape(header_text(c)));
  out += fmt::format("{} \\\\\n\\midrule\n", fmt::join(head, " & "));
  for (const auto& row : t.rows) {
    std::vector<std::string> cells;
    for (std::size_t i = 0; i < row.size(); ++i) cells.push_back(latex_escape(cell_text(row[i], t.columns[i].format)));
    out += fmt::format("{} \\\\\n", fmt::join(cells, " & "));
  }
  out += fmt::format("\\bottomrule\n\\end{{tabular}}\n\\par\\smallskip\\footnotesize Revision {}, {} build, {}.\n\\end{{table}}\n",
                     latex_escape(build_info().git_revision), latex_escape(build_info().build_type),
                     latex_escape(build_info().compiler));
  return out;
}

void write_table(const Table& t, const std::filesystem::path& dir) {
  ensure_directory(dir);
  write_file_atomic(dir / (t.id + ".csv"), to_csv(t));
  write_file_atomic(dir / (t.id + ".md"), to_markdown(t));
  write_file_atomic(dir / (t.id + ".tex"), to_latex(t));
}

}  // namespace nsb

namespace nsb {

std::string figures_to_json(const std::vector<Table>& tables) {
  nlohmann::json all = nlohmann::json::array();
  for (const auto& t : tables) {
    const auto header = [&](const std::string& name) {
      for (const auto& c : t.columns)
        if (c.name == name) return header_text(c);
      throw std::logic_error(fmt::format("figure of table {}: no column '{}'", t.id, name));
    };
    const auto headers = [&](const std::vector<std::string>& names) {
      std::vector<std::string> h;
      for (const auto& n : names) h.push_back(header(n));
      return h;
    };
    for (const auto& f : t.figures)
      all.push_back({{"id", f.id}, {"title", f.title}, {"csv", t.id + ".csv"}, {"x", header(f.x)},
                     {"y", header(f.y)}, {"series", headers(f.series)}, {"panels", headers(f.panels)},
                     {"log_x", f.log_x}, {"log_y", f.log_y}});
  }
  return all.dump(2) + "\n";
}

}  // namespace nsb
