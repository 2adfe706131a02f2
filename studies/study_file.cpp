// A study file as a StudyEntry: its cases, the runner of one case and its tables.
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
#include "studies/study_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "core/output.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "reference/cache.hpp"
#include "reference/modal_exact.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"
#include "studies/parallel.hpp"
#include "studies/ranking.hpp"
#include "studies/report_index.hpp"
#include "studies/slip_stop.hpp"

namespace nsb {

namespace {

constexpr int kHistoryIntervals = 200;

// The integrator's label, marked " (python)" for a class written in Python, with the parameters
// a problem's override changed.
std::string shown_label(const FileIntegrator& fi, const std::string& problem_label) {
  std::vector<std::string> changed;
  for (const auto& [key, value] : fi.sweep_for(problem_label).parameters)
    if (const auto it = fi.sweep.parameters.find(key); it == fi.sweep.parameters.end() || it->second != value)
      changed.push_back(key + "=" + value);
  const std::string label = fi.label + integrator_mark(fi.name);
  return changed.empty() ? label : fmt::format("{} [{}]", label, fmt::join(changed, ", "));
}

ReferenceRequest reference_request(const StudySpec& spec, const FileProblem& p) {
  const FileReference& r = *spec.reference_of(p);
  return {p.name, p.parameters, r.integrator, r.parameters, r.dt, r.t_end > 0.0 ? r.t_end : spec.t_end_of(p), r.sample_every};
}

// The end time of a case: its problem's, or its full_t_end under --full.
double case_t_end(const StudySpec& spec, const FileProblem& p, const Json& c) {
  return c.contains("t_end") ? c["t_end"].get<double>() : spec.t_end_of(p);
}

// What a Hausdorff measure's graphs are of: its observable, or each problem's ("v_contact (signorini-bar), ...").
std::string graph_observables(const FileMeasure& m) {
  if (m.problem_observables.empty()) return m.observable;
  std::vector<std::string> each;
  for (const auto& [label, name] : m.problem_observables) each.push_back(fmt::format("{} ({})", name, label));
  return fmt::format("{}", fmt::join(each, ", "));
}

// Whether an [[exclude]] rule removes the run of integrator `entry` on problem `p` at
// `stable_steps` (NaN: a run not set as a fraction of the stable step).
bool excluded(const FileExclusion& x, const IntegratorEntry& entry, const FileProblem& p, double stable_steps, bool full) {
  if ((x.default_only && full) || (x.full_only && !full)) return false;
  const std::string kind = entry.reference ? "references" : entry.peer ? "peers" : "schemes";
  if (x.integrators != kind) return false;
  if (!x.above.empty()) {
    const Params params(find_problem(p.name).parameters(), p.parameters);
    for (const auto& [name, value] : x.above)
      if (!params.values().count(name) || !(params.real(name) > value)) return false;
  }
  return x.stable_steps_except.empty() ||
         std::find(x.stable_steps_except.begin(), x.stable_steps_except.end(), stable_steps) == x.stable_steps_except.end();
}

// The runs of integrator i on problem p: its sweep's steps (or tolerances), then its stable-step
// fractions, less those an [[exclude]] rule removes.
void add_cases(const StudySpec& spec, std::size_t p, std::size_t i, bool full, std::vector<Json>& cases) {
  const FileProblem& problem = spec.problems[p];
  const IntegratorEntry& entry = find_integrator(spec.integrators[i].name);
  const auto kept = [&](double stable_steps) {
    return std::none_of(spec.exclusions.begin(), spec.exclusions.end(),
                        [&](const FileExclusion& x) { return excluded(x, entry, problem, stable_steps, full); });
  };
  const double t_end = spec.t_end_of(problem, full);
  const auto push = [&](Json c) {
    c["file_hash"] = spec.hash;
    if (t_end != spec.t_end_of(problem)) c["t_end"] = t_end;  // full_t_end
    cases.push_back(std::move(c));
  };
  const FileSweep& s = spec.integrators[i].sweep_for(problem.label);
  const bool tol = !s.tolerances.empty();
  for (double x : tol ? s.tolerances : full && !s.full_steps.empty() ? s.full_steps : s.steps)
    if (kept(kNaN)) push({{"problem", p}, {"integrator", i}, {"dt", tol ? s.dt : x}, {"tol", tol ? Json(x) : Json(nullptr)}});
  if (s.stable_fractions.empty()) return;
  const double stable = make_problem(problem.name, problem.parameters)->stable_step();
  for (double f : s.stable_fractions)
    if (kept(f)) push({{"problem", p}, {"integrator", i}, {"dt", f * stable}, {"tol", nullptr}, {"stable_steps", f}});
}

std::vector<Json> file_cases(const StudySpec& spec, bool full) {
  std::vector<Json> cases;
  const std::size_t np = spec.problems.size(), ni = spec.integrators.size();
  if (spec.sweep_major) {
    // Each family (consecutive problems of one joint refinement, or one problem) over the integrators.
    for (std::size_t first = 0, last = 0; first < np; first = last) {
      while (last < np && spec.problems[last].family_label() == spec.problems[first].family_label()) ++last;
      for (std::size_t i = 0; i < ni; ++i)
        for (std::size_t p = first; p < last; ++p)
          if (spec.runs(spec.problems[p], full)) add_cases(spec, p, i, full, cases);
    }
  } else {
    for (std::size_t outer = 0; outer < (spec.integrator_major ? ni : np); ++outer)
      for (std::size_t inner = 0; inner < (spec.integrator_major ? np : ni); ++inner) {
        const std::size_t p = spec.integrator_major ? inner : outer, i = spec.integrator_major ? outer : inner;
        if (spec.runs(spec.problems[p], full)) add_cases(spec, p, i, full, cases);
      }
  }
  return cases;
}

// Observables of a state: the problem's own or the run driver's generic kinetic, potential,
// total_energy, min_gap (series columns of run/run.hpp). `energy`: the scheme's own
// (Integrator::energy), else v^T M v / 2 + V(u).
double state_observable(const Problem& problem, const SpMat& M, const State& s, const Vec& impulses, double dt,
                        const std::string& name, std::span<double> buffer, const Energy* energy) {
  const auto& names = problem.observable_names();
  if (const auto k = std::find(names.begin(), names.end(), name); k != names.end()) {
    problem.observe(s, impulses, dt, buffer);
    return buffer[k - names.begin()];
  }
  if (name == "min_gap" && problem.contacts_move()) {  // the gaps themselves, not their linearisation at U0
    ContactGeometry moving = problem.contact_geometry();
    problem.evaluate_contacts(s.u, moving);
    return moving.gap.minCoeff();
  }
  if (name == "min_gap") return (problem.gap_offset() + problem.gap_operator() * s.u).minCoeff();
  const Energy e = energy ? *energy : Energy{0.5 * s.v.dot(M * s.v), problem.potential(s.u)};
  return name == "kinetic" ? e.kinetic : name == "potential" ? e.potential : e.total();
}

// The observable of an event measure after a step of length dt (impact-count has none: 0).
double event_observable(const Problem& problem, const SpMat& M, const Integrator& it, double dt, const FileMeasure& m,
                        std::span<double> buffer, const Energy& energy) {
  if (m.kind == MeasureKind::ImpactCount || m.kind == MeasureKind::Summary) return 0.0;
  return state_observable(problem, M, it.state(), it.impulses(), dt, m.observable, buffer, &energy);
}

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
    if (exact_) {
      const State exact = *problem_.exact()->state(t);
      return state_observable(problem_, M_, exact, Vec::Zero(problem_.ncontacts()), 0.0, name, buffer, nullptr);
    }
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

// A work counter of study.counters: Work::extra's entry of that name, or a sum "a + b" of
// entries (one a scheme does not count adds 0: the event-driven reference's events and the
// penalty reference's switches in one column); null where it counts none of them.
Json work_counter(const std::map<std::string, double>& extra, const std::string& name) {
  std::optional<double> sum;
  for (std::size_t begin = 0; begin <= name.size();) {
    const std::size_t end = std::min(name.find(" + ", begin), name.size());
    if (const auto it = extra.find(name.substr(begin, end - begin)); it != extra.end()) sum = sum.value_or(0.0) + it->second;
    begin = end + 3;
  }
  return sum ? real(*sum) : Json(nullptr);
}

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

// A run that never started: declined by the scheme (its reason), or the lockstep reference
// itself; its figures those of the initial state (no step, no energy scale).
Json not_run(const std::string& why) {
  return {{"status", "n/a"}, {"message", why}, {"steps", 0}, {"force_evaluations", 0}, {"factorizations", 0}, {"lcp_iterations", 0},
          {"run", {{"t_reached", 0.0}, {"impacts", 0}, {"switches", nullptr}, {"missed_switches", nullptr}, {"max_penetration", 0.0},
                   {"energy_growth", 0.0}, {"final_energy_error", 0.0}, {"energy_scale", 0.0}, {"note", why}}}};
}

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

// An impact-time measure with `located`: max over the first `count` impacts the integrator
// located itself (impacts and Zeno stops, each against the exact impact of its rank before
// t_end) of |t_i - t_i exact|; NaN when it locates none (a time-stepping scheme).
double located_impact_error(const Integrator& integrator, const Problem& problem, double t_end, int count) {
  const auto located = events_of_kind(integrator.events(), {ContactEventKind::Impact, ContactEventKind::ZenoStop});
  const std::vector<double> exact = problem.exact()->impact_times(t_end);
  if (located.empty()) return kNaN;
  double largest = 0.0;
  for (std::size_t i = 0; i < located.size() && i < exact.size() && i < static_cast<std::size_t>(count); ++i)
    largest = std::max(largest, std::abs(located[i].t - exact[i]));
  return largest;
}

// An energy measure with `every` after a step ending at t (nominal step dt): its error e at each
// sample time t_k = from + k every (k = 1, 2, ..., t_k <= t_end) the step reaches, to half a step
// (t >= t_k - dt/2): several when a step spans more than one.
void sample_periodic(const FileMeasure& m, Accumulator& a, double t, double dt, double t_end, double e) {
  const auto next = [&] { return m.from + static_cast<double>(a.periodic.size() + 1) * m.every; };
  while (next() <= t_end && t >= next() - 0.5 * dt) a.periodic.push_back(e);
}

// Its value: the number of samples, the first, the last (final), or the least-squares slope
// against k (drift, per `every`); NaN without the samples it needs.
double periodic_value(const std::string& norm, const std::vector<double>& e) {
  if (norm == "count") return static_cast<double>(e.size());
  if (e.empty()) return kNaN;
  if (norm == "first") return e.front();
  if (norm == "final") return e.back();
  std::vector<double> k(e.size());
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<double>(i + 1);
  return fit_line(k, e).slope;
}

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

// The semi-discrete reference of a run's semi_discrete measures (FileMeasure::semi_discrete):
// modal-exact with its defaults on the run's problem, made by the registry so that its declared
// limits hold (max_dofs: the C++ study bar built it outside the registry, which checked none);
// none on modal-exact's own runs (their error is 0 by construction), where no such measure is
// measured, or where modal-exact refuses the problem: then `note` says why, "LABEL n/a: reason"
// (its measures n/a, the run measured).
std::unique_ptr<ModalExact> semi_discrete_reference(const StudySpec& spec, const FileProblem& fp, const std::string& integrator,
                                                    const Problem& problem, std::string& note) {
  std::vector<std::string> labels;
  for (const FileMeasure& m : spec.measures)
    if (m.semi_discrete && m.applies_to(fp.label)) labels.push_back(m.label);
  if (labels.empty() || integrator == ModalExact::kName) return nullptr;
  std::unique_ptr<Integrator> made = make_integrator(ModalExact::kName);
  try {
    made->init(problem, problem.initial_state());
  } catch (const InputError& e) {
    note = fmt::format("{} n/a: {}", fmt::join(labels, ", "), e.what());
    return nullptr;
  }
  return std::unique_ptr<ModalExact>(&dynamic_cast<ModalExact&>(*made.release()));
}
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
  const SpMat M = problem->mass_matrix();
  Reference reference(spec, *problem, M, fp);
  std::string semi_note;
  const std::unique_ptr<ModalExact> semi = semi_discrete_reference(spec, fp, fi.name, *problem, semi_note);
  const std::size_t nobs = problem->observable_names().size();
  std::vector<double> obs(nobs), obs_ref(nobs);
  std::vector<Accumulator> acc(spec.measures.size());
  std::vector<std::pair<double, double>> windows;  // each measure's window on this problem
  for (std::size_t m = 0; m < acc.size(); ++m) {
    windows.push_back(spec.measures[m].window_for(fp.label));
    acc[m].t_prev = windows[m].first;
  }
  std::vector<bool> on(spec.measures.size());  // measured on this problem
  bool stops = false;                          // a stop-time or onset-time measure is
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    const FileMeasure& fm = spec.measures[m];
    on[m] = fm.applies_to(fp.label);
    stops = stops || (on[m] && (fm.kind == MeasureKind::StopTime || fm.kind == MeasureKind::OnsetTime));
  }
  // P0 and the speed scale from the problem's initial velocity, not the scheme's state after init
  // (modal-exact's passes through its modal basis: round-off in P0).
  MomentumBalance momentum(*problem, problem->initial_state().v);
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && !spec.measures[m].component.empty()) acc[m].mesh_momentum.emplace(*problem, problem->initial_state(), spec.measures[m].component);
  const Energy energy0 = integrator->energy();
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind == MeasureKind::Hausdorff) {
      const State& s = integrator->state();
      acc[m].graph.add(s.t, state_observable(*problem, M, s, Vec::Zero(problem->ncontacts()), 0.0,
                                             spec.measures[m].observable_for(fp.label), obs, &energy0));
    }
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind >= MeasureKind::ImpactRatio)
      acc[m].events.emplace(spec.measures[m], *problem,
                            event_observable(*problem, M, *integrator, 0.0, spec.measures[m], obs, energy0));
  const double e0 = energy0.total();
  const double e_scale = fp.energy_scale > 0.0 ? fp.energy_scale : energy_error_scale(*problem, e0);
  double t_prev = 0.0;
  EnergyGrowth growth(*problem, integrator->state(), e0);
  std::optional<SlipStop> stop;
  if (stops) stop.emplace(*problem, integrator->state());
  IntervalMax history(t_end, kHistoryIntervals, 1);
  const auto history_measure = std::find_if(spec.measures.begin(), spec.measures.end(), [](const FileMeasure& m) {
    return m.kind == MeasureKind::Energy && m.history;
  });
  RunFigures figures(*problem, spec, fp, t_end, e0, e_scale);
  RunSeries series(spec, fp, t_end, *problem, M, *integrator, obs, energy0);
  RunImpulsesAndFields impulses_and_fields(spec, fp, fi, *problem, *integrator, options.dt);
  double e1 = kNaN;  // the energy after the first step
  // An energy measure's error of E: relative to E_1 (relative_to = "first step") or E0 (its scale).
  const auto energy_error = [&](const FileMeasure& fm, double e) { return fm.from_first_step ? (e - e1) / std::abs(e1) : (e - e0) / e_scale; };
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind == MeasureKind::FlightEnergy) {
      const FileMeasure& fm = spec.measures[m];
      std::vector<double> impacts = problem->exact()->impact_times(t_end);
      const std::size_t flights = compared_impacts(impacts, fm.count, fm.min_flight_steps * options.dt);
      acc[m].flights = FlightEnergies(std::move(impacts), problem->exact()->energies_after_impacts(t_end), flights,
                                      fm.at_mid_flight_step ? FlightEnergies::At::mid_flight_step : FlightEnergies::At::exact_mid_flight);
    }
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind == MeasureKind::RestStart) acc[m].rest = FinalRest(spec.measures[m].min_rest);
  // Whether the state after a step is at rest by the bounds of a rest-start measure (each checked
  // only while the others before it hold).
  const auto at_rest = [&](const FileMeasure& fm, const Integrator& it, double dt, const Energy& energy) {
    return std::all_of(fm.rest.begin(), fm.rest.end(), [&](const FileMeasure::RestBound& b) {
      const double o = state_observable(*problem, M, it.state(), it.impulses(), dt, b.observable, obs, &energy);
      return (b.abs ? std::abs(o) : o) <= rest_bound(b.at_most, b.dt_power, options.dt);
    });
  };

  // An error of "v": the velocities, unless the problem has an observable of that name (its own).
  const auto& names = problem->observable_names();
  const bool own_v = std::find(names.begin(), names.end(), "v") != names.end();
  // Whether the problem's exact observable `name` is > 0 at t - dt, t and t + dt (FileMeasure::inside).
  const auto inside_phase = [&](const std::string& name, double t, double dt) {
    const double times[] = {t - dt, t, t + dt};
    return std::all_of(std::begin(times), std::end(times), [&](double at) {
      const std::optional<State> exact = problem->exact()->state(at);
      return exact && state_observable(*problem, M, *exact, Vec::Zero(problem->ncontacts()), 0.0, name, obs_ref, nullptr) > 0.0;
    });
  };
  // The measures at a step of length dt: every_step() measures at each step (each_step), the
  // others every sample_every steps and at the last step (sampled; `energy`: the state's).
  // (every_step() compares strings: asked once per run, not at every step of every measure.)
  std::vector<bool> every_step(spec.measures.size());
  for (std::size_t m = 0; m < spec.measures.size(); ++m) every_step[m] = spec.measures[m].every_step();
  const auto sample = [&](const Integrator& it, const Energy& energy, double dt, bool sampled, bool each_step) {
    const State& s = it.state();
    for (std::size_t m = 0; m < spec.measures.size(); ++m) {
      const FileMeasure& fm = spec.measures[m];
      if (every_step[m] ? !each_step : !sampled) continue;
      const bool inside = s.t >= windows[m].first && s.t <= windows[m].second;
      if (!on[m] || !(inside || fm.scale_over_run)) continue;  // an error relative to the run: its scale
      if (!fm.inside.empty() && !(inside && inside_phase(fm.inside, s.t, dt))) continue;
      Accumulator& a = acc[m];
      if (fm.per_nominal_step) {
        if (s.t < a.next_sample) continue;
        a.next_sample = s.t + (1.0 - 1e-9) * options.dt;
      }
      const double step_dt = every_step[m] ? dt : s.t - t_prev;  // the impulses' step (impulse / dt observables)
      double e = kNaN;
      if (fm.semi_discrete) {
        if (!semi) continue;  // n/a
        semi->advance_to(s.t);
        e = std::abs(s.u[fm.dof] - semi->displacement(fm.dof));
        if (fm.scale > 0.0) e /= fm.scale;
      } else if (fm.kind == MeasureKind::Error) {
        if (fm.observable == "u" || (fm.observable == "v" && !own_v)) {
          const bool u = fm.observable == "u";
          const Vec ref = u ? reference.u(s.t) : reference.v(s.t);
          e = ((u ? s.u : s.v) - ref).lpNorm<Eigen::Infinity>();
          a.scale = std::max(a.scale, ref.lpNorm<Eigen::Infinity>());
        } else {
          const double value = state_observable(*problem, M, s, it.impulses(), step_dt, fm.observable, obs, &energy);
          const double ref = fm.against.empty() ? reference.observable(s.t, fm.observable, obs_ref)
                                                : state_observable(*problem, M, s, it.impulses(), step_dt, fm.against, obs, &energy);
          e = std::abs(value - ref);
          a.scale = std::max(a.scale, std::abs(ref));
        }
        if (fm.scale > 0.0) e /= fm.scale;
      } else if (fm.kind == MeasureKind::Chatter || fm.kind == MeasureKind::ZeroSteps) {
        const double value = state_observable(*problem, M, s, it.impulses(), step_dt, fm.observable, obs, &energy);
        if (inside) a.chatter.add(fm.scale > 0.0 ? value / fm.scale : value);
        continue;
      } else if (fm.kind == MeasureKind::Estimate) {
        if (inside) a.samples.push_back(state_observable(*problem, M, s, it.impulses(), step_dt, fm.observable, obs, &energy));
        continue;
      } else if (fm.kind == MeasureKind::Hausdorff) {
        a.graph.add(s.t, state_observable(*problem, M, s, it.impulses(), s.t - t_prev, fm.observable_for(fp.label), obs, &energy));
      } else if (fm.kind == MeasureKind::Energy) {
        e = energy_error(fm, energy.total());
        a.drift.add(s.t, e);
        e = fm.norm == "final" ? e : std::abs(e);
      } else if (fm.kind == MeasureKind::Momentum && fm.component.empty()) {
        e = momentum.residual(s.v);
        a.scale = fm.initial_speeds_scale ? momentum.speed_scale()
                                          : std::max({a.scale, std::abs(momentum.momentum(s.v)), std::abs(momentum.initial())});
      }
      if (!inside) continue;
      a.largest = std::max(a.largest, std::abs(e));
      a.square += e * e * (s.t - a.t_prev);
      a.t_prev = s.t;
      a.last = e;
      a.timed_square += dt * e * e;
      a.step_square += e * e;
      ++a.steps;
    }
  };
  long step = 0;
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const State& s = it.state();
    const Energy energy = it.energy();  // once per step: every figure below reads it
    reference.advance(info.dt);
    momentum.add(it, info.dt);
    if (step == 0) e1 = energy.total();
    const bool contact = it.impulses().sum() > 0.0;
    for (std::size_t m = 0; m < spec.measures.size(); ++m) {
      if (on[m] && (spec.measures[m].kind == MeasureKind::ImpactTime || spec.measures[m].kind == MeasureKind::ContactDuration))
        acc[m].impacts.add(s.t, contact);
      else if (acc[m].events) acc[m].events->add(s.t, it.impulses(), s.u, event_observable(*problem, M, it, info.dt, spec.measures[m], obs, energy));
      if (on[m] && spec.measures[m].kind == MeasureKind::FlightEnergy) acc[m].flights.add(s.t, contact, energy.total());
      if (on[m] && spec.measures[m].kind == MeasureKind::RestStart) acc[m].rest.add(s.t, at_rest(spec.measures[m], it, info.dt, energy));
      if (acc[m].mesh_momentum) acc[m].mesh_momentum->add(it, info.dt);
      if (on[m] && spec.measures[m].kind == MeasureKind::Energy && spec.measures[m].every > 0.0)
        sample_periodic(spec.measures[m], acc[m], s.t, options.dt, t_end, energy_error(spec.measures[m], energy.total()));
    }
    growth.add(it, info.dt, energy.total());
    if (stop) stop->add(s);
    if (history_measure != spec.measures.end()) history.add(s.t, {std::abs(energy.total() - e0) / e_scale});
    figures.add(it, info.dt, momentum, energy.total());
    series.add(*problem, M, it, info.dt, obs, energy);
    impulses_and_fields.add(*problem, it);
    sample(it, energy, info.dt, ++step % spec.sample_every == 0, true);
    t_prev = s.t;
  });
  Json out = {{"status", status_name(r.status)}, {"message", r.message}, {"steps", r.steps},
              {"force_evaluations", r.work.force_evaluations}, {"factorizations", r.work.factorizations},
              {"lcp_iterations", r.work.lcp_iterations}, {"solver_steps", r.work.steps},
              {"tangent_evaluations", r.work.tangent_evaluations}};
  out.update(figures.result(r, growth.largest() / e_scale));
  if (r.message.empty() && !semi_note.empty()) out["run"]["note"] = semi_note;  // why its semi-discrete errors are n/a
  std::vector<const std::vector<double>*> periodic;
  for (std::size_t m = 0; m < acc.size(); ++m) periodic.push_back(on[m] && spec.measures[m].every > 0.0 ? &acc[m].periodic : nullptr);
  series.write(periodic, out["run"]);
  impulses_and_fields.write(out["run"]);
  if (spec.cpu_repeats == 0) out["cpu"] = r.step_cpu_seconds;  // the observed run's, whatever its end
  // A blow-up or penetration seen before the budget ran out is reported as such.
  if (r.status != RunStatus::Ok && r.status != RunStatus::OverBudget) return out;
  if (const double g = growth.largest() / e_scale; g > spec.energy_blow_up_of(fp)) {
    out["status"] = "energy blow-up";
    out["message"] = fmt::format("max (E - E0 - W) / E scale = {:.3g} > {}", g, spec.energy_blow_up_of(fp));
  } else if (r.max_penetration > spec.max_penetration_of(fp)) {
    out["status"] = "penetration";
    out["message"] = fmt::format("max penetration {:.3g} > {}", r.max_penetration, spec.max_penetration_of(fp));
  }
  if (r.status != RunStatus::Ok && !(r.status == RunStatus::OverBudget && spec.measure_over_budget)) return out;
  if (step % spec.sample_every != 0) sample(*integrator, integrator->energy(), 0.0, true, false);
  history.finish();
  Json values = Json::array();
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    const FileMeasure& fm = spec.measures[m];
    const Accumulator& a = acc[m];
    const double scale = fm.scale > 0.0 || !(a.scale > 0.0) ? 1.0 : a.scale;  // a fixed scale: divided at each step
    double v = kNaN;
    if (!on[m] || (fm.semi_discrete && !semi)) {
      values.push_back(real(v));
      continue;
    }
    switch (fm.kind) {
      case MeasureKind::Error:
        v = (fm.norm == "final"      ? a.last
             : fm.norm == "max"      ? a.largest
             : fm.norm == "rms"      ? std::sqrt(a.timed_square / (a.t_prev - windows[m].first))
             : fm.norm == "step rms" ? std::sqrt(a.step_square / static_cast<double>(a.steps))
             : fm.norm == "l2 in time" ? std::sqrt(a.timed_square)
                                     : std::sqrt(a.square / (std::min(t_end, windows[m].second) - windows[m].first))) / scale;
        break;
      case MeasureKind::ImpactTime: {
        if (fm.located) {
          v = located_impact_error(*integrator, *problem, t_end, fm.count);
          break;
        }
        const auto exact = problem->exact() ? problem->exact()->impact_times(t_end) : std::vector<double>{};
        const std::size_t n = compared_impacts(exact, fm.count, fm.min_flight_steps * options.dt);
        const std::vector<double>& impacts = a.impacts.starts();
        if (fm.norm == "count") {
          v = static_cast<double>(std::min(n, impacts.size()));
          break;
        }
        v = impacts.size() < n ? kNaN : 0.0;  // an impact missed: no error to report
        for (std::size_t i = 0; i < n && i < impacts.size(); ++i) v = std::max(v, std::abs(impacts[i] - exact[i]));
        break;
      }
      case MeasureKind::Energy:
        if (fm.every > 0.0) {
          v = periodic_value(fm.norm, a.periodic);
          break;
        }
        v = fm.norm == "max"      ? a.largest
            : fm.norm == "final"  ? a.last
            : fm.norm == "final abs" ? std::abs(a.last)
            : fm.norm == "offset" ? (e1 - e0) / e_scale
                                  : a.drift.slope();
        break;
      case MeasureKind::FlightEnergy:
        v = fm.norm == "count" ? static_cast<double>(a.flights.compared()) : a.flights.largest();
        break;
      case MeasureKind::RestStart:
        v = fm.exact ? std::abs(a.rest.start() - summary_value(*problem, fm.summary)) : a.rest.start();
        break;
      case MeasureKind::Momentum:
        v = a.mesh_momentum ? a.mesh_momentum->largest() / a.mesh_momentum->scale() : a.largest / scale;
        break;
      case MeasureKind::Penetration: v = r.max_penetration; break;
      case MeasureKind::Estimate: break;  // compared with the next run by the tables
      case MeasureKind::Chatter: v = a.chatter.rms(); break;
      case MeasureKind::ZeroSteps: v = static_cast<double>(a.chatter.zeros()); break;
      case MeasureKind::ContactDuration: {
        const double span = a.impacts.span(options.dt);
        v = fm.exact ? std::abs(span - problem->exact()->value(ExactValue::contact_duration).value()) : span;
        break;
      }
      default: v = a.events->result(*problem); break;
      case MeasureKind::StopTime:
      case MeasureKind::OnsetTime: {
        const ExactStop exact = exact_stop(*problem);
        v = std::abs(stop->time(exact.stays) - exact.stop_time);
        break;
      }
      case MeasureKind::Hausdorff: {
        const std::string& observable = fm.observable_for(fp.label);
        const Polyline ref = reference.graph(observable, t_end, obs_ref);
        const GraphErrors e = graph_errors(a.graph, ref, [&](double t) { return reference.observable(t, observable, obs_ref); },
                                           fm.time_scale > 0.0 ? fm.time_scale : t_end, fm.value_scale);
        v = fm.norm == "to reference"     ? e.to_reference
            : fm.norm == "from reference" ? e.from_reference
            : fm.norm == "max error"      ? e.max_error
            : fm.norm == "value scale"    ? e.value_scale
                                          : e.hausdorff;
        break;
      }
    }
    values.push_back(real(v));
  }
  out["values"] = values;  // an estimate's: NaN until the tables compare it with the next run (with_next_run_estimates)
  for (const FileTable& d : spec.tables)  // a flights table's flights: E_i / E0, exact E_i / E0, E_i / E_i exact - 1
    for (std::size_t m = 0; m < spec.measures.size(); ++m)
      if (d.rows == "flights" && on[m] && spec.measures[m].label == d.measure) {
        const FlightEnergies& f = acc[m].flights;
        std::vector<double> ratio, exact;
        for (std::size_t i = 0; i < f.compared(); ++i) {
          ratio.push_back(f.energies()[i] / e0);
          exact.push_back(f.exact()[i] / e0);
        }
        out["run"]["flights"][d.measure] = {{"ratio", reals(ratio)}, {"exact", reals(exact)}, {"error", reals(f.errors())}};
      }
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (spec.measures[m].kind == MeasureKind::Estimate) out["samples"][std::to_string(m)] = reals(acc[m].samples);
  if (spec.cpu_repeats > 0) out["cpu"] = median_cpu_seconds(*problem, fi.name, params, options, spec.cpu_repeats);
  if (history_measure != spec.measures.end())
    out["history"] = {{"t", reals(history.times())}, {"e", reals(history.largest(0))}};
  return out;
}

}  // namespace

