#pragma once
// A study's result: a table with typed columns (name, unit, number format), rows, and the
// metadata needed to cite and regenerate it. Writers give CSV (raw numbers, full
// precision), Markdown and LaTeX (booktabs), each stamped with the parameters, build type,
// compiler and git revision.
#include <filesystem>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace nsb {

struct Column {
  std::string name;
  std::string unit;      // "" when dimensionless
  std::string format;    // fmt spec for Markdown/LaTeX, e.g. "{:.3e}"; CSV keeps full precision
  std::string description;
};

// Empty cell (monostate) reads "n/a"; a diverged case writes text such as "diverged".
using Cell = std::variant<std::monostate, double, long, std::string>;

struct Table {
  std::string id;      // file stem: <out>/<id>.csv, .md, .tex
  std::string title;
  std::string caption; // what the table shows, norms stated
  std::vector<Column> columns;
  std::vector<std::vector<Cell>> rows;
  std::vector<std::pair<std::string, std::string>> metadata;  // study parameters

  void add_row(std::vector<Cell> row);  // throws std::logic_error on a width mismatch
};

std::string to_csv(const Table& table);
std::string to_markdown(const Table& table);
std::string to_latex(const Table& table);

// Writes <dir>/<id>.csv, .md and .tex, each whole or not at all.
void write_table(const Table& table, const std::filesystem::path& dir);

}  // namespace nsb
