// Impulses tables (the contact impulses per nominal step bin) and field tables (a bar's element
// stresses at every step: space-time pictures).
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "problems/problem_output.hpp"
#include "problems/registry.hpp"
#include "studies/measures.hpp"

namespace nsb::study_files {

namespace {

// The cells of a run's row of an impulses or field table before its own values (the problem,
// the integrator, the run) and after them (the problem's parameters, the integrator's label).
std::pair<std::vector<Cell>, std::vector<Cell>> run_series_cells(const StudySpec& spec, const Json& c) {
  const FileProblem& p = spec.problems[c["problem"].get<std::size_t>()];
  const FileIntegrator& fi = spec.integrators[c["integrator"].get<std::size_t>()];
  std::vector<Cell> after = parameter_cells(p, parameter_column_names(spec));
  after.emplace_back(fi.label);
  return {{p.label, p.name, shown_label(fi, p.label), fi.name, parameters_text(fi, p.label), run_label(c)}, after};
}

// The columns of an impulses or field table, the problems' parameters before the integrator's
// label (run_series_cells).
std::vector<Column> with_parameter_columns(const StudySpec& spec, std::vector<Column> columns) {
  const std::vector<Column> parameters = parameter_columns(spec);
  columns.insert(columns.end() - 1, parameters.begin(), parameters.end());
  return columns;
}

// The centres x of the cells of a 1D field mesh (cells of two points).
std::vector<double> cell_centres(const FieldMesh& mesh) {
  std::vector<double> centres;
  for (Index e = 0; e < mesh.ncells(); ++e) centres.push_back(0.5 * (mesh.points(mesh.cells(e, 0), 0) + mesh.points(mesh.cells(e, 1), 0)));
  return centres;
}

// What a field table is built from: its source columns (`all`: every column but the field's,
// field_columns) and its field, the stress `component` of the cells at `centres` of the mesh of
// `first`, the first problem the table shows (the reader checked that its problems share it).
struct FieldSource {
  const FileTable& d;
  Table all;
  std::size_t field;  // the field's column in `all`
  const FileProblem& first;
  std::unique_ptr<Problem> problem;
  FieldMesh mesh;
  std::vector<double> centres;
  std::string component;

