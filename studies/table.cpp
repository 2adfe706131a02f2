#include "studies/table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <stdexcept>

#include "core/build_info.hpp"
#include "core/environment.hpp"
#include "core/output.hpp"
#include "core/plugin.hpp"
#include "integrators/registry.hpp"  // peer_versions()
#include "run/run.hpp"
#include "studies/report_text.hpp"
#include "studies/study.hpp"  // kStudyStatuses, kDeclinedStatus

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
  s.emplace_back("nsbench_version", b.version);
  s.emplace_back("git_revision", b.git_revision);
  s.emplace_back("build_type", b.build_type);
  s.emplace_back("compiler", b.compiler);
  const Environment& env = environment();
  s.emplace_back("machine", fmt::format("{}, {} cores", env.cpu, env.cores));
  s.emplace_back("libraries", env.libraries);
  s.emplace_back("peers", peer_versions());
  if (!command_line().empty()) s.emplace_back("command", command_line());
  if (const std::string plugins = plugins_stamp(); !plugins.empty()) s.emplace_back("plugins", plugins);
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

std::string csv_escape(const std::string& raw) {
  const std::string s = escape_controls(raw, "\t\n\r");
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char ch : s) out += (ch == '"') ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

// French guillemets (the talk's quotations) need the T1 font encoding, which a paper's
// preamble may not load: they become TeX's quote ligatures, which every encoding has.
std::string latex_quotes(std::string s) {
  for (const auto& [from, to] : {std::pair{"\u00ab\u00a0", "``"}, std::pair{"\u00ab ", "``"}, std::pair{"\u00ab", "``"},
                                 std::pair{"\u00a0\u00bb", "''"}, std::pair{" \u00bb", "''"}, std::pair{"\u00bb", "''"}}) {
    const std::string f = from;
    for (std::size_t at = s.find(f); at != std::string::npos; at = s.find(f, at)) s.replace(at, f.size(), to);
  }
  return s;
}

// Every character TeX treats specially, the backslash included: a label such as
// "x\input /etc/hostname \relax" is printed, not executed.
std::string latex_escape(const std::string& raw) {
  std::string out;
  for (char ch : latex_quotes(one_line(raw))) {
    switch (ch) {
      case '_': case '%': case '&': case '#': case '$': case '{': case '}':
        out += '\\';
        out += ch;
        break;
      case '\\': out += "\\textbackslash{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '|': out += "\\textbar{}"; break;
      case '<': out += "\\textless{}"; break;
      case '>': out += "\\textgreater{}"; break;
      default: out += ch;
    }
  }
  return out;
}

// Escaped text with the Greek letters the labels spell out (theta = 0.5, alpha, mu, rho_inf)
// typeset as symbols. Only whole words (runs of letters) are replaced, so the escapes'
// own commands (\textbackslash) and longer words (beta in "betas", eta in "theta") are not.
std::string latex_text(const std::string& s) {
  static const std::vector<std::string> greek = {"alpha", "beta", "gamma", "delta", "epsilon", "theta", "kappa",
                                                 "lambda", "mu", "rho", "sigma", "tau", "phi", "omega", "Delta",
                                                 "Gamma", "Lambda", "Omega", "Phi", "Sigma", "Theta"};
  const std::string e = latex_escape(s);
  std::string out;
  std::size_t i = 0;
  while (i < e.size()) {
    if (!std::isalpha(static_cast<unsigned char>(e[i]))) {
      out += e[i++];
      continue;
    }
    std::size_t j = i;
    while (j < e.size() && std::isalpha(static_cast<unsigned char>(e[j]))) ++j;
    const std::string word = e.substr(i, j - i);
    const bool command = i > 0 && e[i - 1] == '\\';
    const bool symbol = !command && std::find(greek.begin(), greek.end(), word) != greek.end();
    out += symbol ? "$\\" + word + "$" : word;
    i = j;
  }
  return out;
}

// Markdown cell text: a '|' would end the cell, a newline the row.
std::string markdown_escape(const std::string& s) {
  std::string out;
  for (char ch : one_line(s)) {
    if (ch == '|') out += '\\';
    out += ch;
  }
  return out;
}

