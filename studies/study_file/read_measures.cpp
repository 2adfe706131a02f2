// Reading the keys of each kind of [[measure]], checked against the problems it is measured on.
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "problems/exact_solution.hpp"
#include "studies/measures.hpp"

namespace nsb::study_files {

namespace {

// A measure's required observable of the state: one of every problem `on`'s own, or kinetic,
// potential, total_energy, min_gap (a problem with contacts).
void read_state_observable(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                           const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  m.observable = c.string(c.require(j, path, "observable"), child(path, "observable"));
  for (const std::size_t p : on) {
    check_observable(c, child(path, "observable"), m.observable, state_observable_names(*instances[p]), spec.problems[p].label, "",
                     "name the problems it is measured on: problems = [...]");
  }
}

// `summary` (kind summary, or rest-time, peak-time and rest-start with exact = true) into `m`: the name of
// a summary value every problem `on` has (Problem::summary_values); as an exact time, finite.
void read_summary_name(const Checker& c, const Json& j, const std::string& path, const std::string& kind, FileMeasure& m,
                       const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                       const std::vector<std::size_t>& on) {
  const Json* v = kind == "summary" ? &c.require(j, path, "summary") : c.find(j, "summary");
  if (!v) return;
  m.summary = c.string(*v, child(path, "summary"));
  if (kind != "summary" && !m.exact) c.fail(child(path, "summary"), "an exact time needs exact = true", "exact = true, or no summary");
  for (const std::size_t p : on) {
    std::vector<std::string> valid;
    for (const auto& [name, value] : instances[p]->summary_values()) valid.push_back(name);
    const double value = summary_value(*instances[p], m.summary);
    if (std::find(valid.begin(), valid.end(), m.summary) == valid.end())
      c.fail(child(path, "summary"), fmt::format("'{}' is not a summary value of problem '{}'", m.summary, spec.problems[p].label),
             fmt::format("{} (or problems = [...])", valid.empty() ? std::string("none: the problem has no summary values") : fmt::format("{}", fmt::join(valid, ", "))));
    if (kind != "summary" && !std::isfinite(value))
      c.fail(child(path, "summary"), fmt::format("summary value '{}' of problem '{}' is not a finite time ({})", m.summary, spec.problems[p].label, value),
             "a problem whose event happens (e.g. a sphere that rolls), or problems = [...]");
  }
}

}  // namespace

// An impact-time or flight-energy measure's min_flight_steps (FileMeasure::min_flight_steps).
void read_min_flight_steps(const Checker& c, const Json& j, const std::string& path, FileMeasure& m) {
  if (const Json* v = c.find(j, "min_flight_steps"))
    m.min_flight_steps = static_cast<int>(c.integer(*v, child(path, "min_flight_steps"), 1, 1000000));
}

// A flight-energy measure's count and norm (max or count), checked against the exact impacts of
// the problems it is measured on (`on`): count + 1 of them by the end of each.
void read_flight_energy(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec,
                        const std::vector<std::size_t>& on, const std::vector<std::unique_ptr<Problem>>& instances, FileMeasure& m) {
  m.count = static_cast<int>(c.integer(c.require(j, path, "count"), child(path, "count"), 1, 999));
  m.norm = "max";
  if (const Json* v = c.find(j, "norm")) m.norm = c.choice(*v, child(path, "norm"), {"max", "count"});
  read_min_flight_steps(c, j, path, m);
  if (const Json* v = c.find(j, "at"))
    m.at_mid_flight_step = c.choice(*v, child(path, "at"), {"exact mid-flight", "mid-flight step"}) == "mid-flight step";
  for (const std::size_t p : on) {
    const double t_end = spec.t_end_of(spec.problems[p]);
    const ExactSolution* exact = instances[p]->exact();
    const std::size_t known = exact ? std::min(exact->impact_times(t_end).size(), exact->energies_after_impacts(t_end).size()) : 0;
    if (known < static_cast<std::size_t>(m.count) + 1)
      c.fail(child(path, "count"), fmt::format("problem '{}' knows {} exact impacts and energies by t_end, not count + 1 = {}",
                                               spec.problems[p].label, known, m.count + 1),
             "problems with known impacts and energies (bouncing-mass), a later t_end or end_at_impact, or problems = [...]");
  }
  m.label = m.norm == "count" ? "flights compared" : "flight energy err";
}

// A momentum measure's component (MeshMomentum): one every problem `on` has (a mesh of its
// dimension; jx, jy, jz in 3D); no window or relative_to (its own scale).
void read_momentum_component(const Checker& c, const Json& j, const std::string& path, const Json& v, FileMeasure& m,
                             const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                             const std::vector<std::size_t>& on) {
  const std::string at = child(path, "component");
  m.component = c.choice(v, at, {"px", "py", "pz", "jx", "jy", "jz"});
  for (const char* key : {"window", "relative_to"})
    if (c.find(j, key)) c.fail(child(path, key), "not with component (the identity over every step, relative to its own scale)", "no " + std::string(key));
  for (const std::size_t p : on) {
    const auto valid = MeshMomentum::components(*instances[p]);
    if (std::find(valid.begin(), valid.end(), m.component) == valid.end())
      c.fail(at, fmt::format("problem '{}' has no mesh component {}", spec.problems[p].label, m.component),
             valid.empty() ? std::string("a problem with a field mesh, or problems = [...]") : fmt::format("{} (or problems = [...])", fmt::join(valid, ", ")));
  }
  m.label += " " + m.component;
}

// Fails at `at` unless `name` is one of `valid`, the observables of problem `label` (`detail`:
// which of them, e.g. those its reference run records; `instead`: what else the file can say).
void check_observable(const Checker& c, const std::string& at, const std::string& name, const std::vector<std::string>& valid,
                      const std::string& label, const std::string& detail, const std::string& instead) {
  if (std::find(valid.begin(), valid.end(), name) == valid.end())
    c.fail(at, fmt::format("'{}' is not an observable of problem '{}'{}", name, label, detail),
           fmt::format("{} (or {})", fmt::join(valid, ", "), instead));
}

// The observables of a problem's state (state_observable): its own, kinetic, potential,
// total_energy and, with contacts, min_gap.
std::vector<std::string> state_observable_names(const Problem& problem) {
  std::vector<std::string> valid = problem.observable_names();
  valid.insert(valid.end(), {"kinetic", "potential", "total_energy"});
  if (problem.ncontacts() > 0) valid.push_back("min_gap");
  return valid;
}

// kind = "estimate": the observable (required: one of the problem's own, or kinetic, potential,
// total_energy, min_gap) compared with the next run of the sweep, and the error law's `order`
// (nonzero, finite).
void read_next_run_estimate(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                            const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  read_state_observable(c, j, path, m, spec, instances, on);
  if (const Json* v = c.find(j, "order")) {
    c.expect(*v, child(path, "order"), v->is_number(), "a number");
    m.order = v->get<double>();
    if (m.order == 0.0 || !std::isfinite(m.order))
      c.fail(child(path, "order"), fmt::format("{} is no order of an error law x^q", m.order), "a finite nonzero number (e.g. -0.5: error ~ k^-1/2)");
  }
  m.label = fmt::format("est {}", m.observable);
}

// An error measure's `against`: it and the measured observable both the problem's own
// observables (not u, v or the generic columns), the two distinct.
void check_against(const Checker& c, const std::string& path, const FileMeasure& m, const std::vector<std::string>& names,
                   const std::string& label) {
  for (const auto& [key, o] : {std::pair{"observable", m.observable}, std::pair{"against", m.against}})
    check_observable(c, child(path, key), o, names, label);
  if (m.observable == m.against) c.fail(child(path, "against"), "the observable itself", "its exact column, e.g. o_exact");
}

// An error's `inside` (FileMeasure::inside) into `m`: an observable of every problem `on`, which
// has an exact solution to evaluate it at t - dt and t + dt.
void read_inside_phase(const Checker& c, const Json& v, const std::string& path, FileMeasure& m, const StudySpec& spec,
                       const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  m.inside = c.string(v, path);
  for (const std::size_t p : on) {
    if (!instances[p]->exact())
      c.fail(path, fmt::format("problem '{}' has no exact solution to find where '{}' is positive", spec.problems[p].label, m.inside),
             "problems with an exact solution (or problems = [...])");
    check_observable(c, path, m.inside, instances[p]->observable_names(), spec.problems[p].label);
  }
}

// A chatter or zero-steps measure (an observable's values at consecutive steps: `observable`,
// required, one of the problem's; `scale` > 0; `inside` an exact phase) or a contact-duration
// (`exact`: against the problem's exact contact duration, which it must know) into `m`.
void read_step_values_measure(const Checker& c, const Json& j, const std::string& path, const std::string& kind, FileMeasure& m,
                              const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                              const std::vector<std::size_t>& on) {
  if (kind == "contact-duration") {
    if (const Json* v = c.find(j, "exact")) m.exact = c.boolean(*v, child(path, "exact"));
    for (const std::size_t p : on)
      if (m.exact && !(instances[p]->exact() && instances[p]->exact()->value(ExactValue::contact_duration)))
        c.fail(child(path, "exact"), fmt::format("problem '{}' knows no exact contact duration", spec.problems[p].label),
               "problems that know it (signorini-bar), exact = false, or problems = [...]");
    m.label = m.exact ? "contact duration err" : "contact duration";
    return;
  }
  m.observable = c.string(c.require(j, path, "observable"), child(path, "observable"));
  for (const std::size_t p : on)
    check_observable(c, child(path, "observable"), m.observable, instances[p]->observable_names(), spec.problems[p].label);
  if (const Json* v = c.find(j, "scale")) m.scale = c.positive(*v, child(path, "scale"));
  if (const Json* v = c.find(j, "inside")) read_inside_phase(c, *v, child(path, "inside"), m, spec, instances, on);
  m.label = fmt::format("{} {}", kind == "chatter" ? "chatter" : "zero steps", m.observable);
}

// A rest-start measure (FileMeasure::rest) into `m`: its bounds rest = [{ observable, abs,
// at_most, dt_power }, ...], each observable one every problem `on` has (its own or kinetic,
// potential, total_energy, min_gap), min_rest, and with exact = true the exact time, a finite
// summary value of each problem.
void read_rest_start(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                     const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  c.keys(j, path, {"kind", "label", "problems", "rest", "min_rest", "exact", "summary"});
  const std::string at = child(path, "rest");
  const Json& rest = c.require(j, path, "rest");
  c.expect(rest, at, rest.is_array() && !rest.empty(), "an array of one or more { observable, abs, at_most, dt_power }");
  for (std::size_t k = 0; k < rest.size(); ++k) {
    const std::string bp = element(at, k);
    const Json& b = rest[k];
    c.expect(b, bp, b.is_object(), "a table { observable, abs, at_most, dt_power }");
    c.keys(b, bp, {"observable", "abs", "at_most", "dt_power"});
    FileMeasure::RestBound bound;
    bound.observable = c.string(c.require(b, bp, "observable"), child(bp, "observable"));
    if (const Json* v = c.find(b, "abs")) bound.abs = c.boolean(*v, child(bp, "abs"));
    bound.at_most = c.positive(c.require(b, bp, "at_most"), child(bp, "at_most"));
    if (const Json* v = c.find(b, "dt_power")) bound.dt_power = static_cast<int>(c.integer(*v, child(bp, "dt_power"), 0, 4));
    for (const std::size_t p : on)
      check_observable(c, child(bp, "observable"), bound.observable, state_observable_names(*instances[p]), spec.problems[p].label);
    m.rest.push_back(bound);
  }
  if (const Json* v = c.find(j, "min_rest")) m.min_rest = c.positive(*v, child(path, "min_rest"));
  if (const Json* v = c.find(j, "exact")) m.exact = c.boolean(*v, child(path, "exact"));
  read_summary_name(c, j, path, "rest-start", m, spec, instances, on);
  if (m.exact && m.summary.empty())
    c.fail(child(path, "exact"), "the exact start of a rest is a summary value of the problem", "summary = NAME (e.g. t_zeno_exact)");
  m.label = m.exact ? "err rest start" : "rest start";
}

namespace {

// The closed form each problem of an event measure must have (its law, exact amplitude or
// time, and as many exact impacts as it compares).
void check_event_closed_forms(const Checker& c, const std::string& path, const std::string& kind, const FileMeasure& m,
                              const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                              const std::vector<std::size_t>& on) {
  for (const std::size_t p : on) {
    const Problem& problem = *instances[p];
    const bool rocking = !std::isnan(rocking_law_ratio(problem, ImpactLaw::housner));
    if ((!m.law.empty() || (m.exact && kind != "peak-time" && m.summary.empty())) && !rocking)
      c.fail(child(path, m.law.empty() ? "exact" : "law"), fmt::format("problem '{}' has no closed-form impacts", spec.problems[p].label),
             "rocking-block problems, or problems = [...]");
    if (rocking && m.law == "moreau" && std::isnan(rocking_law_ratio(problem, ImpactLaw::moreau)))
      c.fail(child(path, "law"),
             fmt::format("problem '{}' has no Moreau ratio of a rocking approach (mu below mu_H: its pivot slides before theta = 0)",
                         spec.problems[p].label),
             "law = \"housner\", a block with mu >= mu_H, or problems = [...]");
    const auto last = static_cast<std::size_t>(std::max(m.impact, m.count));
    if (rocking && (!m.law.empty() || (m.exact && kind == "amplitude")) && last > rocking_exact_impacts(problem))
      c.fail(child(path, m.count > 0 ? "count" : "impact"),
             fmt::format("the exact solution of problem '{}' has {} impact(s) (it leaves rocking or rests)", spec.problems[p].label,
                         rocking_exact_impacts(problem)),
             fmt::format("1..{}, or problems = [...]", rocking_exact_impacts(problem)));
    if (!m.summary.empty()) continue;  // its exact time checked by read_summary_name
    if (m.exact && kind == "rest-time" && !std::isfinite(rocking_rest_time(problem)))
      c.fail(child(path, "exact"), fmt::format("problem '{}' does not come to rest", spec.problems[p].label),
             "a rocking block that comes to rest (e = 0), or problems = [...]");
    if (m.exact && kind == "peak-time" && std::isnan(painleve_jam_time(problem)))
      c.fail(child(path, "exact"), fmt::format("problem '{}' has no exact dynamic jam", spec.problems[p].label),
             "painleve-rod problems whose sliding phase ends in a jam, or problems = [...]");
  }
}

// An event measure's default label, from its kind, observable and keys.
std::string event_measure_label(const std::string& kind, const FileMeasure& m) {
  const std::string o = m.observable;
  return kind == "impact-ratio" ? (m.law.empty()   ? fmt::format("{} ratio at impact {}", o, m.impact)
                                   : m.count > 0   ? fmt::format("{} ratio err {}, impacts 1..{}", o, m.law, m.count)
                                                   : fmt::format("{} ratio err {} at impact {}", o, m.law, m.impact))
         : kind == "amplitude"  ? fmt::format("{}amplitude of {} after impact {}", m.exact ? "rel err " : "", o, m.impact)
         : kind == "impact-count" ? std::string("impacts per contact")
         : kind == "rest-time"  ? fmt::format("{} time |{}| <= {:g}", m.exact ? "err rest" : "rest", o, m.threshold)
         : kind == "peak-time"  ? fmt::format("{}time of max {}", m.exact ? "err " : "", o)
         : kind == "summary"    ? m.summary
                                : fmt::format("{} {}", o, m.norm);
}

}  // namespace

// The measures of an observable's events (impact-ratio, amplitude, impact-count, rest-time,
// peak-time, value) into `m`: their keys, the observable of every problem `on`, and for `law`
// or `exact` the problem's closed form (studies/measures.hpp).
void read_event_measure(const Checker& c, const Json& j, const std::string& path, const std::string& kind, FileMeasure& m,
                        const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                        const std::vector<std::size_t>& on) {
  const std::map<std::string, std::vector<std::string>> own{
      {"impact-ratio", {"observable", "impact", "count", "law"}}, {"amplitude", {"observable", "impact", "exact"}},
      {"impact-count", {}}, {"rest-time", {"observable", "threshold", "exact", "summary"}},
      {"peak-time", {"observable", "exact", "summary"}}, {"value", {"observable", "norm"}}, {"summary", {"summary"}}};
  std::vector<std::string> keys = own.at(kind);
  keys.insert(keys.end(), {"kind", "label", "problems"});
  c.keys(j, path, keys);
  if (kind != "impact-count" && kind != "summary") read_state_observable(c, j, path, m, spec, instances, on);
  if (const Json* v = c.find(j, "exact")) m.exact = c.boolean(*v, child(path, "exact"));
  read_summary_name(c, j, path, kind, m, spec, instances, on);
  if (const Json* v = c.find(j, "law")) m.law = c.choice(*v, child(path, "law"), {"housner", "moreau"});
  if (const Json* v = c.find(j, "impact")) m.impact = static_cast<int>(c.integer(*v, child(path, "impact"), 1, 1000000));
  m.count = 0;  // impact-time's default of 3 is not one here
  if (const Json* v = c.find(j, "count")) {
    if (c.find(j, "impact")) c.fail(child(path, "count"), "impact and count both given", "one of them");
    if (m.law.empty()) c.fail(child(path, "count"), "the largest difference over the first count impacts needs a law", "law = \"housner\" | \"moreau\"");
    m.count = static_cast<int>(c.integer(*v, child(path, "count"), 1, 1000000));
  } else if (m.impact == 0 && kind != "impact-count") {
    m.impact = 1;
  }
  if (kind == "rest-time") m.threshold = c.positive(c.require(j, path, "threshold"), child(path, "threshold"));
  m.norm = "final";
  if (const Json* v = c.find(j, "norm")) m.norm = c.choice(*v, child(path, "norm"), {"final", "max", "min"});
  check_event_closed_forms(c, path, kind, m, spec, instances, on);
  m.label = event_measure_label(kind, m);
}

// An error's semi_discrete, dof and per_nominal_step (FileMeasure): against the same
// semi-discrete problem solved exactly, the displacement of the dof `dof` (required, in [0, n - 1]
// for every problem it is measured on, n its dofs), with no `against` or observable of its own.
void read_semi_discrete(const Checker& c, const Json& j, const std::string& path, FileMeasure& m,
                        const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  if (const Json* v = c.find(j, "per_nominal_step")) m.per_nominal_step = c.boolean(*v, child(path, "per_nominal_step"));
  if (const Json* v = c.find(j, "semi_discrete")) m.semi_discrete = c.boolean(*v, child(path, "semi_discrete"));
  if (!m.semi_discrete) {
    if (c.find(j, "dof")) c.fail(child(path, "dof"), "only a semi-discrete error compares one dof's displacement", "semi_discrete = true beside it");
    return;
  }
  for (const char* key : {"against", "observable"})
    if (c.find(j, key))
      c.fail(child(path, key), "a semi-discrete error compares one dof's displacement with modal-exact's",
             "no against or observable with semi_discrete = true (dof = INDEX)");
  long last = std::numeric_limits<long>::max();
  for (const std::size_t p : on) last = std::min(last, static_cast<long>(instances[p]->ndof()) - 1);
  m.dof = c.integer(c.require(j, path, "dof"), child(path, "dof"), 0, last);
}

// study.rank_by: the label of a measure the ranking can rank by; by default the first error.
std::size_t ranked_measure(const Checker& c, const Json& study, const std::vector<FileMeasure>& measures) {
  std::vector<std::string> valid;
  for (const auto& m : measures)
    if (m.rankable()) valid.push_back(m.label);
  const Json* v = c.find(study, "rank_by");
  if (!v) {
    const auto first = std::find_if(measures.begin(), measures.end(), [](const FileMeasure& m) { return m.kind == MeasureKind::Error; });
    return static_cast<std::size_t>(first - measures.begin());
  }
  const std::string label = c.string(*v, "study.rank_by");
  const auto named = std::find_if(measures.begin(), measures.end(), [&](const FileMeasure& m) { return m.label == label; });
  if (named == measures.end())
    c.fail("study.rank_by", fmt::format("'{}' names no measure (nearest: {})", label, nearest_name(label, valid)),
           fmt::format("the label of a measure: {}", fmt::join(valid, ", ")));
  if (!named->rankable())
    c.fail("study.rank_by", fmt::format("measure '{}' is signed (an energy error's final value or drift): not an error to rank by", label),
           fmt::format("{}", fmt::join(valid, ", ")));
  return static_cast<std::size_t>(named - measures.begin());
}

// An energy measure's norm, history and sampling: every step, or with `every` (> 0) at the first
// step past each from + k every (from >= 0; norms count, first, final, drift against k; no
// window or history).
void read_energy_sampling(const Checker& c, const Json& j, const std::string& path, FileMeasure& m) {
  if (const Json* v = c.find(j, "every")) {
    m.every = c.positive(*v, child(path, "every"));
    for (const char* key : {"window", "history"})
      if (c.find(j, key)) c.fail(child(path, key), "an energy sampled every period has no window or history", "one of every or window/history");
    if (const Json* f = c.find(j, "from")) {
      c.expect(*f, child(path, "from"), f->is_number(), "a number");
      m.from = f->get<double>();
      if (!(m.from >= 0.0) || !std::isfinite(m.from)) c.fail(child(path, "from"), fmt::format("{} is no start time", m.from), "[0, inf)");
    }
    m.norm = "final";
    if (const Json* v = c.find(j, "norm")) m.norm = c.choice(*v, child(path, "norm"), {"count", "first", "final", "drift"});
    m.label = fmt::format("energy err {}, every {:g} from {:g}", m.norm, m.every, m.from);
    return;
  }
  if (c.find(j, "from")) c.fail(child(path, "from"), "from without every", "every = T beside it");
  if (const Json* v = c.find(j, "norm")) m.norm = c.choice(*v, child(path, "norm"), {"max", "final", "final abs", "drift", "offset"});
  if (const Json* v = c.find(j, "history")) m.history = c.boolean(*v, child(path, "history"));
  m.label = fmt::format("energy err {}", m.norm);
}

}  // namespace nsb::study_files
