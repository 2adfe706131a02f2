// Reading a problem's own keys (steps, outcome thresholds, end time, grid) and a reference.
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "problems/exact_solution.hpp"

namespace nsb::study_files {

namespace {

// A cached reference run's own end time (reference.t_end, FileReference::t_end): at or past the
// end of every problem it serves (`served`), so that a run whose steps do not divide t_end, and
// whose last step ends past it, is compared with the reference at that step's end.
double read_reference_end(const Checker& c, const Json& v, const std::string& path, const StudySpec& spec,
                          const std::vector<std::size_t>& served) {
  const double t_end = c.positive(v, path);
  for (const std::size_t i : served)
    if (const FileProblem& p = spec.problems[i]; t_end < spec.t_end_of(p))
      c.fail(path, fmt::format("{} is before the end of problem '{}' ({} s)", t_end, p.label, spec.t_end_of(p)),
             "t_end >= the t_end of every problem the reference serves");
  return t_end;
}

// A problem's grid = { key = [values], ... }: one problem per point of the product of the
// lists (keys in alphabetical order, the last varying fastest), each with the base parameters
// and its point's, labelled "label, key = value, ..."; no grid: the problem itself.
constexpr std::size_t kMaxGridPoints = 1000;

}  // namespace

// A problem's steps and full_steps, or stable_steps (checked against its stable step once it
// exists): the sweep of every integrator that gives none of its own.
void read_problem_steps(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileProblem& p) {
  const std::string whose = p.t_end > 0.0 ? fmt::format("the t_end of problem '{}'", p.label) : "study.t_end";
  for (const char* key : {"steps", "full_steps"}) {
    const Json* v = c.find(j, key);
    if (!v) continue;
    std::vector<double>& steps = std::string(key) == "steps" ? p.steps : p.full_steps;
    steps = c.distinct_list(*v, child(path, key));
    for (std::size_t k = 0; k < steps.size(); ++k) check_step(c, steps[k], element(child(path, key), k), spec.t_end_of(p), whose);
  }
  if (!p.full_steps.empty() && p.steps.empty())
    c.fail(child(path, "full_steps"), "full_steps without steps", "steps = [dt, ...] beside it (full_steps: the sweep under --full)");
  if (const Json* v = c.find(j, "stable_steps")) {
    if (!p.steps.empty()) c.fail(path, "give one of steps or stable_steps", "one sweep per problem");
    p.stable_fractions = stable_fractions(c, *v, child(path, "stable_steps"));
  }
}

// A reference: the study's [reference] or a problem's own (`path`), checked against the problems
// it serves (their indices in spec.problems and instances).
FileReference read_reference(const Checker& c, const Json& r, const std::string& path, const StudySpec& spec,
                             const std::vector<std::size_t>& served, const std::vector<std::unique_ptr<Problem>>& instances) {
  c.expect(r, path, r.is_object(), "a table");
  c.keys(r, path, {"solution", "integrator", "parameters", "dt", "sample_every", "floor", "lockstep", "against", "t_end"});
  FileReference ref;
  if (!c.find(r, "solution") == !c.find(r, "integrator")) c.fail(path, "give one of solution = \"exact\" or integrator = NAME");
  if (const Json* v = c.find(r, "solution")) {
    c.choice(*v, child(path, "solution"), {"exact"});
    for (const std::size_t i : served)
      if (const ExactSolution* exact = instances[i]->exact(); !exact || !exact->state(0.0))
        c.fail(child(path, "solution"), fmt::format("problem '{}' ({}) has no exact solution", spec.problems[i].label, spec.problems[i].name),
               "integrator = a reference integrator");
  } else {
    ref.exact = false;
    ref.integrator = c.registered(r["integrator"], child(path, "integrator"), names_of(integrator_registry()), "integrator");
    if (const Json* v = c.find(r, "parameters"))
      ref.parameters = c.parameters(*v, child(path, "parameters"), find_integrator(ref.integrator).parameters());
    if (const Json* v = c.find(r, "lockstep")) ref.lockstep = c.boolean(*v, child(path, "lockstep"));
  }
  if (ref.exact && c.find(r, "lockstep"))
    c.fail(child(path, "lockstep"), "only a reference integrator steps with the runs", "integrator = NAME with lockstep = true");
  if (ref.lockstep) {
    for (const char* key : {"dt", "sample_every", "t_end"})
      if (c.find(r, key)) c.fail(child(path, key), "a lockstep reference steps with each run, at its steps", "no dt, sample_every or t_end with lockstep = true");
  } else if (ref.exact && c.find(r, "t_end")) {
    c.fail(child(path, "t_end"), "the exact solution has no end time", "integrator = NAME with t_end");
  } else if (!ref.exact) {
    ref.dt = c.positive(c.require(r, path, "dt"), child(path, "dt"));
    if (const Json* v = c.find(r, "t_end")) ref.t_end = read_reference_end(c, *v, child(path, "t_end"), spec, served);
    double longest = ref.t_end;
    for (const std::size_t i : served) {
      const FileProblem& p = spec.problems[i];
      check_step(c, ref.dt, child(path, "dt"), spec.t_end_of(p), p.t_end > 0.0 ? fmt::format("the t_end of problem '{}'", p.label) : "study.t_end");
      longest = std::max(longest, spec.t_end_of(p));
    }
    if (const Json* v = c.find(r, "sample_every")) ref.sample_every = c.integer(*v, child(path, "sample_every"), 1, 1L << 40);
    check_held_samples(c, ref.dt, ref.sample_every, longest, child(path, "dt"), "the reference run", child(path, "sample_every"));
  }
  if (const Json* v = c.find(r, "floor")) {
    c.expect(*v, child(path, "floor"), v->is_number(), "a number");
    ref.floor = v->get<double>();
    if (!(ref.floor >= 0.0) || !std::isfinite(ref.floor))
      c.fail(child(path, "floor"), fmt::format("{} is not a finite number >= 0", ref.floor), "[0, inf)");
  }
  if (const Json* v = c.find(r, "against")) ref.against = c.string(*v, child(path, "against"));
  return ref;
}

// A measure's time window [t0, t1] at `at`, checked against the end of each problem of `on`.
std::pair<double, double> read_window(const Checker& c, const Json& v, const std::string& at, const StudySpec& spec,
                                      const std::vector<std::size_t>& on) {
  c.expect(v, at, v.is_array() && v.size() == 2 && v[0].is_number() && v[1].is_number(),
           "an array [t0, t1] of two numbers, or a table of them by problem label");
  const double t0 = v[0].get<double>(), t1 = v[1].get<double>();
  if (!(t0 >= 0.0 && t0 < t1 && std::isfinite(t1))) c.fail(at, fmt::format("[{}, {}] is no time window", t0, t1), "0 <= t0 < t1, finite");
  for (const std::size_t p : on)
    if (!(t0 < spec.t_end_of(spec.problems[p])))
      c.fail(at, fmt::format("the window starts at {} s, not before the end of problem '{}' ({} s)", t0, spec.problems[p].label,
                             spec.t_end_of(spec.problems[p])),
             "t0 < t_end, or problems = [...]");
  return {t0, t1};
}

// refine = KEY (one of the grid's keys): a joint refinement along KEY, each problem's family
// its label without KEY's value (FileProblem::family).
std::vector<FileProblem> grid_points(const Checker& c, const Json& j, const std::string& path, const FileProblem& base,
                                     const ParamSpecs& specs) {
  std::vector<FileProblem> points{base};
  const Json* grid = c.find(j, "grid");
  const Json* refine = c.find(j, "refine");
  if (refine && !(grid && grid->is_object() && grid->contains(c.string(*refine, child(path, "refine")))))
    c.fail(child(path, "refine"), "not a key of the problem's grid", "refine = KEY with grid = { KEY = [values, ...], ... }");
  if (refine) points.front().family = base.label;
  if (!grid) return points;
  const std::string at = child(path, "grid");
  c.expect(*grid, at, grid->is_object() && !grid->empty(), "a table of parameter = [values, ...]");
  double product = 1.0;  // from the lists' lengths, before any point is built (a 1,000 x 4,000 grid took 1.5 GB)
  for (const auto& [key, values] : grid->items()) {
    c.expect(values, child(at, key), values.is_array() && !values.empty(), "an array of one or more values");
    product *= static_cast<double>(values.size());
  }
  if (product > static_cast<double>(kMaxGridPoints))
    c.fail(at, fmt::format("{:.0f} problems in the grid (the product of its lists' lengths)", product),
           fmt::format("at most {} points", kMaxGridPoints));
  for (const auto& [key, values] : grid->items()) {
    const std::string key_path = child(at, key);
    if (base.parameters.count(key)) c.fail(key_path, "also given in parameters", "each parameter in one of parameters and grid");
    std::vector<FileProblem> next;
    for (const FileProblem& point : points)
      for (std::size_t i = 0; i < values.size(); ++i) {
        const Overrides one = c.parameters(Json{{key, values[i]}}, at, specs);
        FileProblem q = point;
        q.parameters[key] = one.at(key);
        q.label += fmt::format(", {} = {}", key, one.at(key));
        if (!q.family.empty() && key != refine->get<std::string>()) q.family += fmt::format(", {} = {}", key, one.at(key));
        next.push_back(q);
      }
    points = std::move(next);
  }
  return points;
}

// A problem's own outcome thresholds and energy scale (energy_blow_up, max_penetration,
// energy_scale) and whether only --full (full_only) or only a run without it (default_only) runs it.
void read_problem_outcome(const Checker& c, const Json& j, const std::string& path, FileProblem& p) {
  if (const Json* v = c.find(j, "energy_blow_up")) p.energy_blow_up = c.positive(*v, child(path, "energy_blow_up"));
  if (const Json* v = c.find(j, "max_penetration")) p.max_penetration = c.positive(*v, child(path, "max_penetration"));
  if (const Json* v = c.find(j, "energy_scale")) p.energy_scale = c.positive(*v, child(path, "energy_scale"));
  if (const Json* v = c.find(j, "full_only")) p.full_only = c.boolean(*v, child(path, "full_only"));
  if (const Json* v = c.find(j, "default_only")) p.default_only = c.boolean(*v, child(path, "default_only"));
  if (p.full_only && p.default_only)
    c.fail(child(path, "default_only"), "full_only and default_only both: the problem would never run", "at most one of them true");
  if (const Json* v = c.find(j, "full_t_end")) {
    if (p.default_only) c.fail(child(path, "full_t_end"), "a default_only problem has no run under --full", "no full_t_end with default_only");
    p.full_t_end = c.positive(*v, child(path, "full_t_end"));
  }
  if (const Json* v = c.find(j, "min_flight")) p.min_flight = c.positive(*v, child(path, "min_flight"));
}

// end_at_impact = n: the problem's t_end is the exact time of its n-th impact (`instance`: the problem).
void read_end_at_impact(const Checker& c, const Json& j, const std::string& path, const Problem& instance, FileProblem& p) {
  const Json* v = c.find(j, "end_at_impact");
  if (!v) return;
  const std::string at = child(path, "end_at_impact");
  if (c.find(j, "t_end") || c.find(j, "full_t_end")) c.fail(at, "the run's end given twice", "one of t_end (with full_t_end) or end_at_impact");
  const long n = c.integer(*v, at, 1, 1000);
  const auto times = instance.exact() ? instance.exact()->impact_times(std::numeric_limits<double>::infinity()) : std::vector<double>{};
  if (static_cast<std::size_t>(n) > times.size())
    c.fail(at, fmt::format("problem '{}' knows {} exact impact times", p.label, times.size()),
           times.empty() ? "problems with known impacts (bouncing-mass)" : fmt::format("[1, {}]", times.size()));
  p.t_end = times[static_cast<std::size_t>(n) - 1];
}

// t_end_exact = { NAME = factor, ..., plus = seconds }: the problem's t_end is the sum of each
// factor times the exact solution's event time or value NAME (ExactEvent, ExactValue: e.g.
// contact_start, slip_stop, rest, contact_duration, wave_time; impact_K: its K-th impact time), then plus
// (`instance`: the problem; a horizon set by the solution's own events, per problem).
void read_t_end_exact(const Checker& c, const Json& j, const std::string& path, const Problem& instance, FileProblem& p) {
  const Json* v = c.find(j, "t_end_exact");
  if (!v) return;
  const std::string at = child(path, "t_end_exact");
  if (c.find(j, "t_end") || c.find(j, "full_t_end") || c.find(j, "end_at_impact"))
    c.fail(at, "the run's end given twice", "one of t_end (with full_t_end), end_at_impact or t_end_exact");
  c.expect(*v, at, v->is_object() && !v->empty(), "a table of exact time or value = factor (and plus = seconds)");
  static const std::vector<std::pair<std::string, ExactEvent>> events{{"contact_start", ExactEvent::contact_start},
                                                                      {"slip_stop", ExactEvent::slip_stop},
                                                                      {"rest", ExactEvent::rest},
                                                                      {"roll_onset", ExactEvent::roll_onset},
                                                                      {"jam", ExactEvent::jam}};
  static const std::vector<std::pair<std::string, ExactValue>> values{{"contact_duration", ExactValue::contact_duration},
                                                                      {"stop_distance", ExactValue::stop_distance},
                                                                      {"wave_time", ExactValue::wave_time}};
  const ExactSolution* exact = instance.exact();
  const std::vector<double> impacts = exact ? exact->impact_times(std::numeric_limits<double>::infinity()) : std::vector<double>{};
  std::vector<std::string> known;  // what this problem's exact solution gives
  for (const auto& [name, e] : events)
    if (exact && exact->event_time(e)) known.push_back(name);
  for (const auto& [name, w] : values)
    if (exact && exact->value(w)) known.push_back(name);
  if (!impacts.empty()) known.push_back(fmt::format("impact_1 .. impact_{}", impacts.size()));
  const std::string valid = fmt::format("{}{}plus", fmt::join(known, ", "), known.empty() ? "" : ", ");
  double t_end = 0.0;
  for (const auto& [name, factor] : v->items()) {
    if (name == "plus") continue;
    const std::string key = child(at, name);
    c.expect(factor, key, factor.is_number(), "a number (the factor)");
    std::optional<double> time;
    if (const auto e = std::find_if(events.begin(), events.end(), [&](const auto& x) { return x.first == name; }); exact && e != events.end())
      time = exact->event_time(e->second);
    else if (const auto w = std::find_if(values.begin(), values.end(), [&](const auto& x) { return x.first == name; });
             exact && w != values.end())
      time = exact->value(w->second);
    else if (std::size_t k = 0; name.rfind("impact_", 0) == 0 && std::from_chars(name.data() + 7, name.data() + name.size(), k).ptr ==
                                                                        name.data() + name.size() && k >= 1 && k <= impacts.size())
      time = impacts[k - 1];  // impact_K: digits only, in [1, the impacts known]
    if (!time || !std::isfinite(*time))
      c.fail(key, fmt::format("problem '{}' has no exact time or value '{}'", p.label, name), valid);
    t_end += factor.get<double>() * *time;
  }
  if (const Json* plus = c.find(*v, "plus")) {
    c.expect(*plus, child(at, "plus"), plus->is_number(), "a number of seconds");
    t_end += plus->get<double>();
  }
  if (!(t_end > 0.0) || !std::isfinite(t_end)) c.fail(at, fmt::format("t_end = {} on problem '{}'", t_end, p.label), "a sum > 0");
  p.t_end = t_end;
}

// The end time of the longest run: the bound of the series held in memory.
double longest_t_end(const StudySpec& spec) {
  double t = spec.t_end;
  for (const auto& p : spec.problems) t = std::max(t, spec.t_end_of(p));
  return t;
}

}  // namespace nsb::study_files
