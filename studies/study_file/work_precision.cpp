// The engine's own tables (work-precision, fitted orders, ranking, energy history) and the
// declared tables built from them.
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "integrators/registry.hpp"
#include "studies/measures.hpp"
#include "studies/ranking.hpp"

namespace nsb::study_files {

namespace {

// What a Hausdorff measure's graphs are of: its observable, or each problem's ("v_contact (signorini-bar), ...").
std::string graph_observables(const FileMeasure& m) {
  if (m.problem_observables.empty()) return m.observable;
  std::vector<std::string> each;
  for (const auto& [label, name] : m.problem_observables) each.push_back(fmt::format("{} ({})", name, label));
  return fmt::format("{}", fmt::join(each, ", "));
}

// What the errors on a problem are measured against, as captions and the ranking say it.
std::string against_text(const FileReference* r) {
  if (!r) return "no reference";
  if (!r->against.empty()) return r->against;
  return r->exact      ? "the exact solution"
         : r->lockstep ? fmt::format("{} stepped with each run (lockstep)", r->integrator)
                       : fmt::format("{} (dt = {}, cached)", r->integrator, r->dt);
}

// The texts of the case-table column `of` in the runs `shown` keeps (none: no cell), each once,
// in the order of the runs.
std::vector<std::string> column_values(const Table& runs, const std::string& of, const std::function<bool(const std::vector<Cell>&)>& shown) {
  const std::size_t column = column_index(runs, of);
  std::vector<std::string> seen;
  for (const auto& row : runs.rows) {
    if (std::holds_alternative<std::monostate>(row[column]) || !shown(row)) continue;
    const std::string text = pivot_value_text(row[column]);
    if (!text.empty() && std::find(seen.begin(), seen.end(), text) == seen.end()) seen.push_back(text);
  }
  return seen;
}

// A declared table's caption with each ${COLUMN} (caption_placeholders; the reader checked that
// each names a case-table column) replaced by that column's values over the runs the table
// shows (its problems, integrators, where, drop_above and except), joined by ", ": a caption
// that says the grid that was run, --full's or the default's.
std::string expanded_caption(const FileTable& d, const Table& runs) {
  std::string out = *d.caption;
  const std::size_t problem = column_index(runs, "problem");
  const std::size_t label = d.integrators.empty() ? 0 : column_index(runs, "integrator label");
  const auto shown = [&](const std::vector<Cell>& row) {
    return d.applies_to(std::get<std::string>(row[problem])) && shows_run(d, runs, row) &&
           (d.integrators.empty() ||
            std::find(d.integrators.begin(), d.integrators.end(), std::get<std::string>(row[label])) != d.integrators.end());
  };
  const std::vector<CaptionPlaceholder> places = caption_placeholders(out);
  for (auto p = places.rbegin(); p != places.rend(); ++p)  // from the last: the earlier positions hold
    out.replace(p->at, p->size, fmt::format("{}", fmt::join(column_values(runs, p->column, shown), ", ")));
  return out;
}

// The study's metadata lines and each declared table's own (MetadataLine) on `tables`, the
// values of a column from the case table `runs` (every column), each once, in its rows' order.
void add_metadata_lines(const StudySpec& spec, const Table& runs, std::vector<Table>& tables) {
  const auto value = [&](const MetadataLine& m) {
    if (m.of.empty()) return m.text;
    return fmt::format("{}", fmt::join(column_values(runs, m.of, [](const std::vector<Cell>&) { return true; }), " "));
  };
  for (Table& t : tables) {
    for (const MetadataLine& m : spec.metadata) t.metadata.emplace_back(m.line, value(m));
    const auto own = std::find_if(spec.tables.begin(), spec.tables.end(), [&](const FileTable& d) { return d.id == t.id; });
    if (own != spec.tables.end())
      for (const MetadataLine& m : own->metadata) t.metadata.emplace_back(m.line, value(m));
  }
}

// The tables the file declares, built from the engine's work-precision (`runs`), orders and
// ranking tables.
std::vector<Table> declared_tables(const StudySpec& spec, const Table& runs, const Table& orders, const std::optional<Table>& rank,
                                   const std::function<Table(const FileTable&)>& history) {
  std::vector<Table> out;
  bool figures_placed = false;
  for (const FileTable& d : spec.tables) {
    Table t;
    if (d.rows == "history" || d.rows == "samples" || d.of_some_runs() || !d.fit_against.empty()) {
      t = history(d);
    } else if (d.rows == "ranking") {
      t = *rank;  // the reader refuses a ranking without a ranked measure
    } else if (d.rows == "case") {
      t = case_table(d, runs, !figures_placed);
      t.caption = runs.caption;
      figures_placed = true;
    } else {
      t = group_table(spec, d, orders, runs);
      t.caption = orders.caption;
    }
    t.id = d.id;
    t.title = d.title;
    if (d.caption) t.caption = expanded_caption(d, runs);
    t.metadata = runs.metadata;
    out.push_back(std::move(t));
  }
  return out;
}

// What the errors are measured against: one text, or one per problem where they differ.
std::string errors_against(const StudySpec& spec) {
  std::vector<std::string> per_problem;
  for (const auto& p : spec.problems) per_problem.push_back(p.label + ": " + against_text(spec.reference_of(p)));
  const bool one_reference = std::all_of(spec.problems.begin(), spec.problems.end(), [&](const FileProblem& p) {
    return against_text(spec.reference_of(p)) == against_text(spec.reference_of(spec.problems.front()));
  });
  return one_reference ? against_text(spec.reference_of(spec.problems.front()))
                       : fmt::format("{}", fmt::join(per_problem, "; "));
}

// The work-precision table of the study's runs: its caption and columns (its rows: EngineTables::add_sweep).
Table work_precision_table(const StudySpec& spec, const std::string& cpu) {
  const std::string against = errors_against(spec);
  Table t;
  t.id = spec.name + "_work_precision";
  t.title = spec.title + ": work-precision";
  t.caption = fmt::format("Errors against {}; CPU: {}. Errors of an observable are relative to its largest reference value "
                          "over the run; an impact time is the end of the step holding the impact (resolution: the step, for "
                          "event-driven the output step dt). Diverged, over-budget and declined runs are rows with their reason.",
                          against, cpu);
  for (const auto& m : spec.measures)
    if (m.kind == MeasureKind::Hausdorff)
      t.caption += fmt::format(" {}: Hausdorff distance between the graphs of {} (jumps of the exact solution as vertical segments) "
                               "in scaled coordinates (t / {}, value / {}).", m.label, graph_observables(m),
                               m.time_scale > 0.0 ? fmt::format("{:g} s", m.time_scale) : "t_end",
                               m.value_scale > 0.0 ? fmt::format("{:g}", m.value_scale) : "the reference's largest |value|");
  for (const auto& m : spec.measures)
    if (!m.problems.empty())
      t.caption += fmt::format(" {}: measured on {} only (n/a on the other problems).", m.label, fmt::join(m.problems, ", "));
  t.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"dt", "s", "{:.2e}", "requested step"},
               {"tol", "", "{:.1e}", "tolerance of a tolerance sweep"}};
  for (const auto& m : spec.measures)
    t.columns.push_back({m.label, (m.kind == MeasureKind::ImpactTime && m.norm != "count") || m.kind == MeasureKind::StopTime || m.kind == MeasureKind::OnsetTime || m.kind == MeasureKind::RestTime || m.kind == MeasureKind::PeakTime || m.kind == MeasureKind::RestStart ? "s" : m.kind == MeasureKind::Energy && m.norm == "drift" && m.every == 0.0 ? "1/s" : "",
                         "{:.3e}", ""});
  t.columns.insert(t.columns.end(), {{"CPU", "s", "{:.2e}", "", true}, {"steps", "", "", ""},
                                     {"F_int evals", "", "", "internal force evaluations"},
                                     {"status", "", "", fmt::format("energy blow-up: E rose above E0 by more than {} E scale "
                                                                    "(|E0|, or the problem's energy scale when E0 = 0) plus the "
                                                                    "work W a moving obstacle and time-dependent loads can have "
                                                                    "done; energy lost never counts (not ranked){}", spec.energy_blow_up,
                                                                    std::isfinite(spec.max_penetration)
                                                                        ? fmt::format("; penetration: max(0, -g) above {}", spec.max_penetration)
                                                                        : "")}});
  return t;
}