Overrides file_case_parameters(const StudySpec& spec, const Json& c) {
  const FileProblem& fp = spec.problems[c["problem"].get<std::size_t>()];
  const FileSweep& sweep = spec.integrators[c["integrator"].get<std::size_t>()].sweep_for(fp.label);
  Overrides params = sweep.parameters;
  if (c["tol"].is_null()) return params;
  params[sweep.tolerance_parameter] = fmt::format("{}", c["tol"].get<double>());
  for (const auto& [name, divisor] : sweep.tolerance_divisors) params[name] = fmt::format("{}", c["tol"].get<double>() / divisor);
  return params;
}

bool FileTable::applies_to(const std::string& problem_label) const {
  return problems.empty() || std::find(problems.begin(), problems.end(), problem_label) != problems.end();
}

bool asked_column(const std::string& source) {
  static const std::vector<std::string> names = {"problem", "problem name", "integrator", "integrator name", "parameters", "dt", "tol",
                                                 "stable steps", "t_end", "budget", "penetration limit", "energy blow-up limit",
                                                 "status", "outcome", "note"};
  return source.rfind("parameter ", 0) == 0 || std::find(names.begin(), names.end(), source) != names.end();
}

bool is_event_time(const FileMeasure& m) {
  return (m.kind == MeasureKind::ImpactTime && m.norm != "count") || m.kind == MeasureKind::StopTime || m.kind == MeasureKind::OnsetTime ||
         ((m.kind == MeasureKind::RestTime || m.kind == MeasureKind::PeakTime || m.kind == MeasureKind::RestStart ||
           m.kind == MeasureKind::ContactDuration) && m.exact);
}
bool measure_converges(const FileMeasure& m) {
  return m.kind == MeasureKind::Error || (m.kind == MeasureKind::Hausdorff && m.norm != "value scale") || is_event_time(m) ||
         (m.kind == MeasureKind::FlightEnergy && m.norm == "max");
}

