// The observables of a run's state, and what a run records besides its classes
// (studies/study_file/run_recorders.hpp).
#include "studies/study_file/run_recorders.hpp"

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

std::optional<double> exact_observable(const Problem& problem, const SpMat& M, double t, const std::string& name,
                                       std::span<double> buffer) {
  if (const auto value = problem.exact()->observable(name, t)) return value;
  const std::optional<State> exact = problem.exact()->state(t);
  if (!exact) return std::nullopt;
  return state_observable(problem, M, *exact, Vec::Zero(problem.ncontacts()), 0.0, name, buffer, nullptr);
}

// The observable of an event measure after a step of length dt (impact-count has none: 0).
double event_observable(const Problem& problem, const SpMat& M, const Integrator& it, double dt, const FileMeasure& m,
                        std::span<double> buffer, const Energy& energy) {
  if (m.kind == MeasureKind::ImpactCount || m.kind == MeasureKind::Summary) return 0.0;
  return state_observable(problem, M, it.state(), it.impulses(), dt, m.observable, buffer, &energy);
}

// A run that never started: declined by the scheme (its reason), or the lockstep reference
// itself; its figures those of the initial state (no step, no energy scale).
Json not_run(const std::string& why) {
  return {{"status", "n/a"}, {"message", why}, {"steps", 0}, {"force_evaluations", 0}, {"factorizations", 0}, {"lcp_iterations", 0},
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

}  // namespace nsb::study_files