Table orders_table(const StudySpec& spec) {
  Table orders;
  orders.id = spec.name + "_orders";
  orders.title = spec.title + ": fitted orders";
  orders.caption = "Least-squares slope of log(error) against log(dt) (log(tol) for a tolerance sweep) with its 95% "
                   "confidence interval (Student t, n - 2 degrees of freedom); errors below 1e-11 are round-off and left out.";
  orders.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"measure", "", "", ""}, {"against", "", "", ""},
                    {"order", "", kOrderFormat, ""}, {"CI low", "", kOrderFormat, "95% confidence interval"},
                    {"CI high", "", kOrderFormat, ""}, {"points", "", "", ""}};
  orders.columns[4].interval = {"CI low", "CI high"};
  return orders;
}

Table energy_history_table(const StudySpec& spec) {
  Table history;
  history.id = spec.name + "_energy_history";
  history.title = spec.title + ": energy error history";
  history.caption = fmt::format("max |E - E0| / |E0| over each of {} equal intervals of [0, t_end]", kHistoryIntervals);
  history.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"run", "", "", ""}, {"t", "s", "", ""},
                     {"energy err", "", "", ""}};
  history.csv_only = true;
  if (!spec.declared_figures_only)
    history.figures = {{spec.name + "_energy_history", spec.title + ": energy error", "t", "energy err", {"integrator", "run"}, {"problem"}, false, true}};
  return history;
}

