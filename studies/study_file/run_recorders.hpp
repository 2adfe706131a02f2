#pragma once
// What a run of a study file's case records as it steps (studies/study_file/run_case.cpp):
// its reference, its energy growth, its own figures, the running figures of its measures and
// the series its tables of some runs show.
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "integrators/registry.hpp"
#include "reference/cache.hpp"
#include "reference/modal_exact.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"
#include "studies/study_file/engine.hpp"

namespace nsb::study_files {

// What a case asks of its reference run (cached by reference/cache.hpp).
ReferenceRequest reference_request(const StudySpec& spec, const FileProblem& p);
Json work_counter(const std::map<std::string, double>& extra, const std::string& name);

// The reference of one case: the exact solution, a reference integrator stepped with the run
// (lockstep), or the cached run interpolated in time.
class Reference {
 public:
  Reference(const StudySpec& spec, const Problem& problem, const SpMat& M, const FileProblem& fp)
      : problem_(problem), M_(M), exact_(!spec.reference_of(fp) || spec.reference_of(fp)->exact) {
    if (exact_) return;
    const FileReference& ref = *spec.reference_of(fp);
    if (ref.lockstep) {
      lockstep_ = make_integrator(ref.integrator, ref.parameters);
      lockstep_->init(problem, problem.initial_state());
      return;
    }
    // Computed by the first case that reads it (cached_reference: once, whatever the threads), so
    // that listing a study's cases, or running one shard of them, runs no reference it does not read.
    try {
      run_ = cached_reference(reference_cache_dir(), reference_request(spec, fp));
    } catch (const InputError& e) {
      throw InputError(fmt::format("study {}, reference run on {}: {}", spec.name, fp.label, e.what()));
    }
    if (run_.summary["status"] != "ok" || run_.series.rows() == 0)
      throw InputError(fmt::format("reference {} on {} failed: {} {}", ref.integrator, fp.label,
                                   run_.summary["status"].dump(), run_.summary["message"].dump()));
    t_ = run_.series.column("t");
  }
  // A lockstep reference takes the run's step.
  void advance(double dt) {
    if (lockstep_) lockstep_->step(dt);
  }
  double observable(double t, const std::string& name, std::span<double> buffer) const {
    if (lockstep_) {
      const Energy energy = lockstep_->energy();
      return state_observable(problem_, M_, lockstep_->state(), lockstep_->impulses(), 0.0, name, buffer, &energy);
    }
    if (exact_) return *exact_observable(problem_, M_, t, name, buffer);
    const Series& s = run_.series;
    const std::size_t col = s.column(name);
    std::size_t lo = 0, hi = s.rows() - 1;
    if (t >= s.at(hi, t_)) return s.at(hi, col);
    while (hi - lo > 1) {
      const std::size_t mid = (lo + hi) / 2;
      (s.at(mid, t_) <= t ? lo : hi) = mid;
    }
    const double t0 = s.at(lo, t_), t1 = s.at(hi, t_), w = t1 > t0 ? (t - t0) / (t1 - t0) : 0.0;
    return (1 - w) * s.at(lo, col) + w * s.at(hi, col);
  }
  Vec u(double t) const { return lockstep_ ? lockstep_->state().u : problem_.exact()->state(t)->u; }
  Vec v(double t) const { return lockstep_ ? lockstep_->state().v : problem_.exact()->state(t)->v; }
  // The reference's graph of an observable on [0, t_end].
  Polyline graph(const std::string& name, double t_end, std::span<double> buffer) const {
    if (exact_) {
      const Vec none = Vec::Zero(problem_.ncontacts());
      return exact_graph(problem_, [&](const State& s) { return state_observable(problem_, M_, s, none, 0.0, name, buffer, nullptr); }, t_end);
    }
    Polyline g;
    const std::size_t col = run_.series.column(name);
    for (std::size_t k = 0; k < run_.series.rows(); ++k) g.add(run_.series.at(k, t_), run_.series.at(k, col));
    return g;
  }

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
  EnergyGrowth(const Problem& problem, const State& initial, double e0)
      : problem_(problem), e0_(e0), u_prev_(initial.u), f_ext_(problem.ndof()) {
    const Vec& w = problem.contacts().tangent_velocity;
    if (w.size() && w.cwiseAbs().maxCoeff() > 0.0) obstacle_speed_ = w.cwiseAbs();
  }
  // After a step ending in state it.state() with total energy `energy`.
  void add(const Integrator& it, double dt, double energy) {
    const State& s = it.state();
    if (obstacle_speed_.size() && it.tangential_impulses().size())
      work_ += obstacle_speed_.dot(it.tangential_impulses().cwiseAbs());
    if (!problem_.external_force_is_constant()) {
      problem_.external_force(s.t - dt, f_ext_);
      work_ += std::max(0.0, f_ext_.dot(s.u - u_prev_));
      u_prev_ = s.u;
    }
    largest_ = std::max(largest_, energy - e0_ - work_);
  }
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
  RunFigures(const Problem& problem, const StudySpec& spec, const FileProblem& fp, double t_end, double e0, double e_scale)
      : problem_(problem), spec_(spec), e0_(e0), e_scale_(e_scale), t_end_(t_end), impacts_(fp.min_flight),
        history_(t_end, spec.history_intervals, 2),
        momentum_history_(t_end, spec.history_intervals, 1), keeps_history_(shows(spec, fp, "history", "")),
        keeps_momentum_(shows(spec, fp, "history", "momentum residual")), keeps_samples_(shows(spec, fp, "samples", "")) {}
  void add(const Integrator& it, double dt, const MomentumBalance& momentum, double energy) {
    const double t = it.state().t;
    impacts_.add(t, it.impulses().sum() > 0.0);
    min_step_ = std::min(min_step_, dt);
    max_step_ = std::max(max_step_, dt);
    if (keeps_samples_ && t >= t_end_ * static_cast<double>(samples_t_.size()) / spec_.history_intervals) {
      samples_t_.push_back(t);
      samples_e_.push_back(energy / e0_);
    }
    if (!keeps_history_) return;
    const double gap = problem_.ncontacts() ? (problem_.gap_offset() + problem_.gap_operator() * it.state().u).minCoeff() : kNaN;
    history_.add(t, {std::abs(energy - e0_) / e_scale_, -gap});
    if (keeps_momentum_) momentum_history_.add(t, {momentum.residual(it.state().v) / momentum.speed_scale()});
  }
  Json result(const RunResult& r, double energy_growth) {
    const auto extra = [&](const std::string& key) {
      const auto it = r.work.extra.find(key);
      return it == r.work.extra.end() ? Json(nullptr) : real(it->second);
    };
    Json figures = {{"t_reached", r.t_final}, {"impacts", static_cast<long>(impacts_.starts().size())},
                    {"switches", extra("switches")}, {"missed_switches", extra("missed_switches")},
                    {"max_penetration", r.max_penetration}, {"energy_growth", real(energy_growth)},
                    {"final_energy_error", real(std::abs(r.final_energy - r.initial_energy) / e_scale_)},
                    {"energy_scale", e_scale_}, {"note", r.message}, {"min_step", min_step_}, {"max_step", max_step_}};
    Json counters = Json::array();
    for (const auto& name : spec_.counters) counters.push_back(work_counter(r.work.extra, name));
    figures["counters"] = counters;
    if (keeps_history_) {
      history_.finish();
      figures["intervals"] = {{"t", reals(history_.times())}, {"energy", reals(history_.largest(0))},
                              {"penetration", reals(history_.largest(1))}};
      if (keeps_momentum_) {
        momentum_history_.finish();
        figures["intervals"]["momentum"] = reals(momentum_history_.largest(0));
      }
    }
    if (keeps_samples_) figures["samples"] = {{"t", reals(samples_t_)}, {"energy_ratio", reals(samples_e_)}};
    return {{"run", figures}};
  }