// The verdict `head` gives a run's reason as Markdown and LaTeX name it (table.hpp): a run status
// or one of the declined status's other spellings, alone or after labels ("u time err n/a");
// nullopt for any other text ("alpha 30, mu 0.8, v0 2" before ": stops, sticks").
std::optional<std::string> reason_verdict(const std::string& head) {
  static const std::vector<std::pair<std::string, std::string>> verdicts = [] {
    std::vector<std::pair<std::string, std::string>> v;
    for (RunStatus s : {RunStatus::Diverged, RunStatus::OverBudget, RunStatus::Interrupted})
      v.emplace_back(status_name(s), status_name(s));
    for (std::string_view s : kStudyStatuses) v.emplace_back(s, s);
    for (const char* older : {"declined", "unsupported"}) v.emplace_back(older, kDeclinedStatus);
    return v;
  }();
  for (const auto& [spelt, name] : verdicts) {
    if (head == spelt) return name;
    if (head.ends_with(" " + spelt)) return head.substr(0, head.size() - spelt.size()) + name;
  }
  return std::nullopt;
}

// The first words of a text over kMaxCellChars, as its row shows it: up to 80 bytes, cut at a
// space so no word is split (or, in one long word, before a UTF-8 character's continuation bytes).
std::string first_words(const std::string& text) {
  std::size_t end = text.rfind(' ', 80);
  if (end == std::string::npos)
    for (end = 80; end > 0 && (static_cast<unsigned char>(text[end]) & 0xC0) == 0x80; --end) {}
  return text.substr(0, end) + " ...";
}

// The footnotes of one table in Markdown or LaTeX (table.hpp): the texts moved out of its cells,
// each once, numbered from 1 in the order the rows first show them.
class Footnotes {
 public:
  explicit Footnotes(const Table& t) {
    std::map<std::string, long> cells_of;  // the long texts, by the number of cells showing them
    for (const auto& row : t.rows)
      for (const auto& c : row)
        if (const auto* text = std::get_if<std::string>(&c); text && text->size() > kRepeatedCellChars) ++cells_of[*text];
    for (const auto& [text, cells] : cells_of)
      if (cells > 1) repeated_.insert(text);
  }

  // Text cell `text` as its row shows it.
  std::string shown(const std::string& text) {
    if (const std::size_t colon = text.find(": "); colon != std::string::npos)
      if (const auto verdict = reason_verdict(text.substr(0, colon))) return numbered(*verdict + " ", text.substr(colon + 2));
    if (text.size() > kMaxCellChars) return numbered(first_words(text) + " ", text);
    if (repeated_.count(text)) return numbered("", text);
    return reason_verdict(text).value_or(text);
  }
  const std::vector<std::string>& notes() const { return notes_; }

 private:
  std::string numbered(const std::string& shown, const std::string& note) {
    auto it = std::find(notes_.begin(), notes_.end(), note);
    if (it == notes_.end()) it = notes_.insert(notes_.end(), note);
    return fmt::format("{}[{}]", shown, it - notes_.begin() + 1);
  }
  std::set<std::string> repeated_;
  std::vector<std::string> notes_;
};

// A cell's text as a Markdown or LaTeX row shows it: a text through the table's footnotes.
std::string shown_text(const Cell& c, const std::string& format, Footnotes& notes) {
  const auto* text = std::get_if<std::string>(&c);
  return text ? notes.shown(*text) : cell_text(c, format);
}

// A column of numbers, a siunitx S column in LaTeX: one with a number format, or one without
// (integers, shortest round-trip numbers, texts) holding more numbers than texts (n/a, diverged).
bool numeric_column(const Table& t, std::size_t i) {
  if (!t.columns[i].format.empty()) return true;
  long numbers = 0, texts = 0;
  for (const auto& row : t.rows) {
    if (std::holds_alternative<double>(row[i]) || std::holds_alternative<long>(row[i])) ++numbers;
    if (std::holds_alternative<std::string>(row[i])) ++texts;
  }
  return numbers > 0 && numbers >= texts;
}