// The work-precision figures of the ranked measure (primary), the convergence figures of the
// measures that converge (the engine's own, unless study.figures = "declared") and the declared
// figures drawn from the runs.
void add_work_precision_figures(const StudySpec& spec, std::vector<FileMeasure>::const_iterator primary, Table& t) {
  if (primary != spec.measures.end() && !spec.declared_figures_only) {
    t.figures = {{spec.name + "_work_precision", spec.title + ": " + primary->label + " against CPU time", "CPU", primary->label, {"integrator"}, {"problem"}, true, true},
                 {spec.name + "_work_precision_evals", spec.title + ": " + primary->label + " against F_int evaluations", "F_int evals", primary->label, {"integrator"}, {"problem"}, true, true}};
  }
  for (const auto& m : spec.measures)
    if (measure_converges(m) && !spec.declared_figures_only)
      t.figures.push_back({fmt::format("{}_convergence_{}", spec.name, &m - spec.measures.data()), spec.title + ": convergence of " + m.label,
                           "dt", m.label, {"integrator"}, {"problem"}, true, true, {1, 2}});

  for (const FileFigure& f : spec.figures)
    if (f.table.empty())  // else drawn from its history table
      t.figures.push_back(declared_figure(spec, f));
}

// The columns only declared tables show: work counters, each error's order against the run
// before it (the previous step or tolerance of the same sweep), the runs' own columns.
std::vector<Column> declared_only_columns(const StudySpec& spec) {
  std::vector<Column> counters = {{"factorizations", "", "", ""}, {"LCP its", "", "", "LCP iterations"}};
  for (const auto& m : spec.measures)
    if (measure_converges(m)) counters.push_back({"pairwise order of " + m.label, "", kOrderFormat, "against the previous run of the sweep"});
  counters.insert(counters.end(), run_columns().begin(), run_columns().end());
  const std::vector<Column> own = study_run_columns(spec), work = sweep_work_columns(spec);
  counters.insert(counters.end(), own.begin(), own.end());
  counters.insert(counters.end(), work.begin(), work.end());
  return counters;
}