std::vector<CaptionPlaceholder> caption_placeholders(const std::string& caption) {
  std::vector<CaptionPlaceholder> out;
  for (std::size_t at = caption.find("${"); at != std::string::npos; at = caption.find("${", at)) {
    const std::size_t end = caption.find('}', at);
    if (end == std::string::npos) {
      out.push_back({at, std::string::npos, caption.substr(at + 2)});
      break;
    }
    out.push_back({at, end + 1 - at, caption.substr(at + 2, end - at - 2)});
    at = end + 1;
  }
  return out;
}

std::string file_result_damage(const StudySpec& spec, const Json& r) {
  const auto reals_or_null = [](const Json& a) {
    return a.is_array() && std::all_of(a.begin(), a.end(), [](const Json& x) { return x.is_number() || x.is_null(); });
  };
  for (const char* key : {"status", "message", "steps", "force_evaluations"})
    if (!r.contains(key)) return fmt::format("no key '{}'", key);
  if (r.contains("values") && !(reals_or_null(r["values"]) && r["values"].size() == spec.measures.size()))
    return fmt::format("values is not an array of {} numbers (or null)", spec.measures.size());
  if (r.contains("cpu") && !(r["cpu"].is_number() || r["cpu"].is_null())) return "cpu is not a number";
  for (const char* key : {"factorizations", "lcp_iterations"})
    if (r.contains(key) && !r[key].is_number_integer()) return fmt::format("{} is not an integer", key);
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

namespace {



// "dt = ..." or "tol = ...", the number in `format` (default {:.2e} for dt, {:.1e} for tol).
std::string run_label(const Json& c, const std::optional<std::string>& format = std::nullopt) {
  const bool tol = !c["tol"].is_null();
  const double x = c[tol ? "tol" : "dt"].get<double>();
  return fmt::format("{} = {}", tol ? "tol" : "dt", fmt::format(fmt::runtime(format.value_or(tol ? "{:.1e}" : "{:.2e}")), x));
}

// What the errors on a problem are measured against, as captions and the ranking say it.
std::string against_text(const FileReference* r) {
  if (!r) return "no reference";
  if (!r->against.empty()) return r->against;
  return r->exact      ? "the exact solution"
         : r->lockstep ? fmt::format("{} stepped with each run (lockstep)", r->integrator)
                       : fmt::format("{} (dt = {}, cached)", r->integrator, r->dt);
}

// A declared figure's id: <name>_<id>, or <id> with study.figures = "declared".
std::string figure_id(const StudySpec& spec, const FileFigure& f) { return spec.declared_figures_only ? f.id : spec.name + "_" + f.id; }

// A figure the file declares, as the report draws it.
Figure declared_figure(const StudySpec& spec, const FileFigure& f) {
  Figure figure{figure_id(spec, f), f.title, f.x, f.y, f.series, f.panels, f.log_x, f.log_y, f.slopes};
  figure.small_multiples = f.small_multiples;
  figure.deviation = f.deviation;
  figure.caption = f.caption;
  return figure;
}

// A declared column: the source column under its own header, unit, format and description.
Column declared_column(const Column& source, const FileColumn& d) {
  return {d.header.value_or(source.name), d.unit.value_or(source.unit), d.format.value_or(source.format),
          d.description.value_or(source.description), source.timing};
}

std::size_t column_index(const Table& t, const std::string& name) {
  const auto it = std::find_if(t.columns.begin(), t.columns.end(), [&](const Column& c) { return c.name == name; });
  if (it == t.columns.end()) throw std::logic_error(fmt::format("table {} has no column '{}'", t.id, name));
  return static_cast<std::size_t>(it - t.columns.begin());
}

// A status cell of a run that never started (declined: "n/a: why").
bool declined(const Cell& status) {
  const auto* text = std::get_if<std::string>(&status);
  return text && text->rfind("n/a", 0) == 0;
}

// A case-table cell as a number (NaN: none, or a text).
double cell_number(const Cell& cell) {
  return std::holds_alternative<double>(cell) ? std::get<double>(cell) : std::holds_alternative<long>(cell) ? static_cast<double>(std::get<long>(cell)) : kNaN;
}

// Whether a table of some runs (or a case table) shows the run of this case-table row
// (FileTable::where, drop_above).
bool shows_run(const FileTable& d, const Table& runs, const std::vector<Cell>& row) {
  for (const auto& [name, want] : d.where) {
    const Cell& cell = row[column_index(runs, name)];
    if (std::holds_alternative<std::string>(want) ? cell != want : cell_number(cell) != std::get<double>(want)) return false;
  }
  return std::none_of(d.drop_above.begin(), d.drop_above.end(),
                      [&](const auto& limit) { return std::abs(cell_number(row[column_index(runs, limit.first)])) > limit.second; }) &&
         std::none_of(d.except.begin(), d.except.end(), [&](const auto& one) { return row[column_index(runs, one.first)] == one.second; });
}

// Whether column i of case table d shows the run's outcome (not_ok = "outcome": a measure's
// column of a run whose outcome is not ok).
bool shows_outcome(const FileTable& d, std::size_t i, const Cell& outcome) {
  return !d.outcome_columns.empty() && outcome != Cell{std::string("ok")} &&
         std::find(d.outcome_columns.begin(), d.outcome_columns.end(), d.columns[i].of) != d.outcome_columns.end();
}

// rows = "case": the work-precision rows (those `where` and `drop_above` keep), their columns
// picked, ordered and renamed; the first such table carries the work-precision figures whose
// columns it shows, under the new names.
Table case_table(const FileTable& d, const Table& runs, bool with_figures) {
  Table out;
  std::vector<std::size_t> at;
  std::map<std::string, std::string> renamed;
  for (const FileColumn& c : d.columns) {
    at.push_back(column_index(runs, c.of));
    out.columns.push_back(declared_column(runs.columns[at.back()], c));
    renamed[c.of] = out.columns.back().name;
  }
  const auto status = std::find_if(runs.columns.begin(), runs.columns.end(), [](const Column& c) { return c.name == "status"; });
  const std::size_t problem = column_index(runs, "problem");
  const std::size_t note = d.declined_reason.empty() ? 0 : column_index(runs, "note");  // a declined run's: the scheme's reason
  // integrators = [...] (case rows only): the file's label of each run.
  const std::size_t label = d.integrators.empty() ? 0 : column_index(runs, "integrator label");
  const std::size_t outcome = d.outcome_columns.empty() ? 0 : column_index(runs, "outcome");  // not_ok = "outcome"
  for (const auto& row : runs.rows) {
    // A table of some runs picked its runs itself (its `all` holds their series, not the case columns).
    if (!d.applies_to(std::get<std::string>(row[problem])) || (d.rows == "case" && !shows_run(d, runs, row))) continue;
    if (!d.integrators.empty() &&
        std::find(d.integrators.begin(), d.integrators.end(), std::get<std::string>(row[label])) == d.integrators.end())
      continue;
    const bool blank = d.declined_blank && status != runs.columns.end() && declined(row[static_cast<std::size_t>(status - runs.columns.begin())]);
    std::vector<Cell> cells;
    const Cell none = d.declined_empty ? Cell(std::string()) : Cell{};
    for (std::size_t i = 0; i < at.size(); ++i) {
      const Cell& cell = row[at[i]];
      const bool missing = std::holds_alternative<std::monostate>(cell) && d.columns[i].missing;
      const Cell blanked = d.columns[i].of == d.declined_reason ? row[note] : none;
      cells.push_back(blank && !asked_column(d.columns[i].of) ? blanked : missing ? Cell(*d.columns[i].missing) : cell);
      if (shows_outcome(d, i, row[outcome])) cells.back() = row[outcome];
    }
    out.add_row(std::move(cells));
  }
  if (!with_figures) return out;
  for (Figure f : runs.figures) {
    const auto rename = [&](std::string& name) {
      const auto it = renamed.find(name);
      return it != renamed.end() && (name = it->second, true);
    };
    bool shown = rename(f.x) && rename(f.y);
    for (auto& s : f.series) shown = shown && rename(s);
    for (auto& s : f.panels) shown = shown && rename(s);
    if (shown) out.figures.push_back(f);
  }
  return out;
}

// The columns of a run's own figures (RunFigures) and their cells for one run.
const std::vector<Column>& run_columns() {
  static const std::vector<Column> columns = {
      {"problem name", "", "", "the registered problem"},
      {"stable steps", "", "{}", "dt / the problem's stable step, when the sweep sets it so"},
      {"t_end", "s", "{}", ""},
      {"outcome", "", "", "the status alone"},
      {"t reached", "s", "{:.4g}", ""},
      {"impacts", "", "", "contact phases started, as seen at the steps"},
      {"switches", "", "{:.0f}", "contact mode switches located inside the steps"},
      {"missed switches", "", "{:.0f}", "switches found only at a step's end, not by a root"},
      {"budget", "", "", "F_int evaluations allowed"},
      {"max penetration", "m", "{:.2e}", "max over the steps of max(0, -g)"},
      {"penetration limit", "m", "{:.2g}", "status penetration above it"},
      {"energy scale", "J", "{:.3g}", "|E0|, or the problem's energy scale when E0 = 0, or the problem's energy_scale"},
      {"energy growth", "", "{:.2e}", "max (E - E0 - W) / E scale"},
      {"energy blow-up limit", "", "{:.0e}", "status energy blow-up above it"},
      {"final energy err", "", "{:.2e}", "|E_end - E0| / E scale"},
      {"note", "", "", "the run driver's message: why a run diverged, stopped or is n/a"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"},
      {"integrator label", "", "", "the integrator's label in the file"},
      {"min step", "s", "{:.2e}", "smallest step taken"},
      {"max step", "s", "{:.2e}", "largest step taken"},
      {"CPU per step", "s", "{:.2e}", "CPU / steps: the cost of a step, observer excluded", true}};
  return columns;
}

// The integrator's parameters the file sets on a problem, "key=value ..." by key, or "default".
std::string parameters_text(const FileIntegrator& fi, const std::string& problem_label) {
  const Overrides& set = fi.sweep_for(problem_label).parameters;
  if (set.empty()) return "default";
  std::vector<std::string> items;
  for (const auto& [key, value] : set) items.push_back(key + "=" + value);
  return fmt::format("{}", fmt::join(items, " "));
}

// The columns "parameter NAME" (parameter_column_names).
std::vector<Column> parameter_columns(const StudySpec& spec) {
  std::vector<Column> columns;
  for (const auto& name : parameter_column_names(spec)) columns.push_back({name, "", "", "the problem's parameter"});
  return columns;
}

// The run columns of this study's own: its counters (Work::extra, n/a where a scheme does not
// count one) and the problems' parameters ("parameter NAME", empty where a problem has none).
std::vector<Column> study_run_columns(const StudySpec& spec) {
  std::vector<Column> columns;
  for (const auto& name : spec.counters) columns.push_back({name, "", "{:.3g}", "the integrator's work counter " + name});
  const std::vector<Column> parameters = parameter_columns(spec);
  columns.insert(columns.end(), parameters.begin(), parameters.end());
  return columns;
}

// The cells of the parameter columns `names` ("parameter NAME") for a run on p: its value
// (integers and reals as numbers, choices as text), empty where p has no such parameter.
std::vector<Cell> parameter_cells(const FileProblem& p, const std::vector<std::string>& names) {
  const ParamSpecs specs = find_problem(p.name).parameters();
  const Params params(specs, p.parameters);
  std::vector<Cell> cells;
  for (const std::string& name : names) {
    const auto s = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& q) { return "parameter " + q.name == name; });
    if (s == specs.end()) {
      cells.emplace_back();
    } else if (s->kind == ParamSpec::Kind::Integer) {
      cells.emplace_back(params.integer(s->name));
    } else if (s->kind == ParamSpec::Kind::Real) {
      const auto v = params.optional_real(s->name);
      cells.push_back(v ? Cell{*v} : Cell{});
    } else {
      cells.emplace_back(params.choice(s->name));
    }
  }
  return cells;
}

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
    if (status != "ok") return status == "n/a" ? "declined" : status;
  }
  return std::string();
}

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

