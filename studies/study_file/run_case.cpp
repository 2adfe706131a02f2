// The run of one case of a study file: its measures and its outcome.
//
//
// Measures (each a column; a run's error against the reference, sampled every sample_every
// steps and at the last step):
//   error        u: ||u - u_ref||_inf (v: ||v - v_ref||_inf, the velocities), an observable:
//                |o - o_ref|, divided by the largest |u_ref| (|v_ref|, |o_ref|) over the run
//                (absolute when that is 0); with `against` = o_exact, o_ref is the problem's
//                own observable o_exact at the run's state instead of the reference's; norm final (last
//                step), max (over the samples) or l2 (sqrt of the time-weighted mean square);
//                over every step (at its own dt): rms (sqrt(sum_k dt_k e_k^2 / (t_last - t0)), in
//                time up to the last step measured) or step rms (sqrt of the mean of e_k^2 over the
//                steps). With `scale`: each step's error divided by that value instead; with
//                `inside` = o: only the steps whose t - dt, t and t + dt lie where the problem's
//                exact observable o is > 0 (the exact contact phases: contact_force_exact).
//                A reference integrator's samples are interpolated linearly in time.
//   impact-time  max over the first `count` impacts of |t_i (scheme) - t_i (exact)|, t_i the
//                end of the first step with an impulse after a step without one [s]; with
//                min_flight_steps n: those up to the first whose exact flight is shorter than n
//                steps (compared_impacts, studies/measures.hpp); norm = "count": how many.
//   flight-energy  max over the first `count` flights of |E / E_i - 1| (FlightEnergies,
//                studies/measures.hpp), E at the exact mid-flight time or at the mid-flight
//                step between the run's own impacts (at = "mid-flight step"); an error that
//                converges with dt (fitted and pairwise orders); norm = "count": how many.
//   rest-start   the start of the run's final rest (FinalRest, studies/measures.hpp): the end of
//                the first step after which every step to the end has each `rest` bound's
//                observable at most at_most dt^dt_power, if that lasts longer than min_rest;
//                with exact = true its distance to the problem's summary value `summary` [s].
//   energy       (E - E0)/|E0| (E0 = 0: the problem's energy_scale(), run/run.hpp), E the scheme's own energy: max |.|, final, or drift (its
//                least-squares slope in time, 1/s); with `every` T, at the first step past each
//                from + k T (k = 1, 2, ... up to t_end, to half a step): count, first, final, or
//                drift (the slope against k, per T).
//   momentum     max over the samples of |P - P0 - sum_k (1^T F_ext(t_k) dt_k + 1^T L^T Lambda_k)|
//                / max |P| (P = 1^T M v, the momentum of a 1D problem): 0 for a scheme that
//                balances momentum exactly when the internal forces sum to zero.
//                With `component` (px, py, pz, jx, jy, jz) the identity of a 3D mesh problem
//                instead (MeshMomentum, studies/measures.hpp: every impulse counted, angular
//                per step), max over the steps, relative to its scale there.
//   penetration  max over the steps of max(0, -g).
//   chatter      RMS of the period-2 component (o_{k+1} - 2 o_k + o_{k-1}) / (4 scale) of an
//                observable over consecutive steps (those `inside` a phase, or every step);
//   zero-steps   how many of those steps have o = 0 (studies/measures.hpp, Chatter): the contact
//                force inside the exact contact, its chatter and the steps it was lost.
//   contact-duration  t_last - t_first + dt over the steps with a contact impulse (dt the nominal
//                step; ContactPhases::span), with exact = true its difference from the problem's
//                exact contact duration (ExactValue::contact_duration, the Signorini bar's 2L/c).
// An error with semi_discrete = true: |u_dof - u_dof,semi| against the same semi-discrete problem
// solved exactly (modal-exact, advanced to each sample), the time error alone; an error with
// per_nominal_step = true is sampled at most once per nominal step dt.
// An error, energy or momentum measure with a `window` [t0, t1] is sampled there only (its l2
// norm the mean over t1 - t0), e.g. a smooth window before the first impact.
//   hausdorff    H(run, ref) between the graphs {(t, o)} of an observable (the run's samples;
//                the exact solution with its jumps as vertical segments, or the reference run's
//                samples), in scaled coordinates (t / time_scale, o / value_scale), by default
//                time_scale = t_end and value_scale = the reference's largest |o|
//                (studies/hausdorff.hpp); norm "to reference" / "from reference": one directed
//                distance, "max error": max over the run's samples of |o - o_ref(t)| / value_scale,
//                "value scale": that scale (GraphErrors).
//   stop-time    |t_stop - t_stop exact| of a sliding mass, onset-time the same for a rolling
//   onset-time   disk's rolling onset: the slip's stop as the friction study measures it
//                (studies/slip_stop.hpp, one code for both) [s].
// A measure naming `problems` is measured on those only (n/a on the others). The ranking and
// the work-precision figures use the measure study.rank_by names (default: the first error).
// Status: ok, diverged, over budget, n/a (declined), or energy blow-up: at some step the
// scheme's energy rose above E0 by more than study.energy_blow_up (default 2) E scale (|E0|, or the problem's
// energy_scale() when E0 = 0) plus the work W the surroundings can have done on the system by
// then:
//     max_k (E_k - E0 - W_k) / E scale > energy_blow_up,
//     W_k = sum_{j<=k} ( sum_i |w_i| |Lambda_T,i,j|  +  max(0, F_ext(t_j) . (U_{j+1} - U_j)) ),
// the first term the work a moving obstacle (tangential velocity w, a belt) can do through
// friction, the second that of a time-dependent load (only then: a constant load's work is in
// the potential, part of E). Energy lost is never a blow-up: friction, inelastic impacts and
// numerical damping only lower E (a mass sliding down a slope against friction goes from
// E0 = 2 J to -5 J). The row keeps its values; the ranking leaves it out and says so. Status
// penetration: max(0, -g) over the steps above study.max_penetration (the same). A per-problem override of an integrator's parameters shows in its rows' integrator cell,
// "label [key=value]".
#include "studies/study_file/run_recorders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "integrators/registry.hpp"
#include "problems/exact_solution.hpp"
#include "problems/registry.hpp"
#include "studies/slip_stop.hpp"
#include "studies/study_file/engine.hpp"

