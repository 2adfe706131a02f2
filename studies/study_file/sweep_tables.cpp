// What a sweep (the runs of one integrator on one problem or joint refinement) gives: the group
// tables of its fitted orders, fits against a problem parameter, and each run compared with the
// next run of its sweep.
#include "core/deterministic_math.hpp"
#include "studies/study_file/engine.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/parameters.hpp"
#include "problems/registry.hpp"
#include "studies/measures.hpp"

namespace nsb::study_files {

namespace {

// A group's cell of column `name` of `orders` (fits_against_parameter's stable steps): its first row's.
Cell group_cell(const Table& orders, const Cell& problem, const Cell& integrator, const std::string& name) {
  const auto row = std::find_if(orders.rows.begin(), orders.rows.end(), [&](const auto& r) { return r[0] == problem && r[1] == integrator; });
  return row == orders.rows.end() ? Cell{} : (*row)[column_index(orders, name)];
}

// The column "note" of a group table: why its fits may be n/a.
Column group_note_column() { return {"note", "", "", "declined (n/a), or the status of the group's first run that failed"}; }

// The note of a group (problem or family label, integrator label): "declined" when its first run
// that is not ok was declined (status n/a), else that run's status (diverged, over budget, ...);
// empty when every run is ok. From the runs table's problem, integrator and outcome columns.
Cell group_note(const StudySpec& spec, const Table& runs, const Cell& problem, const Cell& integrator) {
  const std::size_t outcome = column_index(runs, "outcome");
  for (const auto& row : runs.rows) {
    const auto p = std::find_if(spec.problems.begin(), spec.problems.end(),
                                [&](const FileProblem& q) { return Cell{q.label} == row[0]; });
    if (p == spec.problems.end() || Cell{p->family_label()} != problem || row[1] != integrator) continue;
    const std::string status = std::get<std::string>(row[outcome]);
    if (status != status_name(RunStatus::Ok)) return status == kDeclinedStatus ? "declined" : status;
  }
  return std::string();
}

// An order shown with both ends of its interval ("order of X", "CI low of X", "CI high of X"
// among the table's columns, `columns` under their headers): Markdown and LaTeX print the three
// in its cell (Column::interval).
void mark_intervals(const FileTable& d, std::vector<Column>& columns) {
  const auto declared = [&](const std::string& of) {
    return static_cast<std::size_t>(std::find_if(d.columns.begin(), d.columns.end(), [&](const FileColumn& c) { return c.of == of; }) -
                                    d.columns.begin());
  };
  for (std::size_t i = 0; i < d.columns.size(); ++i) {
    if (d.columns[i].of.rfind("order of ", 0) != 0) continue;
    const std::string measure = d.columns[i].of.substr(std::string("order of ").size());
    const std::size_t low = declared("CI low of " + measure), high = declared("CI high of " + measure);
    if (low < columns.size() && high < columns.size()) columns[i].interval = {columns[low].name, columns[high].name};
  }
}

}  // namespace

// rows = "group": one row per problem (a joint refinement's family) and integrator of the
// table's problems (in the order of the runs), the fitted orders' columns ("order of
// <measure>", ...) side by side, n/a where no fit was made, the problem's parameters
// ("parameter NAME": the first problem's of a joint refinement's family) and the note.
Table group_table(const StudySpec& spec, const FileTable& d, const Table& orders, const Table& runs) {
  Table out;
  std::vector<std::pair<Cell, Cell>> groups;  // (problem, integrator)
  for (const auto& row : orders.rows)
    if (d.applies_to(std::get<std::string>(row[0])) && std::find(groups.begin(), groups.end(), std::pair{row[0], row[1]}) == groups.end())
      groups.emplace_back(row[0], row[1]);
  const std::vector<Column> parameters = parameter_columns(spec);
  const auto parameter = [&](const std::string& name) {
    return std::find_if(parameters.begin(), parameters.end(), [&](const Column& c) { return c.name == name; });
  };
  for (const FileColumn& c : d.columns) {
    const auto of = c.of.find(" of ");
    if (const auto p = parameter(c.of); p != parameters.end()) out.columns.push_back(declared_column(*p, c));
    else if (c.of == "note") out.columns.push_back(declared_column(group_note_column(), c));
    else out.columns.push_back(declared_column(orders.columns[column_index(orders, of == std::string::npos ? c.of : c.of.substr(0, of))], c));
  }
  mark_intervals(d, out.columns);
  for (const auto& [problem, integrator] : groups) {
    const auto fp = std::find_if(spec.problems.begin(), spec.problems.end(),
                                 [&, &problem = problem](const FileProblem& q) { return Cell{q.family_label()} == problem; });
    std::vector<Cell> cells;
    for (const FileColumn& c : d.columns) {
      const auto of = c.of.find(" of ");
      if (parameter(c.of) != parameters.end()) {
        cells.push_back(parameter_cells(*fp, {c.of}).front());
        continue;
      }
      if (c.of == "note") {
        cells.push_back(group_note(spec, runs, problem, integrator));
        continue;
      }
      if (of == std::string::npos) {
        cells.push_back(c.of == "problem" ? problem : c.of == "integrator" ? integrator : group_cell(orders, problem, integrator, c.of));
        continue;
      }
      const std::size_t k = column_index(orders, c.of.substr(0, of));
      const Cell measure = c.of.substr(of + 4);
      const auto row = std::find_if(orders.rows.begin(), orders.rows.end(),
                                    [&](const auto& r) { return r[0] == problem && r[1] == integrator && r[2] == measure; });
      cells.push_back(row == orders.rows.end() ? Cell{} : (*row)[k]);
    }
    out.add_row(std::move(cells));
  }
  return out;
}

// The runs of each sweep, in the order of the first: those of one integrator on one problem,
// or on the problems of one joint refinement (FileProblem::family, refined along the grid's
// key `refine`: the runs of every refinement, by the refinements' order).
std::vector<std::vector<std::size_t>> sweep_runs(const StudySpec& spec, const std::vector<Json>& cases) {
  std::vector<std::vector<std::size_t>> out;
  std::vector<std::pair<std::string, std::size_t>> keys;  // (family label, integrator) of each sweep
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const std::pair<std::string, std::size_t> key{spec.problems[cases[k]["problem"].get<std::size_t>()].family_label(),
                                                  cases[k]["integrator"].get<std::size_t>()};
    const auto it = std::find(keys.begin(), keys.end(), key);
    if (it == keys.end()) {
      keys.push_back(key);
      out.push_back({k});
    } else {
      out[static_cast<std::size_t>(it - keys.begin())].push_back(k);
    }
  }
  return out;
}