std::vector<Cell> study_run_cells(const StudySpec& spec, const Json& c, const Json& r) {
  std::vector<Cell> cells;
  const Json& f = r.contains("run") ? r["run"] : Json::object();
  for (std::size_t k = 0; k < spec.counters.size(); ++k)
    cells.push_back(f.contains("counters") ? number_cell(f["counters"][k]) : Cell{});
  const std::vector<Cell> parameters = parameter_cells(spec.problems[c["problem"].get<std::size_t>()], parameter_column_names(spec));
  cells.insert(cells.end(), parameters.begin(), parameters.end());
  return cells;
}

std::vector<Cell> run_cells(const StudySpec& spec, const Json& c, const Json& r) {
  const FileProblem& p = spec.problems[c["problem"].get<std::size_t>()];
  const FileIntegrator& fi = spec.integrators[c["integrator"].get<std::size_t>()];
  const Json& f = r.contains("run") ? r["run"] : Json::object();
  const auto value = [&](const char* key) { return f.contains(key) ? number_cell(f[key]) : Cell{}; };
  const double t_end = case_t_end(spec, p, c);
  return {p.name, c.contains("stable_steps") ? Cell{c["stable_steps"].get<double>()} : Cell{}, t_end,
          r["status"].get<std::string>(), value("t_reached"), f.contains("impacts") ? Cell{f["impacts"].get<long>()} : Cell{},
          value("switches"), value("missed_switches"), spec.budget_of(p, c["dt"].get<double>(), t_end), value("max_penetration"), spec.max_penetration_of(p),
          value("energy_scale"), value("energy_growth"), spec.energy_blow_up_of(p), value("final_energy_error"),
          f.contains("note") ? Cell{f["note"].get<std::string>()} : Cell{}, fi.name, parameters_text(fi, p.label), fi.label,
          value("min_step"), value("max_step"),
          r["steps"].get<long>() > 0 ? number_cell(real_or_nan(r, "cpu") / static_cast<double>(r["steps"].get<long>())) : Cell{}};
}

