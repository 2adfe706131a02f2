#include <catch2/catch.hpp>

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