// A finite number as siunitx reads it (S column, \num): its text in the column's format with
// the exponent as a plain integer ("5.22e-02" -> "5.22e-2", "1e+20" -> "1e20"); nullopt for
// a text, an empty cell, NaN or an infinity.
std::optional<std::string> siunitx_number(const Cell& c, const std::string& format) {
  if (!std::holds_alternative<long>(c) && !(std::holds_alternative<double>(c) && std::isfinite(std::get<double>(c))))
    return std::nullopt;
  const std::string text = cell_text(c, format);
  const std::size_t e = text.find_first_of("eE");
  if (e == std::string::npos) return text;
  return fmt::format("{}e{}", text.substr(0, e), std::stoi(text.substr(e + 1)));
}

// What is not a number, in LaTeX: infinities as symbols, the rest as escaped text.
std::string latex_word(const Cell& c, const std::string& format, Footnotes& notes) {
  const std::string text = shown_text(c, format, notes);
  if (std::holds_alternative<double>(c) && std::isinf(std::get<double>(c)))
    return text[0] == '-' ? "$-\\infty$" : "$\\infty$";
  return latex_text(text);
}

// The S column of numbers written by siunitx_number: table-format reserves the widest sign,
// integer part, decimals and exponent among them ("-1.2e-2"), so they align on the decimal
// marker and the exponent. A column whose numbers all carry an exponent (an e format) prints
// x 10^0 too, like its other rows (siunitx leaves it out otherwise).
std::string s_column(const std::vector<std::string>& numbers) {
  if (numbers.empty()) return "S";
  bool minus = false, exponent_minus = false, all_exponents = true;
  std::size_t integer = 0, decimals = 0, exponent = 0;
  for (const auto& n : numbers) {
    const std::size_t sign = n[0] == '-' ? 1 : 0;
    const std::size_t e = std::min(n.find('e'), n.size());
    const std::size_t point = std::min(n.find('.'), e);
    minus = minus || sign;
    integer = std::max(integer, point - sign);
    decimals = std::max(decimals, point < e ? e - point - 1 : 0);
    all_exponents = all_exponents && e < n.size();
    if (e == n.size()) continue;
    const std::size_t exponent_sign = n[e + 1] == '-' ? 1 : 0;
    exponent_minus = exponent_minus || exponent_sign;
    exponent = std::max(exponent, n.size() - e - 1 - exponent_sign);
  }
  std::string format = fmt::format("{}{}", minus ? "-" : "", integer);
  if (decimals > 0) format += fmt::format(".{}", decimals);
  if (exponent > 0) format += fmt::format("e{}{}", exponent_minus ? "-" : "", exponent);
  return fmt::format("S[table-format={}{}]", format, all_exponents && exponent > 0 ? ",print-zero-exponent" : "");
}

// The table as Markdown and LaTeX show it: each fitted value and its interval one text cell,
// "1.9 [1.8, 2.0]" (Column::interval; a value that is n/a alone), the interval's columns left out.
Table presented(const Table& t) {
  const auto index = [&](const std::string& name) {
    const auto it = std::find_if(t.columns.begin(), t.columns.end(), [&](const Column& c) { return c.name == name; });
    if (it == t.columns.end()) throw std::logic_error(fmt::format("table {}: no interval column '{}'", t.id, name));
    return static_cast<std::size_t>(it - t.columns.begin());
  };
  std::vector<std::optional<std::pair<std::size_t, std::size_t>>> bounds(t.columns.size());
  std::vector<bool> dropped(t.columns.size(), false);
  for (std::size_t i = 0; i < t.columns.size(); ++i) {
    if (t.columns[i].interval.first.empty()) continue;
    bounds[i] = {index(t.columns[i].interval.first), index(t.columns[i].interval.second)};
    dropped[bounds[i]->first] = dropped[bounds[i]->second] = true;
  }
  if (std::none_of(dropped.begin(), dropped.end(), [](bool d) { return d; })) return t;
  Table out = t;
  out.columns.clear();
  for (std::size_t i = 0; i < t.columns.size(); ++i) {
    if (dropped[i]) continue;
    out.columns.push_back(t.columns[i]);
    if (!bounds[i]) continue;
    Column& c = out.columns.back();
    c.description += fmt::format("{}with its 95% interval [{}, {}]", c.description.empty() ? "" : "; ", c.interval.first, c.interval.second);
    c.format.clear(), c.interval = {};  // its cells are texts now
  }
  out.rows.clear();
  for (const auto& row : t.rows) {
    std::vector<Cell> cells;
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (dropped[i]) continue;
      const bool number = std::holds_alternative<double>(row[i]) && std::isfinite(std::get<double>(row[i]));
      if (!bounds[i] || !number) {
        cells.push_back(row[i]);
        continue;
      }
      const auto text = [&](std::size_t k) { return cell_text(row[k], t.columns[k].format); };
      cells.push_back(fmt::format("{} [{}, {}]", text(i), text(bounds[i]->first), text(bounds[i]->second)));
    }
    out.rows.push_back(std::move(cells));
  }
  return out;
}

}  // namespace