  FieldSource(const StudySpec& spec, const FileTable& table)
      : d(table), first(*std::find_if(spec.problems.begin(), spec.problems.end(), [&](const FileProblem& p) { return table.applies_to(p.label); })),
        problem(make_problem(first.name, first.parameters)), mesh(problem->field_mesh().value()), centres(cell_centres(mesh)),
        component(table.component.empty() ? mesh.stress_components.front() : table.component) {
    all.columns = with_parameter_columns(spec, field_columns());
    field = column_index(all, "field");
  }
  // The cell of `all`'s column `of` in a row of cells of every column but the field.
  const Cell& cell(const std::vector<Cell>& cells, const std::string& of) const {
    const std::size_t k = column_index(all, of);
    return cells[k < field ? k : k - 1];
  }
};

// The columns of field table d: its declared columns, the field's spread over one column per
// cell, its header's {} the cell's centre x (the reader checked the {}); `field_names` their headers.
std::vector<Column> field_table_columns(const FieldSource& f, std::vector<std::string>& field_names) {
  std::vector<Column> columns;
  for (const FileColumn& c : f.d.columns) {
    const Column source = f.all.columns[column_index(f.all, c.of)];
    if (c.of != "field") {
      columns.push_back(declared_column(source, c));
      continue;
    }
    const std::string header = c.header.value_or(f.component + "(x = {})");
    for (const double x : f.centres) {
      Column cell = declared_column(source, c);
      cell.name = header;
      cell.name.replace(header.find("{}"), 2, fmt::format("{:g}", x));
      field_names.push_back(cell.name);
      columns.push_back(cell);
    }
  }
  return columns;
}

// A row of field table d from the cells of every column but the field, the field's values from `values[from]` on.
std::vector<Cell> field_row(const FieldSource& f, const std::vector<Cell>& cells, const Json& values, std::size_t from) {
  std::vector<Cell> row;
  for (const FileColumn& c : f.d.columns) {
    if (c.of != "field") {
      row.push_back(f.cell(cells, c.of));
      continue;
    }
    for (std::size_t e = 0; e < f.centres.size(); ++e) row.push_back(number_cell(values[from + e]));
  }
  return row;
}

// exact_times = n: the exact field of the first problem at t = t_end k / n, k = 0..n, rows "exact".
void add_exact_field_rows(const StudySpec& spec, const FieldSource& f, Table& out) {
  Eigen::MatrixXd stress(f.mesh.nelements(), static_cast<Index>(f.mesh.stress_components.size()));
  const auto& names = f.mesh.stress_components;
  const auto k_component = static_cast<Index>(std::find(names.begin(), names.end(), f.component) - names.begin());
  const double t_end = spec.t_end_of(f.first);
  for (int k = 0; k <= f.d.exact_times; ++k) {
    const double t = t_end * k / f.d.exact_times;
    const bool known = f.problem->exact()->exact_cell_stress(t, stress);
    std::vector<Cell> cells = {f.first.label, f.first.name, std::string("exact"), std::string(), std::string(), std::string(), t};
    cells.insert(cells.end(), f.all.columns.size() - cells.size() - 1, Cell{std::string()});
    Json values = Json::array();
    for (Index e = 0; e < stress.rows(); ++e) values.push_back(real(known ? stress(e, k_component) : kNaN));
    out.add_row(field_row(f, cells, values, 0));
  }
}

// A run shown without a field (declined) as the figure names its panel: "first panel (other
// panels): outcome".
std::string no_panel_text(const FieldSource& f, const FileFigure& figure, const std::vector<Cell>& cells, const Cell& outcome) {
  std::vector<std::string> rest;
  for (std::size_t i = 1; i < figure.panels.size(); ++i) rest.push_back(pivot_value_text(f.cell(cells, figure.panels[i])));
  return fmt::format("{}{}: {}", pivot_value_text(f.cell(cells, figure.panels.front())),
                     rest.empty() ? "" : fmt::format(" ({})", fmt::join(rest, ", ")), pivot_value_text(outcome));
}

// The space-time pictures of field table d, one panel per run: the caption the table's, then the
// figure's, then "." or "; no panel for RUN: outcome, ..." naming `no_field` (FileFigure::caption).
void add_space_time_figures(const StudySpec& spec, const FieldSource& f, const std::vector<std::string>& field_names,
                            const std::vector<std::string>& no_field, Table& out) {
  // A figure's column by source name under its header (the field's and unknown names as they are).
  const auto header = [&](const std::string& of) { return of == "field" ? of : declared_header(f.d, f.all, of).value_or(of); };
  for (const FileFigure& ff : spec.figures) {
    if (ff.table != f.d.id) continue;
    Figure figure = declared_figure(spec, ff);
    figure.x.clear();
    figure.y = header(ff.y);
    for (auto& name : figure.series) name = header(name);
    for (auto& name : figure.panels) name = header(name);
    figure.kind = "space_time";
    figure.values = field_names;
    figure.positions = f.centres;
    figure.value_label = ff.value_label;
    std::string caption = f.d.caption.value_or("");
    if (!ff.caption.empty()) caption += (caption.empty() ? "" : " ") + ff.caption;
    if (!no_field.empty()) caption += fmt::format("{} panel for {}", caption.empty() ? "No" : "; no", fmt::join(no_field, ", "));
    figure.caption = caption.empty() ? caption : caption + ".";
    out.figures.push_back(figure);
  }
}

}  // namespace

// rows = "impulses" (FileTable::scale, exact, exact_per, exact_in): the bins of each run shown,
// in the order of the cases, the exact rows after the first run of each value of exact_per.
Table impulses_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                     const Table& runs, const std::vector<std::size_t>& case_row) {
  Table all;
  all.columns = with_parameter_columns(spec, impulses_columns());
  const std::size_t per = column_index(all, d.exact_per), in = column_index(all, d.exact_in);
  std::vector<Cell> exact_shown;  // the values of exact_per whose exact rows are in
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& run = results[k].contains("run") ? results[k]["run"] : Json::object();
    if (!run.contains("impulses") || !run["impulses"].contains(d.id) || !shows_run(d, runs, runs.rows[case_row[k]])) continue;
    const auto around = run_series_cells(spec, cases[k]);
    const std::vector<Cell>& before = around.first;
    const std::vector<Cell>& after = around.second;
    const auto row = [&](const Json& t, const Json& value) {
      std::vector<Cell> cells = before;
      cells.insert(cells.end(), {number_cell(t), number_cell(value)});
      cells.insert(cells.end(), after.begin(), after.end());
      return cells;
    };
    const Json& bins = run["impulses"][d.id];
    for (std::size_t i = 0; i < bins["t"].size(); ++i) all.add_row(row(bins["t"][i], bins["value"][i]));
    if (d.exact.empty() || bins["t"].empty()) continue;
    const Cell key = row(bins["t"][0], nullptr)[per];
    if (std::find(exact_shown.begin(), exact_shown.end(), key) != exact_shown.end()) continue;
    exact_shown.push_back(key);
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    const auto problem = make_problem(p.name, p.parameters);
    const SpMat M = problem->mass_matrix();
    ObservableBuffer buffer(problem->observable_names().size());
    const Vec none = Vec::Zero(problem->ncontacts());
    for (const Json& t : bins["t"]) {
      const std::optional<State> exact = problem->exact()->state(t.get<double>());
      std::vector<Cell> cells = row(t, real(exact ? state_observable(*problem, M, *exact, none, 0.0, d.exact, buffer, nullptr) / d.scale : kNaN));
      cells[in] = std::string("exact");
      all.add_row(std::move(cells));
    }
  }
  for (const FileFigure& f : spec.figures)
    if (f.table == d.id) all.figures.push_back(declared_figure(spec, f));
  Table out = case_table(d, all, true);
  out.csv_only = true;
  return out;
}

