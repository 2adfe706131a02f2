#pragma once
// Studies read from a file (`nsbench-study run FILE.toml`, or FILE.json with the same schema):
// problems with their parameters, integrators with their step (or tolerance) sweeps, a
// reference (the exact solution or a reference integrator, cached by reference/cache.hpp) and
// measures. The file becomes a StudyEntry whose cases (one per problem, integrator and step)
// run in the built-in studies' driver (parallel, --shard, --merge) and whose tables go
// through the same writers: work-precision table and figures, fitted orders with their 95%
// confidence intervals, energy histories, the headline ranking. Schema: README.md, "Studies
// from a file"; examples: studies/examples/.
//
// Every error in the file is an InputError "FILE:LINE: key.path: what is wrong; valid: ...".
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "studies/study.hpp"

namespace nsb {

using Overrides = std::map<std::string, std::string>;

struct FileReference {
  bool exact = true;       // the problem's exact solution; else `integrator`
  std::string integrator;  // a reference integrator, its run cached
  Overrides parameters;
  double dt = 0.0;
  long sample_every = 1;
  double floor = 0.0;      // the reference's own error in the measures' norm (ranking)
  // Stepped with each run, step for step at the run's own steps (no cache, no interpolation):
  // its states at the run's step times (modal-exact: the semi-discrete system's exact solution).
  bool lockstep = false;
  std::string against;     // what the errors are measured against, as captions and the ranking say it ("": said from the above)
  // A cached run's own end time, at or past its problems' (0: the problem's t_end): a run whose
  // steps do not divide t_end ends up to one step past it, where the reference would otherwise
  // stand still at its last sample (its samples are not extrapolated).
  double t_end = 0.0;
};

struct FileProblem {
  std::string name, label;
  // A joint refinement (refine = KEY, a key of the problem's grid): the label without KEY's
  // value, shared by the grid's problems that differ only in KEY, whose runs make one sweep
  // (fitted orders, pairwise orders, one ranked problem); empty: none.
  std::string family;
  const std::string& family_label() const { return family.empty() ? label : family; }
  Overrides parameters;
  double t_end = 0.0;              // its own end time (0: study.t_end)
  long max_force_evaluations = 0;  // its own F_int budget per run (0: study.max_force_evaluations)
  // Its own outcome thresholds and energy scale (0: the study's; energy_scale 0: |E0|, or the
  // problem's energy_scale() when E0 = 0), and whether only `--full` runs it.
  double energy_blow_up = 0.0, max_penetration = 0.0, energy_scale = 0.0;
  bool full_only = false;
  bool default_only = false;  // only a run without --full runs it (its --full counterpart: another problem)
  double full_t_end = 0.0;    // its end time under --full (0: t_end)
  // A contact phase counts (the impacts column) after at least this long without a contact
  // impulse: a chattering node does not restart a phase within one contact.
  double min_flight = 0.0;
  std::optional<FileReference> reference;  // its own reference (none: the study's [reference])
  // The sweep of every integrator that gives none of its own on this problem (and under --full).
  std::vector<double> steps, full_steps;
  std::vector<double> stable_fractions;  // or its own stable_steps (dt = fraction x its stable step)
};

// What an integrator runs on one problem: its parameters and either a list of steps, a list
// of fractions of the problem's stable step (Problem::stable_step(), 2 / omega_max: dt =
// fraction * stable step) or a list of tolerances (set as `tolerance_parameter`, each run
// with the fixed step `dt`).
struct FileSweep {
  Overrides parameters;
  std::vector<double> steps;
  std::vector<double> full_steps;  // the steps under --full (empty: steps)
  std::vector<double> stable_fractions;
  std::vector<double> tolerances;
  std::string tolerance_parameter = "rtol";
  // Parameters set with each tolerance to tolerance / divisor (atol = rtol / 100), by name.
  std::map<std::string, double> tolerance_divisors;
  double dt = 0.0;
};

struct FileIntegrator {
  std::string name, label;
  FileSweep sweep;
  std::map<std::string, FileSweep> per_problem;  // by problem label: the sweep, overrides applied
  const FileSweep& sweep_for(const std::string& problem_label) const;
};

// The kinds from ImpactRatio on are the measures of an observable's events (EventFigures).
enum class MeasureKind { Error, ImpactTime, Energy, Momentum, Penetration, Hausdorff, StopTime, OnsetTime, FlightEnergy, RestStart,
                         Estimate, Chatter, ZeroSteps, ContactDuration, ImpactRatio, Amplitude, ImpactCount, RestTime, PeakTime, Value, Summary };

struct FileMeasure {
  MeasureKind kind = MeasureKind::Error;
  std::string label;             // the column's name
  std::string observable = "u";  // Error: "u", "v" or one of the problem's observables; Hausdorff: an observable
  // Hausdorff: the observable of each problem by label (observable = { LABEL = NAME }; the
  // problems' graphs differ, e.g. v and v_contact, in one column); empty: `observable`.
  std::map<std::string, std::string> problem_observables;
  const std::string& observable_for(const std::string& problem_label) const;
  // Error of an observable: against the problem's own observable of this name at the run's state
  // (its exact column, e.g. contact_force_exact: an impulse's force is no function of the exact
  // state), not against the reference; "": the reference.
  std::string against;
  // Error: final|max|l2|rms|step rms|l2 in time; Energy: max|final|final abs|drift|offset; ImpactTime, FlightEnergy: max|count;
  // Hausdorff: distance|to reference|from reference|max error|value scale
  std::string norm = "max";
  int count = 3;                 // ImpactTime, FlightEnergy: the first `count` impacts (flights)
  // ImpactTime, FlightEnergy: > 0: the impacts (flights) compared end at the first whose exact
  // flight lasts less than this many steps (compared_impacts, studies/measures.hpp).
  int min_flight_steps = 0;
  // RestStart: a step is at rest when each observable (|o| with abs) is at most at_most dt^dt_power
  // (dt: the run's nominal step); the rest must last longer than min_rest [s] (FinalRest).
  struct RestBound {
    std::string observable;
    bool abs = false;
    double at_most = 0.0;
    int dt_power = 0;
  };
  std::vector<RestBound> rest;
  double min_rest = 0.0;
  // FlightEnergy: the energy at the step midway between the steps starting the run's contact
  // phases (FlightEnergies::At::mid_flight_step), not at the exact mid-flight time.
  bool at_mid_flight_step = false;
  // ImpactTime: the impact times the integrator locates itself (Integrator::events(), impacts
  // and Zeno stops: the event-driven reference), not the steps' ends; n/a where it locates none.
  bool located = false;
  // Estimate: max over the samples of |o - o'| against the next run of the same sweep (its
  // next tolerance, step or swept parameter x'); with `order` q (error ~ x^q) divided by
  // 1 - (x'/x)^q, the run's own error when that law holds.
  double order = 0.0;
  // Energy: errors relative to the energy after the first step E_1 ((E - E_1) / |E_1|), not E0.
  bool from_first_step = false;
  // Momentum: the residual divided by sum_i m_i |v0_i| (nonzero when the total momentum is),
  // not by the largest |P|.
  bool initial_speeds_scale = false;
  // Momentum of a mesh problem's component (px, py, pz, jx, jy, jz: studies/measures.hpp,
  // MeshMomentum) instead of the 1D balance; "": the 1D balance.
  std::string component;
  bool history = false;          // Energy: also a history table and figure
  // Energy: > 0: sampled at the first step past each t_k = from + k every (k = 1, 2, ... while
  // t_k <= t_end, to half a step), its norm count | first | final | drift (slope against k).
  double every = 0.0, from = 0.0;
  double time_scale = 0.0;       // Hausdorff: T (0: t_end)
  double value_scale = 0.0;      // Hausdorff: V (0: the reference's largest |value|)
  // Hausdorff's norm: distance (H, the larger directed distance), "to reference" (run -> ref),
  // "from reference" (ref -> run), "max error" (max over the run's samples of |o - o_ref(t)| / V)
  // or "value scale" (V itself): GraphErrors, studies/hausdorff.hpp.
  std::vector<std::string> problems;  // the labels of the problems it is measured on (empty: all)
  // The measures of an observable's events (README, "Studies from a file"): impact-ratio's
  // law ("housner" | "moreau", "": the ratio itself), the impact it is taken at (impact-ratio,
  // amplitude; 0: `count` for impact-ratio), rest-time's threshold, and `exact`: the difference
  // from the problem's closed form (studies/measures.hpp) instead of the value.
  std::string law;
  int impact = 0;
  double threshold = 0.0;
  bool exact = false;
  // rest-time, peak-time with `exact`: the exact time is the problem's summary value of this
  // name (Problem::summary_values, e.g. a sphere's t_roll_exact), not its closed form of
  // studies/measures.hpp; kind summary: that value itself, the same on every run of a problem.
  std::string summary;
  // Error, energy, momentum: sampled on [window_start, window_end] only (the whole run by default),
  // or on a window of each problem's own (by label; a problem not named: the whole run).
  double window_start = 0.0;
  double window_end = std::numeric_limits<double>::infinity();
  std::map<std::string, std::pair<double, double>> problem_windows;
  std::pair<double, double> window_for(const std::string& problem_label) const;
  // Error: relative to the largest reference value over the whole run, not the window alone.
  bool scale_over_run = false;
  // Error: > 0: each step's error divided by this fixed value (a drop height, a force level), not
  // by the largest reference value; chatter: each value divided by it (default 1).
  double scale = 0.0;
  // Error, chatter, zero-steps: measured only at the steps ending at t whose t - dt, t and t + dt all lie where the
  // problem's exact observable of this name is > 0 (e.g. inside the exact contact phases:
  // contact_force_exact); "": every step.
  std::string inside;
  // Error norms taken over every step (not every sample_every-th), the observables at the step's
  // own length dt: rms (sqrt(sum_k dt_k e_k^2 / (t_last - t0)), in time over the steps measured,
  // t_last the last of them), l2 in time (sqrt(sum_k dt_k e_k^2), not divided by the time) and
  // step rms (sqrt(sum_k e_k^2 / n) over the n steps), any error measured `inside` an
  // observable's phases, and chatter and zero-steps (an observable's values at consecutive
  // steps: Chatter, studies/measures.hpp).
  bool every_step() const {
    return norm == "rms" || norm == "step rms" || norm == "l2 in time" || !inside.empty() || kind == MeasureKind::Chatter ||
           kind == MeasureKind::ZeroSteps;
  }
  bool applies_to(const std::string& problem_label) const;
  // Smaller is better and never negative: a measure the ranking may rank by.
  bool rankable() const;
  // Error with semi_discrete: against the same semi-discrete problem solved exactly (modal-exact
  // with its defaults, reference/modal_exact.hpp) advanced to each sample's time
  // (ModalExact::advance_to), not the reference: the time-discretisation error alone, |u_dof -
  // u_dof,semi| at the dof `dof` (ModalExact::displacement, O(modes) a sample). n/a on
  // modal-exact's own runs (0 by construction) and, with a note "LABEL n/a: why", where
  // modal-exact refuses the problem (e.g. above its max_dofs).
  bool semi_discrete = false;
  long dof = -1;
  // Sampled at most once per nominal step dt: at the first step ending at or after the last
  // sample's time + (1 - 1e-9) dt (an adaptive scheme's smaller steps are not all sampled).
  bool per_nominal_step = false;
};

// A figure the file declares, drawn from the work-precision table: y against x (column names:
// problem, integrator, dt, tol, a measure's label, CPU, steps, F_int evals), one line per
// value of `series`, one panel per value of `panels`.
struct FileFigure {
  std::string id;  // <name>_<id>; with study.figures = "declared": <id>
  std::string title;
  std::string x, y;
  std::vector<std::string> series{"integrator"};
  std::vector<std::string> panels{"problem"};
  bool log_x = true, log_y = true;
  std::vector<double> slopes;  // reference slopes drawn as triangles (log-log)
  bool small_multiples = false;  // one panel per value of the first series column (Figure::small_multiples)
  bool deviation = false;        // y is a ratio to its start: its signed deviation y - 1 drawn (Figure::deviation)
  std::string table;           // a declared history table to draw it from (empty: the runs)
  // Printed under the figure. A figure of a field table (rows = "field") is a space-time
  // picture (Figure::kind "space_time": no x, y the time, a panel per run): its caption is the
  // table's, then this text, then "." or "; no panel for RUN: outcome, ..." naming the runs the
  // table shows that have no field (declined); value_label names its colour scale.
  std::string caption, value_label;
};

// A metadata line of the reports' tables ("# line: value"): a text, or the values the study's
// runs take in a column of the case table `of` (e.g. "parameter N"), each once, in the order
// of the runs, separated by spaces.
struct MetadataLine {
  std::string line, of, text;
};

// A column of a declared table: the source column `of` (a work-precision column for rows =
// "case"; problem, integrator or "order of <measure>", "CI low of <measure>", "CI high of
// <measure>", "points of <measure>" for rows = "group"), its header, unit, number format and
// description (each by default the source's).
struct FileColumn {
  std::string of;
  std::optional<std::string> header, unit, format, description;
  // The text of a cell with no value (n/a: not measured, e.g. an energy sampled every period
  // before its first sample) in a case table; none: n/a.
  std::optional<std::string> missing;
};

// A table the file declares ([[table]]): its id (the file stem, exactly), title, caption and
// rows: "case" (one per run, the work-precision rows), "group" (one per problem and integrator,
// the fitted orders side by side), "ranking" (the headline ranking, its columns fixed) or
// "history" (one per interval of each run on the `problems` it names, all by default: the
// largest energy deviation and penetration over each of 200 equal intervals of [0, t_end]).
// Declared tables replace the engine's work-precision, orders and ranking tables.
struct FileTable {
  std::string id, title;
  // Its caption; each ${COLUMN} in it (caption_placeholders) the values of that case-table
  // column over the runs the table shows, each once in the order of the runs, joined by ", ":
  // the grid that was run (e.g. "N = ${parameter N}": the default's meshes, or --full's).
  std::optional<std::string> caption;
  std::string rows = "case";
  std::vector<FileColumn> columns;
  std::vector<std::string> problems;  // the labels of the problems whose runs (group: fits, by family label too) it shows (empty: all)
  // A declined run's row (status n/a): its measured cells (counts, figures of the run) shown
  // as n/a, only what was asked kept (declined = "n/a"), or empty (declined = "empty": no text
  // at all, as a table built by hand leaves them); by default as the run reports them (0).
  bool declined_blank = false, declined_empty = false;
  // With declined_blank: the measured column (by `of`) whose cell in a declined run's row shows
  // the scheme's reason (the run's note) instead (declined_reason = COLUMN); "": none.
  std::string declined_reason;
  // case: the labels of the integrators whose runs it shows (empty: all).
  std::vector<std::string> integrators;
  bool applies_to(const std::string& problem_label) const;
  // rows = "ranking" (the first such table): its error column's header, unit, format and
  // description (`of` unused), and the number format of dt or tol in its runs cells.
  std::optional<FileColumn> error;
  std::optional<std::string> runs_format;
  // Tables of some runs (rows = "pivot", "periodic", "trajectory", "flights", and "case"): the runs whose case-table
  // column equals each value of `where` (a number or a text), less those whose |column| exceeds
  // the value of `drop_above` (a run with no value there is kept).
  std::vector<std::pair<std::string, Cell>> where;
  std::vector<std::pair<std::string, double>> drop_above;
  // rows = "pivot": one row per value of the columns before the last (e.g. integrator), the
  // last column's value spread over one column per value of the case-table column `across`
  // (header: the last column's header with {} replaced by that value); a run whose outcome is
  // not ok shows its outcome instead, no run an empty cell.
  std::string across;
  // rows = "periodic": one row per sample of the energy measure of this label (sampled `every`);
  // rows = "flights": one row per flight compared by the flight-energy measure of this label
  // (flight i, after impact i: E_i / E0, the exact E_i / E0 and |E_i / E_i exact - 1|, E0 the
  // scheme's energy at the start), for the runs whose measures were taken.
  std::string measure;
  // rows = "trajectory": the observable at the first step at or after each of points + 1 evenly
  // spaced times over the run's last `last` seconds (t_end - last to t_end) (spacing = "times"),
  // or at every s-th step from the first, s = max(1, n / points) in integers, n the run's steps
  // (spacing = "steps": the whole run, each step kept until the run ends); with `relative`,
  // divided by its value at the start (total_energy: E / E0). After the first run shown of each
  // problem, rows "exact": its observable `exact` at the same times (with `relative`, divided by
  // its own value at the start).
  std::string observable, exact;
  double last = 0.0;
  int points = 400;
  bool step_spacing = false, relative = false;
  // rows = "case" with not_ok = "outcome": the columns (by `of`: the measures it shows) whose
  // cell of a run whose outcome is not ok shows that outcome (n/a, diverged, over budget, ...)
  // instead of its value, as the C++ studies' tables did.
  std::vector<std::string> outcome_columns;
  // rows = "group" with fit_against = "1/KEY" (KEY a numeric parameter of its problems, e.g. the
  // refined N): its own fits, each measure's least-squares slope of log(value) against
  // log(1 / KEY) (h = L/N up to log L, which moves no slope) over each sweep's runs, every
  // positive finite value a point (no round-off cut), as the C++ studies fitted against h; its
  // columns "order of <measure>" of every measure. "": the engine's fits against dt.
  std::string fit_against;
  // Tables of some runs and case tables: the runs whose case-table column equals the value of
  // `except` are left out (e.g. a reference whose own error is 0 by construction).
  std::vector<std::pair<std::string, Cell>> except;
  // rows = "pivot": a last column, the least-squares slope of log(value) against log(the
  // case-table column `order->of`) over each row's runs (positive finite values; n/a with
  // fewer than two), under its header, format and description.
  std::optional<FileColumn> order;
  // rows = "impulses": one row per nominal step bin (t_j - dt, t_j], t_j = j dt (dt the run's
  // nominal step; j = 1, 2, ... up to the bin of its last step) of each run shown: the sum of
  // the contact impulses (all contacts) of the steps ending in the bin, over dt (the mean
  // contact force over the bin: a fixed-step run's force step by step, an adaptive run's small
  // steps summed), divided by `scale`. With `exact` (an observable of the problem's exact
  // state, e.g. contact_force_exact, divided by `scale` too): after the first run shown of each
  // value of the column `exact_per`, rows of it at the same t_j, that run's cells but "exact"
  // in the column `exact_in`.
  double scale = 1.0;
  std::string exact_per = "problem", exact_in = "integrator";
  // rows = "field": one row per step of each run shown, the first its initial state: the
  // stress component `component` (default: the first) of each element cell of the problem's
  // field mesh (1D, cells of two points: a column per cell, named by its centre x). With
  // exact_times = n > 0, first n + 1 rows "exact": the exact field (ExactSolution::
  // exact_cell_stress) of the first problem the table shows at t = t_end k / n, k = 0..n.
  std::string component;
  int exact_times = 0;
  // Metadata lines of its own, after the study's (StudySpec::metadata).
  std::vector<MetadataLine> metadata;
  bool of_some_runs() const {
    return rows == "pivot" || rows == "periodic" || rows == "trajectory" || rows == "flights" || rows == "impulses" || rows == "field";
  }
};

// [[exclude]]: runs the study does not make: those of the registered integrators of one kind
// (schemes, peers, references) on a problem whose numeric parameters exceed the values of
// `above` (a problem without such a parameter: not matched) and at a stable-step fraction not in `stable_steps_except`. Every condition given
// must hold; default_only / full_only restrict the rule to runs without / with --full.
struct FileExclusion {
  std::string integrators;                     // "schemes" | "peers" | "references"
  std::map<std::string, double> above;         // problem parameter > value
  std::vector<double> stable_steps_except;     // the run's dt / stable step is none of these
  bool default_only = false, full_only = false;
};

struct StudySpec {
  std::string file;   // as given
  std::string name;   // the file's stem, [a-z0-9_] only: table ids and shard files
  std::string title;
  std::string text;   // the file itself
  std::string hash;   // FNV-1a 64 of text, hex
  double t_end = 0.0;
  long sample_every = 1;
  long check_every = 1;  // the run driver checks the state for a non-finite value every k steps
  int history_intervals = 200;  // the intervals (samples) of a history (samples) table's runs
  // Work counters of the integrators (Work::extra) shown as run columns by name (n/a where a
  // scheme does not count it).
  std::vector<std::string> counters;
  int cpu_repeats = 3;
  long max_force_evaluations = 10'000'000;
  // > 0: each run's budget is floor(this x t_end / dt) F_int evaluations (a count per nominal
  // step, so a slow scheme stops at the same step everywhere) instead of max_force_evaluations.
  double force_evaluations_per_step = 0.0;
  // study.case_order = "integrator": the runs integrator by integrator (each over the problems
  // in their order); by default problem by problem (each over the integrators).
  bool integrator_major = false;
  // study.case_order = "sweep": problem by problem, each over the integrators, a joint
  // refinement's problems (one family) as one problem: each integrator's runs over its refined
  // problems together.
  bool sweep_major = false;
  // study.measure_over_budget: an over-budget run's measures up to its stop (default: none).
  bool measure_over_budget = false;
  std::vector<FileExclusion> exclusions;
  // Outcome thresholds: "energy blow-up" past energy_blow_up E scale (study_file/run_case.cpp),
  // "penetration" when max(0, -g) exceeds max_penetration (infinite: never).
  double energy_blow_up = 2.0;
  double max_penetration = std::numeric_limits<double>::infinity();
  std::vector<double> targets{1e-2, 1e-4};
  std::vector<FileProblem> problems;
  std::vector<FileIntegrator> integrators;
  FileReference reference;
  bool has_reference = false;
  std::vector<FileMeasure> measures;
  std::vector<FileFigure> figures;
  bool declared_figures_only = false;  // study.figures = "declared": no figures of the engine's own, ids unprefixed
  std::vector<FileTable> tables;  // empty: the engine's own tables
  // The measure the ranking and the work-precision figures use (study.rank_by, a measure's
  // label; default: the first error measure); measures.size(): none.
  std::size_t ranked = 0;
  // study.metadata: lines every declared table carries after the engine's (study, file, hash, t_end).
  std::vector<MetadataLine> metadata;
  double t_end_of(const FileProblem& p) const { return p.t_end > 0.0 ? p.t_end : t_end; }
  double t_end_of(const FileProblem& p, bool full) const { return full && p.full_t_end > 0.0 ? p.full_t_end : t_end_of(p); }
  double energy_blow_up_of(const FileProblem& p) const { return p.energy_blow_up > 0.0 ? p.energy_blow_up : energy_blow_up; }
  double max_penetration_of(const FileProblem& p) const { return p.max_penetration > 0.0 ? p.max_penetration : max_penetration; }
  // The F_int budget of a run of step dt to t_end on p: its own, else per step, else the study's.
  long budget_of(const FileProblem& p, double dt, double t_end) const {
    if (p.max_force_evaluations > 0) return p.max_force_evaluations;
    return force_evaluations_per_step > 0.0 ? static_cast<long>(force_evaluations_per_step * t_end / dt) : max_force_evaluations;
  }
  // Whether a run of `full` (--full or not) makes the problem's runs.
  bool runs(const FileProblem& p, bool full) const { return full ? !p.default_only : !p.full_only; }
  // The problem's own reference, else the study's; nullptr: none.
  const FileReference* reference_of(const FileProblem& p) const {
    return p.reference ? &*p.reference : has_reference ? &reference : nullptr;
  }
};

// A column of a case table that says what a case asked for (problem, integrator, step, limits,
// status), not what its run measured: kept in a declined run's row with declined = "n/a".
bool asked_column(const std::string& source);

// A time measured against the problem's exact event times [s] (impact, stop, onset times; a
// rest or peak time, a contact duration with exact = true).
bool is_event_time(const FileMeasure& m);
// An error that converges with dt: a convergence figure and fitted orders.
bool measure_converges(const FileMeasure& m);

// The columns of a run's own figures a declared case table may show (besides the
// work-precision ones), and the columns of a history table.
const std::vector<std::string>& run_column_names();
const std::vector<std::string>& history_column_names();
const std::vector<std::string>& samples_column_names();
const std::vector<std::string>& periodic_column_names();
const std::vector<std::string>& trajectory_column_names();
const std::vector<std::string>& flights_column_names();
// The columns of an impulses table and of a field table ("field": one column per cell).
const std::vector<std::string>& impulses_column_names();
const std::vector<std::string>& field_column_names();
// The columns of a declared case table that compare a run with the next run of its sweep or
// count the solver's own work: "solver steps", "Jacobians" and, for each converging measure,
// "rate of <label>".
std::vector<std::string> sweep_work_column_names(const StudySpec& spec);
// The problems' parameters a declared case, history or samples table may show: "parameter NAME" for each parameter
// of each problem (the first problem's order first); a problem without it shows an empty cell.
std::vector<std::string> parameter_column_names(const StudySpec& spec);

// The placeholders ${COLUMN} of a declared table's caption (FileTable::caption), in order: where
// each starts, its length ("${" to "}") and COLUMN; a "${" without its "}" last, of length npos.
struct CaptionPlaceholder {
  std::size_t at = 0, size = 0;
  std::string column;
};
std::vector<CaptionPlaceholder> caption_placeholders(const std::string& caption);

// Reads and checks a study file (.json: JSON, anything else: TOML).
StudySpec read_study_file(const std::filesystem::path& path);
// The same from text; `file` names it in errors.
StudySpec parse_study_text(const std::string& text, const std::string& file, bool json);

// A reduced copy for tests and smoke runs: t_end (a reference's own t_end too) scaled by
// `t_scale`, each sweep cut to its first `max_runs` entries, one CPU run, at most `budget` F_int
// evaluations per run.
StudySpec reduced_study(StudySpec spec, double t_scale, std::size_t max_runs, long budget);

// The study as the driver runs it.
StudyEntry file_study(const StudySpec& spec);

// The integrator's parameters of a case of the study: its sweep's on the case's problem, with a
// tolerance sweep's tolerance and the parameters divided from it (tolerance_divisors).
Overrides file_case_parameters(const StudySpec& spec, const Json& c);

// Why `result`, read back from a shard (--merge), is not one the file study's run_case returns
// for `spec`: a key missing (status, message, steps, force_evaluations), values not an array of
// one number (or null) per measure, cpu not a number, history not two arrays t and e of
// numbers of the same length, samples without an array of numbers per estimate measure; empty
// when it is.
std::string file_result_damage(const StudySpec& spec, const Json& result);

// Writes <out>/<name>.study.<ext> (the file as read) and <out>/<name>.study.hash.
void write_study_copy(const StudySpec& spec, const std::filesystem::path& out);

// Runs the study as `nsbench-study run FILE --out DIR` does (its cases in parallel) and writes
// its report into `out`, staged and swapped in whole: the tables, figures.json, index.md and
// the file's copy. Returns the tables' ids. (nsbench.run_study from Python.)
std::vector<std::string> run_study_file(const StudySpec& spec, const std::filesystem::path& out);

}  // namespace nsb