const std::vector<Column>& history_columns() {
  static const std::vector<Column> columns = {
      {"problem", "", "", ""}, {"problem name", "", "", "the registered problem"}, {"integrator", "", "", ""}, {"run", "", "", ""},
      {"t", "s", "", "end of the interval"},
      {"energy deviation", "", "", "largest |E - E0| / E scale over the interval"},
      {"penetration", "m", "", "largest -min g over the interval (negative: every gap open)"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"},
      {"momentum residual", "", "", "largest |P - P0 - sum of the impulses| / sum_i m_i |v0_i| over the interval"}};
  return columns;
}

const std::vector<Column>& samples_columns() {
  static const std::vector<Column> columns = {
      {"problem", "", "", ""}, {"problem name", "", "", "the registered problem"}, {"integrator", "", "", ""}, {"run", "", "", ""},
      {"t", "s", "", "the sample's step"}, {"energy ratio", "", "", "E / E0"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"}};
  return columns;
}

// rows = "history" (a row per interval of each run on the table's problems) or "samples" (a
// row per sample), the columns picked; its figures, the [[figure]]s that name it, under its headers.
Table history_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results) {
  const bool samples = d.rows == "samples";
  Table all;
  all.columns = samples ? samples_columns() : history_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end(), parameters.begin(), parameters.end());
  const std::vector<std::string> parameter_names = parameter_column_names(spec);
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& r = results[k];
    const char* key = samples ? "samples" : "intervals";
    if (!r.contains("run") || !r["run"].contains(key)) continue;
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    if (!d.applies_to(p.label)) continue;
    const FileIntegrator& fi = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
    const std::string integrator = shown_label(fi, p.label), variant = parameters_text(fi, p.label);
    const Json& h = r["run"][key];
    const std::vector<Cell> own = parameter_cells(p, parameter_names);
    for (std::size_t i = 0; i < h["t"].size(); ++i) {
      std::vector<Cell> row = {p.label, p.name, integrator, run_label(cases[k]), number_cell(h["t"][i])};
      if (samples) {
        row.insert(row.end(), {number_cell(h["energy_ratio"][i]), fi.name, variant});
      } else {
        row.insert(row.end(), {number_cell(h["energy"][i]), number_cell(h["penetration"][i]), fi.name, variant,
                               h.contains("momentum") ? number_cell(h["momentum"][i]) : Cell{}});
      }
      row.insert(row.end(), own.begin(), own.end());
      all.add_row(std::move(row));
    }
  }
  for (const FileFigure& f : spec.figures)
    if (f.table == d.id) all.figures.push_back(declared_figure(spec, f));
  Table t = case_table(d, all, true);
  t.csv_only = true;
  return t;
}

// The columns of a periodic or trajectory table: which run, then the sample's `own`.
std::vector<Column> run_series_columns(const std::vector<Column>& own) {
  std::vector<Column> columns = {
      {"problem", "", "", ""}, {"problem name", "", "", "the registered problem"}, {"integrator", "", "", "exact: the exact observable"},
      {"integrator name", "", "", "the registered integrator"},
      {"parameters", "", "", "the integrator's parameters set by the file (default: none)"}, {"run", "", "", ""}};
  columns.insert(columns.end(), own.begin(), own.end());
  return columns;
}

const std::vector<Column>& periodic_columns() {
  static const std::vector<Column> columns = run_series_columns(
      {{"k", "", "", "the sample's number: at the first step past from + k every"}, {"value", "", "", "the measure's sample"},
       {"|value|", "", "", "its absolute value (a log scale)"}});
  return columns;
}

const std::vector<Column>& trajectory_columns() {
  static const std::vector<Column> columns = run_series_columns({{"t", "s", "", "the sample's step"}, {"value", "", "", "the observable"}});
  return columns;
}

const std::vector<Column>& flights_columns() {
  static const std::vector<Column> columns = run_series_columns(
      {{"flight", "", "", "i: the flight after impact i"}, {"energy ratio", "", "", "E_i / E0, E_i the flight's measured energy"},
       {"exact energy ratio", "", "", "the exact E_i / E0"}, {"|rel. err|", "", "", "|E_i / E_i exact - 1|"}});
  return columns;
}


// A cell as the text of a pivot's column header.
std::string pivot_value_text(const Cell& cell) {
  if (const auto* text = std::get_if<std::string>(&cell)) return *text;
  if (const auto* n = std::get_if<long>(&cell)) return fmt::format("{}", *n);
  if (const auto* x = std::get_if<double>(&cell)) return fmt::format("{}", *x);
  return "n/a";
}

// A pivot's order (FileTable::order): the point of one run of its row r, (its column `of`, its
// value; NaN when its outcome is not ok), in the order of the runs.
void pivot_order_point(const FileTable& d, const Table& runs, const std::vector<Cell>& row, std::size_t r,
                       std::vector<std::vector<double>>& x, std::vector<std::vector<double>>& y) {
  if (x.size() <= r) x.resize(r + 1), y.resize(r + 1);
  const bool ok = row[column_index(runs, "outcome")] == Cell{std::string("ok")};
  x[r].push_back(cell_number(row[column_index(runs, d.order->of)]));
  y[r].push_back(ok ? cell_number(row[column_index(runs, d.columns.back().of)]) : kNaN);
}