// rows = "field" (FileTable::component, exact_times): the exact rows first, then a row per step
// of each run shown, in the order of the cases; the field's columns those of the first problem
// the table shows (the reader checked that its problems share one mesh). Its figures are
// space-time pictures, one panel per run (FileFigure::caption).
Table field_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                  const Table& runs, const std::vector<std::size_t>& case_row) {
  const FieldSource f(spec, d);
  std::vector<std::string> field_names;
  Table out;
  out.columns = field_table_columns(f, field_names);
  if (d.exact_times > 0) add_exact_field_rows(spec, f, out);
  std::vector<std::string> no_field;  // the runs shown without a field (no_panel_text)
  const std::size_t outcome = column_index(runs, "outcome");
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    const FileIntegrator& fi = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
    const bool named = d.integrators.empty() || std::find(d.integrators.begin(), d.integrators.end(), fi.label) != d.integrators.end();
    if (!d.applies_to(p.label) || !named || !shows_run(d, runs, runs.rows[case_row[k]])) continue;
    const auto [before, after] = run_series_cells(spec, cases[k]);
    std::vector<Cell> cells = before;
    cells.emplace_back();  // t, set below
    cells.insert(cells.end(), after.begin(), after.end());
    const Json& run = results[k].contains("run") ? results[k]["run"] : Json::object();
    if (!run.contains("fields") || !run["fields"].contains(d.id)) {
      const auto panelled = std::find_if(spec.figures.begin(), spec.figures.end(),
                                         [&](const FileFigure& ff) { return ff.table == d.id && !ff.panels.empty(); });
      if (panelled != spec.figures.end()) no_field.push_back(no_panel_text(f, *panelled, cells, runs.rows[case_row[k]][outcome]));
      continue;
    }
    const Json& field = run["fields"][d.id];
    for (std::size_t i = 0; i < field["t"].size(); ++i) {
      cells[6] = number_cell(field["t"][i]);
      out.add_row(field_row(f, cells, field["values"], i * f.centres.size()));
    }
  }
  add_space_time_figures(spec, f, field_names, no_field, out);
  out.csv_only = true;
  return out;
}

}  // namespace nsb::study_files