std::string to_csv(const Table& t) {
  std::string out;
  for (const auto& [k, v] : stamp(t)) out += fmt::format("# {}: {}\n", one_line(k), one_line(v));
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

std::string markdown_grid(const Table& shown) {
  const Table t = presented(shown);
  std::vector<std::string> head, rule;
  for (const auto& c : t.columns) {
    head.push_back(markdown_escape(header_text(c)));
    rule.push_back("---");
  }
  std::string out = fmt::format("| {} |\n| {} |\n", fmt::join(head, " | "), fmt::join(rule, " | "));
  Footnotes notes(t);
  for (const auto& row : t.rows) {
    std::vector<std::string> cells;
    for (std::size_t i = 0; i < row.size(); ++i) cells.push_back(markdown_escape(shown_text(row[i], t.columns[i].format, notes)));
    out += fmt::format("| {} |\n", fmt::join(cells, " | "));
  }
  // One paragraph under the table, a line per note (a backslash ends a line in GitHub Markdown).
  std::vector<std::string> lines;
  for (std::size_t k = 0; k < notes.notes().size(); ++k)
    lines.push_back(fmt::format("[{}] {}", k + 1, markdown_escape(notes.notes()[k])));
  if (!lines.empty()) out += fmt::format("\n{}\n", fmt::join(lines, "\\\n"));
  return out;
}

std::string to_markdown(const Table& shown) {
  const Table t = presented(shown);
  std::string out = fmt::format("## {}\n\n{}\n\n{}\n", one_line(t.title), one_line(t.caption), markdown_grid(t));
  for (const auto& c : t.columns)
    if (!c.description.empty()) out += fmt::format("- `{}`: {}\n", one_line(c.name), one_line(c.description));
  out += "\n";
  std::vector<std::string> meta;
  for (const auto& [k, v] : stamp(t)) meta.push_back(fmt::format("{} = {}", one_line(k), one_line(v)));
  out += fmt::format("<sub>{}</sub>\n", fmt::join(meta, "; "));
  return out;
}

// A longtable (packages booktabs, longtable, siunitx): it breaks across pages, its header
// repeated on each. The title is the \caption (and the list of tables' entry); the caption's
// text, the footnotes ("[k] reason", table.hpp), the column descriptions and the revision follow
// the table as its notes. Number columns
// are siunitx S columns; their texts (n/a, diverged) and headers are braced so siunitx sets them
// as text. The \sisetup inside the table's group keeps numbers as written whatever a paper sets.
std::string to_latex(const Table& shown) {
  const Table t = presented(shown);
  std::string out;
  for (const auto& [k, v] : stamp(t)) out += fmt::format("% {}: {}\n", one_line(k), one_line(v));
  std::vector<bool> numeric;
  std::string spec;
  for (std::size_t i = 0; i < t.columns.size(); ++i) {
    numeric.push_back(numeric_column(t, i));
    if (!numeric[i]) {
      spec += 'l';
      continue;
    }
    std::vector<std::string> numbers;
    for (const auto& row : t.rows)
      if (const auto n = siunitx_number(row[i], t.columns[i].format)) numbers.push_back(*n);
    spec += s_column(numbers);
  }
  std::vector<std::string> head;
  for (std::size_t i = 0; i < t.columns.size(); ++i) {
    const std::string text = latex_text(header_text(t.columns[i]));
    head.push_back(numeric[i] ? "{" + text + "}" : text);
  }
  const std::string header = fmt::format("\\toprule\n{} \\\\\n\\midrule\n", fmt::join(head, " & "));
  out += "% needs \\usepackage{booktabs,longtable,siunitx}\n{\\small\n\\setlength{\\LTcapwidth}{\\linewidth}\n";
  out += "\\sisetup{round-mode=none,exponent-mode=input,group-digits=none,retain-negative-zero}\n";
  out += fmt::format("\\begin{{longtable}}{{@{{}}{}@{{}}}}\n\\caption{{{}}}\\label{{tab:{}}} \\\\\n", spec,
                     latex_text(t.title), t.id);
  out += header + "\\endfirsthead\n";
  out += fmt::format("\\multicolumn{{{}}}{{@{{}}l}}{{\\footnotesize\\itshape Table~\\ref{{tab:{}}}, continued}} \\\\\n",
                     t.columns.size(), t.id);
  out += header + "\\endhead\n";
  out += fmt::format("\\midrule\n\\multicolumn{{{}}}{{r@{{}}}}{{\\footnotesize\\itshape continued on the next page}} \\\\\n"
                     "\\endfoot\n\\bottomrule\n\\endlastfoot\n", t.columns.size());
  Footnotes notes(t);
  for (const auto& row : t.rows) {
    std::vector<std::string> cells;
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (const auto number = siunitx_number(row[i], t.columns[i].format)) {
        cells.push_back(numeric[i] ? *number : "\\num{" + *number + "}");
      } else {
        const std::string word = latex_word(row[i], t.columns[i].format, notes);
        cells.push_back(numeric[i] ? "{" + word + "}" : word);
      }
    }
    // "{}" first in a text column: a row opening with '[' would be read as the optional argument
    // of the \\ before it (an S column's cells open with a digit, a sign or a brace).
    out += fmt::format("{}{} \\\\\n", numeric[0] ? "" : "{}", fmt::join(cells, " & "));
  }
  out += "\\end{longtable}\n}\n\\begingroup\\footnotesize\\noindent ";
  out += latex_text(t.caption);
  for (std::size_t k = 0; k < notes.notes().size(); ++k) {
    const std::string& note = notes.notes()[k];
    out += fmt::format(" [{}] {}{}", k + 1, latex_text(note), note.ends_with('.') ? "" : ".");
  }
  for (const auto& c : t.columns)
    if (!c.description.empty()) out += fmt::format(" {}: {}.", latex_text(c.name), latex_text(c.description));
  const std::string plugins = plugins_stamp();
  out += fmt::format(" nsbench {}, revision {}, {} build, {}{}.\\par\\endgroup\n", latex_escape(build_info().version),
                     latex_escape(build_info().git_revision),
                     latex_escape(build_info().build_type), latex_escape(build_info().compiler),
                     plugins.empty() ? "" : ", plugins " + latex_escape(plugins));
  return out;
}