// A group table's own fits (FileTable::fit_against = "1/KEY"), in the columns of the engine's
// `orders`: for each sweep (a family's runs of one integrator) and each measure measured on it,
// the least-squares order of its values against 1 / KEY of each run's problem (fit_order: every
// positive finite value a point, no round-off cut).
Table fits_against_parameter(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                             const Table& orders) {
  Table out;
  out.columns = orders.columns;
  out.columns.push_back({"stable steps", "", "{}", "dt / the problem's stable step, when the sweep sets it so"});
  const std::string key = d.fit_against.substr(2);
  for (const std::vector<std::size_t>& sweep : sweep_runs(spec, cases)) {
    const FileProblem& first = spec.problems[cases[sweep.front()]["problem"].get<std::size_t>()];
    const std::string integrator = shown_label(spec.integrators[cases[sweep.front()]["integrator"].get<std::size_t>()], first.label);
    std::vector<double> h;
    for (const std::size_t k : sweep) {
      const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
      const ParamSpecs specs = find_problem(p.name).parameters();
      const Params params(specs, p.parameters);
      const bool integer = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.name == key; })->kind == ParamSpec::Kind::Integer;
      h.push_back(1.0 / (integer ? static_cast<double>(params.integer(key)) : params.real(key)));
    }
    for (std::size_t m = 0; m < spec.measures.size(); ++m) {
      if (!spec.measures[m].applies_to(first.label)) continue;
      std::vector<double> e;
      for (const std::size_t k : sweep) e.push_back(results[k].contains("values") ? real(results[k]["values"][m]) : kNaN);
      const OrderFit fit = fit_order(h, e);
      const Json& c = cases[sweep.front()];
      out.add_row({first.family_label(), integrator, spec.measures[m].label, d.fit_against, number_cell(fit.order), number_cell(fit.low),
                   number_cell(fit.high), static_cast<long>(fit.points), c.contains("stable_steps") ? Cell{c["stable_steps"].get<double>()} : Cell{}});
    }
  }
  return out;
}

// What compares a run with the next run of its sweep (the next step, tolerance or swept
// parameter x'), when both are ok: each estimate measure's value, max over the common samples
// of |o - o'| (divided by 1 - (x'/x)^q with its order q), and the rate of each converging
// measure against it, observed_order(1/x, e, 1/x', e') (the order in 1/x: a stiffness's rate,
// positive when the error falls as x grows). A run last in its sweep has neither.
std::vector<Json> with_next_run_estimates(const StudySpec& spec, const std::vector<Json>& cases, std::vector<Json> results) {
  const auto x_of = [&](std::size_t k) { return cases[k]["tol"].is_null() ? cases[k]["dt"].get<double>() : cases[k]["tol"].get<double>(); };
  for (const std::vector<std::size_t>& sweep : sweep_runs(spec, cases))
    for (std::size_t i = 0; i < sweep.size(); ++i) {
      Json& r = results[sweep[i]];
      const bool next = i + 1 < sweep.size() && results[sweep[i + 1]]["status"] == status_name(RunStatus::Ok) &&
                        r["status"] == status_name(RunStatus::Ok) && r.contains("values");
      Json rates = Json::array();
      for (std::size_t m = 0; m < spec.measures.size(); ++m) {
        const FileMeasure& fm = spec.measures[m];
        if (!next) {
          if (measure_converges(fm)) rates.push_back(nullptr);
          continue;
        }
        const Json& n = results[sweep[i + 1]];
        const double x = x_of(sweep[i]), x_next = x_of(sweep[i + 1]);
        if (measure_converges(fm)) {
          const auto e = [&](const Json& run) { return is_event_time(fm) ? real(run["values"][m]) : above_round_off(real(run["values"][m])); };
          rates.push_back(real(observed_order(1.0 / x, e(r), 1.0 / x_next, e(n))));
        }
        if (fm.kind != MeasureKind::Estimate || !r.contains("samples") || !n.contains("samples")) continue;
        const std::string key = std::to_string(m);
        const auto a = r["samples"][key].get<std::vector<double>>(), b = n["samples"][key].get<std::vector<double>>();
        double d = 0.0;
        for (std::size_t k = 0; k < std::min(a.size(), b.size()); ++k) d = std::max(d, std::abs(a[k] - b[k]));
        r["values"][m] = real(fm.order != 0.0 ? d / (1.0 - nsb::dmath::pow(x_next / x, fm.order)) : d);
      }
      r["next_rates"] = rates;
    }
  return results;
}

}  // namespace nsb::study_files
