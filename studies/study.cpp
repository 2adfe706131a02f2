#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/parameters.hpp"
#include "integrators/registry.hpp"
#include "studies/study.hpp"

namespace nsb {

std::vector<Json> study_cases(const StudyEntry& study, const StudyOptions& options) {
  if (!study.script.empty())
    throw InputError(fmt::format("study {} is written in Python ({}): nsbench-study runs it with the Python module", study.name,
                                 study.source));
  if (study.run) return {Json::object()};
  return study.cases(options);
}

CpuCost cpu_cost(const Problem& problem, const std::string& integrator, const std::map<std::string, std::string>& params,
                 RunOptions options, int repeats) {
  options.sample_every = std::numeric_limits<long>::max();
  std::vector<double> cpu;
  double warm_up = 0.0;
  for (int k = 0; k <= repeats; ++k) {
    auto timed = make_integrator(integrator, params);
    timed->init(problem, problem.initial_state());
    const double t = run(problem, *timed, options).step_cpu_seconds;
    if (k > 0) cpu.push_back(t);  // run 0 is the warm-up
    if (k == 0) warm_up = t;
    if (k == 0 && t > kLongRunSeconds) repeats = 1;
  }
  std::sort(cpu.begin(), cpu.end());
  const double median = cpu[cpu.size() / 2];
  const double spread = cpu.size() > 1 ? (cpu.back() - cpu.front()) / median : std::abs(median - warm_up) / median;
  return {median, median > 0.0 ? spread : std::numeric_limits<double>::infinity()};  // a zero time tells nothing
}

std::string median_cpu_text(int repeats) {
  return fmt::format("median thread CPU time of {} unobserved runs after a warm-up (one run when the warm-up takes "
                     "over {} s); its spread (largest - least) / median (one run: |run - warm-up| / run)", repeats, kLongRunSeconds);
}


Json real(double v) { return std::isnan(v) ? Json(nullptr) : Json(v); }
double real(const Json& j) { return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>(); }
Json reals(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(std::isfinite(x) ? Json(x) : Json(nullptr));
  return a;
}
Cell number_cell(double v) { return std::isnan(v) ? Cell{} : Cell{v}; }
Cell number_cell(const Json& j) { return j.is_number() ? number_cell(j.get<double>()) : Cell{}; }

double real_or_nan(const Json& result, const std::string& key) { return result.contains(key) ? real(result[key]) : std::numeric_limits<double>::quiet_NaN(); }

std::string status_note(const Json& result) {
  const std::string status = result["status"];
  return status == "ok" ? "" : fmt::format("{}: {}", status, result["message"].get<std::string>());
}

void add_integrator_rows(Table& t, const std::vector<Json>& cases, const std::vector<Json>& results,
                         const std::function<bool(std::size_t k)>& member,
                         const std::function<std::vector<Cell>(std::size_t i, std::optional<std::size_t> previous)>& row) {
  std::size_t k = 0;
  while (k < cases.size()) {
    const std::string integrator = cases[k]["integrator"];
    std::vector<std::size_t> mine;
    for (; k < cases.size() && cases[k]["integrator"] == integrator; ++k)
      if (member(k)) mine.push_back(k);
    if (mine.empty()) continue;
    if (std::all_of(mine.begin(), mine.end(), [&](std::size_t i) { return results[i]["status"] == "n/a"; })) {
      std::vector<Cell> cells(t.columns.size());
      cells[0] = integrator;
      cells[1] = std::string("n/a");
      cells.back() = results[mine.front()]["message"].get<std::string>();
      t.add_row(cells);
      continue;
    }
    for (std::size_t j = 0; j < mine.size(); ++j) {
      const bool same_case = j > 0 && cases[mine[j - 1]]["case"] == cases[mine[j]]["case"];
      t.add_row(row(mine[j], same_case ? std::optional(mine[j - 1]) : std::nullopt));
    }
  }
}

void add_ranking_curves(std::vector<RankingProblem>& rankings, const std::vector<std::string>& ids,
                        const std::vector<Json>& cases, const std::vector<Json>& results,
                        const std::function<WorkPoint(std::size_t i)>& point) {
  std::size_t k = 0;
  while (k < cases.size()) {
    const std::string integrator = cases[k]["integrator"];
    const IntegratorEntry& entry = find_integrator(integrator);
    std::size_t end = k;
    while (end < cases.size() && cases[end]["integrator"] == integrator) ++end;
    for (std::size_t p = 0; p < ids.size(); ++p) {
      WorkCurve curve{integrator, entry.reference, {}, entry.peer};
      for (std::size_t i = k; i < end; ++i)
        if (cases[i]["case"] == ids[p] && results[i]["status"] != "n/a") curve.points.push_back(point(i));
      rankings[p].curves.push_back(curve);
    }
    k = end;
  }
}

IntervalMax::IntervalMax(double t_end, int intervals, std::size_t quantities)
    : t_end_(t_end), intervals_(intervals), current_(quantities, 0.0), largest_(quantities) {}

void IntervalMax::add(double t, std::initializer_list<double> values) {
  std::size_t i = 0;
  for (double v : values) {
    current_[i] = std::max(current_[i], v);  // a NaN is not a largest value
    ++i;
  }
  t_last_ = t;
  open_ = true;
  if (t >= t_end_ * static_cast<double>(times_.size() + 1) / intervals_) close();
}

const std::vector<double>& IntervalMax::largest(std::size_t quantity) const {
  static const std::vector<double> none;
  return quantity < largest_.size() ? largest_[quantity] : none;
}

void IntervalMax::finish() {
  if (open_) close();
}

void IntervalMax::close() {
  times_.push_back(t_last_);
  for (std::size_t i = 0; i < current_.size(); ++i) {
    largest_[i].push_back(current_[i]);
    current_[i] = 0.0;
  }
  open_ = false;
}

std::optional<std::string> init_or_decline(Integrator& integrator, const Problem& problem) {
  try {
    integrator.init(problem, problem.initial_state());
  } catch (const InputError& e) {
    return e.what();
  }
  return std::nullopt;
}

Json run_study_case(const StudyEntry& study, const Json& the_case, const StudyOptions& options) {
  if (!study.run) {
    try {
      return study.run_case(the_case);
    } catch (const InputError& e) {  // a bad study definition: say which study and case
      throw InputError(fmt::format("study {}, case {}: {}", study.name, the_case.dump(), e.what()));
    }
  }
  Json tables = Json::array();
  for (const auto& t : study.run(options)) tables.push_back(table_to_json_text(t));
  return tables;
}

std::string case_lock(const StudyEntry& study, const Json& the_case) {
  if (!study.case_integrators) return "";
  for (const std::string& name : study.case_integrators(the_case))
    if (const std::string& lock = find_integrator(name).shared_lock; !lock.empty()) return lock;
  return "";
}

std::vector<std::string> integrators_named(const Json& the_case) {
  std::vector<std::string> names;
  if (const auto it = the_case.find("integrator"); it != the_case.end() && it->is_string()) names.push_back(*it);
  if (const auto it = the_case.find("integrators"); it != the_case.end() && it->is_array())
    for (const Json& name : *it) names.push_back(name.get<std::string>());
  return names;
}

std::vector<Table> study_tables(const StudyEntry& study, const std::vector<Json>& cases,
                                const std::vector<Json>& results, const StudyOptions& options) {
  if (!study.run) return study.tables(cases, results, options);
  if (results.size() != 1) throw std::logic_error("single-function study " + study.name + " has one result");
  std::vector<Table> tables;
  for (const auto& text : results[0]) tables.push_back(table_from_json_text(text.get<std::string>()));
  return tables;
}

}  // namespace nsb
