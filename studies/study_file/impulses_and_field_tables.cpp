// Impulses tables (the contact impulses per nominal step bin) and field tables (a bar's element
// stresses at every step: space-time pictures).
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "core/output.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "reference/cache.hpp"
#include "reference/modal_exact.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"
#include "studies/parallel.hpp"
#include "studies/ranking.hpp"
#include "studies/report_index.hpp"
#include "studies/slip_stop.hpp"

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

}  // namespace

// rows = "impulses" (FileTable::scale, exact, exact_per, exact_in): the bins of each run shown,
// in the order of the cases, the exact rows after the first run of each value of exact_per.
Table impulses_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                     const Table& runs, const std::vector<std::size_t>& case_row) {
  Table all;
  all.columns = impulses_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end() - 1, parameters.begin(), parameters.end());
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
    std::vector<double> buffer(problem->observable_names().size());
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
  const FileProblem& first = *std::find_if(spec.problems.begin(), spec.problems.end(), [&](const FileProblem& p) { return d.applies_to(p.label); });
  const auto problem = make_problem(first.name, first.parameters);
  const FieldMesh mesh = problem->field_mesh().value();
  std::vector<double> centres;
  for (Index e = 0; e < mesh.ncells(); ++e) centres.push_back(0.5 * (mesh.points(mesh.cells(e, 0), 0) + mesh.points(mesh.cells(e, 1), 0)));
  const std::string component = d.component.empty() ? mesh.stress_components.front() : d.component;
  Table all;  // the columns but the field's, by source name
  all.columns = field_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end() - 1, parameters.begin(), parameters.end());
  const std::size_t field = column_index(all, "field");
  Table out;
  std::vector<std::string> field_names;
  std::map<std::string, std::string> renamed;
  for (const FileColumn& c : d.columns) {
    const Column source = all.columns[column_index(all, c.of)];
    if (c.of != "field") {
      out.columns.push_back(declared_column(source, c));
      renamed[c.of] = out.columns.back().name;
      continue;
    }
    const std::string header = c.header.value_or(component + "(x = {})");
    for (const double x : centres) {
      Column cell = declared_column(source, c);
      cell.name = header;
      cell.name.replace(header.find("{}"), 2, fmt::format("{:g}", x));  // the reader checked the {}
      field_names.push_back(cell.name);
      out.columns.push_back(cell);
    }
  }
  // A row from the cells of `all`'s columns but the field, and the field's values from `values[from]` on.
  const auto add = [&](const std::vector<Cell>& cells, const Json& values, std::size_t from) {
    std::vector<Cell> row;
    for (const FileColumn& c : d.columns) {
      if (c.of != "field") {
        const std::size_t k = column_index(all, c.of);
        row.push_back(cells[k < field ? k : k - 1]);
        continue;
      }
      for (std::size_t e = 0; e < centres.size(); ++e) row.push_back(number_cell(values[from + e]));
    }
    out.add_row(std::move(row));
  };
  if (d.exact_times > 0) {
    Eigen::MatrixXd stress(mesh.nelements(), static_cast<Index>(mesh.stress_components.size()));
    const auto k_component = static_cast<Index>(std::find(mesh.stress_components.begin(), mesh.stress_components.end(), component) -
                                                mesh.stress_components.begin());
    const double t_end = spec.t_end_of(first);
    for (int k = 0; k <= d.exact_times; ++k) {
      const double t = t_end * k / d.exact_times;
      const bool known = problem->exact()->exact_cell_stress(t, stress);
      std::vector<Cell> cells = {first.label, first.name, std::string("exact"), std::string(), std::string(), std::string(), t};
      cells.insert(cells.end(), all.columns.size() - cells.size() - 1, Cell{std::string()});
      Json values = Json::array();
      for (Index e = 0; e < stress.rows(); ++e) values.push_back(real(known ? stress(e, k_component) : kNaN));
      add(cells, values, 0);
    }
  }
  std::vector<std::string> no_field;  // the runs shown without a field: "first panel (other panels): outcome"
  const std::size_t outcome = column_index(runs, "outcome");
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    const FileIntegrator& fi = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
    const bool named = d.integrators.empty() || std::find(d.integrators.begin(), d.integrators.end(), fi.label) != d.integrators.end();
    if (!d.applies_to(p.label) || !named || !shows_run(d, runs, runs.rows[case_row[k]])) continue;
    const auto around = run_series_cells(spec, cases[k]);
    const std::vector<Cell>& before = around.first;
    const std::vector<Cell>& after = around.second;
    std::vector<Cell> cells = before;
    cells.emplace_back();  // t, set below
    cells.insert(cells.end(), after.begin(), after.end());
    const Json& run = results[k].contains("run") ? results[k]["run"] : Json::object();
    if (!run.contains("fields") || !run["fields"].contains(d.id)) {
      for (const FileFigure& f : spec.figures)
        if (f.table == d.id && !f.panels.empty()) {
          std::vector<std::string> rest;
          for (std::size_t i = 1; i < f.panels.size(); ++i) {
            const std::size_t at = column_index(all, f.panels[i]);
            rest.push_back(pivot_value_text(cells[at < field ? at : at - 1]));
          }
          const std::size_t at = column_index(all, f.panels.front());
          no_field.push_back(fmt::format("{}{}: {}", pivot_value_text(cells[at < field ? at : at - 1]),
                                         rest.empty() ? "" : fmt::format(" ({})", fmt::join(rest, ", ")),
                                         pivot_value_text(runs.rows[case_row[k]][outcome])));
          break;
        }
      continue;
    }
    const Json& f = run["fields"][d.id];
    for (std::size_t i = 0; i < f["t"].size(); ++i) {
      cells[6] = number_cell(f["t"][i]);
      add(cells, f["values"], i * centres.size());
    }
  }
  const auto rename = [&](const std::string& name) {
    const auto it = renamed.find(name);
    return it == renamed.end() ? name : it->second;
  };
  for (const FileFigure& f : spec.figures) {
    if (f.table != d.id) continue;
    Figure figure = declared_figure(spec, f);
    figure.x.clear();
    figure.y = rename(f.y);
    for (auto& name : figure.series) name = rename(name);
    for (auto& name : figure.panels) name = rename(name);
    figure.kind = "space_time";
    figure.values = field_names;
    figure.positions = centres;
    figure.value_label = f.value_label;
    std::string caption = d.caption.value_or("");
    if (!f.caption.empty()) caption += (caption.empty() ? "" : " ") + f.caption;
    if (!no_field.empty()) caption += fmt::format("{} panel for {}", caption.empty() ? "No" : "; no", fmt::join(no_field, ", "));
    figure.caption = caption.empty() ? caption : caption + ".";
    out.figures.push_back(figure);
  }
  out.csv_only = true;
  return out;
}

}  // namespace nsb::study_files
