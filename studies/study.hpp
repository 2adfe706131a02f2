#pragma once
// A study is data: the list of its cases (each a JSON object saying what to run), how to
// run one case (a pure function of the case: the same case gives the same numbers, CPU
// times aside), and how to turn all the cases' results into tables. The driver
// (nsbench-study) runs the cases in parallel, or one shard of them (--shard i/n, for a job
// array), and merges the shards' results into the tables (nsbench-study merge).
//
// Studies are listed in studies/registry.cpp, one line each: C++ studies and study files
// (studies/builtin/). A study written as a single function returning tables (`run`) is a study
// of one case.
#include <nlohmann/json.hpp>
#include <array>
#include <functional>
#include <initializer_list>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "run/run.hpp"
#include "studies/measures.hpp"
#include "studies/ranking.hpp"
#include "studies/table.hpp"

namespace nsb {

using Json = nlohmann::json;

struct StudyOptions {
  bool full = false;  // the long sweep (finer steps, bigger meshes) instead of the default
};

struct StudyEntry {
  std::string name;
  std::string description;
  // Either a single function...
  // (std::function: a study read from a file carries its definition in them.)
  std::function<std::vector<Table>(const StudyOptions&)> run;
  // ...or cases, a case runner and a table builder.
  std::function<std::vector<Json>(const StudyOptions&)> cases;
  std::function<Json(const Json& the_case)> run_case;
  std::function<std::vector<Table>(const std::vector<Json>& cases, const std::vector<Json>& results,
                                   const StudyOptions&)> tables;
  // The integrators a case runs, by name: the scheduler runs one case at a time of those whose
  // integrators take the same process-wide lock (case_lock). Unset: its cases take none.
  std::function<std::vector<std::string>(const Json& the_case)> case_integrators = nullptr;
  // The file that defines it, relative to the repository: its study file (studies/builtin/, see
  // studies/registry.hpp) or its C++ source. Set by the registry.
  std::string source = "";
  // A study written in Python (studies/builtin/NAME.py, nsbench.study): the script's text, which
  // nsbench-study runs with the Python module and the same options; empty for the others.
  std::string_view script = {};
};

const std::vector<StudyEntry>& study_registry();

// The cases of a study (one empty case for a single-function study), running one case
// (an InputError from a bad definition is rethrown naming the study and the case), and
// building the tables from all results.
std::vector<Json> study_cases(const StudyEntry& study, const StudyOptions& options);
Json run_study_case(const StudyEntry& study, const Json& the_case, const StudyOptions& options);
// The process-wide lock a case's run takes (IntegratorEntry::shared_lock of the first of its
// integrators that names one); "" when it takes none. Its integrators are registered ones (an
// unknown name is an InputError listing the valid names, as find_integrator gives it).
std::string case_lock(const StudyEntry& study, const Json& the_case);
// The integrators a C++ study's case names: its "integrator" (a name) and "integrators" (names).
std::vector<std::string> integrators_named(const Json& the_case);
std::vector<Table> study_tables(const StudyEntry& study, const std::vector<Json>& cases,
                                const std::vector<Json>& results, const StudyOptions& options);

// JSON has no NaN: a missing number travels as null through case results and shard files.
Json real(double v);          // NaN -> null
double real(const Json& j);   // null -> NaN
Json reals(const std::vector<double>& v);  // a non-finite number (NaN, an overflow) -> null
// A number as a table cell; NaN, null or a non-number -> an empty cell (n/a).
Cell number_cell(double v);
Cell number_cell(const Json& j);
// A result's number under `key`; NaN when the result has none (n/a, diverged, a measure that
// does not apply).
double real_or_nan(const Json& result, const std::string& key);

// "status: message" for a run that did not end ok (n/a, diverged, over budget), else "".
std::string status_note(const Json& result);

// The statuses a study's result may carry besides the run statuses (status_name): a run the
// integrator declined, and a study file's outcome thresholds (README: `energy_blow_up`,
// `max_penetration`) met by a run that otherwise ended ok or over budget.
inline constexpr const char* kDeclinedStatus = "n/a";
inline constexpr const char* kEnergyBlowUpStatus = "energy blow-up";
inline constexpr const char* kPenetrationStatus = "penetration";
inline constexpr std::array<std::string_view, 3> kStudyStatuses = {kDeclinedStatus, kEnergyBlowUpStatus, kPenetrationStatus};

// The rows of a table with a block per integrator: `cases` (each naming its "integrator" and
// "case") come in runs of one integrator, of which member(k) picks those the table shows. An
// integrator that declined all of them (status n/a) gets one row instead, empty but for the
// integrator, "n/a" and its reason in the last column; otherwise row(i, previous) is run i's
// row, previous the run of the same case just before it, when there is one (for orders).
void add_integrator_rows(Table& t, const std::vector<Json>& cases, const std::vector<Json>& results,
                         const std::function<bool(std::size_t k)>& member,
                         const std::function<std::vector<Cell>(std::size_t i, std::optional<std::size_t> previous)>& row);
// The rankings' curves read off the same blocks: for each integrator and each ranked case
// ids[p], a curve in rankings[p] of point(i) over its runs of that case that it took (not n/a);
// an integrator that declined the case gets an empty curve.
void add_ranking_curves(std::vector<RankingProblem>& rankings, const std::vector<std::string>& ids,
                        const std::vector<Json>& cases, const std::vector<Json>& results,
                        const std::function<WorkPoint(std::size_t i)>& point);

// CPU time of a run, as the work-precision tables report it: the median thread CPU time of
// `repeats` runs of a fresh `integrator` (with `params`) on `problem`, after a warm-up run,
// none of them observed or sampled (options.sample_every is set past the end). A run whose
// warm-up takes over kLongRunSeconds is timed once after it: the median is there for the
// scheduler's and the caches' noise, milliseconds, under 1 % of such a run, and each repeat
// would cost the whole run again (Siconos at the finest steps of `precision`: 5 s a run).
// The spread says how far apart the timings were: (largest - least) / median over the repeats,
// or |timed - warm-up| / timed for a run timed once after its warm-up. The rankings declare a
// winner only when the runner-up costs more than the spread allows (ranking.hpp).
inline constexpr double kLongRunSeconds = 1.0;
struct CpuCost {
  double median;  // thread CPU seconds
  double spread;  // relative, >= 0
};
// What the cost captions say cpu_cost measures.
std::string median_cpu_text(int repeats = 3);
CpuCost cpu_cost(const Problem& problem, const std::string& integrator, const std::map<std::string, std::string>& params,
                 RunOptions options, int repeats = 3);
inline double median_cpu_seconds(const Problem& problem, const std::string& integrator,
                                 const std::map<std::string, std::string>& params, RunOptions options, int repeats = 3) {
  return cpu_cost(problem, integrator, params, options, repeats).median;
}

// The largest values of a few non-negative quantities over each of `intervals` equal intervals of
// [0, t_end], each with the time of the interval's last step: a history that, unlike samples,
// keeps a spike or a blow-up between them. Fed after every step; finish() closes the last,
// partial interval of a run that stopped early (or short of t_end by round-off).
class IntervalMax {
 public:
  IntervalMax() = default;  // no quantities, no intervals: an empty history
  IntervalMax(double t_end, int intervals, std::size_t quantities);
  void add(double t, std::initializer_list<double> values);
  void finish();
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& largest(std::size_t quantity) const;  // empty in an empty history

 private:
  double t_end_ = 0.0;
  int intervals_ = 1;
  double t_last_ = 0.0;
  bool open_ = false;  // steps added since the last interval closed
  std::vector<double> times_, current_;
  std::vector<std::vector<double>> largest_;
  void close();
};

// Binds `integrator` to `problem` (init at its initial state). When the scheme declines the
// problem (an InputError from init, e.g. a massless dof) the reason, which a study writes as
// an n/a row; nullopt when the scheme took it.
std::optional<std::string> init_or_decline(Integrator& integrator, const Problem& problem);

}  // namespace nsb
