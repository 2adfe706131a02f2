#include "run/run.hpp"

#include <fmt/format.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/team_size.hpp"
#include "core/threads.hpp"
#include "problems/contact_gaps.hpp"

namespace nsb {

namespace {

double clock_seconds(clockid_t clock) {
  timespec ts{};
  clock_gettime(clock, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// CPU time of this run: its thread's when it runs single-threaded (alone or as one case of a
// parallel study), the process's when its loops use more threads.
double cpu_seconds() { return clock_seconds(run_threads() > 1 ? CLOCK_PROCESS_CPUTIME_ID : CLOCK_THREAD_CPUTIME_ID); }

const std::vector<std::string> kGenericColumns = {
    "t", "dt", "kinetic", "potential", "total_energy", "min_gap", "impulse", "active_contacts", "tangential_impulse"};

const char* nonfinite_or_negative(const Vec& values, double lower) {
  if (!values.allFinite()) return "non-finite";
  return values.size() && values.minCoeff() < lower ? "negative" : nullptr;
}

// What the problem and the integrator report after a step that no valid run reports, "" when
// nothing: a step longer than both the requested dt and t_end (it ends past twice t_end),
// non-finite gaps or contact rows (a plugin problem's geometry), non-finite or negative
// normal impulses (below -1e-6 of the run's largest, `largest_impulse`: the references'
// impulses are differences of integrals), non-finite tangential impulses, negative work
// counters. O(contacts) a step. A non-finite state is left to the run's own check on the
// sampled steps, so that a blow-up ends where it always did.
std::string output_fault(double dt_taken, const RunOptions& options, const ContactGaps& gaps, const Integrator& integrator,
                         double& largest_impulse) {
  std::string fault;
  if (dt_taken > std::max(options.dt, options.t_end) * (1.0 + 1e-12))
    return fmt::format("a step of {:g} taken, longer than the requested dt = {:g} and t_end = {:g} (the integrator's)", dt_taken,
                       options.dt, options.t_end);
  const auto rows_finite = [](const RowSpMat& rows) {
    return Eigen::Map<const Vec>(rows.valuePtr(), rows.nonZeros()).allFinite();
  };
  const Vec& lambda = integrator.impulses();
  if (lambda.size()) largest_impulse = std::max(largest_impulse, lambda.cwiseAbs().maxCoeff());
  const WorkCounters& w = integrator.work();
  const ContactGeometry* moving = gaps.moving_rows();
  if (!gaps.last().allFinite())
    fault = "non-finite contact gap (the problem's contact geometry)";
  else if (moving && !(rows_finite(moving->normal) && rows_finite(moving->tangent) && rows_finite(moving->tangent2)))
    fault = "non-finite contact rows (the problem's contact geometry)";
  else if (const char* bad = nonfinite_or_negative(lambda, -1e-6 * largest_impulse))
    fault = fmt::format("{} normal impulse (the integrator's; valid: finite, >= 0)", bad);
  else if (!integrator.tangential_impulses().allFinite() || !integrator.tangential_impulses2().allFinite())
    fault = "non-finite tangential impulse (the integrator's)";
  else if (std::min({w.steps, w.force_evaluations, w.tangent_evaluations, w.factorizations, w.linear_solves,
                     w.lcp_iterations, w.lcp_unconverged}) < 0)
    fault = "negative work counter (the integrator's; valid: >= 0)";
  if (fault.empty() || !integrator.state().u.allFinite() || !integrator.state().v.allFinite()) return "";
  return fault;
}

// Progress lines on stderr every `every` seconds of wall time (RunOptions::progress_every),
// "NAME: P% of t_end, elapsed E s, about L s left". The clock is read every stride_ steps,
// set at each reading to about a tenth of a second of steps: a step of tens of ns pays no
// clock read each, and a step of seconds (a 1e8-element bar) is not waited for 16 times
// before the first line, as with the fixed stride of 16 before.
class ProgressLine {
 public:
  ProgressLine(double every, std::string name, double t_start, double t_end)
      : every_(every), next_line_(every), name_(std::move(name)), t_start_(t_start), t_end_(t_end) {}

  void before_step(long steps, double t) {
    if (every_ <= 0.0 || steps < next_read_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (elapsed > read_at_) {
      const double per_tenth = 0.1 * static_cast<double>(steps - read_steps_) / (elapsed - read_at_);
      stride_ = static_cast<long>(std::clamp(per_tenth, 1.0, 1048576.0));
    }
    read_steps_ = steps;
    read_at_ = elapsed;
    next_read_ = steps + stride_;
    if (elapsed < next_line_) return;
    const double done = (t - t_start_) / (t_end_ - t_start_);
    fmt::print(stderr, "{}: {:.1f}% of t_end, elapsed {:.1f} s, about {:.1f} s left\n", name_, 100.0 * done, elapsed,
               done > 0.0 ? elapsed * (1.0 - done) / done : NAN);
    next_line_ = elapsed + every_;  // one line per period, however long a step
  }

 private:
  double every_, next_line_;
  std::string name_;
  double t_start_, t_end_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  long stride_ = 1, next_read_ = 0, read_steps_ = 0;
  double read_at_ = 0.0;
};

}  // namespace

std::size_t Series::column(const std::string& name) const {
  for (std::size_t i = 0; i < columns.size(); ++i)
    if (columns[i] == name) return i;
  throw std::out_of_range("no column '" + name + "' in series");
}

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::Ok: return "ok";
    case RunStatus::Diverged: return "diverged";
    case RunStatus::OverBudget: return "over budget";
    case RunStatus::Interrupted: return "interrupted";
  }
  return "?";
}

double relative_error(double value, double reference) {
  if (reference == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return std::abs(value - reference) / std::abs(reference);
}

double energy_error_scale(const Problem& problem, double E0) {
  if (E0 != 0.0) return std::abs(E0);
  return problem.energy_scale() > 0.0 ? problem.energy_scale() : std::numeric_limits<double>::quiet_NaN();
}

RunResult run(const Problem& problem, Integrator& integrator, const RunOptions& options,
              const StepObserver& observer) {
  if (!(options.dt > 0.0) || !std::isfinite(options.dt))
    throw InputError(fmt::format("--dt {}: must be a finite number > 0", options.dt));
  if (!(options.t_end > 0.0) || !std::isfinite(options.t_end))
    throw InputError(fmt::format("--t-end {}: must be a finite number > 0", options.t_end));
  if (options.max_force_evaluations < 0)
    throw InputError(fmt::format("max_force_evaluations {}: must be >= 0 (0: no budget)", options.max_force_evaluations));
  if (options.sample_every < 1)
    throw InputError(fmt::format("sample_every {}: must be >= 1", options.sample_every));
  if (options.state_every < 1) throw InputError(fmt::format("state_every {}: must be >= 1", options.state_every));
  if (options.t_end / options.dt > static_cast<double>(options.max_steps))
    throw InputError(fmt::format("--dt {} with --t-end {} needs more than {} steps; valid: t_end/dt <= {}",
                                 options.dt, options.t_end, options.max_steps, options.max_steps));

  RunResult result;
  const auto extra = problem.observable_names();
  if (options.record_series) {
    result.series.columns = kGenericColumns;
    result.series.columns.insert(result.series.columns.end(), extra.begin(), extra.end());
    if (options.series_sink) options.series_sink->columns(result.series.columns);
  }
  ContactGaps gaps(problem);
  std::vector<double> row(kGenericColumns.size() + extra.size());

  // |Lambda_T| summed over the contacts: |(Lambda_T1, Lambda_T2)| on 3D contacts; the 2D sum
  // of |Lambda_T| itself otherwise (the same bits as before 3D contacts).
  const auto tangential_magnitude = [&]() {
    const Vec &t1 = integrator.tangential_impulses(), &t2 = integrator.tangential_impulses2();
    if (t2.size() == 0 || t2.isZero(0.0)) return t1.cwiseAbs().sum();
    return (t1.array().square() + t2.array().square()).sqrt().sum();
  };
  const auto min_gap = [&]() { return gaps.min_at(integrator.state().u); };
  const auto sample = [&](double dt) {
    const State& s = integrator.state();
    const Energy E = integrator.energy();
    const Vec& lambda = integrator.impulses();
    const double E_total = E.total();
    const double err = std::abs(E_total - result.initial_energy) / result.energy_scale;
    if (!(err <= result.max_energy_error)) result.max_energy_error = err;  // NaN (no scale) sticks
    if (!options.record_series) return;
    row[0] = s.t;
    row[1] = dt;
    row[2] = E.kinetic;
    row[3] = E.potential;
    row[4] = E_total;
    row[5] = min_gap();
    row[6] = lambda.sum();
    row[7] = static_cast<double>((lambda.array() > 0.0).count());
    row[8] = tangential_magnitude();
    problem.observe(s, lambda, dt, std::span<double>(row).subspan(kGenericColumns.size()));
    if (options.series_sink)
      options.series_sink->row(row);
    else
      result.series.values.insert(result.series.values.end(), row.begin(), row.end());
  };
  const auto finite = [&]() {
    const State& s = integrator.state();
    return s.u.allFinite() && s.v.allFinite() && std::isfinite(integrator.energy().total());
  };
  long state_written = -1;  // the step of the last state given to the sink
  const auto write_state = [&]() {
    if (!options.state_sink || state_written == result.steps) return;
    options.state_sink->state(integrator.state(), integrator.impulses(), integrator.tangential_impulses(),
                              integrator.tangential_impulses2());
    state_written = result.steps;
  };

  result.initial_energy = integrator.energy().total();
  result.energy_scale = energy_error_scale(problem, result.initial_energy);
  result.energy_scale_text = result.initial_energy != 0.0 ? "|E0|" : "E0 = 0: " + problem.energy_scale_text();
  sample(0.0);
  write_state();
  const double cpu_start = cpu_seconds();
  // The observer's and sampling's share is timed on the wall clock, read in user space (tens
  // of ns); a thread CPU clock is a system call (a microsecond or more on a virtual machine,
  // more than a bouncing-mass step: read around every observed step, it was half of the
  // bouncing study's CPU time), read here only at the ends of the loop.
  double observe_seconds = 0.0;  // wall time in the observer and sampling
  const auto wall_now = [] { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); };
  StepInfo info;
  double largest_impulse = 0.0;  // of the run so far (output_fault)
  TeamSize team(run_threads());  // one thread or all, whichever steps faster now (core/team_size.hpp)
  const auto wall_start = std::chrono::steady_clock::now();
  ProgressLine progress(options.progress_every, integrator.name(), integrator.state().t, options.t_end);
  // A scheme that evaluates no F_int (modal-exact) publishes its work in F_int-evaluation
  // equivalents (work().extra "force_equivalents", set up by init: the node stays put), and
  // the budget counts them as evaluations, so that it stops that scheme too.
  const auto& counters = integrator.work().extra;
  const auto equivalents_slot = counters.find("force_equivalents");
  const double* equivalents = equivalents_slot == counters.end() ? nullptr : &equivalents_slot->second;
  try {
    while (integrator.state().t < options.t_end * (1.0 - 1e-12)) {
      if (options.interrupt && *options.interrupt) {
        result.status = RunStatus::Interrupted;
        result.message = fmt::format("interrupted at t = {:.6g}", integrator.state().t);
        // The series ends where the summary does, at the last step taken.
        if (result.steps % options.sample_every != 0 && finite()) sample(info.dt);
        break;
      }
      progress.before_step(result.steps, integrator.state().t);
      const bool timed = team.timing();
      const double step_start = timed ? wall_now() : 0.0;
      {
        const ThreadScope scope(team.threads());
        info = integrator.step(options.dt);
      }
      team.step_done(timed ? wall_now() - step_start : 0.0);
      ++result.steps;
      result.max_penetration = std::max(result.max_penetration, -min_gap());
      if (const std::string fault = output_fault(info.dt, options, gaps, integrator, largest_impulse);
          !fault.empty()) {
        result.status = RunStatus::Diverged;
        result.message = fmt::format("{} at t = {:.6g}", fault, integrator.state().t);
        break;
      }
      const bool last = integrator.state().t >= options.t_end * (1.0 - 1e-12);
      const bool sampled = result.steps % options.sample_every == 0 || last;
      const bool stored = options.state_sink && (result.steps % options.state_every == 0 || last);
      if (observer || sampled || stored) {
        const double observe_start = wall_now();
        if (observer) observer(integrator, info);
        const bool diverged = sampled && !finite();
        if (sampled && !diverged) sample(info.dt);
        // Divergence is found where it was without a sink (the run's numbers do not change);
        // a non-finite state is not written.
        if (stored && !diverged && finite()) write_state();
        observe_seconds += wall_now() - observe_start;
        if (diverged) {
          result.status = RunStatus::Diverged;
          result.message = fmt::format("non-finite state at t = {:.6g}", integrator.state().t);
          break;
        }
      }
      if (result.steps >= options.max_steps) {
        result.status = RunStatus::Diverged;
        result.message = fmt::format("step limit {} reached at t = {:.6g}", options.max_steps, integrator.state().t);
        break;
      }
      const long spent = integrator.work().force_evaluations + (equivalents ? static_cast<long>(*equivalents) : 0);
      if (options.max_force_evaluations > 0 && spent > options.max_force_evaluations) {
        result.status = RunStatus::OverBudget;
        result.message = fmt::format("budget of {} F_int evaluations{} exceeded at t = {:.6g} after {} steps",
                                     options.max_force_evaluations, equivalents ? " (or their equivalents)" : "",
                                     integrator.state().t, result.steps);
        break;
      }
    }
  } catch (const InputError&) {
    throw;
  } catch (const RunCancelled&) {
    throw;
  } catch (const std::exception& ex) {
    result.status = RunStatus::Diverged;
    result.message = ex.what();
  }
  if (options.state_sink && state_written != result.steps && finite()) {  // stopped early: the last state too
    const double observe_start = wall_now();
    write_state();
    observe_seconds += wall_now() - observe_start;
  }
  result.cpu_seconds = cpu_seconds() - cpu_start;
  result.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  // The CPU time split as the wall time was: exact on a quiet core, and unbiased where
  // preemption strikes the steps and the observer alike.
  const double observed_share = result.wall_seconds > 0.0 ? std::min(1.0, observe_seconds / result.wall_seconds) : 0.0;
  result.step_cpu_seconds = result.cpu_seconds * (1.0 - observed_share);
  result.t_final = integrator.state().t;
  result.final_energy = integrator.energy().total();
  result.work = integrator.work();
  if (result.status != RunStatus::Diverged && result.status != RunStatus::Interrupted && !finite()) {  // over budget and non-finite: diverged
    result.status = RunStatus::Diverged;
    result.message = fmt::format("non-finite state at t = {:.6g}", result.t_final);
  }
  return result;
}

}  // namespace nsb

namespace nsb {

namespace {

void append_csv_row(std::string& out, std::span<const double> values) {
  for (std::size_t c = 0; c < values.size(); ++c) {
    fmt::format_to(std::back_inserter(out), "{}", values[c]);
    out += (c + 1 == values.size()) ? '\n' : ',';
  }
}

}  // namespace

std::string series_to_csv(const Series& series) {
  std::string out = fmt::format("{}\n", fmt::join(series.columns, ","));
  const std::size_t ncol = series.columns.size();
  for (std::size_t r = 0; r < series.rows(); ++r) append_csv_row(out, std::span(series.values).subspan(r * ncol, ncol));
  return out;
}

CsvSeriesFile::CsvSeriesFile(std::filesystem::path path)
    : path_(std::move(path)),
      tmp_(path_.parent_path() / fmt::format(".{}.tmp.{}", path_.filename().string(), static_cast<long>(::getpid()))) {
  file_ = std::fopen(tmp_.c_str(), "wb");
  if (!file_) throw InputError(fmt::format("cannot write '{}'", path_.string()));
}

CsvSeriesFile::~CsvSeriesFile() {
  if (!file_) return;
  std::fclose(file_);
  std::error_code ignored;
  std::filesystem::remove(tmp_, ignored);
}

void CsvSeriesFile::columns(const std::vector<std::string>& names) { buffer_ += fmt::format("{}\n", fmt::join(names, ",")); }

void CsvSeriesFile::row(std::span<const double> values) {
  append_csv_row(buffer_, values);
  if (buffer_.size() >= (1u << 16)) {  // written in blocks: a few write calls per MB
    if (std::fwrite(buffer_.data(), 1, buffer_.size(), file_) != buffer_.size())
      throw InputError(fmt::format("cannot write '{}': {}", path_.string(), std::strerror(errno)));
    buffer_.clear();
  }
}

void CsvSeriesFile::commit() {
  const bool ok = std::fwrite(buffer_.data(), 1, buffer_.size(), file_) == buffer_.size();
  const bool closed = std::fclose(file_) == 0;
  file_ = nullptr;
  std::error_code ec;
  if (ok && closed) std::filesystem::rename(tmp_, path_, ec);
  if (!ok || !closed || ec) {
    std::filesystem::remove(tmp_, ec);
    throw InputError(fmt::format("cannot write '{}'", path_.string()));
  }
}

}  // namespace nsb

#include <nlohmann/json.hpp>

#include "core/build_info.hpp"
#include "core/plugin.hpp"

namespace nsb {

std::string summary_to_json(const Problem& problem, const Integrator& integrator,
                            const RunOptions& options, const RunResult& result) {
  using nlohmann::json;
  const auto params = [](const Params& p) {
    json j = json::object();
    for (const auto& [k, v] : p.values()) {
      if (v.empty()) continue;  // an unset optional parameter
      char* end = nullptr;
      const double x = std::strtod(v.c_str(), &end);
      if (end != v.c_str() + v.size())
        j[k] = v;
      else if (x == std::floor(x) && std::abs(x) < 1e15)
        j[k] = static_cast<long long>(x);
      else
        j[k] = x;
    }
    return j;
  };
  json work = {{"steps", result.work.steps},
               {"force_evaluations", result.work.force_evaluations},
               {"tangent_evaluations", result.work.tangent_evaluations},
               {"factorizations", result.work.factorizations},
               {"linear_solves", result.work.linear_solves},
               {"lcp_iterations", result.work.lcp_iterations},
               {"lcp_unconverged", result.work.lcp_unconverged}};
  for (const auto& [k, v] : result.work.extra) work[k] = v;
  const BuildInfo& b = build_info();
  json j = {
      {"problem", problem.name()},
      {"problem_parameters", params(problem.parameters())},
      {"integrator", integrator.name()},
      {"integrator_parameters", params(integrator.parameters())},
      {"dt", options.dt},
      {"t_end", options.t_end},
      {"sample_every", options.sample_every},
      {"status", status_name(result.status)},
      {"message", result.message},
      {"steps", result.steps},
      {"t_final", result.t_final},
      {"cpu_seconds", result.cpu_seconds},
      {"step_cpu_seconds", result.step_cpu_seconds},
      {"wall_seconds", result.wall_seconds},
      {"threads", run_threads()},
      {"initial_energy", result.initial_energy},
      {"final_energy", result.final_energy},
      {"final_energy_error", result.final_energy_error()},
      {"final_energy_change", result.final_energy_change()},
      {"max_energy_error", result.max_energy_error},
      {"energy_error_scale", result.energy_scale},
      {"energy_error_scale_is", result.energy_scale_text},
      {"max_penetration", result.max_penetration},
      {"work", work},
      {"build", {{"version", b.version}, {"git_revision", b.git_revision}, {"build_type", b.build_type}, {"compiler", b.compiler}}},
  };
  if (!b.dirty_files.empty()) j["build"]["dirty_files"] = b.dirty_files;  // what the -dirty revision ran
  if (const auto figures = problem.summary_values(); !figures.empty()) {
    json summary = json::object();
    for (const auto& [name, value] : figures) summary[name] = std::isfinite(value) ? json(value) : json(nullptr);
    j["problem_summary"] = summary;
  }
  if (!loaded_plugins().empty()) {
    json plugins = json::array();
    for (const auto& p : loaded_plugins()) {
      json plugin = {{"file", p.file}, {"hash", p.hash}, {"build_known", p.build_known}};
      if (p.build_known)
        plugin.update({{"optimized", p.optimized}, {"build_type", p.build_type}, {"compile_flags", p.compile_flags}});
      plugins.push_back(plugin);
    }
    j["build"]["plugins"] = plugins;
  }
  return j.dump(2) + "\n";
}

}  // namespace nsb
