#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>
#include <string>

#include "studies/table.hpp"

namespace {

// A label an attacker (or a careless plugin) could choose: TeX commands, Markdown's cell bar.
nsb::Table hostile_table() {
  nsb::Table t;
  t.id = "hostile";
  t.title = "Hostile labels, theta and mu";
  t.caption = "A caption apart from the title.";
  t.columns = {{"label", "", "", ""}, {"err", "m", "{:.2e}", "an error"}, {"order", "", "{:.2f}", ""},
               {"steps", "", "", ""}};
  t.add_row({std::string("x\\input /etc/hostname \\relax"), 1.5e-3, 1.98, 10L});
  t.add_row({std::string("a|b"), -2.25e-12, std::numeric_limits<double>::quiet_NaN(), 20L});
  t.add_row({std::string("[theta=0.5, alpha=0.9, mu=0.3, rho_inf]"), std::string("diverged"), nsb::Cell{}, 30L});
  return t;
}

}  // namespace

TEST_CASE("LaTeX tables: every special character escaped, no command of a label reaches TeX", "[studies][tables]") {
  const std::string tex = nsb::to_latex(hostile_table());
  CHECK_THAT(tex, Catch::Contains("x\\textbackslash{}input /etc/hostname \\textbackslash{}relax"));
  CHECK_THAT(tex, !Catch::Contains("\\input") && !Catch::Contains("\\relax"));
  CHECK_THAT(tex, Catch::Contains("a\\textbar{}b"));
  // The escapes' own commands are left whole: no $\...$ inside \textbackslash.
  CHECK_THAT(tex, !Catch::Contains("text$"));
}

TEST_CASE("LaTeX tables: symbols typeset, numbers in siunitx S columns, title apart from caption, longtable",
          "[studies][tables]") {
  const std::string tex = nsb::to_latex(hostile_table());
  CHECK_THAT(tex, Catch::Contains("{}[$\\theta$=0.5, $\\alpha$=0.9, $\\mu$=0.3, $\\rho$\\_inf] & {diverged} & {n/a} & 30 \\\\"));
  // label (text) l; err, order (number formats) and steps (integers) S, each with room for its
  // numbers: err's sign, one digit, two decimals, a signed two-digit exponent (printed when 0,
  // as every err has one).
  CHECK_THAT(tex, Catch::Contains("\\begin{longtable}{@{}lS[table-format=-1.2e-2,print-zero-exponent]"
                                  "S[table-format=1.2]S[table-format=2]@{}}"));
  CHECK_THAT(tex, Catch::Contains("% needs \\usepackage{booktabs,longtable,siunitx}\n{\\small\n"));
  CHECK_THAT(tex, Catch::Contains("\\sisetup{round-mode=none,exponent-mode=input,group-digits=none,retain-negative-zero}\n"
                                  "\\begin{longtable}"));
  // Numbers raw, for siunitx; the header and the texts of number columns braced.
  CHECK_THAT(tex, Catch::Contains("label & {err [m]} & {order} & {steps} \\\\"));
  CHECK_THAT(tex, Catch::Contains(" & 1.50e-3 & 1.98 & 10 \\\\"));
  CHECK_THAT(tex, Catch::Contains("{}a\\textbar{}b & -2.25e-12 & {n/a} & 20 \\\\"));
  CHECK_THAT(tex, Catch::Contains("\\caption{Hostile labels, $\\theta$ and $\\mu$}\\label{tab:hostile}"));
  CHECK_THAT(tex, Catch::Contains("\\endhead") && Catch::Contains("\\endfirsthead") && Catch::Contains("\\endlastfoot"));
  // The caption's text is a note after the table, not run into the title.
  const auto caption = tex.find("A caption apart from the title.");
  REQUIRE(caption != std::string::npos);
  CHECK(caption > tex.find("\\end{longtable}"));
  CHECK_THAT(tex, Catch::Contains("err: an error."));
  // Balanced braces: TeX would read past the table otherwise (escaped braces do not count).
  long depth = 0;
  for (std::size_t i = 0; i < tex.size(); ++i) {
    if (tex[i] == '%') { i = tex.find('\n', i); continue; }  // the stamp's comment lines
    if (tex[i] == '\\') { ++i; continue; }
    depth += tex[i] == '{' ? 1 : tex[i] == '}' ? -1 : 0;
    REQUIRE(depth >= 0);
  }
  CHECK(depth == 0);
}

