// Pivot tables (rows = "pivot"): a case-table column spread over one column per value of another.
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/parameters.hpp"
#include "studies/measures.hpp"

namespace nsb::study_files {

namespace {

// A pivot's order (FileTable::order): the point of one run of its row r, (its column `of`, its
// value; NaN when its outcome is not ok), in the order of the runs.
void pivot_order_point(const FileTable& d, const Table& runs, const std::vector<Cell>& row, std::size_t r,
                       std::vector<std::vector<double>>& x, std::vector<std::vector<double>>& y) {
  if (x.size() <= r) x.resize(r + 1), y.resize(r + 1);
  const bool ok = row[column_index(runs, "outcome")] == Cell{std::string(status_name(RunStatus::Ok))};
  x[r].push_back(cell_number(row[column_index(runs, d.order->of)]));
  y[r].push_back(ok ? cell_number(row[column_index(runs, d.columns.back().of)]) : kNaN);
}

// Its column: by default "order against <of>", two significant digits.
Column pivot_order_column(const FileTable& d, const Table& runs) {
  const Column& of = runs.columns[column_index(runs, d.order->of)];
  return declared_column({"order against " + of.name, "", kOrderFormat, fmt::format("least-squares slope of log(value) against log({})", of.name)},
                         *d.order);
}

}  // namespace

// rows = "pivot" (FileTable::across): from the case table `runs` with every column.
Table pivot_table(const StudySpec& spec, const FileTable& d, const Table& runs) {
  const std::size_t across = column_index(runs, d.across), outcome = column_index(runs, "outcome");
  const std::size_t value = column_index(runs, d.columns.back().of);
  std::vector<std::size_t> keys;
  for (std::size_t k = 0; k + 1 < d.columns.size(); ++k) keys.push_back(column_index(runs, d.columns[k].of));
  std::vector<std::vector<Cell>> rows;  // the key cells, then one cell per spread value
  std::vector<std::string> spread;
  std::map<std::pair<std::size_t, std::size_t>, Cell> cells;
  std::vector<std::vector<double>> order_x, order_y;  // d.order: each row's runs
  for (const auto& row : runs.rows) {
    if (!d.applies_to(std::get<std::string>(row[column_index(runs, "problem")])) || !shows_run(d, runs, row)) continue;
    std::vector<Cell> key;
    for (const std::size_t k : keys) key.push_back(row[k]);
    const std::size_t r = static_cast<std::size_t>(std::find(rows.begin(), rows.end(), key) - rows.begin());
    if (r == rows.size()) rows.push_back(key);
    const std::string at = pivot_value_text(row[across]);
    const std::size_t a = static_cast<std::size_t>(std::find(spread.begin(), spread.end(), at) - spread.begin());
    if (a == spread.size()) spread.push_back(at);
    cells[{r, a}] = row[outcome] == Cell{std::string(status_name(RunStatus::Ok))} ? row[value] : row[outcome];
    if (d.order) pivot_order_point(d, runs, row, r, order_x, order_y);
  }
  Table out;
  for (std::size_t k = 0; k < keys.size(); ++k) out.columns.push_back(declared_column(runs.columns[keys[k]], d.columns[k]));
  for (const std::string& at : spread) {
    Column c = declared_column(runs.columns[value], d.columns.back());
    const auto hole = c.name.find("{}");
    c.name = hole == std::string::npos ? c.name + ", " + at : c.name.replace(hole, 2, at);
    out.columns.push_back(c);
  }
  if (d.order) out.columns.push_back(pivot_order_column(d, runs));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t a = 0; a < spread.size(); ++a) {
      const auto it = cells.find({r, a});
      rows[r].push_back(it == cells.end() ? Cell(d.columns.back().missing.value_or("")) : it->second);
    }
    if (d.order) rows[r].push_back(number_cell(fitted_order(order_x[r], order_y[r])));
    out.add_row(std::move(rows[r]));
  }
  // Its figures: x, series and panels name key columns (by `of`, drawn under their headers), y a
  // spread column by its header (the reader checked both).
  const auto header = [&](const std::string& of) { return declared_header(d, runs, of).value(); };
  for (const FileFigure& f : spec.figures) {
    if (f.table != d.id) continue;
    Figure figure = declared_figure(spec, f);
    figure.x = header(f.x);
    for (auto& s : figure.series) s = header(s);
    for (auto& p : figure.panels) p = header(p);
    std::vector<std::string> names;
    for (const Column& c : out.columns) names.push_back(c.name);
    if (std::find(names.begin(), names.end(), f.y) == names.end())
      throw InputError(fmt::format("figure {}: y '{}' is not a column of table {}; its runs gave: {}", f.id, f.y, d.id, fmt::join(names, ", ")));
    out.figures.push_back(figure);
  }
  return out;
}

}  // namespace nsb::study_files