 private:
  // Whether a declared table of `rows` shows the runs of `fp` (and the column `column`, unless empty).
  static bool shows(const StudySpec& spec, const FileProblem& fp, const std::string& rows, const std::string& column) {
    return std::any_of(spec.tables.begin(), spec.tables.end(), [&](const FileTable& t) {
      return t.rows == rows && t.applies_to(fp.label) &&
             (column.empty() || std::any_of(t.columns.begin(), t.columns.end(), [&](const FileColumn& c) { return c.of == column; }));
    });
  }
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
  EventFigures(const FileMeasure& m, const Problem& problem, double value0)
      : m_(m), problem_(problem), geometry_(problem.contact_geometry()),
        impacts_(gaps(problem.initial_state().u), value0), largest_(value0), smallest_(value0), last_(value0) {
    add(0.0, Vec::Zero(problem.ncontacts()), problem.initial_state().u, value0);
  }
  // After a step ending at t with configuration u.
  void add(double t, const Vec& impulses, const Vec& u, double value) {
    if (t > 0.0) impacts_.add(t, impulses, gaps(u), value);
    above_ = std::abs(value) > m_.threshold;
    if (above_) last_above_ = t;
    if (std::isnan(peak_t_) || value > largest_) peak_t_ = t;
    largest_ = std::max(largest_, value);
    smallest_ = std::min(smallest_, value);
    last_ = value;
  }
  double result(const Problem& problem) const {
    const auto& seen = impacts_.impacts();
    const auto ratio = [&](std::size_t k) { return seen[k].after / seen[k].before; };
    const double law = m_.law.empty() ? kNaN : rocking_law_ratio(problem, m_.law == "housner" ? ImpactLaw::housner : ImpactLaw::moreau);
    switch (m_.kind) {
      case MeasureKind::ImpactRatio: {
        if (m_.count > 0 && m_.impact == 0) {
          double worst = seen.empty() ? kNaN : 0.0;
          for (std::size_t k = 0; k < seen.size() && k < static_cast<std::size_t>(m_.count); ++k) worst = std::max(worst, std::abs(ratio(k) - law));
          return worst;
        }
        const auto k = static_cast<std::size_t>(m_.impact);
        if (seen.size() < k) return kNaN;
        return m_.law.empty() ? ratio(k - 1) : std::abs(ratio(k - 1) - law);
      }
      case MeasureKind::Amplitude: {
        const std::size_t k = std::min(seen.size(), static_cast<std::size_t>(m_.impact));
        if (k == 0) return kNaN;
        const double exact = rocking_amplitude_after(problem, k);
        return m_.exact ? std::abs(seen[k - 1].amplitude - exact) / exact : seen[k - 1].amplitude;
      }
      case MeasureKind::ImpactCount: return static_cast<double>(seen.size());
      case MeasureKind::RestTime:
        if (above_) return kNaN;
        return m_.exact ? std::abs(last_above_ - exact_time(problem, rocking_rest_time)) : last_above_;
      case MeasureKind::PeakTime: return m_.exact ? std::abs(peak_t_ - exact_time(problem, painleve_jam_time)) : peak_t_;
      case MeasureKind::Summary: return summary_value(problem, m_.summary);
      default: return m_.norm == "max" ? largest_ : m_.norm == "min" ? smallest_ : last_;
    }
  }

