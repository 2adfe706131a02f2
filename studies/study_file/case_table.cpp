// The pieces every declared table is built from: its columns and figures under their declared
// names, the runs it shows, and the case table itself (rows = "case").
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "studies/measures.hpp"

namespace nsb::study_files {

namespace {

// A declared figure's id: <name>_<id>, or <id> with study.figures = "declared".
std::string figure_id(const StudySpec& spec, const FileFigure& f) { return spec.declared_figures_only ? f.id : spec.name + "_" + f.id; }

// A status cell of a run that never started (declined: "n/a: why").
bool declined(const Cell& status) {
  const auto* text = std::get_if<std::string>(&status);
  return text && text->rfind(kDeclinedStatus, 0) == 0;
}

// Whether column i of case table d shows the run's outcome (not_ok = "outcome": a measure's
// column of a run whose outcome is not ok).
bool shows_outcome(const FileTable& d, std::size_t i, const Cell& outcome) {
  return !d.outcome_columns.empty() && outcome != Cell{std::string(status_name(RunStatus::Ok))} &&
         std::find(d.outcome_columns.begin(), d.outcome_columns.end(), d.columns[i].of) != d.outcome_columns.end();
}

}  // namespace

// "dt = ..." or "tol = ...", the number in `format` (default {:.2e} for dt, {:.1e} for tol).
std::string run_label(const Json& c, const std::optional<std::string>& format) {
  const bool tol = !c["tol"].is_null();
  const double x = c[tol ? "tol" : "dt"].get<double>();
  return fmt::format("{} = {}", tol ? "tol" : "dt", fmt::format(fmt::runtime(format.value_or(tol ? "{:.1e}" : "{:.2e}")), x));
}

// A figure the file declares, as the report draws it.
Figure declared_figure(const StudySpec& spec, const FileFigure& f) {
  Figure figure{figure_id(spec, f), f.title, f.x, f.y, f.series, f.panels, f.log_x, f.log_y, f.slopes};
  figure.small_multiples = f.small_multiples;
  figure.deviation = f.deviation;
  figure.caption = f.caption;
  return figure;
}

// A declared column: the source column under its own header, unit, format and description.
Column declared_column(const Column& source, const FileColumn& d) {
  return {d.header.value_or(source.name), d.unit.value_or(source.unit), d.format.value_or(source.format),
          d.description.value_or(source.description), source.timing};
}

std::size_t column_index(const Table& t, const std::string& name) {
  const auto it = std::find_if(t.columns.begin(), t.columns.end(), [&](const Column& c) { return c.name == name; });
  if (it == t.columns.end()) throw std::logic_error(fmt::format("table {} has no column '{}'", t.id, name));
  return static_cast<std::size_t>(it - t.columns.begin());
}

std::optional<std::string> declared_header(const FileTable& d, const Table& source, const std::string& of) {
  const auto c = std::find_if(d.columns.begin(), d.columns.end(), [&](const FileColumn& c) { return c.of == of; });
  if (c == d.columns.end()) return std::nullopt;
  return declared_column(source.columns[column_index(source, of)], *c).name;
}

// A case-table cell as a number (NaN: none, or a text).
double cell_number(const Cell& cell) {
  return std::holds_alternative<double>(cell) ? std::get<double>(cell) : std::holds_alternative<long>(cell) ? static_cast<double>(std::get<long>(cell)) : kNaN;
}

// Whether a table of some runs (or a case table) shows the run of this case-table row
// (FileTable::where, drop_above).
bool shows_run(const FileTable& d, const Table& runs, const std::vector<Cell>& row) {
  for (const auto& [name, want] : d.where) {
    const Cell& cell = row[column_index(runs, name)];
    if (std::holds_alternative<std::string>(want) ? cell != want : cell_number(cell) != std::get<double>(want)) return false;
  }
  return std::none_of(d.drop_above.begin(), d.drop_above.end(),
                      [&](const auto& limit) { return std::abs(cell_number(row[column_index(runs, limit.first)])) > limit.second; }) &&
         std::none_of(d.except.begin(), d.except.end(), [&](const auto& one) { return row[column_index(runs, one.first)] == one.second; });
}

// rows = "case": the work-precision rows (those `where` and `drop_above` keep), their columns
// picked, ordered and renamed; the first such table carries the work-precision figures whose
// columns it shows, under the new names.
Table case_table(const FileTable& d, const Table& runs, bool with_figures) {
  Table out;
  std::vector<std::size_t> at;
  for (const FileColumn& c : d.columns) {
    at.push_back(column_index(runs, c.of));
    out.columns.push_back(declared_column(runs.columns[at.back()], c));
  }
  const auto status = std::find_if(runs.columns.begin(), runs.columns.end(), [](const Column& c) { return c.name == "status"; });
  const std::size_t problem = column_index(runs, "problem");
  const std::size_t note = d.declined_reason.empty() ? 0 : column_index(runs, "note");  // a declined run's: the scheme's reason
  // integrators = [...] (case rows only): the file's label of each run.
  const std::size_t label = d.integrators.empty() ? 0 : column_index(runs, "integrator label");
  const std::size_t outcome = d.outcome_columns.empty() ? 0 : column_index(runs, "outcome");  // not_ok = "outcome"
  for (const auto& row : runs.rows) {
    // A table of some runs picked its runs itself (its `all` holds their series, not the case columns).
    if (!d.applies_to(std::get<std::string>(row[problem])) || (d.rows == "case" && !shows_run(d, runs, row))) continue;
    if (!d.integrators.empty() &&
        std::find(d.integrators.begin(), d.integrators.end(), std::get<std::string>(row[label])) == d.integrators.end())
      continue;
    const bool blank = d.declined_blank && status != runs.columns.end() && declined(row[static_cast<std::size_t>(status - runs.columns.begin())]);
    std::vector<Cell> cells;
    const Cell none = d.declined_empty ? Cell(std::string()) : Cell{};
    for (std::size_t i = 0; i < at.size(); ++i) {
      const Cell& cell = row[at[i]];
      const bool missing = std::holds_alternative<std::monostate>(cell) && d.columns[i].missing;
      const Cell blanked = d.columns[i].of == d.declined_reason ? row[note] : none;
      cells.push_back(blank && !asked_column(d.columns[i].of) ? blanked : missing ? Cell(*d.columns[i].missing) : cell);
      if (shows_outcome(d, i, row[outcome])) cells.back() = row[outcome];
    }
    out.add_row(std::move(cells));
  }
  if (!with_figures) return out;
  for (Figure f : runs.figures) {
    const auto rename = [&](std::string& name) {
      const auto header = declared_header(d, runs, name);
      return header && (name = *header, true);
    };
    bool shown = rename(f.x) && rename(f.y);
    for (auto& s : f.series) shown = shown && rename(s);
    for (auto& s : f.panels) shown = shown && rename(s);
    if (shown) out.figures.push_back(f);
  }
  return out;
}

// A cell as the text of a pivot's column header.
std::string pivot_value_text(const Cell& cell) {
  if (const auto* text = std::get_if<std::string>(&cell)) return *text;
  if (const auto* n = std::get_if<long>(&cell)) return fmt::format("{}", *n);
  if (const auto* x = std::get_if<double>(&cell)) return fmt::format("{}", *x);
  return "n/a";
}

}  // namespace nsb::study_files
