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

TEST_CASE("LaTeX tables: symbols typeset, numbers right-aligned in math, title apart from caption, longtable",
          "[studies][tables]") {
  const std::string tex = nsb::to_latex(hostile_table());
  CHECK_THAT(tex, Catch::Contains("{}[$\\theta$=0.5, $\\alpha$=0.9, $\\mu$=0.3, $\\rho$\\_inf]"));
  // label (text) l; err, order and steps numbers r (err holds one text, "diverged", among numbers).
  CHECK_THAT(tex, Catch::Contains("\\begin{longtable}{@{}lrrr@{}}"));
  CHECK_THAT(tex, Catch::Contains("$1.50\\times 10^{-3}$ & $1.98$ & $10$ \\\\"));
  CHECK_THAT(tex, Catch::Contains("$-2.25\\times 10^{-12}$ & n/a & $20$"));
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

TEST_CASE("Markdown tables: a '|' in a label is escaped, the row keeps its cells", "[studies][tables]") {
  const std::string md = nsb::markdown_grid(hostile_table());
  CHECK_THAT(md, Catch::Contains("| a\\|b | -2.25e-12 | n/a | 20 |"));
  CHECK_THAT(md, Catch::Contains("| x\\input /etc/hostname \\relax | 1.50e-03 | 1.98 | 10 |"));
}
