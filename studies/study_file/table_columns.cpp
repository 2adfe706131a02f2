// The columns the study-file engine's tables may show, and the cells of a run's own columns.
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "problems/registry.hpp"

namespace nsb::study_files {

namespace {

// The columns of a periodic or trajectory table: which run, then the sample's `own`.
std::vector<Column> run_series_columns(const std::vector<Column>& own) {
  std::vector<Column> columns = {
      {"problem", "", "", ""}, {"problem name", "", "", "the registered problem"}, {"integrator", "", "", "exact: the exact observable"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"}, {"run", "", "", ""}};
  columns.insert(columns.end(), own.begin(), own.end());
  return columns;
}

// The columns of an impulses or field table: a run series' (its `own` two), then the
// integrator's label (run_series_cells).
std::vector<Column> labelled_run_series_columns(const std::vector<Column>& own) {
  std::vector<Column> columns = run_series_columns(own);
  columns.push_back({"integrator label", "", "", "the integrator's label in the file"});
  return columns;
}

std::vector<std::string> column_names(const std::vector<Column>& columns) {
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  return names;
}

}  // namespace

// The columns of a run's own figures (RunFigures) and their cells for one run.
const std::vector<Column>& run_columns() {
  static const std::vector<Column> columns = {
      {"problem name", "", "", "the registered problem"},
      {"stable steps", "", "{}", "dt / the problem's stable step, when the sweep sets it so"},
      {"t_end", "s", "{}", ""},
      {"outcome", "", "", "the status alone"},
      {"t reached", "s", "{:.4g}", ""},
      {"impacts", "", "", "contact phases started, as seen at the steps"},
      {"switches", "", "{:.0f}", "contact mode switches located inside the steps"},
      {"missed switches", "", "{:.0f}", "switches found only at a step's end, not by a root"},
      {"budget", "", "", "F_int evaluations allowed"},
      {"max penetration", "m", "{:.2e}", "max over the steps of max(0, -g)"},
      {"penetration limit", "m", "{:.2g}", "status penetration above it"},
      {"energy scale", "J", "{:.3g}", "|E0|, or the problem's energy scale when E0 = 0, or the problem's energy_scale"},
      {"energy growth", "", "{:.2e}", "max (E - E0 - W) / E scale"},
      {"energy blow-up limit", "", "{:.0e}", "status energy blow-up above it"},
      {"final energy err", "", "{:.2e}", "|E_end - E0| / E scale"},
      {"note", "", "", "the run driver's message: why a run diverged, stopped or is n/a"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"},
      {"integrator label", "", "", "the integrator's label in the file"},
      {"min step", "s", "{:.2e}", "smallest step taken"},
      {"max step", "s", "{:.2e}", "largest step taken"},
      {"CPU per step", "s", "{:.2e}", "CPU / steps: the cost of a step, observer excluded", true}};
  return columns;
}

// The integrator's parameters the file sets on a problem, "key=value ..." by key, or "default".
std::string parameters_text(const FileIntegrator& fi, const std::string& problem_label) {
  const Overrides& set = fi.sweep_for(problem_label).parameters;
  if (set.empty()) return "default";
  std::vector<std::string> items;
  for (const auto& [key, value] : set) items.push_back(key + "=" + value);
  return fmt::format("{}", fmt::join(items, " "));
}

// The columns "parameter NAME" (parameter_column_names).
std::vector<Column> parameter_columns(const StudySpec& spec) {
  std::vector<Column> columns;
  for (const auto& name : parameter_column_names(spec)) columns.push_back({name, "", "", "the problem's parameter"});
  return columns;
}

// The run columns of this study's own: its counters (Work::extra, n/a where a scheme does not
// count one) and the problems' parameters ("parameter NAME", empty where a problem has none).
std::vector<Column> study_run_columns(const StudySpec& spec) {
  std::vector<Column> columns;
  for (const auto& name : spec.counters) columns.push_back({name, "", "{:.3g}", "the integrator's work counter " + name});
  const std::vector<Column> parameters = parameter_columns(spec);
  columns.insert(columns.end(), parameters.begin(), parameters.end());
  return columns;
}

// The cells of the parameter columns `names` ("parameter NAME") for a run on p: its value
// (integers and reals as numbers, choices as text), empty where p has no such parameter.
std::vector<Cell> parameter_cells(const FileProblem& p, const std::vector<std::string>& names) {
  const ParamSpecs specs = find_problem(p.name).parameters();
  const Params params(specs, p.parameters);
  std::vector<Cell> cells;
  for (const std::string& name : names) {
    const auto s = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& q) { return "parameter " + q.name == name; });
    if (s == specs.end()) {
      cells.emplace_back();
    } else if (s->kind == ParamSpec::Kind::Integer) {
      cells.emplace_back(params.integer(s->name));
    } else if (s->kind == ParamSpec::Kind::Real) {
      const auto v = params.optional_real(s->name);
      cells.push_back(v ? Cell{*v} : Cell{});
    } else {
      cells.emplace_back(params.choice(s->name));
    }
  }
  return cells;
}

std::vector<Cell> study_run_cells(const StudySpec& spec, const Json& c, const Json& r) {
  std::vector<Cell> cells;
  const Json& f = r.contains("run") ? r["run"] : Json::object();
  for (std::size_t k = 0; k < spec.counters.size(); ++k)
    cells.push_back(f.contains("counters") ? number_cell(f["counters"][k]) : Cell{});
  const std::vector<Cell> parameters = parameter_cells(spec.problems[c["problem"].get<std::size_t>()], parameter_column_names(spec));
  cells.insert(cells.end(), parameters.begin(), parameters.end());
  return cells;
}

std::vector<Cell> run_cells(const StudySpec& spec, const Json& c, const Json& r) {
  const FileProblem& p = spec.problems[c["problem"].get<std::size_t>()];
  const FileIntegrator& fi = spec.integrators[c["integrator"].get<std::size_t>()];
  const Json& f = r.contains("run") ? r["run"] : Json::object();
  const auto value = [&](const char* key) { return f.contains(key) ? number_cell(f[key]) : Cell{}; };
  const double t_end = case_t_end(spec, p, c);
  return {p.name, c.contains("stable_steps") ? Cell{c["stable_steps"].get<double>()} : Cell{}, t_end,
          r["status"].get<std::string>(), value("t_reached"), f.contains("impacts") ? Cell{f["impacts"].get<long>()} : Cell{},
          value("switches"), value("missed_switches"), spec.budget_of(p, c["dt"].get<double>(), t_end), value("max_penetration"), spec.max_penetration_of(p),
          value("energy_scale"), value("energy_growth"), spec.energy_blow_up_of(p), value("final_energy_error"),
          f.contains("note") ? Cell{f["note"].get<std::string>()} : Cell{}, fi.name, parameters_text(fi, p.label), fi.label,
          value("min_step"), value("max_step"),
          r["steps"].get<long>() > 0 ? number_cell(real_or_nan(r, "cpu") / static_cast<double>(r["steps"].get<long>())) : Cell{}};
}

const std::vector<Column>& history_columns() {
  static const std::vector<Column> columns = {
      {"problem", "", "", ""}, {"problem name", "", "", "the registered problem"}, {"integrator", "", "", ""}, {"run", "", "", ""},
      {"t", "s", "", "end of the interval"},
      {"energy deviation", "", "", "largest |E - E0| / E scale over the interval"},
      {"penetration", "m", "", "largest -min g over the interval (negative: every gap open)"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"},
      {"momentum residual", "", "", "largest |P - P0 - sum of the impulses| / sum_i m_i |v0_i| over the interval"}};
  return columns;
}

const std::vector<Column>& samples_columns() {
  static const std::vector<Column> columns = {
      {"problem", "", "", ""}, {"problem name", "", "", "the registered problem"}, {"integrator", "", "", ""}, {"run", "", "", ""},
      {"t", "s", "", "the sample's step"}, {"energy ratio", "", "", "E / E0"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"}};
  return columns;
}

const std::vector<Column>& periodic_columns() {
  static const std::vector<Column> columns = run_series_columns(
      {{"k", "", "", "the sample's number: at the first step past from + k every"}, {"value", "", "", "the measure's sample"},
       {"|value|", "", "", "its absolute value (a log scale)"}});
  return columns;
}

const std::vector<Column>& trajectory_columns() {
  static const std::vector<Column> columns = run_series_columns({{"t", "s", "", "the sample's step"}, {"value", "", "", "the observable"}});
  return columns;
}

const std::vector<Column>& flights_columns() {
  static const std::vector<Column> columns = run_series_columns(
      {{"flight", "", "", "i: the flight after impact i"}, {"energy ratio", "", "", "E_i / E0, E_i the flight's measured energy"},
       {"exact energy ratio", "", "", "the exact E_i / E0"}, {"|rel. err|", "", "", "|E_i / E_i exact - 1|"}});
  return columns;
}

// The columns of an impulses and of a field table ("field": one column per cell at table time).
const std::vector<Column>& impulses_columns() {
  static const std::vector<Column> columns = labelled_run_series_columns(
      {{"t", "s", "", "the bin's end t_j = j dt"}, {"value", "", "", "the contact impulses of the bin (t_j - dt, t_j] over dt and the scale"}});
  return columns;
}

const std::vector<Column>& field_columns() {
  static const std::vector<Column> columns = labelled_run_series_columns(
      {{"t", "s", "", "the step's end (a run's first row: its start)"}, {"field", "", "", "the element stress of each cell"}});
  return columns;
}

// The columns of sweep_work_column_names: the solver's own steps and Jacobians (CVODE's counts,
// which the driver's steps and F_int evaluations are not for the references), and each
// converging measure's rate against the next run of the sweep.
std::vector<Column> sweep_work_columns(const StudySpec& spec) {
  std::vector<Column> columns = {{"solver steps", "", "{:.0f}", "the integrator's own steps (CVODE's internal steps)"},
                                 {"Jacobians", "", "{:.0f}", "tangent (Jacobian) evaluations"}};
  for (const auto& m : spec.measures)
    if (measure_converges(m))
      columns.push_back({"rate of " + m.label, "", kOrderFormat,
                         "log(e / e') / log(x' / x) against the next run x' of the sweep (x: its step, tolerance or swept parameter)"});
  return columns;
}

std::vector<Cell> sweep_work_cells(const StudySpec& spec, const Json& r) {
  const auto count = [&](const char* key) { return r.contains(key) ? Cell{r[key].get<long>()} : Cell{}; };
  std::vector<Cell> cells = {count("solver_steps"), count("tangent_evaluations")};
  std::size_t k = 0;
  for (const auto& m : spec.measures)
    if (measure_converges(m)) cells.push_back(r.contains("next_rates") ? number_cell(r["next_rates"][k++]) : Cell{});
  return cells;
}

}  // namespace nsb::study_files

namespace nsb {

const std::vector<std::string>& run_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::run_columns());
  return names;
}

const std::vector<std::string>& history_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::history_columns());
  return names;
}

std::vector<std::string> sweep_work_column_names(const StudySpec& spec) { return study_files::column_names(study_files::sweep_work_columns(spec)); }

const std::vector<std::string>& samples_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::samples_columns());
  return names;
}

const std::vector<std::string>& periodic_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::periodic_columns());
  return names;
}

const std::vector<std::string>& trajectory_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::trajectory_columns());
  return names;
}

const std::vector<std::string>& flights_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::flights_columns());
  return names;
}

const std::vector<std::string>& impulses_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::impulses_columns());
  return names;
}

const std::vector<std::string>& field_column_names() {
  static const std::vector<std::string> names = study_files::column_names(study_files::field_columns());
  return names;
}

std::vector<std::string> parameter_column_names(const StudySpec& spec) {
  std::vector<std::string> names;
  for (const auto& p : spec.problems)
    for (const auto& s : find_problem(p.name).parameters())
      if (std::find(names.begin(), names.end(), "parameter " + s.name) == names.end()) names.push_back("parameter " + s.name);
  return names;
}

}  // namespace nsb
