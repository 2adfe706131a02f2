// Reading the [[measure]] list: each measure's kind, problems, window and label, and the keys of
// errors, Hausdorff distances, impact times and stop times (the other kinds: read_measures.cpp).
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "studies/slip_stop.hpp"

namespace nsb::study_files {

namespace {

// The measures' kinds, in the order of MeasureKind.
const std::vector<std::string>& measure_kinds() {
  static const std::vector<std::string> kinds{"error",        "impact-time", "energy",      "momentum",     "penetration",
                                              "hausdorff",    "stop-time",   "onset-time",  "flight-energy", "rest-start", "estimate", "chatter",
                                              "zero-steps",   "contact-duration", "impact-ratio",
                                              "amplitude",    "impact-count", "rest-time",  "peak-time",    "value",
                                              "summary"};
  return kinds;
}

// The keys every kind of measure takes, and its own.
void measure_keys(const Checker& c, const Json& j, const std::string& path, std::vector<std::string> own) {
  own.insert(own.end(), {"kind", "label", "problems"});
  c.keys(j, path, own);
}

// A Hausdorff distance's keys.
void read_hausdorff_keys(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                         const std::vector<std::size_t>& on) {
  measure_keys(c, j, path, {"observable", "time_scale", "value_scale", "norm"});
  // An observable, or one per problem (by label, or a joint refinement's by its family
  // label: each problem it is measured on named).
  if (const Json& o = c.require(j, path, "observable"); o.is_object()) {
    const std::string at = child(path, "observable");
    std::vector<std::string> labels;
    for (const std::size_t p : on)
      for (const std::string& label : {spec.problems[p].label, spec.problems[p].family_label()})
        if (std::find(labels.begin(), labels.end(), label) == labels.end()) labels.push_back(label);
    c.keys(o, at, labels);
    for (const std::size_t p : on) {
      const FileProblem& fp = spec.problems[p];
      const std::string& key = o.contains(fp.label) ? fp.label : fp.family_label();
      m.problem_observables[fp.label] = c.string(c.require(o, at, key), child(at, key));
    }
    m.observable.clear();
  } else {
    m.observable = c.string(o, child(path, "observable"));
  }
  m.norm = "distance";
  if (const Json* v = c.find(j, "norm"))
    m.norm = c.choice(*v, child(path, "norm"), {"distance", "to reference", "from reference", "max error", "value scale"});
  if (const Json* v = c.find(j, "time_scale")) m.time_scale = c.positive(*v, child(path, "time_scale"));
  if (const Json* v = c.find(j, "value_scale")) m.value_scale = c.positive(*v, child(path, "value_scale"));
}

// An error's own keys.
void read_error_keys(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                     const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  measure_keys(c, j, path, {"observable", "norm", "window", "relative_to", "against", "scale", "inside", "semi_discrete", "dof", "per_nominal_step"});
  read_semi_discrete(c, j, path, m, instances, on);
  if (const Json* v = c.find(j, "against")) m.against = c.string(*v, child(path, "against"));
  if (const Json* v = c.find(j, "relative_to"))
    m.scale_over_run = c.choice(*v, child(path, "relative_to"), {"window", "run"}) == "run";
  if (const Json* v = c.find(j, "scale")) {
    m.scale = c.positive(*v, child(path, "scale"));
    if (c.find(j, "relative_to")) c.fail(child(path, "scale"), "a fixed scale and relative_to both say what the error is relative to", "one of them");
  }
  if (const Json* v = c.find(j, "inside")) read_inside_phase(c, *v, child(path, "inside"), m, spec, instances, on);
}

// An error or a Hausdorff distance: its keys, its reference and observable on each problem it
// is measured on, its label.
void read_error_or_hausdorff(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                             const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  const bool hausdorff = m.kind == MeasureKind::Hausdorff;
  if (hausdorff)
    read_hausdorff_keys(c, j, path, m, spec, on);
  else
    read_error_keys(c, j, path, m, spec, instances, on);
  for (const std::size_t p : on) {
    const FileReference* ref = spec.reference_of(spec.problems[p]);
    if (!ref && m.against.empty() && !m.semi_discrete) c.fail(path, fmt::format("{} needs a [reference]", hausdorff ? "a Hausdorff distance" : "an error"),
                     "[reference] solution = \"exact\" or integrator = NAME (or the problem's own reference = { ... })");
    if (hausdorff && ref->lockstep)
      c.fail(path, "a Hausdorff distance needs the reference's whole graph, which a lockstep reference does not keep",
             "[reference] solution = \"exact\" or a cached integrator (lockstep = false)");
  }
  if (const Json* v = c.find(j, "norm"); v && !hausdorff) m.norm = c.choice(*v, child(path, "norm"), {"final", "max", "l2", "rms", "step rms", "l2 in time"});
  if (const Json* v = c.find(j, "observable"); v && !hausdorff) m.observable = c.string(*v, child(path, "observable"));
  for (const std::size_t p : on) {
    if (m.semi_discrete) continue;  // modal-exact's displacement of its dof
    if (!m.against.empty()) {
      check_against(c, path, m, instances[p]->observable_names(), spec.problems[p].label);
      continue;
    }
    const FileReference& ref = *spec.reference_of(spec.problems[p]);
    std::vector<std::string> valid = state_observable_names(*instances[p]);
    if ((ref.exact || ref.lockstep) && !hausdorff) {  // the state's u and v (a problem's own v: its observable)
      if (std::find(valid.begin(), valid.end(), "v") == valid.end()) valid.insert(valid.begin(), "v");
      valid.insert(valid.begin(), "u");
    }
    const std::string& observable = m.observable_for(spec.problems[p].label);
    const std::string at = m.problem_observables.empty() ? child(path, "observable") : child(child(path, "observable"), spec.problems[p].label);
    check_observable(c, at, observable, valid, spec.problems[p].label, ref.exact ? "" : " recorded by its reference run",
                     "name the problems it is measured on: problems = [...]");
  }
  const std::string graph = m.observable.empty() ? "hausdorff" : fmt::format("hausdorff {}", m.observable);  // "": per problem
  m.label = hausdorff           ? (m.norm == "distance" ? graph : fmt::format("{} {}", graph, m.norm))
            : m.against.empty() ? fmt::format("err {} {}", m.observable, m.norm)
                                : fmt::format("err {} {} against {}", m.observable, m.norm, m.against);
  if (m.semi_discrete) m.label = fmt::format("err u[{}] {} against the semi-discrete solution", m.dof, m.norm);
}

void read_impact_time(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                      const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  measure_keys(c, j, path, {"count", "located", "min_flight_steps", "norm"});
  if (const Json* v = c.find(j, "count")) m.count = static_cast<int>(c.integer(*v, child(path, "count"), 1, 1000));
  if (const Json* v = c.find(j, "located")) m.located = c.boolean(*v, child(path, "located"));
  if (const Json* v = c.find(j, "norm")) m.norm = c.choice(*v, child(path, "norm"), {"max", "count"});
  read_min_flight_steps(c, j, path, m);
  if (m.located && (m.min_flight_steps > 0 || m.norm == "count"))
    c.fail(child(path, "located"), "located impacts are compared by rank, all of the first count",
           "located = true without min_flight_steps and norm = \"count\"");
  for (const std::size_t p : on)
    if (!instances[p]->exact() || instances[p]->exact()->impact_times(spec.t_end_of(spec.problems[p])).empty())
      c.fail(child(path, "kind"), fmt::format("problem '{}' knows no impact times before t_end", spec.problems[p].label),
             "problems with known impacts (bouncing-mass, rolling-disk dropped from h0 > 0), or problems = [...]");
  m.label = m.norm == "count" ? "impacts compared" : "impact time err";
}

// stop-time, onset-time: on problems with an exact stop (rolling onset) by t_end.
void read_stop_time(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                    const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on) {
  measure_keys(c, j, path, {});
  const bool onset = m.kind == MeasureKind::OnsetTime;
  for (const std::size_t p : on) {
    const ExactStop exact = exact_stop(*instances[p]);
    if (exact.rolling != onset || !(exact.stop_time <= spec.t_end_of(spec.problems[p])))
      c.fail(child(path, "kind"), fmt::format("problem '{}' has no exact {} by t_end", spec.problems[p].label,
                                              onset ? "rolling onset" : "stop time"),
             onset ? "rolling-disk problems that roll by t_end, or problems = [...]"
                   : "sliding-mass problems that stop by t_end (mu > tan alpha, or v0 < 0), or problems = [...]");
  }
  m.label = onset ? "onset time err" : "stop time err";
}

// window = [t0, t1], or a window per problem (by label).
void read_measure_window(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                         const std::vector<std::string>& problem_labels, const std::vector<std::size_t>& on) {
  const Json* v = c.find(j, "window");
  if (!v) return;
  const std::string at = child(path, "window");
  if (v->is_object()) {  // a window per problem, by label
    c.keys(*v, at, problem_labels);
    for (const auto& [label, w] : v->items()) {
      if (!m.applies_to(label)) c.fail(child(at, label), fmt::format("the measure is not measured on problem '{}'", label), "the problems it is measured on");
      const auto p = static_cast<std::size_t>(std::find(problem_labels.begin(), problem_labels.end(), label) - problem_labels.begin());
      m.problem_windows[label] = read_window(c, w, child(at, label), spec, {p});
    }
    m.label += ", a window per problem";
  } else {
    std::tie(m.window_start, m.window_end) = read_window(c, *v, at, spec, on);
    m.label += fmt::format(", t in [{:g}, {:g}]", m.window_start, m.window_end);
  }
}

// [[measure]] j: its kind, the problems it is measured on, its kind's keys, its window and label.
FileMeasure read_measure(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec,
                         const std::vector<std::unique_ptr<Problem>>& instances) {
  const std::vector<std::string>& kinds = measure_kinds();
  std::vector<std::string> problem_labels;
  for (const auto& p : spec.problems) problem_labels.push_back(p.label);
  FileMeasure m;
  const std::string kind = c.choice(c.require(j, path, "kind"), child(path, "kind"), kinds);
  m.kind = static_cast<MeasureKind>(std::find(kinds.begin(), kinds.end(), kind) - kinds.begin());
  if (const Json* v = c.find(j, "problems")) {
    const std::string at = child(path, "problems");
    c.expect(*v, at, v->is_array() && !v->empty(), "an array of one or more problem labels");
    for (std::size_t k = 0; k < v->size(); ++k) m.problems.push_back(c.choice((*v)[k], element(at, k), problem_labels));
  }
  // The problems it is measured on: their index in spec.problems.
  std::vector<std::size_t> on;
  for (std::size_t p = 0; p < instances.size(); ++p)
    if (m.applies_to(spec.problems[p].label)) on.push_back(p);
  if (m.kind >= MeasureKind::ImpactRatio) {
    read_event_measure(c, j, path, kind, m, spec, instances, on);
  } else if (m.kind == MeasureKind::Error || m.kind == MeasureKind::Hausdorff) {
    read_error_or_hausdorff(c, j, path, m, spec, instances, on);
  } else if (m.kind == MeasureKind::ImpactTime) {
    read_impact_time(c, j, path, m, spec, instances, on);
  } else if (m.kind == MeasureKind::StopTime || m.kind == MeasureKind::OnsetTime) {
    read_stop_time(c, j, path, m, spec, instances, on);
  } else if (m.kind == MeasureKind::Energy) {
    measure_keys(c, j, path, {"norm", "history", "window", "every", "from", "relative_to"});
    if (const Json* v = c.find(j, "relative_to"))
      m.from_first_step = c.choice(*v, child(path, "relative_to"), {"initial", "first step"}) == "first step";
    read_energy_sampling(c, j, path, m);
    if (m.from_first_step && m.norm == "offset")
      c.fail(child(path, "relative_to"), "the offset is E_1 - E0 relative to E0's scale", "relative_to = \"initial\" with norm = \"offset\"");
  } else if (m.kind == MeasureKind::Chatter || m.kind == MeasureKind::ZeroSteps || m.kind == MeasureKind::ContactDuration) {
    measure_keys(c, j, path, m.kind == MeasureKind::ContactDuration ? std::vector<std::string>{"exact"} : std::vector<std::string>{"observable", "scale", "inside"});
    read_step_values_measure(c, j, path, kind, m, spec, instances, on);
  } else if (m.kind == MeasureKind::Estimate) {
    measure_keys(c, j, path, {"observable", "order"});
    read_next_run_estimate(c, j, path, m, spec, instances, on);
  } else if (m.kind == MeasureKind::RestStart) {
    read_rest_start(c, j, path, m, spec, instances, on);
  } else if (m.kind == MeasureKind::FlightEnergy) {
    read_flight_energy(c, j, path, spec, on, instances, m);
    measure_keys(c, j, path, {"count", "norm", "min_flight_steps", "at"});
  } else {
    measure_keys(c, j, path, kind == "momentum" ? std::vector<std::string>{"window", "relative_to", "component"} : std::vector<std::string>{});
    if (const Json* v = c.find(j, "relative_to"))
      m.initial_speeds_scale = c.choice(*v, child(path, "relative_to"), {"momentum", "initial speeds"}) == "initial speeds";
    m.label = kind == "momentum" ? "momentum residual" : "penetration";
    if (const Json* v = c.find(j, "component")) read_momentum_component(c, j, path, *v, m, spec, instances, on);
  }
  read_measure_window(c, j, path, m, spec, problem_labels, on);
  if (const Json* v = c.find(j, "label")) m.label = c.string(*v, child(path, "label"));
  for (const auto& q : spec.measures)
    if (q.label == m.label) c.fail(path, fmt::format("a second measure labelled '{}'", m.label), "distinct labels (label = ...)");
  return m;
}

}  // namespace

void read_measures(const Checker& c, const Json& root, StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances) {
  // A study of declared tables may show its runs' own figures alone (outcome, steps, histories).
  const Json& measures = c.find(root, "measure") || !c.find(root, "table") ? required_tables(c, root, "measure") : Json::array();
  for (std::size_t i = 0; i < measures.size(); ++i) spec.measures.push_back(read_measure(c, measures[i], element("measure", i), spec, instances));
}

}  // namespace nsb::study_files