// The engine's own tables of a study's runs, filled sweep by sweep (add_sweep): the
// work-precision rows and the cells of each run only declared tables show, the fitted orders,
// the energy histories and the ranking's curves.
class EngineTables {
 public:
  EngineTables(const StudySpec& spec, const std::string& cpu, std::size_t ncases);
  // The runs of one sweep (sweep_runs), in its order; runs_format: the number format of dt or tol
  // in the ranking's runs cells.
  void add_sweep(const std::vector<Json>& cases, const std::vector<Json>& results, const std::vector<std::size_t>& sweep,
                 const std::optional<std::string>& runs_format);
  // The ranking of the ranked measure (none: no measure to rank by).
  std::optional<Table> rank(const std::string& cpu);
  // The work-precision table with the columns only declared tables show.
  Table runs_all() const;

  Table t, orders, history;
  std::vector<std::size_t> case_row;  // each case's row in t

 private:
  std::size_t ranked_index(const FileProblem& p) const;
  // The cells of a run (the sweep's k-th: xs, ys up to it) only declared tables show.
  std::vector<Cell> declared_only_cells(const Json& c, const Json& r, const std::vector<double>& xs,
                                        const std::vector<std::vector<double>>& ys) const;

  const StudySpec& spec;
  std::vector<FileMeasure>::const_iterator primary;  // the ranked measure (end: none)
  std::vector<std::vector<Cell>> counter_rows;       // each row's cells of declared_only_columns
  std::vector<RankingProblem> ranking;
  std::vector<std::string> ranking_first;  // the label of each ranked problem's first problem
  std::vector<std::pair<std::string, std::string>> meta;
};

EngineTables::EngineTables(const StudySpec& spec, const std::string& cpu, std::size_t ncases)
    : t(work_precision_table(spec, cpu)), orders(orders_table(spec)), history(energy_history_table(spec)), case_row(ncases), spec(spec),
      primary(spec.measures.begin() + static_cast<long>(std::min(spec.ranked, spec.measures.size()))),
      meta({{"study", spec.name}, {"study_file", spec.file}, {"study_file_fnv1a64", spec.hash}, {"t_end", fmt::format("{}", spec.t_end)}}) {
  t.metadata = orders.metadata = history.metadata = meta;
  add_work_precision_figures(spec, primary, t);
  // Event times are against the problem's exact solution whatever the reference.
  const bool exact_times = primary != spec.measures.end() && is_event_time(*primary);
  // One ranked problem per sweep's problem: a joint refinement's problems are one (its family).
  for (const auto& p : spec.problems) {
    if (std::any_of(ranking.begin(), ranking.end(), [&](const RankingProblem& r) { return r.label == p.family_label(); })) continue;
    const FileReference* ref = spec.reference_of(p);
    ranking.push_back({p.family_label(), exact_times ? "the exact solution" : against_text(ref), exact_times || !ref ? 0.0 : ref->floor,
                       spec.targets, {}});
    ranking_first.push_back(p.label);
  }
}

std::size_t EngineTables::ranked_index(const FileProblem& p) const {
  return static_cast<std::size_t>(std::find_if(ranking.begin(), ranking.end(), [&](const RankingProblem& r) { return r.label == p.family_label(); }) -
                                  ranking.begin());
}

