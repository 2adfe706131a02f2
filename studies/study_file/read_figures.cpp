// Reading [[figure]]s, and checking a figure against the declared table it is drawn from.
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <utility>
#include <vector>

namespace nsb::study_files {

bool is_file_stem(const std::string& id) {
  return !id.empty() && std::all_of(id.begin(), id.end(), [](char ch) {
    return std::islower(static_cast<unsigned char>(ch)) || std::isdigit(static_cast<unsigned char>(ch)) || ch == '_';
  });
}

// An optional array of tables [[key]], each checked to be a table; empty when absent.
const Json& optional_tables(const Checker& c, const Json& root, const char* key) {
  static const Json none = Json::array();
  const Json* list = c.find(root, key);
  if (!list) return none;
  c.expect(*list, key, list->is_array(), fmt::format("one or more [[{}]] tables", key));
  for (std::size_t i = 0; i < list->size(); ++i) c.expect((*list)[i], element(key, i), (*list)[i].is_object(), "a table");
  return *list;
}

namespace {

// The columns a figure of a history or samples table may draw: any of their columns (its
// table's checked with the tables), and the problem parameters.
std::vector<std::string> figure_table_columns(const std::vector<std::string>& parameters) {
  std::vector<std::string> columns = history_column_names();
  for (const auto* more : {&samples_column_names(), &periodic_column_names(), &trajectory_column_names(), &flights_column_names()})
    for (const auto& name : *more)
      if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
  columns.insert(columns.end(), parameters.begin(), parameters.end());
  return columns;
}

// The columns a figure of the work-precision table may draw.
std::vector<std::string> figure_run_columns(const Checker& c, const Json& root, const StudySpec& spec, const std::vector<std::string>& parameters) {
  std::vector<std::string> columns{"problem", "integrator", "dt", "tol"};
  for (const auto& m : spec.measures) columns.push_back(m.label);
  columns.insert(columns.end(), {"CPU", "steps", "F_int evals"});
  columns.insert(columns.end(), parameters.begin(), parameters.end());  // a problem parameter: e.g. a panel per mass model
  // Drawn from a declared case table: any column it may show too (e.g. a panel per "problem name").
  if (c.find(root, "table"))
    for (const auto& name : run_column_names())
      if (std::find(columns.begin(), columns.end(), name) == columns.end()) columns.push_back(name);
  return columns;
}

// A figure's id: a file stem, not used by an earlier figure, nor (unless the study draws only
// its declared figures) the id of a figure the study draws itself.
void check_figure_id(const Checker& c, const std::string& path, const std::string& id, const std::vector<FileFigure>& earlier,
                     bool declared_only) {
  if (!is_file_stem(id)) c.fail(child(path, "id"), fmt::format("'{}' is not a file name of a-z, 0-9 and _", id), "[a-z0-9_]+");
  for (const auto& g : earlier)
    if (g.id == id) c.fail(child(path, "id"), fmt::format("id '{}' used twice", id), "distinct ids");
  if (!declared_only && (id == "work_precision" || id == "work_precision_evals" || id == "energy_history" || id.rfind("convergence_", 0) == 0))
    c.fail(child(path, "id"), fmt::format("'{}' is the id of a figure the study draws itself", id),
           "another id than work_precision, work_precision_evals, energy_history, convergence_* (or study.figures = \"declared\")");
}

// A figure's optional array of column names `key` (series, panels), each one of `columns`.
void read_figure_names(const Checker& c, const Json& j, const std::string& path, const char* key, const std::vector<std::string>& columns,
                       std::vector<std::string>& out) {
  const Json* v = c.find(j, key);
  if (!v) return;
  const std::string at = child(path, key);
  c.expect(*v, at, v->is_array(), "an array of column names");
  out.clear();
  for (std::size_t k = 0; k < v->size(); ++k) out.push_back(c.choice((*v)[k], element(at, k), columns));
}

// A figure's optional keys of its drawing: log axes, small multiples, deviation, caption,
// colour-scale label and reference slopes.
void read_figure_options(const Checker& c, const Json& j, const std::string& path, FileFigure& f) {
  if (const Json* v = c.find(j, "log_x")) f.log_x = c.boolean(*v, child(path, "log_x"));
  if (const Json* v = c.find(j, "log_y")) f.log_y = c.boolean(*v, child(path, "log_y"));
  if (const Json* v = c.find(j, "small_multiples")) f.small_multiples = c.boolean(*v, child(path, "small_multiples"));
  if (const Json* v = c.find(j, "deviation")) f.deviation = c.boolean(*v, child(path, "deviation"));
  if (const Json* v = c.find(j, "caption")) f.caption = c.string(*v, child(path, "caption"));
  if (const Json* v = c.find(j, "value_label")) f.value_label = c.string(*v, child(path, "value_label"));
  if (const Json* v = c.find(j, "slopes")) {
    const std::string at = child(path, "slopes");
    c.expect(*v, at, v->is_array(), "an array of numbers");
    for (std::size_t k = 0; k < v->size(); ++k) {
      c.expect((*v)[k], element(at, k), (*v)[k].is_number(), "a number");
      f.slopes.push_back((*v)[k].get<double>());
    }
  }
}

// One [[figure]] at `path`: its columns one of `run_columns`, or of `table_columns` when it names a table.
FileFigure read_figure(const Checker& c, const Json& j, const std::string& path, const std::vector<FileFigure>& earlier, bool declared_only,
                       const std::vector<std::string>& run_columns, const std::vector<std::string>& table_columns) {
  c.expect(j, path, j.is_object(), "a table");
  c.keys(j, path, {"id", "title", "x", "y", "series", "panels", "log_x", "log_y", "slopes", "table", "small_multiples", "deviation",
                   "caption", "value_label"});
  FileFigure f;
  if (const Json* v = c.find(j, "table")) f.table = c.string(*v, child(path, "table"));
  const std::vector<std::string>& columns = f.table.empty() ? run_columns : table_columns;
  f.id = c.string(c.require(j, path, "id"), child(path, "id"));
  check_figure_id(c, path, f.id, earlier, declared_only);
  f.title = c.string(c.require(j, path, "title"), child(path, "title"));
  if (const Json* v = c.find(j, "x"); v || f.table.empty()) f.x = c.choice(c.require(j, path, "x"), child(path, "x"), columns);  // a field table's figure: none
  // Of a named table: checked against that table's columns (a pivot's spread column by its header).
  f.y = f.table.empty() ? c.choice(c.require(j, path, "y"), child(path, "y"), columns) : c.string(c.require(j, path, "y"), child(path, "y"));
  read_figure_names(c, j, path, "series", columns, f.series);
  read_figure_names(c, j, path, "panels", columns, f.panels);
  read_figure_options(c, j, path, f);
  return f;
}

}  // namespace

// [[figure]]: drawn from the work-precision table, its columns named by their headers.
std::vector<FileFigure> read_figures(const Checker& c, const Json& root, const StudySpec& spec) {
  const auto parameters = parameter_column_names(spec);
  const std::vector<std::string> table_columns = figure_table_columns(parameters);
  std::vector<FileFigure> figures;
  const Json* list = c.find(root, "figure");
  if (!list) return figures;
  c.expect(*list, "figure", list->is_array(), "one or more [[figure]] tables");
  const std::vector<std::string> run_columns = figure_run_columns(c, root, spec, parameters);
  for (std::size_t i = 0; i < list->size(); ++i)
    figures.push_back(read_figure(c, (*list)[i], element("figure", i), figures, spec.declared_figures_only, run_columns, table_columns));
  return figures;
}

// A figure of a field table is a space-time picture (no x); the others have an x and no colour scale.
void check_field_figure(const Checker& c, const std::string& path, const FileFigure& f, const FileTable& table) {
  if (table.rows == "field") {
    if (!f.x.empty()) c.fail(child(path, "x"), "a space-time picture's horizontal axis is the cells' position", "no x with a table of rows = \"field\"");
    if (std::none_of(table.columns.begin(), table.columns.end(), [](const FileColumn& col) { return col.of == "field"; }))
      c.fail(child(path, "table"), fmt::format("table '{}' shows no field to draw", table.id), "a table whose columns hold \"field\"");
    return;
  }
  if (f.x.empty()) c.fail(path, "missing key 'x'");
  if (!f.value_label.empty())
    c.fail(child(path, "value_label"), "only a space-time picture has a colour scale", "table = a table of rows = \"field\"");
}

// A figure of a pivot table draws one of its spread columns: y is its header, the value
// column's header with "{}" replaced by a value of `across` (no "{}": the header, ", ", the value).
void check_pivot_figure_y(const Checker& c, const std::string& at, const std::string& y, const FileTable& pivot) {
  const FileColumn& value = pivot.columns.back();
  std::string header = value.header.value_or(value.of);
  if (header.find("{}") == std::string::npos) header += ", {}";
  const std::size_t hole = header.find("{}");
  const std::string before = header.substr(0, hole), after = header.substr(hole + 2);
  const bool spread = y.size() > before.size() + after.size() && y.starts_with(before) && y.ends_with(after);
  if (!spread)
    c.fail(at, fmt::format("'{}' is not a spread column of pivot table '{}'", y, pivot.id),
           fmt::format("'{}' with {{}} a value of '{}'", header, pivot.across));
}

// The figures are drawn from the first table of one row per run (or the table they name): it
// shows their columns.
void check_table_figures(const Checker& c, const StudySpec& spec, const std::vector<FileTable>& tables) {
  const auto first_runs = std::find_if(tables.begin(), tables.end(), [](const FileTable& t) { return t.rows == "case"; });
  for (std::size_t i = 0; i < spec.figures.size(); ++i) {
    const std::string path = element("figure", i);
    auto runs = first_runs;
    if (!spec.figures[i].table.empty()) {
      runs = std::find_if(tables.begin(), tables.end(), [&](const FileTable& t) { return t.id == spec.figures[i].table; });
      const auto series = [](const FileTable& t) { return t.rows == "history" || t.rows == "samples" || t.of_some_runs(); };
      if (runs == tables.end() || !series(*runs)) {
        std::vector<std::string> histories;
        for (const auto& t : tables)
          if (series(t)) histories.push_back(t.id);
        c.fail(child(path, "table"), fmt::format("'{}' is no declared table a figure names (rows = history, samples, periodic, trajectory, flights, impulses, field or pivot)",
                                                 spec.figures[i].table),
               histories.empty() ? "a [[table]] with rows = \"history\", \"samples\", \"periodic\", \"trajectory\", \"flights\", \"impulses\", \"field\" or \"pivot\""
                                 : fmt::format("{}", fmt::join(histories, ", ")));
      }
    }
    if (runs == tables.end()) c.fail(path, "declared tables hold no table of one row per run to draw it from", "a [[table]] with rows = \"case\"");
    std::vector<std::string> shown;
    for (const auto& col : runs->columns) shown.push_back(col.of);
    if (runs->rows == "pivot") shown.pop_back();  // its value column is drawn by a spread column's header
    const FileFigure& f = spec.figures[i];
    check_field_figure(c, path, f, *runs);
    std::vector<std::pair<std::string, std::string>> used;
    if (!f.x.empty()) used.emplace_back("x", f.x);
    used.emplace_back("y", f.y);
    for (const auto& s : f.series) used.emplace_back("series", s);
    for (const auto& s : f.panels) used.emplace_back("panels", s);
    for (const auto& [key, name] : used) {
      if (runs->rows == "pivot" && key == "y") {
        check_pivot_figure_y(c, child(path, key), name, *runs);
        continue;
      }
      if (std::find(shown.begin(), shown.end(), name) == shown.end())
        c.fail(child(path, key), fmt::format("'{}' is not a column of table '{}'", name, runs->id), fmt::format("{}", fmt::join(shown, ", ")));
    }
  }
}

}  // namespace nsb::study_files
