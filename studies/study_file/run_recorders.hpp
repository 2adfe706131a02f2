#pragma once
// What a run of a study file's case records as it steps (studies/study_file/run_case.cpp):
// its reference, its energy growth, its own figures, the running figures of its measures and
// the series its tables of some runs show.
#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "problems/problem.hpp"
#include "problems/state.hpp"
#include "reference/cache.hpp"
#include "reference/modal_exact.hpp"
#include "run/run.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"
#include "studies/study.hpp"
#include "studies/study_file.hpp"
#include "studies/study_file/engine.hpp"

namespace nsb::study_files {

// What a case asks of its reference run (cached by reference/cache.hpp).
ReferenceRequest reference_request(const StudySpec& spec, const FileProblem& p);
Json work_counter(const std::map<std::string, double>& extra, const std::string& name);

// The reference of one case: the exact solution, a reference integrator stepped with the run
// (lockstep), or the cached run interpolated in time.
class Reference {
 public:
  Reference(const StudySpec& spec, const Problem& problem, const SpMat& M, const FileProblem& fp);
  // A lockstep reference takes the run's step.
  void advance(double dt) {
    if (lockstep_) lockstep_->step(dt);
  }
  double observable(double t, const std::string& name, ObservableBuffer& buffer) const;
  Vec u(double t) const { return lockstep_ ? lockstep_->state().u : problem_.exact()->state(t)->u; }
  Vec v(double t) const { return lockstep_ ? lockstep_->state().v : problem_.exact()->state(t)->v; }
  // The reference's graph of an observable on [0, t_end].
  Polyline graph(const std::string& name, double t_end, ObservableBuffer& buffer) const;

 private:
  const Problem& problem_;
  const SpMat& M_;
  bool exact_;
  CachedReference run_;
  std::size_t t_ = 0;
  std::unique_ptr<Integrator> lockstep_;
};

// The largest rise of a run's energy above E0 and the work W its surroundings can have done
// (the formula above): max_k E_k - E0 - W_k.
class EnergyGrowth {
 public:
  EnergyGrowth(const Problem& problem, const State& initial, double e0);
  // After a step ending in state it.state() with total energy `energy`.
  void add(const Integrator& it, double dt, double energy);
  double largest() const { return largest_; }

 private:
  const Problem& problem_;
  double e0_, work_ = 0.0, largest_ = 0.0;
  Vec obstacle_speed_, u_prev_, f_ext_;
};

// What every run reports besides its measures (the run columns of a declared case table and
// the rows of its history tables): where it stopped, its contact phases (a phase after at least
// the problem's min_flight without impulse) and the mode switches a scheme locates inside its
// steps, its smallest and largest step, the study's work counters, its largest energy rise and
// penetration against the problem's limits. Histories (only for the problems a history or
// samples table shows): over each of study.history_intervals equal intervals of [0, t_end],
// the largest |E - E0| / E scale, the largest penetration -min g (negative while every gap is
// open) and, where a table shows it, the largest momentum residual (momentum_history); and
// E/E0 at the first step at or after each of as many evenly spaced times (samples).
class RunFigures {
 public:
  RunFigures(const Problem& problem, const StudySpec& spec, const FileProblem& fp, double t_end, double e0, double e_scale);
  void add(const Integrator& it, double dt, const MomentumBalance& momentum, double energy);
  Json result(const RunResult& r, double energy_growth);

 private:
  // Whether a declared table of `rows` shows the runs of `fp` (and the column `column`, unless empty).
  static bool shows(const StudySpec& spec, const FileProblem& fp, const std::string& rows, const std::string& column);
  const Problem& problem_;
  const StudySpec& spec_;
  double e0_, e_scale_, t_end_;
  ContactPhases impacts_;
  double min_step_ = std::numeric_limits<double>::max(), max_step_ = 0.0;
  IntervalMax history_, momentum_history_;
  bool keeps_history_, keeps_momentum_, keeps_samples_;
  std::vector<double> samples_t_, samples_e_;
};

// The running figures of a measure of an observable's events, fed the observable after every
// step (README, "Studies from a file"):
//   impact-ratio  o+ / o- across impact `impact` (ContactImpacts: a contact's impulse after a
//                 step without one), or with `law` its difference from the law's ratio, there
//                 or the largest over the first `count` impacts (as many as happen);
//   amplitude     the largest |o| after impact `impact` (or the last that happens) up to the
//                 next; `exact`: relative to the exact amplitude after the same impact;
//   impact-count  the impacts seen;
//   rest-time     the end of the last step with |o| > threshold (NaN while still above at the
//                 run's end); `exact`: its distance to the exact time to rest [s];
//   peak-time     the end of the step where o is largest; `exact`: its distance to the exact
//                 dynamic jam [s];
//   value         o at the last step, or its max or min over the steps;
//   summary       the problem's summary value `summary` (no observable), e.g. an exact event
//                 time; rest-time and peak-time with `exact` and `summary`: against that value.
class EventFigures {
 public:
  EventFigures(const FileMeasure& m, const Problem& problem, double value0);
  // After a step ending at t with configuration u.
  void add(double t, const Vec& impulses, const Vec& u, double value);
  double result(const Problem& problem) const;