void EngineTables::add_sweep(const std::vector<Json>& cases, const std::vector<Json>& results, const std::vector<std::size_t>& sweep,
                             const std::optional<std::string>& runs_format) {
  const std::size_t begin = sweep.front();
  const std::size_t pi = cases[begin]["problem"], ii = cases[begin]["integrator"];
  const std::string plabel = spec.problems[pi].family_label();
  const FileIntegrator& fi = spec.integrators[ii];
  const std::string ilabel = shown_label(fi, spec.problems[pi].label);
  const IntegratorEntry& entry = find_integrator(fi.name);
  WorkCurve curve{ilabel, entry.reference, {}, entry.peer};
  std::vector<double> xs;
  std::vector<std::vector<double>> ys(spec.measures.size());
  for (const std::size_t k : sweep) {
    const Json& r = results[k];
    const bool tol = !cases[k]["tol"].is_null();
    xs.push_back(tol ? cases[k]["tol"].get<double>() : cases[k]["dt"].get<double>());
    std::vector<Cell> row = {spec.problems[cases[k]["problem"].get<std::size_t>()].label, ilabel, cases[k]["dt"].get<double>(),
                             number_cell(cases[k]["tol"])};
    for (std::size_t m = 0; m < spec.measures.size(); ++m) {
      const double v = r.contains("values") ? real(r["values"][m]) : kNaN;
      ys[m].push_back(v);
      row.push_back(number_cell(v));
    }
    const std::string status = r["status"];
    row.insert(row.end(), {number_cell(real_or_nan(r, "cpu")), r["steps"].get<long>(), r["force_evaluations"].get<long>(),
                           status == status_name(RunStatus::Ok) ? status : status + ": " + r["message"].get<std::string>()});
    case_row[k] = t.rows.size();
    t.add_row(std::move(row));
    counter_rows.push_back(declared_only_cells(cases[k], r, xs, ys));
    // A declined run is no point; a run an outcome threshold removed (its values kept: energy
    // blow-up, penetration) names the rule; one without values (diverged, over budget) has no error.
    if (primary != spec.measures.end() && status != kDeclinedStatus)
      curve.points.push_back({run_label(cases[k], runs_format), real_or_nan(r, "cpu"), ys[primary - spec.measures.begin()].back(),
                              status != status_name(RunStatus::Ok) && r.contains("values") ? status : "",
                              real_or_nan(r, "cpu_spread")});
    if (r.contains("history"))
      for (std::size_t h = 0; h < r["history"]["t"].size(); ++h)
        history.add_row({spec.problems[cases[k]["problem"].get<std::size_t>()].label, ilabel, run_label(cases[k]),
                         number_cell(r["history"]["t"][h]), number_cell(r["history"]["e"][h])});
  }
  ranking[ranked_index(spec.problems[pi])].curves.push_back(curve);
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    if (!measure_converges(spec.measures[m]) || !spec.measures[m].applies_to(spec.problems[pi].label)) continue;
    std::vector<double> e = ys[m];
    for (double& x : e)
      if (!is_event_time(spec.measures[m])) x = above_round_off(x);
    const OrderFit fit = fit_order(xs, e);
    orders.add_row({plabel, ilabel, spec.measures[m].label, cases[begin]["tol"].is_null() ? "dt" : "tol",
                    number_cell(fit.order), number_cell(fit.low), number_cell(fit.high), static_cast<long>(fit.points)});
  }
}

std::vector<Cell> EngineTables::declared_only_cells(const Json& c, const Json& r, const std::vector<double>& xs,
                                                    const std::vector<std::vector<double>>& ys) const {
  const auto count = [&](const char* key) { return r.contains(key) ? Cell{r[key].get<long>()} : Cell{}; };
  std::vector<Cell> more = {count("factorizations"), count("lcp_iterations")};
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    if (!measure_converges(spec.measures[m])) continue;
    const std::size_t i = xs.size() - 1;
    const auto e = [&](std::size_t j) { return is_event_time(spec.measures[m]) ? ys[m][j] : above_round_off(ys[m][j]); };
    more.push_back(i ? number_cell(observed_order(xs[i - 1], e(i - 1), xs[i], e(i))) : Cell{});
  }
  const std::vector<Cell> run = run_cells(spec, c, r), study = study_run_cells(spec, c, r),
                          work = sweep_work_cells(spec, r);
  more.insert(more.end(), run.begin(), run.end());
  more.insert(more.end(), study.begin(), study.end());
  more.insert(more.end(), work.begin(), work.end());
  return more;
}