namespace nsb::study_files {

namespace {

// The run of one case, measure by measure: set up before its first step (the constructor),
// fed after every step (step) and read at its end (result).
class CaseRun {
 public:
  // After the integrator's init; dt the run's nominal step.
  CaseRun(const StudySpec& spec, const FileProblem& fp, const FileIntegrator& fi, const Problem& problem, const Integrator& integrator,
          double t_end, double dt);
  void step(const Integrator& it, const StepInfo& info);
  // Its status, figures and series and, when its outcome lets them be measured, its measures'
  // values ("values": none when they were not).
  Json result(const RunResult& r);
  // The energy history of a history measure (none: empty).
  Json history() const;

 private:
  void start_measures();
  bool at_rest(const FileMeasure& fm, const Integrator& it, double dt, const Energy& energy);
  bool inside_phase(const std::string& name, double t, double dt);
  // An energy measure's error of E: relative to E_1 (relative_to = "first step") or E0 (its scale).
  double energy_error(const FileMeasure& fm, double e) const { return fm.from_first_step ? (e - e1_) / std::abs(e1_) : (e - e0_) / e_scale_; }
  void record_events(const Integrator& it, double dt, const Energy& energy);
  void sample(const Integrator& it, const Energy& energy, double dt, bool sampled, bool each_step);
  void sample_measure(std::size_t m, const Integrator& it, const Energy& energy, double dt);
  double observed_error(const FileMeasure& fm, Accumulator& a, const Integrator& it, const Energy& energy, double step_dt);
  bool set_outcome(const RunResult& r, Json& out) const;
  Json values(const RunResult& r);
  double value(std::size_t m, const RunResult& r);
  double error_value(std::size_t m) const;
  double impact_time_value(const FileMeasure& fm, const Accumulator& a) const;
  double energy_value(const FileMeasure& fm, const Accumulator& a) const;
  void start_graph(const std::string& observable, Polyline& graph);
  double hausdorff_value(const FileMeasure& fm, const Accumulator& a);
  void write_flights(Json& out) const;