void write_table(const Table& t, const std::filesystem::path& dir) {
  ensure_directory(dir);
  write_file_atomic(dir / (t.id + ".csv"), to_csv(t));
  if (t.csv_only) return;
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
    for (const auto& f : t.figures) {
      all.push_back({{"id", f.id}, {"title", f.title}, {"csv", t.id + ".csv"}, {"x", f.x.empty() ? std::string() : header(f.x)},
                     {"y", header(f.y)}, {"series", headers(f.series)}, {"panels", headers(f.panels)},
                     {"log_x", f.log_x}, {"log_y", f.log_y}, {"slopes", f.slopes},
                     {"small_multiples", f.small_multiples}, {"deviation", f.deviation}});
      auto& j = all.back();
      // Only where set: the figures of lines keep their entries as they were.
      if (!f.overlay.empty()) j["overlay"] = f.overlay;
      if (!f.caption.empty()) j["caption"] = f.caption;
      if (!f.kind.empty()) {
        j.update({{"kind", f.kind}, {"values", headers(f.values)}, {"positions", f.positions},
                  {"value_label", f.value_label}});
        if (!f.arrows.empty()) j["arrows_csv"] = f.arrows + ".csv";
      }
    }
  }
  return all.dump(2) + "\n";
}

}  // namespace nsb