TEST_CASE("LaTeX tables: table-format from the numbers written, infinities braced, numbers of text columns through \\num",
          "[studies][tables]") {
  nsb::Table t;
  t.id = "formats";
  t.columns = {{"#", "", "", ""}, {"x", "", "{:.3g}", ""}, {"note", "", "", ""}, {"big", "", "{}", ""}};
  const double inf = std::numeric_limits<double>::infinity();
  t.add_row({1L, 0.0123, std::string("a"), 1e20});
  t.add_row({2L, 1.23e-5, std::string("b"), 0.5});
  t.add_row({3L, -123.0, 7L, 2.0});
  t.add_row({4L, inf, std::string("c"), -inf});
  const std::string tex = nsb::to_latex(t);
  // x: a sign, three digits ("-123"), four decimals ("0.0123"), a signed one-digit exponent
  // ("1.23e-5"), 10^0 not printed (not every x has an exponent); big: "1e+20" written 1e20.
  CHECK_THAT(tex, Catch::Contains("{@{}S[table-format=1]S[table-format=-3.4e-1]lS[table-format=1.1e2]@{}}"));
  // A first S column needs no "{}" guard: its cells open with a digit, a sign or a brace.
  CHECK_THAT(tex, Catch::Contains("\n1 & 0.0123 & a & 1e20 \\\\\n2 & 1.23e-5 & b & 0.5 \\\\\n"));
  CHECK_THAT(tex, Catch::Contains("\n3 & -123 & \\num{7} & 2 \\\\\n"));
  CHECK_THAT(tex, Catch::Contains("\n4 & {$\\infty$} & c & {$-\\infty$} \\\\\n"));
  CHECK_THAT(tex, Catch::Contains("{\\#} & {x} & note & {big} \\\\"));
}

TEST_CASE("Markdown tables: a '|' in a label is escaped, the row keeps its cells", "[studies][tables]") {
  const std::string md = nsb::markdown_grid(hostile_table());
  CHECK_THAT(md, Catch::Contains("| a\\|b | -2.25e-12 | n/a | 20 |"));
  CHECK_THAT(md, Catch::Contains("| x\\input /etc/hostname \\relax | 1.50e-03 | 1.98 | 10 |"));
}

// Issue 30, finding 9: a '\r' went unquoted into CSV, NUL and ESC bytes reached every
// format, and a newline in a label or title split Markdown rows and added headings.
TEST_CASE("tables: control bytes and newlines in labels never split a row, a heading or a comment", "[studies][tables]") {
  nsb::Table t;
  t.id = "controls";
  t.title = "title\n# injected heading";
  t.caption = "caption\n\n| a | fake row |";
  t.columns = {{"label\nsplit", "", "", "a\ndescription"}, {"err", "", "{:.2e}", ""}};
  t.add_row({std::string("cr\rin"), 1.0});
  t.add_row({std::string("nul\0esc\x1b[31mred", 15), 2.0});
  t.add_row({std::string("new\nline"), 3.0});
  t.metadata = {{"study_file", "a\nb.toml"}};
  const auto lines = [](const std::string& text) {
    std::vector<std::string> v;
    std::size_t begin = 0;
    for (std::size_t end; (end = text.find('\n', begin)) != std::string::npos; begin = end + 1) v.push_back(text.substr(begin, end - begin));
    return v;
  };
  const auto has_control = [](const std::string& text, const std::string& kept) {
    return std::any_of(text.begin(), text.end(), [&](char c) {
      return (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) && kept.find(c) == std::string::npos;
    });
  };
  const std::string csv = nsb::to_csv(t), md = nsb::to_markdown(t), tex = nsb::to_latex(t);
  CHECK_FALSE(has_control(md, "\n"));
  CHECK_FALSE(has_control(tex, "\n"));
  CHECK_FALSE(has_control(csv, "\n\r"));  // inside quotes only
  CHECK_THAT(csv, Catch::Contains("\"cr\rin\",1\n") && Catch::Contains("\"new\nline\",3\n") &&
                      Catch::Contains("nul\\x00esc\\x1b[31mred,2\n") && Catch::Contains("# study_file: a b.toml\n"));
  CHECK_THAT(md, Catch::Contains("| nul\\x00esc\\x1b[31mred | 2.00e+00 |"));
  // Markdown: one heading, the grid's lines all rows, the caption one paragraph.
  int headings = 0, rows = 0;
  for (const auto& line : lines(md)) {
    headings += line.rfind("#", 0) == 0;
    rows += line.rfind("|", 0) == 0;
  }
  CHECK(headings == 1);
  CHECK(rows == 2 + 3);
  CHECK_THAT(md, Catch::StartsWith("## title # injected heading\n\ncaption  | a | fake row |\n"));
  // TeX: no blank line (a paragraph break) inside the table, every comment line one line.
  for (const auto& line : lines(tex)) CHECK_FALSE(line.empty());
  CHECK_THAT(tex, Catch::Contains("% study_file: a b.toml\n") && Catch::Contains("new line & "));
}