 private:
  // The exact time of a rest-time or peak-time measure: the problem's summary value the
  // measure names, else the closed form studies/measures.hpp gives.
  double exact_time(const Problem& problem, double (*closed_form)(const Problem&)) const;
  // The gaps g(u) (moving contacts: evaluated, not linearised at U0).
  const Vec& gaps(const Vec& u);

  const FileMeasure& m_;
  const Problem& problem_;
  ContactGeometry geometry_;
  ContactImpacts impacts_;
  bool above_ = false;
  double last_above_ = 0.0, peak_t_ = kNaN, largest_, smallest_, last_;
};

// One measure's running figures.
struct Accumulator {
  double scale = 0.0, largest = 0.0, square = 0.0, last = kNaN, t_prev = 0.0;
  // An error over every step: sum dt_k e_k^2 (rms), sum e_k^2 and the steps counted (step rms).
  double timed_square = 0.0, step_square = 0.0;
  long steps = 0;
  RunningSlope drift;
  ContactPhases impacts;  // impact-time; contact-duration: its span
  Chatter chatter;        // chatter, zero-steps
  Polyline graph;  // Hausdorff: the run's samples
  FlightEnergies flights;
  FinalRest rest;
  std::optional<EventFigures> events;
  std::optional<MeshMomentum> mesh_momentum;  // a momentum measure's component
  std::vector<double> periodic;  // Energy with `every`: the error at each sample time from + k every
  std::vector<double> samples;   // Estimate: the observable at each sample (compared with the next run's)
  double next_sample = 0.0;      // per_nominal_step: the time from which the next step is sampled
};

// The series of one run that the tables of some runs show (FileTable::of_some_runs): each
// trajectory table's observable (and exact observable) at its sample steps (FileTable::points,
// spacing, relative); and, at the end, each periodic table's energy samples (its measure's own).
class RunSeries {
 public:
  // After the integrator's init: `energy0` its energy at the start (a relative trajectory's start values).
  RunSeries(const StudySpec& spec, const FileProblem& fp, double t_end, const Problem& problem, const SpMat& M, const Integrator& it,
            ObservableBuffer& buffer, const Energy& energy0);
  void add(const Problem& problem, const SpMat& M, const Integrator& it, double dt, ObservableBuffer& buffer, const Energy& energy);
  // Into the run's figures: "trajectories" by table id {t, value, exact} (spacing = "steps":
  // every s-th step kept), "periodic" by measure label (the samples of `periodic`, each
  // measure's, in the order of spec.measures).
  void write(const std::vector<const std::vector<double>*>& periodic, Json& run) const;

 private:
  struct Trajectory {
    const FileTable* table;
    double start;
    double value0 = 1.0, exact0 = 1.0;  // relative: the values at the start
    std::vector<double> t, value, exact;
  };
  const StudySpec& spec_;
  std::vector<Trajectory> trajectories_;
};

// The series of one run that impulses and field tables show (FileTable rows "impulses",
// "field"), for the runs of the problems and integrators they name: each impulses table's sum
// of the contact impulses per nominal step bin, each field table's element stresses at the
// start and after every step.
class RunImpulsesAndFields {
 public:
  // After the integrator's init (its state: the field's first row); `dt` the run's nominal step.
  RunImpulsesAndFields(const StudySpec& spec, const FileProblem& fp, const FileIntegrator& fi, const Problem& problem,
                       const Integrator& it, double dt);
  void add(const Problem& problem, const Integrator& it);
  // Into the run's figures: "impulses" by table id {t, value}, "fields" by table id {t, values:
  // the cells of each row, row after row}.
  void write(Json& run) const;

 private:
  void add_fields(const Problem& problem, const State& s);
  struct Bins {
    const FileTable* table;
    std::vector<double> impulses;  // by bin j
  };
  struct Field {
    const FileTable* table;
    Index component;
    std::vector<double> t, values;
  };
  double dt_;
  std::vector<Bins> bins_;
  std::vector<Field> fields_;
  Eigen::MatrixXd stress_;
};

double event_observable(const Problem& problem, const SpMat& M, const Integrator& it, double dt, const FileMeasure& m,
                        ObservableBuffer& buffer, const Energy& energy);
Json not_run(const std::string& why);
double located_impact_error(const Integrator& integrator, const Problem& problem, double t_end, int count);
void sample_periodic(const FileMeasure& m, Accumulator& a, double t, double dt, double t_end, double e);
double periodic_value(const std::string& norm, const std::vector<double>& e);
std::unique_ptr<ModalExact> semi_discrete_reference(const StudySpec& spec, const FileProblem& fp, const std::string& integrator,
                                                    const Problem& problem, std::string& note);

}  // namespace nsb::study_files