namespace nsb {

namespace {

nlohmann::json cell_to_json(const Cell& c) {
  switch (c.index()) {
    case 0: return nullptr;
    case 1: {
      const double v = std::get<double>(c);
      // JSON has no NaN or infinity: keep them as tagged strings.
      if (std::isnan(v)) return {{"real", "nan"}};
      if (std::isinf(v)) return {{"real", v > 0 ? "inf" : "-inf"}};
      return {{"real", v}};
    }
    case 2: return {{"int", std::get<long>(c)}};
    default: return {{"text", std::get<std::string>(c)}};
  }
}

Cell cell_from_json(const nlohmann::json& j) {
  if (j.is_null()) return {};
  if (j.contains("int")) return j["int"].get<long>();
  if (j.contains("text")) return j["text"].get<std::string>();
  const auto& r = j["real"];
  if (r.is_string()) {
    const std::string s = r.get<std::string>();
    return s == "nan" ? std::numeric_limits<double>::quiet_NaN()
                      : (s == "inf" ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity());
  }
  return r.get<double>();
}

}  // namespace

std::string table_to_json_text(const Table& t) {
  nlohmann::json j;
  j["id"] = t.id;
  j["title"] = t.title;
  j["caption"] = t.caption;
  for (const auto& c : t.columns) j["columns"].push_back({c.name, c.unit, c.format, c.description, c.timing, c.interval});
  j["rows"] = nlohmann::json::array();
  for (const auto& row : t.rows) {
    nlohmann::json r = nlohmann::json::array();
    for (const auto& c : row) r.push_back(cell_to_json(c));
    j["rows"].push_back(r);
  }
  j["metadata"] = t.metadata;
  j["csv_only"] = t.csv_only;
  j["headline"] = t.headline;
  j["lead"] = t.lead;
  j["lead_figures"] = t.lead_figures;
  j["figures"] = nlohmann::json::array();
  for (const auto& f : t.figures)
    j["figures"].push_back({{"id", f.id}, {"title", f.title}, {"x", f.x}, {"y", f.y}, {"series", f.series},
                            {"panels", f.panels}, {"log_x", f.log_x}, {"log_y", f.log_y}, {"slopes", f.slopes},
                            {"small_multiples", f.small_multiples}, {"deviation", f.deviation},
                            {"overlay", f.overlay}, {"caption", f.caption}, {"kind", f.kind}, {"values", f.values},
                            {"positions", f.positions}, {"value_label", f.value_label}, {"arrows", f.arrows}});
  return j.dump();
}

Table table_from_json_text(const std::string& text) {
  const auto j = nlohmann::json::parse(text);
  Table t;
  t.id = j["id"];
  t.title = j["title"];
  t.caption = j["caption"];
  for (const auto& c : j["columns"])
    t.columns.push_back({c[0], c[1], c[2], c[3], c.size() > 4 && c[4].get<bool>(),
                         c.size() > 5 ? c[5].get<std::pair<std::string, std::string>>() : std::pair<std::string, std::string>{}});
  for (const auto& r : j["rows"]) {
    std::vector<Cell> row;
    for (const auto& c : r) row.push_back(cell_from_json(c));
    t.rows.push_back(std::move(row));
  }
  t.metadata = j["metadata"].get<std::vector<std::pair<std::string, std::string>>>();
  t.csv_only = j["csv_only"];
  t.headline = j["headline"];
  t.lead = j.value("lead", false);
  t.lead_figures = j.value("lead_figures", false);
  for (const auto& f : j["figures"])
    t.figures.push_back({f["id"], f["title"], f["x"], f["y"], f["series"], f["panels"], f["log_x"], f["log_y"],
                         f["slopes"], f["small_multiples"], f["deviation"], f.value("overlay", ""),
                         f.value("caption", ""), f.value("kind", ""), f.value("values", std::vector<std::string>{}),
                         f.value("positions", std::vector<double>{}), f.value("value_label", ""), f.value("arrows", "")});
  return t;
}

}  // namespace nsb
