#pragma once
// A study's result: a table with typed columns (name, unit, number format), rows, and the
// metadata needed to cite and regenerate it. Writers give CSV (raw numbers, full
// precision), Markdown and LaTeX (booktabs, siunitx), each stamped with the parameters, build
// type, compiler and git revision.
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace nsb {

struct Column {
  std::string name;
  std::string unit;      // "" when dimensionless
  // fmt spec for Markdown/LaTeX, e.g. "{:.3e}"; CSV keeps full precision. Integer cells (long)
  // print whole whatever it says.
  std::string format;
  std::string description;
  bool timing = false;   // a CPU time or derived from one (machine, load): not compared by --verify
  // A fitted value's 95% interval: the names of the columns of its low and high ends. Markdown
  // and LaTeX show "value [low, high]" in this column ("1.9 [1.8, 2.0]", each in its column's
  // format) and leave those two out; the CSV keeps the three columns. Empty: none.
  std::pair<std::string, std::string> interval = {};
};

// A fitted or observed order and its interval's ends: two significant digits, trailing zeros kept
// ("1.9", "2.0", "0.93"; fmt's '#' writes 37.2 as "37.0").
inline constexpr const char* kOrderFormat = "{:#.2g}";

// Empty cell (monostate) reads "n/a"; a diverged case writes text such as "diverged".
using Cell = std::variant<std::monostate, double, long, std::string>;

// Markdown and LaTeX keep every cell short and every reason said once: a text cell goes to a
// footnote, numbered once per table (the same text, the same number), listed under the table as
// "[k] text", by the first of these rules that applies:
// - it is a run's reason, "verdict: reason" with the verdict a run status (n/a, diverged,
//   over budget, interrupted, energy blow-up, penetration), alone or after labels ("u time err
//   n/a: ..."): the row says "n/a [k]", the footnote the reason. The declined status has one
//   name, n/a: "declined" and "unsupported", older spellings of it, print as n/a, with a
//   reason or without;
// - it is over kMaxCellChars characters: the row shows its first words, "... [k]";
// - it is over kRepeatedCellChars characters and more than one row shows it (a declined run's
//   bare reason in each of its rows): the row says "[k]".
// Other texts and every number print whole. The CSV keeps every text as it is.
inline constexpr std::size_t kMaxCellChars = 300;
inline constexpr std::size_t kRepeatedCellChars = 80;

// A figure drawn from a table's CSV by scripts/figures.py: y against x, one line per
// distinct value of the `series` columns, one panel per distinct value of the `panels`
// columns. Rows whose x or y is not a number (n/a, diverged) are left out.
struct Figure {
  std::string id;     // <out>/figures/<id>.png and .pdf
  std::string title;
  std::string x, y;   // column names
  std::vector<std::string> series;
  std::vector<std::string> panels;
  bool log_x = false;
  bool log_y = false;
  // Reference slopes drawn as triangles on a log-log panel: exponents p of y ~ x^p (1 and 2
  // for errors against dt; -1 and -2 against a mesh's N).
  std::vector<double> slopes = {};
  // One panel per value of the first series column (the scheme), shared axes; the other
  // series and panel columns are lines within it.
  bool small_multiples = false;
  // y is a ratio to its start (E/E0): draw its signed deviation y - 1.
  bool deviation = false;
  // Small multiples: the value of the first series column (the exact solution) whose lines are
  // drawn in every panel, black and dashed, over the scheme's own.
  std::string overlay = {};
  // What the figure shows and at which parameters: index.md prints it under the picture.
  std::string caption = {};
  // Pictures of the motion, other than lines (kind empty):
  // - "space_time": a colour map of a field over position (horizontal) and time, the column `y`
  //   (vertical; `x` empty), one panel per distinct value of `panels`; each row is one time, the
  //   field's values at the positions `positions` in the columns `values` (a shared, diverging
  //   colour scale, `value_label`).
  // - "deformed": one panel per distinct value of `panels`, each row a quadrilateral cell by its
  //   corners' columns `values` (x1, y1, ..., x4, y4, deformed) coloured by the column `y` (`x`
  //   empty); the contact impulses, arrows from (x, y) along (Lambda_x, Lambda_y), in the table
  //   `arrows` (the same panel columns, then x, y, Lambda_x, Lambda_y).
  std::string kind = {};
  std::vector<std::string> values = {};
  std::vector<double> positions = {};
  std::string value_label = {};
  std::string arrows = {};
};

struct Table {
  std::string id;      // file stem: <out>/<id>.csv, .md, .tex
  std::string title;
  std::string caption; // what the table shows, norms stated
  std::vector<Column> columns;
  std::vector<std::vector<Cell>> rows;
  std::vector<std::pair<std::string, std::string>> metadata;  // study parameters
  std::vector<Figure> figures;
  bool csv_only = false;  // raw data behind a figure (histories): no Markdown or LaTeX
  bool headline = false;  // also shown first in index.md, under "Headline ranking"
  bool lead = false;      // shown in full at the very top of index.md, before the headline ranking
  bool lead_figures = false;  // its figures (not the table) shown at the top with the lead tables

  void add_row(std::vector<Cell> row);  // throws std::logic_error on a width mismatch
};

std::string to_csv(const Table& table);
std::string to_markdown(const Table& table);
// The Markdown table alone (header, rule, rows) and its footnotes, as to_markdown writes it.
std::string markdown_grid(const Table& table);
std::string to_latex(const Table& table);

// "name [unit]": a column's header in every format.
std::string header_text(const Column& column);

// The figures of the tables as JSON for scripts/figures.py (CSV file, header texts).
std::string figures_to_json(const std::vector<Table>& tables);

// Lossless JSON form of a table (shard files of single-function studies).
std::string table_to_json_text(const Table& table);
Table table_from_json_text(const std::string& text);

// Writes <dir>/<id>.csv, .md and .tex, each whole or not at all.
void write_table(const Table& table, const std::filesystem::path& dir);

}  // namespace nsb