// Its column: by default "order against <of>", two decimals.
Column pivot_order_column(const FileTable& d, const Table& runs) {
  const Column& of = runs.columns[column_index(runs, d.order->of)];
  return declared_column({"order against " + of.name, "", "{:.2f}", fmt::format("least-squares slope of log(value) against log({})", of.name)},
                         *d.order);
}

// rows = "pivot" (FileTable::across): from the case table `runs` with every column.
Table pivot_table(const StudySpec& spec, const FileTable& d, const Table& runs) {
  const std::size_t across = column_index(runs, d.across), outcome = column_index(runs, "outcome");
  const std::size_t value = column_index(runs, d.columns.back().of);
  std::vector<std::size_t> keys;
  for (std::size_t k = 0; k + 1 < d.columns.size(); ++k) keys.push_back(column_index(runs, d.columns[k].of));
  std::vector<std::vector<Cell>> rows;  // the key cells, then one cell per spread value
  std::vector<std::string> spread;
  std::map<std::pair<std::size_t, std::size_t>, Cell> cells;
  std::vector<std::vector<double>> order_x, order_y;  // d.order: each row's runs
  for (const auto& row : runs.rows) {
    if (!d.applies_to(std::get<std::string>(row[column_index(runs, "problem")])) || !shows_run(d, runs, row)) continue;
    std::vector<Cell> key;
    for (const std::size_t k : keys) key.push_back(row[k]);
    const std::size_t r = static_cast<std::size_t>(std::find(rows.begin(), rows.end(), key) - rows.begin());
    if (r == rows.size()) rows.push_back(key);
    const std::string at = pivot_value_text(row[across]);
    const std::size_t a = static_cast<std::size_t>(std::find(spread.begin(), spread.end(), at) - spread.begin());
    if (a == spread.size()) spread.push_back(at);
    cells[{r, a}] = row[outcome] == Cell{std::string("ok")} ? row[value] : row[outcome];
    if (d.order) pivot_order_point(d, runs, row, r, order_x, order_y);
  }
  Table out;
  for (std::size_t k = 0; k < keys.size(); ++k) out.columns.push_back(declared_column(runs.columns[keys[k]], d.columns[k]));
  for (const std::string& at : spread) {
    Column c = declared_column(runs.columns[value], d.columns.back());
    const auto hole = c.name.find("{}");
    c.name = hole == std::string::npos ? c.name + ", " + at : c.name.replace(hole, 2, at);
    out.columns.push_back(c);
  }
  if (d.order) out.columns.push_back(pivot_order_column(d, runs));
  for (std::size_t r = 0; r < rows.size(); ++r) {
    for (std::size_t a = 0; a < spread.size(); ++a) {
      const auto it = cells.find({r, a});
      rows[r].push_back(it == cells.end() ? Cell(d.columns.back().missing.value_or("")) : it->second);
    }
    if (d.order) rows[r].push_back(number_cell(fitted_order(order_x[r], order_y[r])));
    out.add_row(std::move(rows[r]));
  }
  // Its figures: x, series and panels name key columns (by `of`, drawn under their headers), y a
  // spread column by its header (the reader checked both).
  const auto header = [&](const std::string& of) {
    for (std::size_t k = 0; k < keys.size(); ++k)
      if (d.columns[k].of == of) return out.columns[k].name;
    throw std::logic_error(fmt::format("pivot table {} has no key column '{}'", d.id, of));
  };
  for (const FileFigure& f : spec.figures) {
    if (f.table != d.id) continue;
    Figure figure = declared_figure(spec, f);
    figure.x = header(f.x);
    for (auto& s : figure.series) s = header(s);
    for (auto& p : figure.panels) p = header(p);
    std::vector<std::string> names;
    for (const Column& c : out.columns) names.push_back(c.name);
    if (std::find(names.begin(), names.end(), f.y) == names.end())
      throw InputError(fmt::format("figure {}: y '{}' is not a column of table {}; its runs gave: {}", f.id, f.y, d.id, fmt::join(names, ", ")));
    out.figures.push_back(figure);
  }
  return out;
}

// rows = "periodic", "trajectory" or "flights": a row per sample (flight) of each run shown (its
// case-table row in `runs`: case_row), in the order of the cases; a trajectory's rows "exact"
// after the first run shown of each problem, at its times.
Table run_series_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                       const Table& runs, const std::vector<std::size_t>& case_row) {
  const bool periodic = d.rows == "periodic", flights = d.rows == "flights";
  Table all;
  all.columns = periodic ? periodic_columns() : flights ? flights_columns() : trajectory_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end(), parameters.begin(), parameters.end());
  const std::vector<std::string> parameter_names = parameter_column_names(spec);
  std::vector<std::string> exact_drawn;  // the problems whose exact rows are in
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& run = results[k].contains("run") ? results[k]["run"] : Json::object();
    const char* key = periodic ? "periodic" : flights ? "flights" : "trajectories";
    const std::string& id = periodic || flights ? d.measure : d.id;
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    if (!run.contains(key) || !run[key].contains(id) || !d.applies_to(p.label) || !shows_run(d, runs, runs.rows[case_row[k]])) continue;
    const FileIntegrator& fi = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
    const std::vector<Cell> own = parameter_cells(p, parameter_names);
    const auto add = [&](std::vector<Cell> row) {
      row.insert(row.end(), own.begin(), own.end());
      all.add_row(std::move(row));
    };
    const std::vector<Cell> head = {p.label, p.name, shown_label(fi, p.label), fi.name, parameters_text(fi, p.label), run_label(cases[k])};
    const Json& samples = run[key][id];
    if (periodic) {
      for (std::size_t i = 0; i < samples.size(); ++i) {
        std::vector<Cell> row = head;
        row.insert(row.end(), {static_cast<long>(i + 1), number_cell(samples[i]), number_cell(std::abs(real(samples[i])))});
        add(row);
      }
      continue;
    }
    if (flights) {
      for (std::size_t i = 0; i < samples["ratio"].size(); ++i) {
        std::vector<Cell> row = head;
        row.insert(row.end(), {static_cast<long>(i + 1), number_cell(samples["ratio"][i]), number_cell(samples["exact"][i]),
                               number_cell(std::abs(real(samples["error"][i])))});
        add(row);
      }
      continue;
    }
    const Json& t = samples["t"];
    for (std::size_t i = 0; i < t.size(); ++i) {
      std::vector<Cell> row = head;
      row.insert(row.end(), {number_cell(t[i]), number_cell(samples["value"][i])});
      add(row);
    }
    if (d.exact.empty() || t.empty() || std::find(exact_drawn.begin(), exact_drawn.end(), p.label) != exact_drawn.end()) continue;
    exact_drawn.push_back(p.label);
    for (std::size_t i = 0; i < t.size(); ++i)
      add({p.label, p.name, "exact", "", "", "", number_cell(t[i]), number_cell(samples["exact"][i])});
  }
  for (const FileFigure& f : spec.figures)
    if (f.table == d.id) all.figures.push_back(declared_figure(spec, f));
  Table out = case_table(d, all, true);
  out.csv_only = !flights;  // a few rows per run: readable as text too
  return out;
}

// The columns of an impulses and of a field table ("field": one column per cell at table time).
const std::vector<Column>& impulses_columns() {
  static const std::vector<Column> columns = [] {
    std::vector<Column> c = run_series_columns(
        {{"t", "s", "", "the bin's end t_j = j dt"}, {"value", "", "", "the contact impulses of the bin (t_j - dt, t_j] over dt and the scale"}});
    c.push_back({"integrator label", "", "", "the integrator's label in the file"});
    return c;
  }();
  return columns;
}

const std::vector<Column>& field_columns() {
  static const std::vector<Column> columns = [] {
    std::vector<Column> c = run_series_columns(
        {{"t", "s", "", "the step's end (a run's first row: its start)"}, {"field", "", "", "the element stress of each cell"}});
    c.push_back({"integrator label", "", "", "the integrator's label in the file"});
    return c;
  }();
  return columns;
}

// The cells of a run's row of an impulses or field table before its own values (the problem,
// the integrator, the run) and after them (the problem's parameters, the integrator's label).
std::pair<std::vector<Cell>, std::vector<Cell>> run_series_cells(const StudySpec& spec, const Json& c) {
  const FileProblem& p = spec.problems[c["problem"].get<std::size_t>()];
  const FileIntegrator& fi = spec.integrators[c["integrator"].get<std::size_t>()];
  std::vector<Cell> after = parameter_cells(p, parameter_column_names(spec));
  after.emplace_back(fi.label);
  return {{p.label, p.name, shown_label(fi, p.label), fi.name, parameters_text(fi, p.label), run_label(c)}, after};
}

// rows = "impulses" (FileTable::scale, exact, exact_per, exact_in): the bins of each run shown,
// in the order of the cases, the exact rows after the first run of each value of exact_per.
Table impulses_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                     const Table& runs, const std::vector<std::size_t>& case_row) {
  Table all;
  all.columns = impulses_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end() - 1, parameters.begin(), parameters.end());
  const std::size_t per = column_index(all, d.exact_per), in = column_index(all, d.exact_in);
  std::vector<Cell> exact_shown;  // the values of exact_per whose exact rows are in
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Json& run = results[k].contains("run") ? results[k]["run"] : Json::object();
    if (!run.contains("impulses") || !run["impulses"].contains(d.id) || !shows_run(d, runs, runs.rows[case_row[k]])) continue;
    const auto around = run_series_cells(spec, cases[k]);
    const std::vector<Cell>& before = around.first;
    const std::vector<Cell>& after = around.second;
    const auto row = [&](const Json& t, const Json& value) {
      std::vector<Cell> cells = before;
      cells.insert(cells.end(), {number_cell(t), number_cell(value)});
      cells.insert(cells.end(), after.begin(), after.end());
      return cells;
    };
    const Json& bins = run["impulses"][d.id];
    for (std::size_t i = 0; i < bins["t"].size(); ++i) all.add_row(row(bins["t"][i], bins["value"][i]));
    if (d.exact.empty() || bins["t"].empty()) continue;
    const Cell key = row(bins["t"][0], nullptr)[per];
    if (std::find(exact_shown.begin(), exact_shown.end(), key) != exact_shown.end()) continue;
    exact_shown.push_back(key);
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    const auto problem = make_problem(p.name, p.parameters);
    const SpMat M = problem->mass_matrix();
    std::vector<double> buffer(problem->observable_names().size());
    const Vec none = Vec::Zero(problem->ncontacts());
    for (const Json& t : bins["t"]) {
      const std::optional<State> exact = problem->exact()->state(t.get<double>());
      std::vector<Cell> cells = row(t, real(exact ? state_observable(*problem, M, *exact, none, 0.0, d.exact, buffer, nullptr) / d.scale : kNaN));
      cells[in] = std::string("exact");
      all.add_row(std::move(cells));
    }
  }
  for (const FileFigure& f : spec.figures)
    if (f.table == d.id) all.figures.push_back(declared_figure(spec, f));
  Table out = case_table(d, all, true);
  out.csv_only = true;
  return out;
}

