#pragma once
// The run driver: advances an integrator on a problem to t_end, samples observables into
// a series (columns below, then the problem's own) and gathers the run's figures.
//
// Generic columns: t, dt, kinetic, potential, total_energy, min_gap, impulse (sum of the
// contact impulses of the step), active_contacts (contacts with a positive impulse),
// tangential_impulse (sum of |Lambda_T| of the step, |(Lambda_T1, Lambda_T2)| for 3D contacts; 0
// without friction).
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <span>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"

namespace nsb {

// Where a run's samples go instead of RunResult::series (RunOptions::series_sink): memory
// bounded whatever the run's length. columns() once, then row() per sample.
class SeriesSink {
 public:
  virtual ~SeriesSink() = default;
  virtual void columns(const std::vector<std::string>& names) = 0;
  virtual void row(std::span<const double> values) = 0;
};

// Where a run's states go (RunOptions::state_sink; field output, run/field_output.hpp):
// the initial state, every state_every-th step's and the last one's (the state the summary
// reports, also when the run stops early), with the impulses of the step that ended there
// (zero for the initial state; tangential_impulses2: along T2, zero for 2D contacts). It only
// reads: the run's numbers are the same without it.
class StateSink {
 public:
  virtual ~StateSink() = default;
  virtual void state(const State& s, const Vec& normal_impulses, const Vec& tangential_impulses,
                     const Vec& tangential_impulses2) = 0;
};

// Thrown by an integrator's step to end the run and reach run()'s caller unchanged, not as a
// diverged run: a KeyboardInterrupt or SystemExit in a Python step (python/python_integrator.hpp).
class RunCancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct RunOptions {
  double dt = 0.0;          // requested step (> 0)
  double t_end = 0.0;       // the run stops at the first step reaching t_end
  long sample_every = 1;    // record every k-th step (and the first and last)
  bool record_series = true;
  SeriesSink* series_sink = nullptr;  // set: the samples go there, RunResult::series stays empty
  StateSink* state_sink = nullptr;    // set: states go there (StateSink)
  long state_every = 1;               // every k-th step's state (and the first and last)
  long max_steps = 200'000'000;
  // Work budget: the run stops with status OverBudget once the integrator's F_int
  // evaluations (WorkCounters::force_evaluations), plus the F_int-evaluation equivalents a
  // scheme that evaluates no F_int publishes as work().extra "force_equivalents"
  // (modal-exact), exceed it; 0: no budget. A count, not a
  // clock, so the same run stops at the same step on any machine. Checked after each step:
  // a run may overshoot by one step's work (an event-driven step can take many).
  long max_force_evaluations = 0;
  // When set, the run stops with status Interrupted at the first step after *interrupt
  // becomes non-zero (a signal handler's flag).
  const volatile std::sig_atomic_t* interrupt = nullptr;
  // Progress lines on stderr (percent of t_end, elapsed, estimate left) every
  // progress_every seconds of wall time, from the first such period on; 0: none.
  double progress_every = 0.0;
};

// Samples in row-major order.
struct Series {
  std::vector<std::string> columns;
  std::vector<double> values;
  std::size_t rows() const { return columns.empty() ? 0 : values.size() / columns.size(); }
  double at(std::size_t row, std::size_t col) const { return values[row * columns.size() + col]; }
  // Column index by name; throws std::out_of_range when absent.
  std::size_t column(const std::string& name) const;
};

enum class RunStatus { Ok, Diverged, OverBudget, Interrupted };
// "ok", "diverged", "over budget", "interrupted".
const char* status_name(RunStatus status);

struct RunResult {
  RunStatus status = RunStatus::Ok;
  std::string message;      // why a run diverged
  Series series;
  long steps = 0;
  double t_final = 0.0;
  double cpu_seconds = 0.0;      // CPU time of the stepping loop (sampling included): the
                                 // thread's, or the process's when run_threads() > 1
  // The same less the share spent in the observer and in sampling (the series, the energy
  // check, the finiteness check): the integrator's cost. That share is the wall time around
  // the observed or sampled steps over the loop's wall time (the wall clock costs tens of ns a
  // read, a thread CPU clock a system call); each such step's stepping time carries about
  // one clock read.
  double step_cpu_seconds = 0.0;
  double wall_seconds = 0.0;     // elapsed time of the same loop
  double initial_energy = 0.0;
  double final_energy = 0.0;
  // Energy errors are |E - E0| / energy_scale: |E0|, or the problem's energy_scale() when
  // E0 = 0 (energy_scale_text says which); NaN when both are 0.
  double energy_scale = 0.0;
  std::string energy_scale_text;
  double max_energy_error = 0.0;  // max over the samples
  double max_penetration = 0.0;   // max over steps of max(0, -g)
  WorkCounters work;
  double final_energy_error() const { return std::abs(final_energy - initial_energy) / energy_scale; }
  // (E_end - E0) / energy_scale, signed: the energy change, a loss (< 0) on a dissipative run
  // and no error there; what `nsbench run` prints.
  double final_energy_change() const { return (final_energy - initial_energy) / energy_scale; }
};

// Called after every step (impact detection and the like in studies).
using StepObserver = std::function<void(const Integrator&, const StepInfo&)>;

// Throws InputError for a bad dt or t_end; a non-finite state or a solver failure ends the
// run with status Diverged, an exhausted work budget with OverBudget, the reason in message.
RunResult run(const Problem& problem, Integrator& integrator, const RunOptions& options,
              const StepObserver& observer = {});

// What energy errors of a run starting at energy E0 are relative to: |E0|, or the problem's
// energy_scale() when E0 = 0; NaN when both are 0.
double energy_error_scale(const Problem& problem, double E0);

// |value - reference| / |reference|; NaN when reference is 0 (a relative error is then
// undefined: callers with a natural scale divide by it themselves).
double relative_error(double value, double reference);

}  // namespace nsb

namespace nsb {
// The series as CSV: a header row, then one row per sample (shortest round-trip numbers).
std::string series_to_csv(const Series& series);

// The same written as the run goes, into a hidden temporary beside `path`
// (".NAME.tmp.PID", as write_file_atomic) renamed over `path` by commit(): the run's memory
// does not grow with its length, and a reader never sees half a series. Destroyed without
// commit(): the temporary is removed. Write errors are InputErrors naming the file.
class CsvSeriesFile final : public SeriesSink {
 public:
  explicit CsvSeriesFile(std::filesystem::path path);
  ~CsvSeriesFile() override;
  void columns(const std::vector<std::string>& names) override;
  void row(std::span<const double> values) override;
  void commit();

 private:
  std::filesystem::path path_, tmp_;
  std::FILE* file_ = nullptr;
  std::string buffer_;
};
}  // namespace nsb

namespace nsb {
// summary.json of a run: problem, integrator, every parameter, the run's figures, the work
// counters and the build stamp.
std::string summary_to_json(const Problem& problem, const Integrator& integrator,
                            const RunOptions& options, const RunResult& result);
}  // namespace nsb