 private:
  // The exact time of a rest-time or peak-time measure: the problem's summary value the
  // measure names, else the closed form studies/measures.hpp gives.
  double exact_time(const Problem& problem, double (*closed_form)(const Problem&)) const {
    return m_.summary.empty() ? closed_form(problem) : summary_value(problem, m_.summary);
  }
  // The gaps g(u) (moving contacts: evaluated, not linearised at U0).
  const Vec& gaps(const Vec& u) {
    problem_.evaluate_contacts(u, geometry_);
    return geometry_.gap;
  }

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
            std::span<double> buffer, const Energy& energy0)
      : spec_(spec) {
    for (const FileTable& d : spec.tables) {
      if (d.rows != "trajectory" || !d.applies_to(fp.label)) continue;
      Trajectory tr{&d, t_end - d.last, 1.0, 1.0, {}, {}, {}};
      if (d.relative) {
        const Vec none = Vec::Zero(problem.ncontacts());
        tr.value0 = state_observable(problem, M, it.state(), none, 0.0, d.observable, buffer, &energy0);
        if (!d.exact.empty()) tr.exact0 = state_observable(problem, M, it.state(), none, 0.0, d.exact, buffer, &energy0);
      }
      trajectories_.push_back(tr);
    }
  }
  void add(const Problem& problem, const SpMat& M, const Integrator& it, double dt, std::span<double> buffer, const Energy& energy) {
    const State& s = it.state();
    for (Trajectory& tr : trajectories_) {
      const auto n = static_cast<double>(tr.t.size());
      const bool due = tr.table->step_spacing ||
                       (tr.t.size() <= static_cast<std::size_t>(tr.table->points) && s.t >= tr.start + tr.table->last * n / tr.table->points);
      if (!due) continue;
      tr.t.push_back(s.t);
      tr.value.push_back(state_observable(problem, M, s, it.impulses(), dt, tr.table->observable, buffer, &energy) / tr.value0);
      if (!tr.table->exact.empty())
        tr.exact.push_back(state_observable(problem, M, s, it.impulses(), dt, tr.table->exact, buffer, &energy) / tr.exact0);
    }
  }
  // Into the run's figures: "trajectories" by table id {t, value, exact} (spacing = "steps":
  // every s-th step kept), "periodic" by measure label (the samples of `periodic`, each
  // measure's, in the order of spec.measures).
  void write(const std::vector<const std::vector<double>*>& periodic, Json& run) const {
    for (const Trajectory& tr : trajectories_) {
      std::vector<double> t, value, exact;
      const std::size_t stride = tr.table->step_spacing ? std::max<std::size_t>(1, tr.t.size() / static_cast<std::size_t>(tr.table->points)) : 1;
      for (std::size_t k = 0; k < tr.t.size(); k += stride) {
        t.push_back(tr.t[k]);
        value.push_back(tr.value[k]);
        if (!tr.exact.empty()) exact.push_back(tr.exact[k]);
      }
      run["trajectories"][tr.table->id] = {{"t", t}, {"value", reals(value)}, {"exact", reals(exact)}};
    }
    for (const FileTable& d : spec_.tables)
      for (std::size_t m = 0; m < spec_.measures.size(); ++m)
        if (d.rows == "periodic" && spec_.measures[m].label == d.measure && periodic[m])
          run["periodic"][d.measure] = reals(*periodic[m]);
  }

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
                       const Integrator& it, double dt)
      : dt_(dt) {
    const auto shown = [&](const FileTable& d) {
      return d.applies_to(fp.label) &&
             (d.integrators.empty() || std::find(d.integrators.begin(), d.integrators.end(), fi.label) != d.integrators.end());
    };
    for (const FileTable& d : spec.tables) {
      if (d.rows == "impulses" && shown(d)) bins_.push_back({&d, {}});
      if (d.rows != "field" || !shown(d)) continue;
      const FieldMesh mesh = problem.field_mesh().value();  // the reader checked it: 1D, cells of two points
      const auto& names = mesh.stress_components;
      const auto component = d.component.empty() ? names.begin() : std::find(names.begin(), names.end(), d.component);
      fields_.push_back({&d, static_cast<Index>(component - names.begin()), {}, {}});
      if (stress_.size() == 0) stress_.resize(mesh.nelements(), static_cast<Index>(names.size()));
    }
    add_fields(problem, it.state());
  }
  void add(const Problem& problem, const Integrator& it) {
    const double t = it.state().t;
    for (Bins& b : bins_) {
      const auto j = static_cast<std::size_t>(std::ceil(t / dt_ - 1e-9));  // (t_j - dt, t_j] holds t
      if (b.impulses.size() <= j) b.impulses.resize(j + 1, 0.0);
      b.impulses[j] += it.impulses().sum();
    }
    add_fields(problem, it.state());
  }
  // Into the run's figures: "impulses" by table id {t, value}, "fields" by table id {t, values:
  // the cells of each row, row after row}.
  void write(Json& run) const {
    for (const Bins& b : bins_) {
      std::vector<double> t, value;
      for (std::size_t j = 1; j < b.impulses.size(); ++j) {
        t.push_back(static_cast<double>(j) * dt_);
        value.push_back(b.impulses[j] / dt_ / b.table->scale);
      }
      run["impulses"][b.table->id] = {{"t", t}, {"value", reals(value)}};
    }
    for (const Field& f : fields_) run["fields"][f.table->id] = {{"t", f.t}, {"values", reals(f.values)}};
  }

 private:
  void add_fields(const Problem& problem, const State& s) {
    if (fields_.empty()) return;
    problem.cell_stress(s.u, stress_);
    for (Field& f : fields_) {
      f.t.push_back(s.t);
      f.values.insert(f.values.end(), stress_.col(f.component).begin(), stress_.col(f.component).end());
    }
  }
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
                        std::span<double> buffer, const Energy& energy);
Json not_run(const std::string& why);
double located_impact_error(const Integrator& integrator, const Problem& problem, double t_end, int count);
void sample_periodic(const FileMeasure& m, Accumulator& a, double t, double dt, double t_end, double e);
double periodic_value(const std::string& norm, const std::vector<double>& e);
std::unique_ptr<ModalExact> semi_discrete_reference(const StudySpec& spec, const FileProblem& fp, const std::string& integrator,
                                                    const Problem& problem, std::string& note);

}  // namespace nsb::study_files
