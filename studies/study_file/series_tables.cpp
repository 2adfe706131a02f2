// Tables of a row per sample of each run: history and samples tables (every run on their
// problems), periodic, trajectory and flights tables (the runs they pick).
#include "studies/study_file/engine.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace nsb::study_files {

// rows = "history" (a row per interval of each run on the table's problems) or "samples" (a
// row per sample), the columns picked; its figures, the [[figure]]s that name it, under its headers.
Table history_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results) {
  const bool samples = d.rows == "samples";
  Table all;
  all.columns = samples ? samples_columns() : history_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end(), parameters.begin(), parameters.end());
  const std::vector<std::string> parameter_names = parameter_column_names(spec);
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& r = results[k];
    const char* key = samples ? "samples" : "intervals";
    if (!r.contains("run") || !r["run"].contains(key)) continue;
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    if (!d.applies_to(p.label)) continue;
    const FileIntegrator& fi = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
    const std::string integrator = shown_label(fi, p.label), variant = parameters_text(fi, p.label);
    const Json& h = r["run"][key];
    const std::vector<Cell> own = parameter_cells(p, parameter_names);
    for (std::size_t i = 0; i < h["t"].size(); ++i) {
      std::vector<Cell> row = {p.label, p.name, integrator, run_label(cases[k]), number_cell(h["t"][i])};
      if (samples) {
        row.insert(row.end(), {number_cell(h["energy_ratio"][i]), fi.name, variant});
      } else {
        row.insert(row.end(), {number_cell(h["energy"][i]), number_cell(h["penetration"][i]), fi.name, variant,
                               h.contains("momentum") ? number_cell(h["momentum"][i]) : Cell{}});
      }
      row.insert(row.end(), own.begin(), own.end());
      all.add_row(std::move(row));
    }
  }
  for (const FileFigure& f : spec.figures)
    if (f.table == d.id) all.figures.push_back(declared_figure(spec, f));
  Table t = case_table(d, all, true);
  t.csv_only = true;
  return t;
}

// rows = "periodic", "trajectory" or "flights": a row per sample (flight) of each run shown (its
// case-table row in `runs`: case_row), in the order of the cases; a trajectory's rows "exact"
// after the first run shown of each problem, at its times.
Table run_series_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                       const Table& runs, const std::vector<std::size_t>& case_row) {
  const bool periodic = d.rows == "periodic", flights = d.rows == "flights";
  Table all;
  all.columns = periodic ? periodic_columns() : flights ? flights_columns() : trajectory_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end(), parameters.begin(), parameters.end());
  const std::vector<std::string> parameter_names = parameter_column_names(spec);
  std::vector<std::string> exact_drawn;  // the problems whose exact rows are in
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& run = results[k].contains("run") ? results[k]["run"] : Json::object();
    const char* key = periodic ? "periodic" : flights ? "flights" : "trajectories";
    const std::string& id = periodic || flights ? d.measure : d.id;
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    if (!run.contains(key) || !run[key].contains(id) || !d.applies_to(p.label) || !shows_run(d, runs, runs.rows[case_row[k]])) continue;
    const FileIntegrator& fi = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
    const std::vector<Cell> own = parameter_cells(p, parameter_names);
    const auto add = [&](std::vector<Cell> row) {
      row.insert(row.end(), own.begin(), own.end());
      all.add_row(std::move(row));
    };
    const std::vector<Cell> head = {p.label, p.name, shown_label(fi, p.label), fi.name, parameters_text(fi, p.label), run_label(cases[k])};
    const Json& samples = run[key][id];
    if (periodic) {
      for (std::size_t i = 0; i < samples.size(); ++i) {
        std::vector<Cell> row = head;
        row.insert(row.end(), {static_cast<long>(i + 1), number_cell(samples[i]), number_cell(std::abs(real(samples[i])))});
        add(row);
      }
      continue;
    }
    if (flights) {
      for (std::size_t i = 0; i < samples["ratio"].size(); ++i) {
        std::vector<Cell> row = head;
        row.insert(row.end(), {static_cast<long>(i + 1), number_cell(samples["ratio"][i]), number_cell(samples["exact"][i]),
                               number_cell(std::abs(real(samples["error"][i])))});
        add(row);
      }
      continue;
    }
    const Json& t = samples["t"];
    for (std::size_t i = 0; i < t.size(); ++i) {
      std::vector<Cell> row = head;
      row.insert(row.end(), {number_cell(t[i]), number_cell(samples["value"][i])});
      add(row);
    }
    if (d.exact.empty() || t.empty() || std::find(exact_drawn.begin(), exact_drawn.end(), p.label) != exact_drawn.end()) continue;
    exact_drawn.push_back(p.label);
    for (std::size_t i = 0; i < t.size(); ++i)
      add({p.label, p.name, "exact", "", "", "", number_cell(t[i]), number_cell(samples["exact"][i])});
  }
  for (const FileFigure& f : spec.figures)
    if (f.table == d.id) all.figures.push_back(declared_figure(spec, f));
  Table out = case_table(d, all, true);
  out.csv_only = !flights;  // a few rows per run: readable as text too
  return out;
}

}  // namespace nsb::study_files