// rows = "field" (FileTable::component, exact_times): the exact rows first, then a row per step
// of each run shown, in the order of the cases; the field's columns those of the first problem
// the table shows (the reader checked that its problems share one mesh). Its figures are
// space-time pictures, one panel per run (FileFigure::caption).
Table field_table(const StudySpec& spec, const FileTable& d, const std::vector<Json>& cases, const std::vector<Json>& results,
                  const Table& runs, const std::vector<std::size_t>& case_row) {
  const FileProblem& first = *std::find_if(spec.problems.begin(), spec.problems.end(), [&](const FileProblem& p) { return d.applies_to(p.label); });
  const auto problem = make_problem(first.name, first.parameters);
  const FieldMesh mesh = problem->field_mesh().value();
  std::vector<double> centres;
  for (Index e = 0; e < mesh.ncells(); ++e) centres.push_back(0.5 * (mesh.points(mesh.cells(e, 0), 0) + mesh.points(mesh.cells(e, 1), 0)));
  const std::string component = d.component.empty() ? mesh.stress_components.front() : d.component;
  Table all;  // the columns but the field's, by source name
  all.columns = field_columns();
  const std::vector<Column> parameters = parameter_columns(spec);
  all.columns.insert(all.columns.end() - 1, parameters.begin(), parameters.end());
  const std::size_t field = column_index(all, "field");
  Table out;
  std::vector<std::string> field_names;
  std::map<std::string, std::string> renamed;
  for (const FileColumn& c : d.columns) {
    const Column source = all.columns[column_index(all, c.of)];
    if (c.of != "field") {
      out.columns.push_back(declared_column(source, c));
      renamed[c.of] = out.columns.back().name;
      continue;
    }
    const std::string header = c.header.value_or(component + "(x = {})");
    for (const double x : centres) {
      Column cell = declared_column(source, c);
      cell.name = header;
      cell.name.replace(header.find("{}"), 2, fmt::format("{:g}", x));  // the reader checked the {}
      field_names.push_back(cell.name);
      out.columns.push_back(cell);
    }
  }
  // A row from the cells of `all`'s columns but the field, and the field's values from `values[from]` on.
  const auto add = [&](const std::vector<Cell>& cells, const Json& values, std::size_t from) {
    std::vector<Cell> row;
    for (const FileColumn& c : d.columns) {
      if (c.of != "field") {
        const std::size_t k = column_index(all, c.of);
        row.push_back(cells[k < field ? k : k - 1]);
        continue;
      }
      for (std::size_t e = 0; e < centres.size(); ++e) row.push_back(number_cell(values[from + e]));
    }
    out.add_row(std::move(row));
  };
  if (d.exact_times > 0) {
    Eigen::MatrixXd stress(mesh.nelements(), static_cast<Index>(mesh.stress_components.size()));
    const auto k_component = static_cast<Index>(std::find(mesh.stress_components.begin(), mesh.stress_components.end(), component) -
                                                mesh.stress_components.begin());
    const double t_end = spec.t_end_of(first);
    for (int k = 0; k <= d.exact_times; ++k) {
      const double t = t_end * k / d.exact_times;
      const bool known = problem->exact()->exact_cell_stress(t, stress);
      std::vector<Cell> cells = {first.label, first.name, std::string("exact"), std::string(), std::string(), std::string(), t};
      cells.insert(cells.end(), all.columns.size() - cells.size() - 1, Cell{std::string()});
      Json values = Json::array();
      for (Index e = 0; e < stress.rows(); ++e) values.push_back(real(known ? stress(e, k_component) : kNaN));
      add(cells, values, 0);
    }
  }
  std::vector<std::string> no_field;  // the runs shown without a field: "first panel (other panels): outcome"
  const std::size_t outcome = column_index(runs, "outcome");
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
    const FileIntegrator& fi = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
    const bool named = d.integrators.empty() || std::find(d.integrators.begin(), d.integrators.end(), fi.label) != d.integrators.end();
    if (!d.applies_to(p.label) || !named || !shows_run(d, runs, runs.rows[case_row[k]])) continue;
    const auto around = run_series_cells(spec, cases[k]);
    const std::vector<Cell>& before = around.first;
    const std::vector<Cell>& after = around.second;
    std::vector<Cell> cells = before;
    cells.emplace_back();  // t, set below
    cells.insert(cells.end(), after.begin(), after.end());
    const Json& run = results[k].contains("run") ? results[k]["run"] : Json::object();
    if (!run.contains("fields") || !run["fields"].contains(d.id)) {
      for (const FileFigure& f : spec.figures)
        if (f.table == d.id && !f.panels.empty()) {
          std::vector<std::string> rest;
          for (std::size_t i = 1; i < f.panels.size(); ++i) {
            const std::size_t at = column_index(all, f.panels[i]);
            rest.push_back(pivot_value_text(cells[at < field ? at : at - 1]));
          }
          const std::size_t at = column_index(all, f.panels.front());
          no_field.push_back(fmt::format("{}{}: {}", pivot_value_text(cells[at < field ? at : at - 1]),
                                         rest.empty() ? "" : fmt::format(" ({})", fmt::join(rest, ", ")),
                                         pivot_value_text(runs.rows[case_row[k]][outcome])));
          break;
        }
      continue;
    }
    const Json& f = run["fields"][d.id];
    for (std::size_t i = 0; i < f["t"].size(); ++i) {
      cells[6] = number_cell(f["t"][i]);
      add(cells, f["values"], i * centres.size());
    }
  }
  const auto rename = [&](const std::string& name) {
    const auto it = renamed.find(name);
    return it == renamed.end() ? name : it->second;
  };
  for (const FileFigure& f : spec.figures) {
    if (f.table != d.id) continue;
    Figure figure = declared_figure(spec, f);
    figure.x.clear();
    figure.y = rename(f.y);
    for (auto& name : figure.series) name = rename(name);
    for (auto& name : figure.panels) name = rename(name);
    figure.kind = "space_time";
    figure.values = field_names;
    figure.positions = centres;
    figure.value_label = f.value_label;
    std::string caption = d.caption.value_or("");
    if (!f.caption.empty()) caption += (caption.empty() ? "" : " ") + f.caption;
    if (!no_field.empty()) caption += fmt::format("{} panel for {}", caption.empty() ? "No" : "; no", fmt::join(no_field, ", "));
    figure.caption = caption.empty() ? caption : caption + ".";
    out.figures.push_back(figure);
  }
  out.csv_only = true;
  return out;
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

// The columns of sweep_work_column_names: the solver's own steps and Jacobians (CVODE's counts,
// which the driver's steps and F_int evaluations are not for the references), and each
// converging measure's rate against the next run of the sweep.
std::vector<Column> sweep_work_columns(const StudySpec& spec) {
  std::vector<Column> columns = {{"solver steps", "", "{:.0f}", "the integrator's own steps (CVODE's internal steps)"},
                                 {"Jacobians", "", "{:.0f}", "tangent (Jacobian) evaluations"}};
  for (const auto& m : spec.measures)
    if (measure_converges(m))
      columns.push_back({"rate of " + m.label, "", "{:.2f}",
                         "log(e / e') / log(x' / x) against the next run x' of the sweep (x: its step, tolerance or swept parameter)"});
  return columns;
}

std::vector<Cell> sweep_work_cells(const StudySpec& spec, const Json& r) {
  const auto count = [&](const char* key) { return r.contains(key) ? Cell{r[key].get<long>()} : Cell{}; };
  std::vector<Cell> cells = {count("solver_steps"), count("tangent_evaluations")};
  std::size_t k = 0;
  for (const auto& m : spec.measures)
    if (measure_converges(m)) cells.push_back(r.contains("next_rates") ? number_cell(r["next_rates"][k++]) : Cell{});
  return cells;
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
      const bool next = i + 1 < sweep.size() && results[sweep[i + 1]]["status"] == "ok" && r["status"] == "ok" && r.contains("values");
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
        r["values"][m] = real(fm.order != 0.0 ? d / (1.0 - std::pow(x_next / x, fm.order)) : d);
      }
      r["next_rates"] = rates;
    }
  return results;
}

