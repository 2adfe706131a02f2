#pragma once
// The study-file engine's own functions shared between its files (studies/study_file/*.cpp):
// the cases, the run of one case and the tables. Not part of the library's interface
// (studies/study_file.hpp is).
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "problems/problem.hpp"
#include "problems/state.hpp"
#include "studies/study.hpp"
#include "studies/study_file.hpp"
#include "studies/table.hpp"

namespace nsb::study_files {

// The intervals of the energy-history table of the engine's own tables.
inline constexpr int kHistoryIntervals = 200;

// The problem's observables of one state, observed once however many measures of the case read
// them after a step (Problem::observe fills them all; an exact column, e.g. the rocking block's
// omega_exact, integrates the exact solution to t, the cost of one measure): kept while the
// arguments are the same, compared by value (an exact graph's two sides of a jump share t).
class ObservableBuffer {
 public:
  explicit ObservableBuffer(std::size_t size) : values_(size) {}
  std::span<const double> of(const Problem& problem, const State& s, const Vec& impulses, double dt) {
    const auto same = [](const Vec& a, const Vec& b) { return a.size() == b.size() && a == b; };
    if (!(filled_ && t_ == s.t && dt_ == dt && same(u_, s.u) && same(v_, s.v) && same(impulses_, impulses))) {
      problem.observe(s, impulses, dt, values_);
      t_ = s.t, dt_ = dt, u_ = s.u, v_ = s.v, impulses_ = impulses, filled_ = true;
    }
    return values_;
  }

 private:
  std::vector<double> values_;
  Vec u_, v_, impulses_;
  double t_ = 0.0, dt_ = 0.0;
  bool filled_ = false;
};

// run_recorders.cpp
double state_observable(const Problem& problem, const SpMat& M, const State& s, const Vec& impulses, double dt,
                        const std::string& name, ObservableBuffer& buffer, const Energy* energy);
// The exact solution's observable `name` at t: ExactSolution::observable where offered (a few
// points of the solution), else observed on state(t); nullopt where the solution does not hold.
std::optional<double> exact_observable(const Problem& problem, const SpMat& M, double t, const std::string& name,
                                       ObservableBuffer& buffer);

// cases.cpp
std::string shown_label(const FileIntegrator& fi, const std::string& problem_label);
double case_t_end(const StudySpec& spec, const FileProblem& p, const Json& c);
std::vector<Json> file_cases(const StudySpec& spec, bool full);

// run_case.cpp
Json run_file_case(const StudySpec& spec, const Json& c);

// case_table.cpp
std::string run_label(const Json& c, const std::optional<std::string>& format = std::nullopt);
Figure declared_figure(const StudySpec& spec, const FileFigure& f);
Column declared_column(const Column& source, const FileColumn& d);
std::size_t column_index(const Table& t, const std::string& name);
// The header table d shows its column of source `of` under (its declared_column's name): the
// declared column's header, else the name of the column of `source` (the table d is built from)
// it shows; none when d shows no such column.
std::optional<std::string> declared_header(const FileTable& d, const Table& source, const std::string& of);
double cell_number(const Cell& cell);
bool shows_run(const FileTable& d, const Table& runs, const std::vector<Cell>& row);
Table case_table(const FileTable& d, const Table& runs, bool with_figures);
std::string pivot_value_text(const Cell& cell);

// table_columns.cpp
const std::vector<Column>& run_columns();
std::string parameters_text(const FileIntegrator& fi, const std::string& problem_label);
std::vector<Column> parameter_columns(const StudySpec& spec);
std::vector<Column> study_run_columns(const StudySpec& spec);
std::vector<Cell> parameter_cells(const FileProblem& p, const std::vector<std::string>& names);
std::vector<Cell> study_run_cells(const StudySpec& spec, const Json& c, const Json& r);
std::vector<Cell> run_cells(const StudySpec& spec, const Json& c, const Json& r);
const std::vector<Column>& history_columns();
const std::vector<Column>& samples_columns();
const std::vector<Column>& periodic_columns();
const std::vector<Column>& trajectory_columns();
const std::vector<Column>& flights_columns();
const std::vector<Column>& impulses_columns();
const std::vector<Column>& field_columns();
std::vector<Column> sweep_work_columns(const StudySpec& spec);
std::vector<Cell> sweep_work_cells(const StudySpec& spec, const Json& r);

// sweep_tables.cpp
Table group_table(const StudySpec& spec, const FileTable& d, const Table& orders, const Table& runs);
std::vector<std::vector<std::size_t>> sweep_runs(const StudySpec& spec, const std::vector<Json>& cases);
Table fits_against_parameter(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                             const Table& orders);
std::vector<Json> with_next_run_estimates(const StudySpec& spec, const std::vector<Json>& cases, std::vector<Json> results);

// series_tables.cpp
Table history_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results);
Table run_series_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                       const Table& runs, const std::vector<std::size_t>& case_row);

// pivot_table.cpp
Table pivot_table(const StudySpec& spec, const FileTable& d, const Table& runs);

// impulses_and_field_tables.cpp
Table impulses_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                     const Table& runs, const std::vector<std::size_t>& case_row);
Table field_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                  const Table& runs, const std::vector<std::size_t>& case_row);

// work_precision.cpp
std::vector<Table> file_tables(const StudySpec& spec, const std::vector<Json>& cases, const std::vector<Json>& results);

}  // namespace nsb::study_files