  const StudySpec& spec_;
  const FileProblem& fp_;
  const Problem& problem_;
  const Integrator& integrator_;
  double t_end_, dt_;
  const SpMat M_;
  Reference reference_;
  std::string semi_note_;  // why its semi-discrete errors are n/a
  const std::unique_ptr<ModalExact> semi_;
  ObservableBuffer obs_, obs_ref_;
  std::vector<Accumulator> acc_;
  std::vector<std::pair<double, double>> windows_;  // each measure's window on this problem
  std::vector<bool> on_;                            // measured on this problem
  // Measured at every step (every_step(): it compares strings, asked once per run, not at every
  // step of every measure); the others every sample_every steps and at the last step.
  std::vector<bool> every_step_;
  bool stops_ = false;  // a stop-time or onset-time measure is measured
  bool own_v_;          // an error of "v" is of the problem's own observable v, not the velocities
  MomentumBalance momentum_;
  const Energy energy0_;
  const double e0_, e_scale_;
  double e1_ = kNaN;  // the energy after the first step
  double t_prev_ = 0.0;
  long steps_ = 0;
  EnergyGrowth growth_;
  std::optional<SlipStop> stop_;
  IntervalMax history_;
  bool keeps_history_;
  RunFigures figures_;
  RunSeries series_;
  RunImpulsesAndFields impulses_and_fields_;
};

bool has_observable(const Problem& problem, const std::string& name) {
  const auto& names = problem.observable_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

bool history_measured(const StudySpec& spec) {
  return std::any_of(spec.measures.begin(), spec.measures.end(), [](const FileMeasure& m) { return m.kind == MeasureKind::Energy && m.history; });
}

CaseRun::CaseRun(const StudySpec& spec, const FileProblem& fp, const FileIntegrator& fi, const Problem& problem, const Integrator& integrator,
                 double t_end, double dt)
    : spec_(spec), fp_(fp), problem_(problem), integrator_(integrator), t_end_(t_end), dt_(dt), M_(problem.mass_matrix()),
      reference_(spec, problem, M_, fp), semi_(semi_discrete_reference(spec, fp, fi.name, problem, semi_note_)),
      obs_(problem.observable_names().size()), obs_ref_(problem.observable_names().size()), acc_(spec.measures.size()), own_v_(has_observable(problem, "v")),
      // P0 and the speed scale from the problem's initial velocity, not the scheme's state after
      // init (modal-exact's passes through its modal basis: round-off in P0).
      momentum_(problem, problem.initial_state().v), energy0_(integrator.energy()), e0_(energy0_.total()),
      e_scale_(fp.energy_scale > 0.0 ? fp.energy_scale : energy_error_scale(problem, e0_)), growth_(problem, integrator.state(), e0_),
      history_(t_end, kHistoryIntervals, 1), keeps_history_(history_measured(spec)), figures_(problem, spec, fp, t_end, e0_, e_scale_),
      series_(spec, fp, t_end, problem, M_, integrator, obs_, energy0_), impulses_and_fields_(spec, fp, fi, problem, integrator, dt) {
  start_measures();
}

// Each measure's own start: its window, whether it is measured here, and the running figures
// that begin with the initial state.
void CaseRun::start_measures() {
  for (std::size_t m = 0; m < spec_.measures.size(); ++m) {
    const FileMeasure& fm = spec_.measures[m];
    Accumulator& a = acc_[m];
    windows_.push_back(fm.window_for(fp_.label));
    a.t_prev = windows_[m].first;
    on_.push_back(fm.applies_to(fp_.label));
    every_step_.push_back(fm.every_step());
    if (!on_[m]) continue;
    stops_ = stops_ || fm.kind == MeasureKind::StopTime || fm.kind == MeasureKind::OnsetTime;
    if (!fm.component.empty()) a.mesh_momentum.emplace(problem_, problem_.initial_state(), fm.component);
    if (fm.kind == MeasureKind::Hausdorff) start_graph(fm.observable_for(fp_.label), a.graph);
    if (fm.kind >= MeasureKind::ImpactRatio) a.events.emplace(fm, problem_, event_observable(problem_, M_, integrator_, 0.0, fm, obs_, energy0_));
    if (fm.kind == MeasureKind::FlightEnergy) {
      std::vector<double> impacts = problem_.exact()->impact_times(t_end_);
      const std::size_t flights = compared_impacts(impacts, fm.count, fm.min_flight_steps * dt_);
      a.flights = FlightEnergies(std::move(impacts), problem_.exact()->energies_after_impacts(t_end_), flights,
                                 fm.at_mid_flight_step ? FlightEnergies::At::mid_flight_step : FlightEnergies::At::exact_mid_flight);
    }
    if (fm.kind == MeasureKind::RestStart) a.rest = FinalRest(fm.min_rest);
  }
  if (stops_) stop_.emplace(problem_, integrator_.state());
}

// Whether the state after a step is at rest by the bounds of a rest-start measure (each checked
// only while the others before it hold).
bool CaseRun::at_rest(const FileMeasure& fm, const Integrator& it, double dt, const Energy& energy) {
  return std::all_of(fm.rest.begin(), fm.rest.end(), [&](const FileMeasure::RestBound& b) {
    const double o = state_observable(problem_, M_, it.state(), it.impulses(), dt, b.observable, obs_, &energy);
    return (b.abs ? std::abs(o) : o) <= rest_bound(b.at_most, b.dt_power, dt_);
  });
}

// Whether the problem's exact observable `name` is > 0 at t - dt, t and t + dt (FileMeasure::inside).
bool CaseRun::inside_phase(const std::string& name, double t, double dt) {
  const double times[] = {t - dt, t, t + dt};
  return std::all_of(std::begin(times), std::end(times), [&](double at) {
    const std::optional<double> exact = exact_observable(problem_, M_, at, name, obs_ref_);
    return exact && *exact > 0.0;
  });
}

void CaseRun::step(const Integrator& it, const StepInfo& info) {
  const State& s = it.state();
  const Energy energy = it.energy();  // once per step: every figure below reads it
  reference_.advance(info.dt);
  momentum_.add(it, info.dt);
  if (steps_ == 0) e1_ = energy.total();
  record_events(it, info.dt, energy);
  growth_.add(it, info.dt, energy.total());
  if (stop_) stop_->add(s);
  if (keeps_history_) history_.add(s.t, {std::abs(energy.total() - e0_) / e_scale_});
  figures_.add(it, info.dt, momentum_, energy.total());
  series_.add(problem_, M_, it, info.dt, obs_, energy);
  impulses_and_fields_.add(problem_, it);
  sample(it, energy, info.dt, ++steps_ % spec_.sample_every == 0, true);
  t_prev_ = s.t;
}

// The running figures of the measures of events after a step: impacts, an observable's events,
// flights, rests, a mesh's momentum, an energy's periodic samples.
void CaseRun::record_events(const Integrator& it, double dt, const Energy& energy) {
  const State& s = it.state();
  const bool contact = it.impulses().sum() > 0.0;
  for (std::size_t m = 0; m < spec_.measures.size(); ++m) {
    const FileMeasure& fm = spec_.measures[m];
    Accumulator& a = acc_[m];
    if (on_[m] && (fm.kind == MeasureKind::ImpactTime || fm.kind == MeasureKind::ContactDuration))
      a.impacts.add(s.t, contact);
    else if (a.events) a.events->add(s.t, it.impulses(), s.u, event_observable(problem_, M_, it, dt, fm, obs_, energy));
    if (on_[m] && fm.kind == MeasureKind::FlightEnergy) a.flights.add(s.t, contact, energy.total());
    if (on_[m] && fm.kind == MeasureKind::RestStart) a.rest.add(s.t, at_rest(fm, it, dt, energy));
    if (a.mesh_momentum) a.mesh_momentum->add(it, dt);
    if (on_[m] && fm.kind == MeasureKind::Energy && fm.every > 0.0) sample_periodic(fm, a, s.t, dt_, t_end_, energy_error(fm, energy.total()));
  }
}

// The measures at a step of length dt: every_step() measures at each step (each_step), the
// others every sample_every steps and at the last step (sampled; `energy`: the state's).
void CaseRun::sample(const Integrator& it, const Energy& energy, double dt, bool sampled, bool each_step) {
  const double t = it.state().t;
  for (std::size_t m = 0; m < spec_.measures.size(); ++m) {
    const FileMeasure& fm = spec_.measures[m];
    if (every_step_[m] ? !each_step : !sampled) continue;
    const bool inside = t >= windows_[m].first && t <= windows_[m].second;
    if (!on_[m] || !(inside || fm.scale_over_run)) continue;  // an error relative to the run: its scale
    if (!fm.inside.empty() && !(inside && inside_phase(fm.inside, t, dt))) continue;
    Accumulator& a = acc_[m];
    if (fm.per_nominal_step) {
      if (t < a.next_sample) continue;
      a.next_sample = t + (1.0 - 1e-9) * dt_;
    }
    sample_measure(m, it, energy, dt);
  }
}

// One measure's sample at the step: its error e added to its norms (inside its window), or its
// observable to its own figures.
void CaseRun::sample_measure(std::size_t m, const Integrator& it, const Energy& energy, double dt) {
  const FileMeasure& fm = spec_.measures[m];
  Accumulator& a = acc_[m];
  const State& s = it.state();
  const bool inside = s.t >= windows_[m].first && s.t <= windows_[m].second;
  const double step_dt = every_step_[m] ? dt : s.t - t_prev_;  // the impulses' step (impulse / dt observables)
  double e = kNaN;
  if (fm.semi_discrete) {
    if (!semi_) return;  // n/a
    semi_->advance_to(s.t);
    e = std::abs(s.u[fm.dof] - semi_->displacement(fm.dof));
    if (fm.scale > 0.0) e /= fm.scale;
  } else if (fm.kind == MeasureKind::Error) {
    e = observed_error(fm, a, it, energy, step_dt);
  } else if (fm.kind == MeasureKind::Chatter || fm.kind == MeasureKind::ZeroSteps) {
    const double value = state_observable(problem_, M_, s, it.impulses(), step_dt, fm.observable, obs_, &energy);
    if (inside) a.chatter.add(fm.scale > 0.0 ? value / fm.scale : value);
    return;
  } else if (fm.kind == MeasureKind::Estimate) {
    if (inside) a.samples.push_back(state_observable(problem_, M_, s, it.impulses(), step_dt, fm.observable, obs_, &energy));
    return;
  } else if (fm.kind == MeasureKind::Hausdorff) {
    a.graph.add(s.t, state_observable(problem_, M_, s, it.impulses(), s.t - t_prev_, fm.observable_for(fp_.label), obs_, &energy));
  } else if (fm.kind == MeasureKind::Energy) {
    e = energy_error(fm, energy.total());
    a.drift.add(s.t, e);
    e = fm.norm == "final" ? e : std::abs(e);
  } else if (fm.kind == MeasureKind::Momentum && fm.component.empty()) {
    e = momentum_.residual(s.v);
    a.scale = fm.initial_speeds_scale ? momentum_.speed_scale()
                                      : std::max({a.scale, std::abs(momentum_.momentum(s.v)), std::abs(momentum_.initial())});
  }
  if (!inside) return;
  a.largest = std::max(a.largest, std::abs(e));
  a.square += e * e * (s.t - a.t_prev);
  a.t_prev = s.t;
  a.last = e;
  a.timed_square += dt * e * e;
  a.step_square += e * e;
  ++a.steps;
}

// An error measure's error at the step: of u or v against the reference's, or of an observable
// against the reference's or the problem's own `against` observable; its scale the largest
// reference value seen.
double CaseRun::observed_error(const FileMeasure& fm, Accumulator& a, const Integrator& it, const Energy& energy, double step_dt) {
  const State& s = it.state();
  double e = kNaN;
  if (fm.observable == "u" || (fm.observable == "v" && !own_v_)) {
    const bool u = fm.observable == "u";
    const Vec ref = u ? reference_.u(s.t) : reference_.v(s.t);
    e = ((u ? s.u : s.v) - ref).lpNorm<Eigen::Infinity>();
    a.scale = std::max(a.scale, ref.lpNorm<Eigen::Infinity>());
  } else {
    const double value = state_observable(problem_, M_, s, it.impulses(), step_dt, fm.observable, obs_, &energy);
    const double ref = fm.against.empty() ? reference_.observable(s.t, fm.observable, obs_ref_)
                                          : state_observable(problem_, M_, s, it.impulses(), step_dt, fm.against, obs_, &energy);
    e = std::abs(value - ref);
    a.scale = std::max(a.scale, std::abs(ref));
  }
  return fm.scale > 0.0 ? e / fm.scale : e;
}

Json CaseRun::result(const RunResult& r) {
  Json out = {{"status", status_name(r.status)}, {"message", r.message}, {"steps", r.steps},
              {"force_evaluations", r.work.force_evaluations}, {"factorizations", r.work.factorizations},
              {"lcp_iterations", r.work.lcp_iterations}, {"solver_steps", r.work.steps},
              {"tangent_evaluations", r.work.tangent_evaluations}};
  out.update(figures_.result(r, growth_.largest() / e_scale_));
  if (r.message.empty() && !semi_note_.empty()) out["run"]["note"] = semi_note_;  // why its semi-discrete errors are n/a
  std::vector<const std::vector<double>*> periodic;
  for (std::size_t m = 0; m < acc_.size(); ++m) periodic.push_back(on_[m] && spec_.measures[m].every > 0.0 ? &acc_[m].periodic : nullptr);
  series_.write(periodic, out["run"]);
  impulses_and_fields_.write(out["run"]);
  if (spec_.cpu_repeats == 0) out["cpu"] = r.step_cpu_seconds;  // the observed run's, whatever its end
  if (!set_outcome(r, out)) return out;
  if (steps_ % spec_.sample_every != 0) sample(integrator_, integrator_.energy(), 0.0, true, false);
  history_.finish();
  out["values"] = values(r);  // an estimate's: NaN until the tables compare it with the next run (with_next_run_estimates)
  write_flights(out);
  for (std::size_t m = 0; m < spec_.measures.size(); ++m)
    if (spec_.measures[m].kind == MeasureKind::Estimate) out["samples"][std::to_string(m)] = reals(acc_[m].samples);
  return out;
}

// The outcome thresholds (a blow-up or penetration seen before the budget ran out is reported as
// such); whether the run's measures are taken: an ok run's, and an over-budget run's with
// study.measure_over_budget.
bool CaseRun::set_outcome(const RunResult& r, Json& out) const {
  if (r.status != RunStatus::Ok && r.status != RunStatus::OverBudget) return false;
  if (const double g = growth_.largest() / e_scale_; g > spec_.energy_blow_up_of(fp_)) {
    out["status"] = kEnergyBlowUpStatus;
    out["message"] = fmt::format("max (E - E0 - W) / E scale = {:.3g} > {}", g, spec_.energy_blow_up_of(fp_));
  } else if (r.max_penetration > spec_.max_penetration_of(fp_)) {
    out["status"] = kPenetrationStatus;
    out["message"] = fmt::format("max penetration {:.3g} > {}", r.max_penetration, spec_.max_penetration_of(fp_));
  }
  return r.status == RunStatus::Ok || (r.status == RunStatus::OverBudget && spec_.measure_over_budget);
}

Json CaseRun::values(const RunResult& r) {
  Json values = Json::array();
  for (std::size_t m = 0; m < spec_.measures.size(); ++m)
    values.push_back(real(!on_[m] || (spec_.measures[m].semi_discrete && !semi_) ? kNaN : value(m, r)));
  return values;
}

// A measure's value at the run's end.
double CaseRun::value(std::size_t m, const RunResult& r) {
  const FileMeasure& fm = spec_.measures[m];
  const Accumulator& a = acc_[m];
  switch (fm.kind) {
    case MeasureKind::Error: return error_value(m);
    case MeasureKind::ImpactTime: return impact_time_value(fm, a);
    case MeasureKind::Energy: return energy_value(fm, a);
    case MeasureKind::FlightEnergy: return fm.norm == "count" ? static_cast<double>(a.flights.compared()) : a.flights.largest();
    case MeasureKind::RestStart: return fm.exact ? std::abs(a.rest.start() - summary_value(problem_, fm.summary)) : a.rest.start();
    case MeasureKind::Momentum: {
      const double scale = fm.scale > 0.0 || !(a.scale > 0.0) ? 1.0 : a.scale;
      return a.mesh_momentum ? a.mesh_momentum->largest() / a.mesh_momentum->scale() : a.largest / scale;
    }
    case MeasureKind::Penetration: return r.max_penetration;
    case MeasureKind::Estimate: return kNaN;  // compared with the next run by the tables
    case MeasureKind::Chatter: return a.chatter.rms();
    case MeasureKind::ZeroSteps: return static_cast<double>(a.chatter.zeros());
    case MeasureKind::ContactDuration: {
      const double span = a.impacts.span(dt_);
      return fm.exact ? std::abs(span - problem_.exact()->value(ExactValue::contact_duration).value()) : span;
    }
    case MeasureKind::StopTime:
    case MeasureKind::OnsetTime: {
      const ExactStop exact = exact_stop(problem_);
      return std::abs(stop_->time(exact.stays) - exact.stop_time);
    }
    case MeasureKind::Hausdorff: return hausdorff_value(fm, a);
    default: return a.events->result(problem_);
  }
}

// An error measure's norm over its samples, relative to its scale (a fixed scale: divided at each step).
double CaseRun::error_value(std::size_t m) const {
  const FileMeasure& fm = spec_.measures[m];
  const Accumulator& a = acc_[m];
  const double scale = fm.scale > 0.0 || !(a.scale > 0.0) ? 1.0 : a.scale;
  return (fm.norm == "final"        ? a.last
          : fm.norm == "max"        ? a.largest
          : fm.norm == "rms"        ? std::sqrt(a.timed_square / (a.t_prev - windows_[m].first))
          : fm.norm == "step rms"   ? std::sqrt(a.step_square / static_cast<double>(a.steps))
          : fm.norm == "l2 in time" ? std::sqrt(a.timed_square)
                                    : std::sqrt(a.square / (std::min(t_end_, windows_[m].second) - windows_[m].first))) / scale;
}

double CaseRun::impact_time_value(const FileMeasure& fm, const Accumulator& a) const {
  if (fm.located) return located_impact_error(integrator_, problem_, t_end_, fm.count);
  const auto exact = problem_.exact() ? problem_.exact()->impact_times(t_end_) : std::vector<double>{};
  const std::size_t n = compared_impacts(exact, fm.count, fm.min_flight_steps * dt_);
  const std::vector<double>& impacts = a.impacts.starts();
  if (fm.norm == "count") return static_cast<double>(std::min(n, impacts.size()));
  double v = impacts.size() < n ? kNaN : 0.0;  // an impact missed: no error to report
  for (std::size_t i = 0; i < n && i < impacts.size(); ++i) v = std::max(v, std::abs(impacts[i] - exact[i]));
  return v;
}

double CaseRun::energy_value(const FileMeasure& fm, const Accumulator& a) const {
  if (fm.every > 0.0) return periodic_value(fm.norm, a.periodic);
  return fm.norm == "max"         ? a.largest
         : fm.norm == "final"     ? a.last
         : fm.norm == "final abs" ? std::abs(a.last)
         : fm.norm == "offset"    ? (e1_ - e0_) / e_scale_
                                  : a.drift.slope();
}

// A graph starts where the run started, the problem's initial state: a scheme that resolves an
// impact at t0 inside init() (modal-exact on a bar touching at t = 0) then has that jump as a
// vertical segment at t0, as the exact graph has, instead of a graph that begins after it.
void CaseRun::start_graph(const std::string& observable, Polyline& graph) {
  const Vec no_impulses = Vec::Zero(problem_.ncontacts());
  const State& s = integrator_.state();
  const State initial = problem_.initial_state();
  const double before = state_observable(problem_, M_, initial, no_impulses, 0.0, observable, obs_, &energy0_);
  const double after = state_observable(problem_, M_, s, no_impulses, 0.0, observable, obs_, &energy0_);
  if (initial.t == s.t && before != after) graph.add(initial.t, before);
  graph.add(s.t, after);
}

double CaseRun::hausdorff_value(const FileMeasure& fm, const Accumulator& a) {
  const std::string& observable = fm.observable_for(fp_.label);
  const Polyline ref = reference_.graph(observable, t_end_, obs_ref_);
  const GraphErrors e = graph_errors(a.graph, ref, [&](double t) { return reference_.observable(t, observable, obs_ref_); },
                                     fm.time_scale > 0.0 ? fm.time_scale : t_end_, fm.value_scale);
  return fm.norm == "to reference"     ? e.to_reference
         : fm.norm == "from reference" ? e.from_reference
         : fm.norm == "max error"      ? e.max_error
         : fm.norm == "value scale"    ? e.value_scale
                                       : e.hausdorff;
}

// A flights table's flights: E_i / E0, exact E_i / E0, E_i / E_i exact - 1.
void CaseRun::write_flights(Json& out) const {
  for (const FileTable& d : spec_.tables)
    for (std::size_t m = 0; m < spec_.measures.size(); ++m)
      if (d.rows == "flights" && on_[m] && spec_.measures[m].label == d.measure) {
        const FlightEnergies& f = acc_[m].flights;
        std::vector<double> ratio, exact;
        for (std::size_t i = 0; i < f.compared(); ++i) {
          ratio.push_back(f.energies()[i] / e0_);
          exact.push_back(f.exact()[i] / e0_);
        }
        out["run"]["flights"][d.measure] = {{"ratio", reals(ratio)}, {"exact", reals(exact)}, {"error", reals(f.errors())}};
      }
}

Json CaseRun::history() const {
  if (!keeps_history_) return nullptr;
  return {{"t", reals(history_.times())}, {"e", reals(history_.largest(0))}};
}

}  // namespace

Json run_file_case(const StudySpec& spec, const Json& c) {
  const FileProblem& fp = spec.problems[c["problem"].get<std::size_t>()];
  const FileIntegrator& fi = spec.integrators[c["integrator"].get<std::size_t>()];
  auto problem = make_problem(fp.name, fp.parameters);
  const Overrides params = file_case_parameters(spec, c);
  RunOptions options;
  options.dt = c["dt"];
  const double t_end = case_t_end(spec, fp, c);
  options.t_end = t_end;
  options.record_series = false;
  options.max_force_evaluations = spec.budget_of(fp, options.dt, t_end);
  options.sample_every = spec.check_every;  // the driver checks the state for NaN at its samples
  if (const FileReference* ref = spec.reference_of(fp); ref && ref->lockstep && fi.name == ref->integrator)  // its error is 0 by construction
    return not_run("the reference of this problem");
  auto integrator = make_integrator(fi.name, params);
  if (const auto declined = init_or_decline(*integrator, *problem)) return not_run(*declined);
  CaseRun measured(spec, fp, fi, *problem, *integrator, t_end, options.dt);
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo& info) { measured.step(it, info); });
  Json out = measured.result(r);
  if (!out.contains("values")) return out;  // its measures not taken: nor its CPU time
  if (spec.cpu_repeats > 0) {
    const CpuCost cpu = cpu_cost(*problem, fi.name, params, options, spec.cpu_repeats);
    out["cpu"] = cpu.median;
    out["cpu_spread"] = real(cpu.spread);
  }
  if (Json history = measured.history(); !history.is_null()) out["history"] = history;
  return out;
}

}  // namespace nsb::study_files