std::vector<Table> file_tables(const StudySpec& spec, const std::vector<Json>& cases, const std::vector<Json>& results) {
  const std::vector<std::pair<std::string, std::string>> meta = {
      {"study", spec.name}, {"study_file", spec.file}, {"study_file_fnv1a64", spec.hash}, {"t_end", fmt::format("{}", spec.t_end)}};
  // What the errors are measured against: one text, or one per problem where they differ.
  std::vector<std::string> per_problem;
  for (const auto& p : spec.problems) per_problem.push_back(p.label + ": " + against_text(spec.reference_of(p)));
  const bool one_reference = std::all_of(spec.problems.begin(), spec.problems.end(), [&](const FileProblem& p) {
    return against_text(spec.reference_of(p)) == against_text(spec.reference_of(spec.problems.front()));
  });
  const std::string against = one_reference ? against_text(spec.reference_of(spec.problems.front()))
                                            : fmt::format("{}", fmt::join(per_problem, "; "));
  const std::string cpu = spec.cpu_repeats > 0
                              ? median_cpu_text(spec.cpu_repeats)
                              : "thread CPU time of the stepping of the observed run (observer excluded)";
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
  t.metadata = meta;
  Table orders;
  orders.id = spec.name + "_orders";
  orders.title = spec.title + ": fitted orders";
  orders.caption = "Least-squares slope of log(error) against log(dt) (log(tol) for a tolerance sweep) with its 95% "
                   "confidence interval (Student t, n - 2 degrees of freedom); errors below 1e-11 are round-off and left out.";
  orders.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"measure", "", "", ""}, {"against", "", "", ""},
                    {"order", "", "{:.2f}", ""}, {"CI low", "", "{:.2f}", "95% confidence interval"},
                    {"CI high", "", "{:.2f}", ""}, {"points", "", "", ""}};
  orders.metadata = meta;
  Table history;
  history.id = spec.name + "_energy_history";
  history.title = spec.title + ": energy error history";
  history.caption = fmt::format("max |E - E0| / |E0| over each of {} equal intervals of [0, t_end]", kHistoryIntervals);
  history.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"run", "", "", ""}, {"t", "s", "", ""},
                     {"energy err", "", "", ""}};
  history.csv_only = true;
  history.metadata = meta;
  if (!spec.declared_figures_only)
    history.figures = {{spec.name + "_energy_history", spec.title + ": energy error", "t", "energy err", {"integrator", "run"}, {"problem"}, false, true}};

  const auto primary = spec.measures.begin() + static_cast<long>(std::min(spec.ranked, spec.measures.size()));
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

  // Event times are against the problem's exact solution whatever the reference.
  const bool exact_times = primary != spec.measures.end() && is_event_time(*primary);
  // One ranked problem per sweep's problem: a joint refinement's problems are one (its family).
  std::vector<RankingProblem> ranking;
  std::vector<std::string> ranking_first;  // the label of each ranked problem's first problem
  for (const auto& p : spec.problems) {
    if (std::any_of(ranking.begin(), ranking.end(), [&](const RankingProblem& r) { return r.label == p.family_label(); })) continue;
    const FileReference* ref = spec.reference_of(p);
    ranking.push_back({p.family_label(), exact_times ? "the exact solution" : against_text(ref), exact_times || !ref ? 0.0 : ref->floor,
                       spec.targets, {}});
    ranking_first.push_back(p.label);
  }
  const auto ranked_index = [&](const FileProblem& p) {
    return static_cast<std::size_t>(std::find_if(ranking.begin(), ranking.end(), [&](const RankingProblem& r) { return r.label == p.family_label(); }) -
                                    ranking.begin());
  };
  // The first declared ranking's error column and runs' number format.
  const auto ranking_declared = std::find_if(spec.tables.begin(), spec.tables.end(), [](const FileTable& d) { return d.rows == "ranking"; });
  const std::optional<std::string> runs_format = ranking_declared == spec.tables.end() ? std::nullopt : ranking_declared->runs_format;
  // The columns only declared tables show: work counters, and each error's order against the
  // run before it (the previous step or tolerance of the same sweep).
  std::vector<Column> counters = {{"factorizations", "", "", ""}, {"LCP its", "", "", "LCP iterations"}};
  for (const auto& m : spec.measures)
    if (measure_converges(m)) counters.push_back({"pairwise order of " + m.label, "", "{:.2f}", "against the previous run of the sweep"});
  counters.insert(counters.end(), run_columns().begin(), run_columns().end());
  const std::vector<Column> own = study_run_columns(spec), work = sweep_work_columns(spec);
  counters.insert(counters.end(), own.begin(), own.end());
  counters.insert(counters.end(), work.begin(), work.end());
  std::vector<std::vector<Cell>> counter_rows;
  std::vector<std::size_t> case_row(cases.size());  // each case's row in t
  for (const std::vector<std::size_t>& sweep : sweep_runs(spec, cases)) {
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
                             status == "ok" ? status : status + ": " + r["message"].get<std::string>()});
      case_row[k] = t.rows.size();
      t.add_row(std::move(row));
      const auto count = [&](const char* key) { return r.contains(key) ? Cell{r[key].get<long>()} : Cell{}; };
      std::vector<Cell> more = {count("factorizations"), count("lcp_iterations")};
      for (std::size_t m = 0; m < spec.measures.size(); ++m) {
        if (!measure_converges(spec.measures[m])) continue;
        const std::size_t i = xs.size() - 1;
        const auto e = [&](std::size_t j) { return is_event_time(spec.measures[m]) ? ys[m][j] : above_round_off(ys[m][j]); };
        more.push_back(i ? number_cell(observed_order(xs[i - 1], e(i - 1), xs[i], e(i))) : Cell{});
      }
      const std::vector<Cell> run = run_cells(spec, cases[k], r), study = study_run_cells(spec, cases[k], r),
                              work = sweep_work_cells(spec, r);
      more.insert(more.end(), run.begin(), run.end());
      more.insert(more.end(), study.begin(), study.end());
      more.insert(more.end(), work.begin(), work.end());
      counter_rows.push_back(std::move(more));
      // A declined run is no point; a run an outcome threshold removed (its values kept: energy
      // blow-up, penetration) names the rule; one without values (diverged, over budget) has no error.
      if (primary != spec.measures.end() && status != "n/a")
        curve.points.push_back({run_label(cases[k], runs_format), real_or_nan(r, "cpu"), ys[primary - spec.measures.begin()].back(),
                                status != "ok" && r.contains("values") ? status : ""});
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
  const auto runs = std::find_if(spec.tables.begin(), spec.tables.end(), [](const FileTable& d) { return d.rows == "case"; });
  const std::string runs_id = runs == spec.tables.end() ? t.id : runs->id;  // where the ranked errors are shown
  std::optional<Table> rank;
  if (primary != spec.measures.end()) {
    for (std::size_t r = ranking.size(); r-- > 0;)
      if (!primary->applies_to(ranking_first[r])) ranking.erase(ranking.begin() + static_cast<long>(r));
    Column error{primary->label, is_event_time(*primary) ? "s" : "", "{:.1e}", primary->label + " of " + runs_id};
    if (ranking_declared != spec.tables.end() && ranking_declared->error) error = declared_column(error, *ranking_declared->error);
    rank = ranking_table(spec.name + "_ranking", spec.title + ": cheapest integrator at each target error", error, cpu, ranking);
    rank->metadata = meta;
  }
  std::vector<Table> tables;
  if (!spec.tables.empty()) {
    Table runs_all = t;  // and the columns only declared tables show
    runs_all.columns.insert(runs_all.columns.end(), counters.begin(), counters.end());
    for (std::size_t r = 0; r < runs_all.rows.size(); ++r)
      runs_all.rows[r].insert(runs_all.rows[r].end(), counter_rows[r].begin(), counter_rows[r].end());
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
  if (!history.rows.empty()) tables.push_back(history);
  return tables;
}

}  // namespace

namespace {

std::vector<std::string> column_names(const std::vector<Column>& columns) {
  std::vector<std::string> names;
  for (const auto& c : columns) names.push_back(c.name);
  return names;
}

}  // namespace

const std::vector<std::string>& run_column_names() {
  static const std::vector<std::string> names = column_names(run_columns());
  return names;
}

const std::vector<std::string>& history_column_names() {
  static const std::vector<std::string> names = column_names(history_columns());
  return names;
}

std::vector<std::string> sweep_work_column_names(const StudySpec& spec) { return column_names(sweep_work_columns(spec)); }

const std::vector<std::string>& samples_column_names() {
  static const std::vector<std::string> names = column_names(samples_columns());
  return names;
}

const std::vector<std::string>& periodic_column_names() {
  static const std::vector<std::string> names = column_names(periodic_columns());
  return names;
}

const std::vector<std::string>& trajectory_column_names() {
  static const std::vector<std::string> names = column_names(trajectory_columns());
  return names;
}

const std::vector<std::string>& flights_column_names() {
  static const std::vector<std::string> names = column_names(flights_columns());
  return names;
}

const std::vector<std::string>& impulses_column_names() {
  static const std::vector<std::string> names = column_names(impulses_columns());
  return names;
}

const std::vector<std::string>& field_column_names() {
  static const std::vector<std::string> names = column_names(field_columns());
  return names;
}

std::vector<std::string> parameter_column_names(const StudySpec& spec) {
  std::vector<std::string> names;
  for (const auto& p : spec.problems)
    for (const auto& s : find_problem(p.name).parameters())
      if (std::find(names.begin(), names.end(), "parameter " + s.name) == names.end()) names.push_back("parameter " + s.name);
  return names;
}

StudyEntry file_study(const StudySpec& spec) {
  StudyEntry e;
  e.name = spec.name;
  e.description = fmt::format("{} (study file {}, FNV-1a 64 {})", spec.title, spec.file, spec.hash);
  e.cases = [spec](const StudyOptions& options) { return file_cases(spec, options.full); };
  e.run_case = [spec](const Json& c) { return run_file_case(spec, c); };
  e.tables = [spec](const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions&) {
    return file_tables(spec, cases, with_next_run_estimates(spec, cases, results));
  };
  return e;
}

void write_study_copy(const StudySpec& spec, const std::filesystem::path& out) {
  ensure_directory(out);
  const std::string ext = std::filesystem::path(spec.file).extension() == ".json" ? "json" : "toml";
  write_file_atomic(out / fmt::format("{}.study.{}", spec.name, ext), spec.text);
  write_file_atomic(out / fmt::format("{}.study.hash", spec.name), fmt::format("FNV-1a 64 {}  {}\n", spec.hash, spec.file));
}

std::vector<std::string> run_study_file(const StudySpec& spec, const std::filesystem::path& out) {
  const StudyEntry study = file_study(spec);
  const StudyOptions options{false};
  const std::vector<Json> cases = study_cases(study, options);
  const auto results = parallel_map<Json>(cases.size(), [&](std::size_t k) { return run_study_case(study, cases[k], options); },
                                          study.name);
  const auto tables = study_tables(study, cases, results, options);
  claim_output_directory(out, "out");  // a directory the suite did not write is refused
  ReportDirectory report(out, "out");
  const ReportIndex index(false, report.path());
  index.add_study(study, tables);
  write_study_copy(spec, report.path());
  index.write();
  report.commit();
  std::vector<std::string> ids;
  for (const auto& t : tables) ids.push_back(t.id);
  return ids;
}

}  // namespace nsb
