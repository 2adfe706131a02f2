#include <catch2/catch.hpp>

#include <algorithm>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

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

// CI, stop 61: the claims table quotes the talk in French; a guillemet needs the T1 encoding and
// stopped a default (OT1) document.
TEST_CASE("LaTeX tables: French guillemets become quote ligatures any font encoding has", "[studies][tables]") {
  nsb::Table t;
  t.id = "quotes";
  t.columns = {{"claim", "", "", ""}};
  t.add_row({std::string("un int\u00e9grateur de type \u00ab\u00a0time stepping\u00a0\u00bb, \u00abbis\u00bb, \u00ab ter \u00bb")});
  const std::string tex = nsb::to_latex(t);
  CHECK_THAT(tex, Catch::Contains("un int\u00e9grateur de type ``time stepping'', ``bis'', ``ter''"));
  CHECK_THAT(tex, !Catch::Contains("\u00ab") && !Catch::Contains("\u00bb"));
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

namespace {

// The cells of every row of the Markdown tables in `md` (lines "| a | b |"; "\|" is a bar inside a cell).
std::vector<std::string> markdown_cells(const std::string& md) {
  std::vector<std::string> cells;
  std::istringstream in(md);
  for (std::string line; std::getline(in, line);) {
    if (line.size() < 2 || line.front() != '|' || line.back() != '|') continue;
    std::string cell;
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      if (line[i] == '\\' && line[i + 1] == '|') {
        cell += '|';
        ++i;
      } else if (line[i] == '|') {
        cells.push_back(cell.substr(1, cell.size() - 2));  // the spaces around the bar
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    cells.push_back(cell.substr(1, cell.size() - 2));
  }
  return cells;
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

nsb::Table reasons_table() {
  nsb::Table t;
  t.id = "reasons";
  t.columns = {{"integrator", "", "", ""}, {"err", "", "{:.2e}", ""}, {"note", "", "", ""}};
  const std::string why = "integrator cd-lagrange needs a diagonal mass matrix; problem signorini-bar has a non-diagonal one";
  t.add_row({std::string("a"), nsb::Cell{}, std::string("declined: " + why)});
  t.add_row({std::string("b"), nsb::Cell{}, std::string("n/a: " + why)});
  t.add_row({std::string("c"), nsb::Cell{}, std::string("unsupported: --integrator bullet: not a rigid problem")});
  t.add_row({std::string("d"), 1.0, std::string("diverged: step limit 100000 reached")});
  t.add_row({std::string("e"), 2.0, std::string("u time err n/a: modal-exact needs at most 2000 dofs")});
  t.add_row({std::string("alpha 30, mu 0.8, v0 2: stops, sticks"), 3.0, std::string("declined")});
  t.add_row({std::string("f"), 4.0, std::string("over budget")});
  return t;
}

}  // namespace

// Issue 51, item 6: a run's reason once per table, the verdict in the row under one name.
TEST_CASE("tables: a run's reason is a numbered footnote, once per table; the row keeps its verdict", "[studies][tables]") {
  const std::string md = nsb::markdown_grid(reasons_table());
  // The same reason twice (declined, n/a), one number; "declined" and "unsupported" print as n/a.
  CHECK_THAT(md, Catch::Contains("| a | n/a | n/a [1] |\n| b | n/a | n/a [1] |\n| c | n/a | n/a [2] |\n"));
  CHECK_THAT(md, Catch::Contains("| d | 1.00e+00 | diverged [3] |\n| e | 2.00e+00 | u time err n/a [4] |\n"));
  // A label's colon is no verdict's; a bare verdict stays in its row, under its one name.
  CHECK_THAT(md, Catch::Contains("| alpha 30, mu 0.8, v0 2: stops, sticks | 3.00e+00 | n/a |\n| f | 4.00e+00 | over budget |\n"));
  CHECK_THAT(md, Catch::EndsWith("|\n\n[1] integrator cd-lagrange needs a diagonal mass matrix; problem signorini-bar has a "
                                 "non-diagonal one\\\n[2] --integrator bullet: not a rigid problem\\\n[3] step limit 100000 "
                                 "reached\\\n[4] modal-exact needs at most 2000 dofs\n"));
  CHECK(occurrences(md, "needs a diagonal mass matrix") == 1);
  CHECK_THAT(md, !Catch::Contains("declined") && !Catch::Contains("unsupported"));
  // The full Markdown: the notes between the table and the columns' descriptions.
  nsb::Table described = reasons_table();
  described.columns[1].description = "an error";
  CHECK_THAT(nsb::to_markdown(described), Catch::Contains("reached\\\n[4] modal-exact needs at most 2000 dofs\n\n- `err`: an error\n"));
  // LaTeX: the same cells, the notes after the caption.
  const std::string tex = nsb::to_latex(reasons_table());
  CHECK_THAT(tex, Catch::Contains("{}a & {n/a} & n/a [1] \\\\\n{}b & {n/a} & n/a [1] \\\\\n{}c & {n/a} & n/a [2] \\\\\n"));
  CHECK_THAT(tex, Catch::Contains(" [1] integrator cd-lagrange needs a diagonal mass matrix; problem signorini-bar has a non-diagonal one."
                                  " [2] --integrator bullet: not a rigid problem. [3] step limit 100000 reached."));
  CHECK(occurrences(tex, "needs a diagonal mass matrix") == 1);
  // The CSV keeps every text as it was.
  CHECK_THAT(nsb::to_csv(reasons_table()), Catch::Contains("\na,n/a,declined: integrator cd-lagrange needs") &&
                                               Catch::Contains("\nc,n/a,unsupported: --integrator bullet: not a rigid problem\n"));
}

TEST_CASE("tables: no Markdown cell over 300 characters; a long text shown in several rows is a footnote", "[studies][tables]") {
  nsb::Table t;
  t.id = "long";
  t.columns = {{"evidence", "", "", ""}, {"note", "", "", ""}};
  std::string evidence = "Hausdorff orders, as claimed:";
  while (evidence.size() <= nsb::kMaxCellChars) evidence += " signorini-bar singular u_contact 0.928;";
  const std::string bare(nsb::kRepeatedCellChars + 1, 'x'), once = bare + "y";
  t.add_row({evidence, bare});
  t.add_row({std::string("short"), bare});
  t.add_row({std::string("word"), once});
  const std::string md = nsb::markdown_grid(t);
  for (const auto& cell : markdown_cells(md)) CHECK(cell.size() <= nsb::kMaxCellChars);
  // The long text's first words (at most 80 characters, no word cut) and its number; the bare
  // reason of two rows a number alone; a text of one row under the limit printed whole.
  CHECK_THAT(md, Catch::Contains("| Hausdorff orders, as claimed: signorini-bar singular u_contact 0.928; ... [1] | [2] |\n"
                                 "| short | [2] |\n| word | " + once + " |\n"));
  CHECK_THAT(md, Catch::Contains("\n[1] " + evidence + "\\\n[2] " + bare + "\n"));
  // LaTeX: the same, every row's cells (lines "a & b \\\\") short, the long text once.
  const std::string tex = nsb::to_latex(t);
  std::istringstream rows(tex.substr(tex.find("\\endlastfoot")));
  for (std::string line; std::getline(rows, line) && line != "\\end{longtable}";)
    for (std::size_t begin = 0, end = 0; end != std::string::npos; begin = end + 3)
      CHECK((end = line.find(" & ", begin), std::min(end, line.size()) - begin) <= nsb::kMaxCellChars);
  std::string escaped = evidence;  // as TeX reads it
  for (std::size_t at = escaped.find('_'); at != std::string::npos; at = escaped.find('_', at + 2)) escaped.insert(at, "\\");
  CHECK(occurrences(tex, escaped) == 1);
}

TEST_CASE("tables: counts print as integers, fitted orders with two significant digits", "[studies][tables]") {
  nsb::Table t;
  t.id = "digits";
  t.columns = {{"value", "", "{:.3e}", ""}, {"order", "", nsb::kOrderFormat, ""}};
  t.add_row({4599978L, 1.9449});
  t.add_row({0L, 2.0});
  t.add_row({981L, 0.928});
  t.add_row({1.5e-3, -0.0604});
  t.add_row({2.5, 37.21});
  const std::string md = nsb::markdown_grid(t);
  CHECK_THAT(md, Catch::Contains("| 4599978 | 1.9 |\n| 0 | 2.0 |\n| 981 | 0.93 |\n| 1.500e-03 | -0.060 |\n| 2.500e+00 | 37.0 |\n"));
  CHECK_THAT(nsb::to_latex(t), Catch::Contains("\n4599978 & 1.9 \\\\\n0 & 2.0 \\\\\n"));
  CHECK_THAT(nsb::to_csv(t), Catch::Contains("\n4599978,1.9449\n0,2\n981,0.928\n"));
}

TEST_CASE("tables: a fitted order and its interval in one Markdown and LaTeX cell, the CSV's three columns kept", "[studies][tables]") {
  nsb::Table t;
  t.id = "interval";
  t.columns = {{"integrator", "", "", ""}, {"order", "", nsb::kOrderFormat, "slope"}, {"CI low", "", nsb::kOrderFormat, ""},
               {"CI high", "", nsb::kOrderFormat, ""}, {"points", "", "", ""}};
  t.columns[1].interval = {"CI low", "CI high"};
  t.add_row({std::string("a"), 1.9449, 1.8123, 2.0345, 4L});
  t.add_row({std::string("b"), nsb::Cell{}, nsb::Cell{}, nsb::Cell{}, 1L});
  const std::string md = nsb::to_markdown(t);
  CHECK_THAT(md, Catch::Contains("| integrator | order | points |\n| --- | --- | --- |\n| a | 1.9 [1.8, 2.0] | 4 |\n| b | n/a | 1 |\n"));
  CHECK_THAT(md, Catch::Contains("- `order`: slope; with its 95% interval [CI low, CI high]\n"));
  CHECK_THAT(nsb::to_latex(t), Catch::Contains("{}a & 1.9 [1.8, 2.0] & 4 \\\\\n"));
  CHECK_THAT(nsb::to_csv(t), Catch::Contains("integrator,order,CI low,CI high,points\na,1.9449,1.8123,2.0345,4\nb,n/a,n/a,n/a,1\n"));
  // The shards' JSON keeps it.
  CHECK(nsb::table_from_json_text(nsb::table_to_json_text(t)).columns[1].interval == t.columns[1].interval);
}