std::optional<Table> EngineTables::rank(const std::string& cpu) {
  // The first declared ranking's error column.
  const auto ranking_declared = std::find_if(spec.tables.begin(), spec.tables.end(), [](const FileTable& d) { return d.rows == "ranking"; });
  const auto runs = std::find_if(spec.tables.begin(), spec.tables.end(), [](const FileTable& d) { return d.rows == "case"; });
  const std::string runs_id = runs == spec.tables.end() ? t.id : runs->id;  // where the ranked errors are shown
  if (primary == spec.measures.end()) return std::nullopt;
  for (std::size_t r = ranking.size(); r-- > 0;)
    if (!primary->applies_to(ranking_first[r])) ranking.erase(ranking.begin() + static_cast<long>(r));
  Column error{primary->label, is_event_time(*primary) ? "s" : "", "{:.1e}", primary->label + " of " + runs_id};
  if (ranking_declared != spec.tables.end() && ranking_declared->error) error = declared_column(error, *ranking_declared->error);
  Table rank = ranking_table(spec.name + "_ranking", spec.title + ": cheapest integrator at each target error", error, cpu, ranking);
  rank.metadata = meta;
  return rank;
}

Table EngineTables::runs_all() const {
  Table all = t;
  const std::vector<Column> declared_only = declared_only_columns(spec);
  all.columns.insert(all.columns.end(), declared_only.begin(), declared_only.end());
  for (std::size_t r = 0; r < all.rows.size(); ++r) all.rows[r].insert(all.rows[r].end(), counter_rows[r].begin(), counter_rows[r].end());
  return all;
}

}  // namespace

std::vector<Table> file_tables(const StudySpec& spec, const std::vector<Json>& cases, const std::vector<Json>& results) {
  const std::string cpu = spec.cpu_repeats > 0
                              ? median_cpu_text(spec.cpu_repeats)
                              : "thread CPU time of the stepping of the observed run (observer excluded)";
  EngineTables engine(spec, cpu, cases.size());
  // The first declared ranking's number format of its runs cells.
  const auto ranking_declared = std::find_if(spec.tables.begin(), spec.tables.end(), [](const FileTable& d) { return d.rows == "ranking"; });
  const std::optional<std::string> runs_format = ranking_declared == spec.tables.end() ? std::nullopt : ranking_declared->runs_format;
  for (const std::vector<std::size_t>& sweep : sweep_runs(spec, cases)) engine.add_sweep(cases, results, sweep, runs_format);
  const std::optional<Table> rank = engine.rank(cpu);
  const Table& t = engine.t;
  const Table& orders = engine.orders;
  const std::vector<std::size_t>& case_row = engine.case_row;
  std::vector<Table> tables;
  if (!spec.tables.empty()) {
    const Table runs_all = engine.runs_all();
    tables = declared_tables(spec, runs_all, orders, rank, [&](const FileTable& d) {
      if (!d.fit_against.empty()) {
        Table fits = group_table(spec, d, fits_against_parameter(spec, d, cases, results, orders), runs_all);
        fits.caption = fmt::format("Least-squares slope of log(value) against log({}) over the runs of each sweep.", d.fit_against);
        return fits;
      }
      if (d.rows == "pivot") return pivot_table(spec, d, runs_all);
      if (d.rows == "impulses") return impulses_table(spec, d, cases, results, runs_all, case_row);
      if (d.rows == "field") return field_table(spec, d, cases, results, runs_all, case_row);
      return d.of_some_runs() ? run_series_table(spec, d, cases, results, runs_all, case_row) : history_table(spec, d, cases, results);
    });
    add_metadata_lines(spec, runs_all, tables);
  } else {
    tables.push_back(t);
    if (!orders.rows.empty()) tables.push_back(orders);
    if (rank) tables.push_back(*rank);
  }
  if (!engine.history.rows.empty()) tables.push_back(engine.history);
  return tables;
}

}  // namespace nsb::study_files
