// The observables of a run's state, and what a run records (studies/study_file/run_recorders.hpp).
#include "studies/study_file/run_recorders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "integrators/registry.hpp"
#include "problems/contact_gaps.hpp"
#include "problems/problem_output.hpp"
#include "studies/study_file/engine.hpp"

namespace nsb::study_files {

ReferenceRequest reference_request(const StudySpec& spec, const FileProblem& p) {
  const FileReference& r = *spec.reference_of(p);
  return {p.name, p.parameters, r.integrator, r.parameters, r.dt, r.t_end > 0.0 ? r.t_end : spec.t_end_of(p), r.sample_every};
}

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

// Observables of a state: the problem's own or the run driver's generic kinetic, potential,
// total_energy, min_gap (series columns of run/run.hpp). `energy`: the scheme's own
// (Integrator::energy), else v^T M v / 2 + V(u).
double state_observable(const Problem& problem, const SpMat& M, const State& s, const Vec& impulses, double dt,
                        const std::string& name, ObservableBuffer& buffer, const Energy* energy) {
  const auto& names = problem.observable_names();
  if (const auto k = std::find(names.begin(), names.end(), name); k != names.end()) {
    return buffer.of(problem, s, impulses, dt)[k - names.begin()];
  }
  if (name == "min_gap") return ContactGaps(problem).min_at(s.u);
  const Energy e = energy ? *energy : Energy{0.5 * s.v.dot(M * s.v), problem.potential(s.u)};
  return name == "kinetic" ? e.kinetic : name == "potential" ? e.potential : e.total();
}

std::optional<double> exact_observable(const Problem& problem, const SpMat& M, double t, const std::string& name,
                                       ObservableBuffer& buffer) {
  if (const auto value = problem.exact()->observable(name, t)) return value;
  const std::optional<State> exact = problem.exact()->state(t);
  if (!exact) return std::nullopt;
  return state_observable(problem, M, *exact, Vec::Zero(problem.ncontacts()), 0.0, name, buffer, nullptr);
}

// The observable of an event measure after a step of length dt (impact-count has none: 0).
double event_observable(const Problem& problem, const SpMat& M, const Integrator& it, double dt, const FileMeasure& m,
                        ObservableBuffer& buffer, const Energy& energy) {
  if (m.kind == MeasureKind::ImpactCount || m.kind == MeasureKind::Summary) return 0.0;
  return state_observable(problem, M, it.state(), it.impulses(), dt, m.observable, buffer, &energy);
}

// A run that never started: declined by the scheme (its reason), or the lockstep reference
// itself; its figures those of the initial state (no step, no energy scale).
Json not_run(const std::string& why) {
  return {{"status", kDeclinedStatus}, {"message", why}, {"steps", 0}, {"force_evaluations", 0}, {"factorizations", 0}, {"lcp_iterations", 0},
          {"run", {{"t_reached", 0.0}, {"impacts", 0}, {"switches", nullptr}, {"missed_switches", nullptr}, {"max_penetration", 0.0},
                   {"energy_growth", 0.0}, {"final_energy_error", 0.0}, {"energy_scale", 0.0}, {"note", why}}}};
}

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

Reference::Reference(const StudySpec& spec, const Problem& problem, const SpMat& M, const FileProblem& fp)
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
  if (run_.summary["status"] != status_name(RunStatus::Ok) || run_.series.rows() == 0)
    throw InputError(fmt::format("reference {} on {} failed: {} {}", ref.integrator, fp.label,
                                 run_.summary["status"].dump(), run_.summary["message"].dump()));
  t_ = run_.series.column("t");
}