namespace nsb {

namespace {

// The parts every run's result holds (CaseRun::result, not_run): the work counters as whole
// numbers >= 0, `run` a table with t_reached and max_penetration, and but for a declined run
// the study's counters, one number (or null) each; an error or a Hausdorff distance >= 0.
std::string run_damage(const StudySpec& spec, const Json& r) {
  for (const char* key : {"status", "message", "steps", "force_evaluations", "factorizations", "lcp_iterations", "run"})
    if (!r.contains(key)) return fmt::format("no key '{}'", key);
  for (const char* key : {"factorizations", "lcp_iterations"})
    if (!(r[key].is_number_integer() && r[key].get<long>() >= 0)) return fmt::format("{} {} is not a whole number >= 0", key, r[key].dump());
  const Json& run = r["run"];
  if (!run.is_object() || !run.contains("t_reached") || !run["t_reached"].is_number() || !run.contains("max_penetration"))
    return "run is not a table with t_reached and max_penetration";
  if (r["status"] != kDeclinedStatus &&
      !(run.contains("counters") && run["counters"].is_array() && run["counters"].size() == spec.counters.size()))
    return fmt::format("run.counters is not an array of the study's {} counters", spec.counters.size());
  if (!r.contains("values") || !r["values"].is_array() || r["values"].size() != spec.measures.size()) return {};
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    const Json& v = r["values"][m];
    const MeasureKind kind = spec.measures[m].kind;
    if ((kind == MeasureKind::Error || kind == MeasureKind::Hausdorff) && v.is_number() && !(v.get<double>() >= 0.0))
      return fmt::format("values[{}] ({}) is {}, not >= 0", m, spec.measures[m].label, v.dump());
  }
  return {};
}

}  // namespace