double Reference::observable(double t, const std::string& name, ObservableBuffer& buffer) const {
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

Polyline Reference::graph(const std::string& name, double t_end, ObservableBuffer& buffer) const {
  if (exact_) {
    const Vec none = Vec::Zero(problem_.ncontacts());
    return exact_graph(problem_, [&](const State& s) { return state_observable(problem_, M_, s, none, 0.0, name, buffer, nullptr); }, t_end);
  }
  Polyline g;
  const std::size_t col = run_.series.column(name);
  for (std::size_t k = 0; k < run_.series.rows(); ++k) g.add(run_.series.at(k, t_), run_.series.at(k, col));
  return g;
}

EnergyGrowth::EnergyGrowth(const Problem& problem, const State& initial, double e0)
    : problem_(problem), e0_(e0), u_prev_(initial.u), f_ext_(problem.ndof()) {
  const Vec& w = problem.contacts().tangent_velocity;
  if (w.size() && w.cwiseAbs().maxCoeff() > 0.0) obstacle_speed_ = w.cwiseAbs();
}

void EnergyGrowth::add(const Integrator& it, double dt, double energy) {
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

RunFigures::RunFigures(const Problem& problem, const StudySpec& spec, const FileProblem& fp, double t_end, double e0, double e_scale)
    : problem_(problem), spec_(spec), e0_(e0), e_scale_(e_scale), t_end_(t_end), impacts_(fp.min_flight),
      history_(t_end, spec.history_intervals, 2),
      momentum_history_(t_end, spec.history_intervals, 1), keeps_history_(shows(spec, fp, "history", "")),
      keeps_momentum_(shows(spec, fp, "history", "momentum residual")), keeps_samples_(shows(spec, fp, "samples", "")) {}

void RunFigures::add(const Integrator& it, double dt, const MomentumBalance& momentum, double energy) {
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

Json RunFigures::result(const RunResult& r, double energy_growth) {
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

bool RunFigures::shows(const StudySpec& spec, const FileProblem& fp, const std::string& rows, const std::string& column) {
  return std::any_of(spec.tables.begin(), spec.tables.end(), [&](const FileTable& t) {
    return t.rows == rows && t.applies_to(fp.label) &&
           (column.empty() || std::any_of(t.columns.begin(), t.columns.end(), [&](const FileColumn& c) { return c.of == column; }));
  });
}

EventFigures::EventFigures(const FileMeasure& m, const Problem& problem, double value0)
    : m_(m), problem_(problem), geometry_(problem.contact_geometry()),
      impacts_(gaps(problem.initial_state().u), value0), largest_(value0), smallest_(value0), last_(value0) {
  add(0.0, Vec::Zero(problem.ncontacts()), problem.initial_state().u, value0);
}

void EventFigures::add(double t, const Vec& impulses, const Vec& u, double value) {
  if (t > 0.0) impacts_.add(t, impulses, gaps(u), value);
  above_ = std::abs(value) > m_.threshold;
  if (above_) last_above_ = t;
  if (std::isnan(peak_t_) || value > largest_) peak_t_ = t;
  largest_ = std::max(largest_, value);
  smallest_ = std::min(smallest_, value);
  last_ = value;
}

double EventFigures::result(const Problem& problem) const {
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

double EventFigures::exact_time(const Problem& problem, double (*closed_form)(const Problem&)) const {
  return m_.summary.empty() ? closed_form(problem) : summary_value(problem, m_.summary);
}

const Vec& EventFigures::gaps(const Vec& u) {
  problem_.evaluate_contacts(u, geometry_);
  return geometry_.gap;
}

RunSeries::RunSeries(const StudySpec& spec, const FileProblem& fp, double t_end, const Problem& problem, const SpMat& M, const Integrator& it,
          ObservableBuffer& buffer, const Energy& energy0)
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

void RunSeries::add(const Problem& problem, const SpMat& M, const Integrator& it, double dt, ObservableBuffer& buffer, const Energy& energy) {
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

void RunSeries::write(const std::vector<const std::vector<double>*>& periodic, Json& run) const {
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

RunImpulsesAndFields::RunImpulsesAndFields(const StudySpec& spec, const FileProblem& fp, const FileIntegrator& fi, const Problem& problem,
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

void RunImpulsesAndFields::add(const Problem& problem, const Integrator& it) {
  const double t = it.state().t;
  for (Bins& b : bins_) {
    const auto j = static_cast<std::size_t>(std::ceil(t / dt_ - 1e-9));  // (t_j - dt, t_j] holds t
    if (b.impulses.size() <= j) b.impulses.resize(j + 1, 0.0);
    b.impulses[j] += it.impulses().sum();
  }
  add_fields(problem, it.state());
}

void RunImpulsesAndFields::write(Json& run) const {
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

void RunImpulsesAndFields::add_fields(const Problem& problem, const State& s) {
  if (fields_.empty()) return;
  problem.cell_stress(s.u, stress_);
  for (Field& f : fields_) {
    f.t.push_back(s.t);
    f.values.insert(f.values.end(), stress_.col(f.component).begin(), stress_.col(f.component).end());
  }
}

}  // namespace nsb::study_files