std::string file_result_damage(const StudySpec& spec, const Json& r) {
  const auto reals_or_null = [](const Json& a) {
    return a.is_array() && std::all_of(a.begin(), a.end(), [](const Json& x) { return x.is_number() || x.is_null(); });
  };
  if (const std::string damage = run_damage(spec, r); !damage.empty()) return damage;
  if (r.contains("values") && !(reals_or_null(r["values"]) && r["values"].size() == spec.measures.size()))
    return fmt::format("values is not an array of {} numbers (or null)", spec.measures.size());
  for (const char* key : {"cpu", "cpu_spread"})
    if (r.contains(key) && !(r[key].is_number() || r[key].is_null())) return fmt::format("{} is not a number", key);
  if (r.contains("samples")) {  // an estimate's samples: an array of numbers per estimate measure, by its index
    const Json& samples = r["samples"];
    if (!samples.is_object()) return "samples is not a table";
    for (std::size_t m = 0; m < spec.measures.size(); ++m)
      if (spec.measures[m].kind == MeasureKind::Estimate &&
          !(samples.contains(std::to_string(m)) && samples[std::to_string(m)].is_array() &&
            std::all_of(samples[std::to_string(m)].begin(), samples[std::to_string(m)].end(), [](const Json& x) { return x.is_number(); })))
        return fmt::format("samples has no array of numbers for measure {}", m);
  }
  if (r.contains("history")) {
    const Json& h = r["history"];
    if (!h.is_object() || !h.contains("t") || !h.contains("e") || !reals_or_null(h["t"]) || !reals_or_null(h["e"]) ||
        h["t"].size() != h["e"].size())
      return "history is not two arrays t and e of numbers of the same length";
  }
  return {};
}

}  // namespace nsb
