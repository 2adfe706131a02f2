// Reading and checking a study file (schema: studies/study_file.hpp, README.md). TOML and JSON
// are both read into one JSON tree with the line of each key path, then checked against the
// schema here, so both formats give the same errors: "FILE:LINE: key.path: what; valid: ...".
#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <numeric>
#include <set>
#include <sstream>
#include <toml++/toml.h>

#include "core/output.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "studies/measures.hpp"
#include "studies/report_text.hpp"
#include "studies/slip_stop.hpp"
#include "studies/study_file.hpp"

namespace nsb {

namespace {

using Lines = std::map<std::string, long>;

// A study file is a page of text; anything larger is not one (/dev/zero, a data file given by mistake).
constexpr std::size_t kMaxStudyFileBytes = 1 << 20;

std::string child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string element(const std::string& path, std::size_t i) { return fmt::format("{}[{}]", path, i); }

void toml_to_json(const toml::node& node, const std::string& path, Json& out, Lines& lines) {
  if (node.source().begin.line) lines.emplace(path, node.source().begin.line);
  if (const auto* t = node.as_table()) {
    out = Json::object();
    for (const auto& [k, v] : *t) {
      const std::string p = child(path, std::string(k.str()));
      if (k.source().begin.line) lines[p] = k.source().begin.line;
      toml_to_json(v, p, out[std::string(k.str())], lines);
    }
  } else if (const auto* a = node.as_array()) {
    out = Json::array();
    for (std::size_t i = 0; i < a->size(); ++i) toml_to_json((*a)[i], element(path, i), out[i], lines);
  } else if (const auto* s = node.as_string()) {
    out = s->get();
  } else if (const auto* i = node.as_integer()) {
    out = i->get();
  } else if (const auto* f = node.as_floating_point()) {
    out = f->get();
  } else if (const auto* b = node.as_boolean()) {
    out = b->get();
  } else {
    out = Json::object({{"<date or time>", true}});  // no such value in the schema: a wrong type
  }
}

// JSON gives no positions: the line of a key path is found by looking for each of its keys
// in turn, from where the previous one was found.
long json_line(const std::string& text, const std::string& path) {
  std::size_t pos = 0;
  std::stringstream parts(path);
  for (std::string part; std::getline(parts, part, '.');) {
    const std::string key = part.substr(0, part.find('['));
    const std::size_t at = text.find("\"" + key + "\"", pos);
    if (at != std::string::npos) pos = at;
  }
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
}

// JSON allows a key twice in one object (the last wins); TOML does not, and neither does a
// study file: a parser callback that fails on the second occurrence.
Json::parser_callback_t duplicate_key_check(const std::string& text, const std::string& file) {
  auto open = std::make_shared<std::vector<std::set<std::string>>>();
  return [open, &text, &file](int, Json::parse_event_t event, Json& parsed) {
    if (event == Json::parse_event_t::object_start) open->emplace_back();
    if (event == Json::parse_event_t::object_end) open->pop_back();
    if (event == Json::parse_event_t::key && !open->empty() && !open->back().insert(parsed.get<std::string>()).second) {
      const std::string key = parsed.get<std::string>(), quoted = Json(key).dump();
      const std::size_t first = text.find(quoted), second = first == std::string::npos ? first : text.find(quoted, first + 1);
      const long line = second == std::string::npos ? 0 : 1 + static_cast<long>(std::count(text.begin(), text.begin() + static_cast<long>(second), '\n'));
      throw InputError(fmt::format("{}:{}: key '{}' given twice in one table; valid: each key once", file, line, key));
    }
    return true;
  };
}

std::string type_name(const Json& j) {
  if (j.is_object()) return "a table";
  if (j.is_array()) return "an array";
  if (j.is_string()) return "a string";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number_integer()) return "an integer";
  return "a number";
}

class Checker {
 public:
  Checker(std::string file, Lines lines, const std::string* json_text)
      : file_(std::move(file)), lines_(std::move(lines)), json_text_(json_text) {}

  [[noreturn]] void fail(const std::string& path, const std::string& what, const std::string& valid = "") const {
    throw InputError(fmt::format("{}:{}: {}: {}{}", file_, line(path), path, what, valid.empty() ? "" : "; valid: " + valid));
  }

  // Fails on a key of `obj` not in `valid`, naming the nearest valid one.
  void keys(const Json& obj, const std::string& path, const std::vector<std::string>& valid) const {
    for (const auto& [k, v] : obj.items())
      if (std::find(valid.begin(), valid.end(), k) == valid.end())
        fail(child(path, k), fmt::format("unknown key (nearest valid key: {})", nearest_name(k, valid)),
             fmt::format("{}", fmt::join(valid, ", ")));
  }

  const Json* find(const Json& obj, const std::string& key) const {
    return obj.contains(key) ? &obj[key] : nullptr;
  }
  const Json& require(const Json& obj, const std::string& path, const std::string& key) const {
    if (!obj.contains(key)) fail(path, fmt::format("missing key '{}'", key));
    return obj[key];
  }
  void expect(const Json& j, const std::string& path, bool ok, const std::string& wanted) const {
    if (!ok) fail(path, fmt::format("expected {}, got {}", wanted, type_name(j)));
  }
  std::string string(const Json& j, const std::string& path) const {
    expect(j, path, j.is_string(), "a string");
    return j.get<std::string>();
  }
  double positive(const Json& j, const std::string& path) const {
    expect(j, path, j.is_number(), "a number");
    const double v = j.get<double>();
    if (!(v > 0.0) || !std::isfinite(v)) fail(path, fmt::format("{} is not positive and finite", v), "(0, inf)");
    return v;
  }
  long integer(const Json& j, const std::string& path, long lo, long hi) const {
    expect(j, path, j.is_number_integer(), "an integer");
    const long v = j.get<long>();
    if (v < lo || v > hi) fail(path, fmt::format("{} is out of range", v), fmt::format("[{}, {}]", lo, hi));
    return v;
  }
  bool boolean(const Json& j, const std::string& path) const {
    expect(j, path, j.is_boolean(), "a boolean");
    return j.get<bool>();
  }
  std::vector<double> positive_list(const Json& j, const std::string& path) const {
    expect(j, path, j.is_array(), "an array of positive numbers");
    if (j.empty()) fail(path, "empty list", "one or more positive numbers");
    std::vector<double> v;
    for (std::size_t i = 0; i < j.size(); ++i) v.push_back(positive(j[i], element(path, i)));
    return v;
  }
  // A sweep: positive, each value once (a repeated step is no new point of a convergence fit).
  std::vector<double> distinct_list(const Json& j, const std::string& path) const {
    const std::vector<double> v = positive_list(j, path);
    const std::string key = path.substr(path.rfind('.') + 1);
    for (std::size_t i = 1; i < v.size(); ++i)
      for (std::size_t k = 0; k < i; ++k)
        if (v[i] == v[k]) fail(element(path, i), fmt::format("{} repeats {}[{}]", v[i], key, k), "distinct values");
    return v;
  }
  std::string choice(const Json& j, const std::string& path, const std::vector<std::string>& valid) const {
    const std::string s = string(j, path);
    if (std::find(valid.begin(), valid.end(), s) == valid.end())
      fail(path, fmt::format("'{}' is not valid (nearest: {})", s, nearest_name(s, valid)), fmt::format("{}", fmt::join(valid, ", ")));
    return s;
  }
  // The name of a registered integrator or problem (`kind`); an unknown one may be a plugin's.
  std::string registered(const Json& j, const std::string& path, const std::vector<std::string>& valid,
                         const std::string& kind) const {
    const std::string s = string(j, path);
    if (std::find(valid.begin(), valid.end(), s) == valid.end())
      fail(path, fmt::format("'{}' is not valid (nearest: {})", s, nearest_name(s, valid)),
           fmt::format("{}; {}", fmt::join(valid, ", "), missing_plugin_hint(kind)));
    return s;
  }
  // A problem's or integrator's parameters, each checked against its declaration.
  Overrides parameters(const Json& j, const std::string& path, const ParamSpecs& specs) const {
    expect(j, path, j.is_object(), "a table of parameters");
    std::vector<std::string> names;
    for (const auto& s : specs) names.push_back(s.name);
    Overrides out;
    for (const auto& [k, v] : j.items()) {
      const std::string p = child(path, k);
      const auto spec = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& s) { return s.name == k; });
      if (spec == specs.end())
        fail(p, fmt::format("unknown parameter (nearest: {})", nearest_name(k, names)),
             names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", ")));
      expect(v, p, v.is_string() || v.is_number(), "a number or a string");
      const std::string text = v.is_string() ? v.get<std::string>() : v.dump();
      try {
        spec->validate(text);
      } catch (const InputError& e) {
        fail(p, e.what(), spec->range_text());
      }
      out[k] = text;
    }
    return out;
  }

 private:
  long line(std::string path) const {
    if (json_text_) return json_line(*json_text_, path);
    while (true) {
      if (const auto it = lines_.find(path); it != lines_.end()) return it->second;
      const auto cut = path.find_last_of(".[");
      if (cut == std::string::npos) return 1;
      path = path.substr(0, cut);
    }
  }
  std::string file_;
  Lines lines_;
  const std::string* json_text_;
};

std::vector<std::string> names_of(const auto& registry) {
  std::vector<std::string> names;
  for (const auto& e : registry) names.push_back(e.name);
  return names;
}

// The run driver's limits (run/run.cpp), checked here so that a study stops at its
// file's line before any run or any file is written.
void check_step(const Checker& c, double dt, const std::string& path, double t_end, const std::string& whose = "study.t_end") {
  const long limit = RunOptions{}.max_steps;
  if (dt > t_end) c.fail(path, fmt::format("dt = {:g} is larger than {} = {:g}", dt, whose, t_end), "dt <= t_end");
  if (t_end / dt > static_cast<double>(limit))
    c.fail(path, fmt::format("{} / dt = {:g} / {:g} = {:.3g} steps, more than a run's limit of {}", whose, t_end, dt, t_end / dt, limit),
           fmt::format("dt >= t_end / {} = {:g}", limit, t_end / static_cast<double>(limit)));
}

// A series held in memory whole (a reference run's samples; a run's graph for a Hausdorff
// distance) is bounded before any work: at most kMaxHeldSamples samples (1e7: 160 MB as a
// Hausdorff graph, 80 MB a column of a reference).
constexpr double kMaxHeldSamples = 1e7;

void check_held_samples(const Checker& c, double dt, long sample_every, double t_end, const std::string& path,
                        const std::string& what, const std::string& sample_key) {
  const auto samples = [&](double every) { return t_end / dt / every; };
  if (samples(static_cast<double>(sample_every)) > kMaxHeldSamples) {
    double least = std::ceil(samples(kMaxHeldSamples));  // the least sample_every that fits, to the rounding
    if (samples(least) > kMaxHeldSamples) ++least;
    c.fail(path, fmt::format("{} holds t_end / dt / sample_every = {:g} / {:g} / {} = {:.3g} samples in memory, more than the limit of {:g}",
                             what, t_end, dt, sample_every, samples(static_cast<double>(sample_every)), kMaxHeldSamples),
           fmt::format("{} >= {:.0f}", sample_key, least));
  }
}

// The steps of a sweep on one problem (`stable`: its stable step), against its end time.
void check_steps(const Checker& c, const FileSweep& s, const std::string& path, const StudySpec& spec, const FileProblem& p,
                 double stable) {
  const double t_end = spec.t_end_of(p);
  const std::string whose = p.t_end > 0.0 ? fmt::format("the t_end of problem '{}'", p.label) : "study.t_end";
  for (std::size_t i = 0; i < s.steps.size(); ++i) check_step(c, s.steps[i], element(child(path, "steps"), i), t_end, whose);
  for (std::size_t i = 0; i < s.full_steps.size(); ++i) check_step(c, s.full_steps[i], element(child(path, "full_steps"), i), t_end, whose);
  for (std::size_t i = 0; i < s.stable_fractions.size(); ++i)
    check_step(c, s.stable_fractions[i] * stable, element(child(path, "stable_steps"), i), t_end,
               fmt::format("{} (problem '{}', stable step {:g})", whose, p.label, stable));
  if (!s.tolerances.empty()) check_step(c, s.dt, child(path, "dt"), t_end, whose);
}

// A stiff part's stable step can be far below the step an implicit scheme takes (the hard
// study's 900 x CFL): a multiple up to 1000.
constexpr double kMaxStableFraction = 1000.0;

// stable_steps: dt as a multiple of the problem's stable step, (0, 1000].
std::vector<double> stable_fractions(const Checker& c, const Json& j, const std::string& path) {
  std::vector<double> v = c.distinct_list(j, path);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] > kMaxStableFraction)
      c.fail(element(path, i), fmt::format("{} stable steps is no step of a study", v[i]),
             fmt::format("(0, {:g}]: dt as a multiple of the problem's stable step 2 / omega_max", kMaxStableFraction));
  return v;
}

// tolerance_divisors = { atol = 100 }: real parameters of the integrator, other than the swept
// one, set with each tolerance to tolerance / divisor (divisor > 0; each value in its range).
void read_tolerance_divisors(const Checker& c, const Json& j, const std::string& path, const IntegratorEntry& entry, FileSweep& s) {
  const Json* v = c.find(j, "tolerance_divisors");
  if (!v) return;
  const std::string at = child(path, "tolerance_divisors");
  if (s.tolerances.empty()) c.fail(at, "divisors of a tolerance without a tolerance sweep", "tolerances = [...] beside it");
  c.expect(*v, at, v->is_object(), "a table of parameter = divisor");
  const auto specs = entry.parameters();
  std::vector<std::string> reals;
  for (const auto& p : specs)
    if (p.kind == ParamSpec::Kind::Real && p.name != s.tolerance_parameter) reals.push_back(p.name);
  c.keys(*v, at, reals);
  s.tolerance_divisors.clear();
  for (const auto& [name, d] : v->items()) {
    const double divisor = c.positive(d, child(at, name));
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& p) { return p.name == name; });
    for (double tol : s.tolerances) try {
        spec->validate(fmt::format("{}", tol / divisor));
      } catch (const InputError& e) {
        c.fail(child(at, name), fmt::format("tolerance {:g} / {:g}: {}", tol, divisor, e.what()), spec->range_text());
      }
    s.tolerance_divisors[name] = divisor;
  }
}

// An integrator's sweep (`base`: its own, under a per_problem table). Empty: the problems' steps
// serve it (sweep_from_problems).
FileSweep read_sweep(const Checker& c, const Json& j, const std::string& path, const IntegratorEntry& entry,
                     const FileSweep* base) {
  FileSweep s = base ? *base : FileSweep{};
  if (const Json* p = c.find(j, "parameters"))
    for (const auto& [k, v] : c.parameters(*p, child(path, "parameters"), entry.parameters())) s.parameters[k] = v;
  // A sweep given here replaces the base's (steps, stable_steps or tolerances).
  const auto given = [&](const char* key) { return c.find(j, key) != nullptr; };
  if (given("steps") || given("stable_steps") || given("tolerances")) {
    s.steps.clear();
    s.full_steps.clear();
    s.stable_fractions.clear();
    s.tolerances.clear();
  }
  if (const Json* v = c.find(j, "steps")) s.steps = c.distinct_list(*v, child(path, "steps"));
  if (const Json* v = c.find(j, "full_steps")) {
    if (!given("steps")) c.fail(child(path, "full_steps"), "full_steps without steps", "steps = [dt, ...] beside it (full_steps: the sweep under --full)");
    s.full_steps = c.distinct_list(*v, child(path, "full_steps"));
  }
  if (const Json* v = c.find(j, "stable_steps")) s.stable_fractions = stable_fractions(c, *v, child(path, "stable_steps"));
  if (const Json* v = c.find(j, "tolerances")) s.tolerances = c.distinct_list(*v, child(path, "tolerances"));
  if (const Json* v = c.find(j, "tolerance_parameter")) {
    std::vector<std::string> reals;
    for (const auto& p : entry.parameters())
      if (p.kind == ParamSpec::Kind::Real) reals.push_back(p.name);
    s.tolerance_parameter = c.choice(*v, child(path, "tolerance_parameter"), reals);
  }
  if (const Json* v = c.find(j, "dt")) s.dt = c.positive(*v, child(path, "dt"));
  if (!s.steps.empty() + !s.stable_fractions.empty() + !s.tolerances.empty() > 1)
    c.fail(path, "give one of steps, stable_steps or tolerances", "one sweep per integrator and problem");
  if (!s.tolerances.empty()) {
    if (!(s.dt > 0.0)) c.fail(path, "a tolerance sweep needs its step: dt = ...");
    const auto specs = entry.parameters();
    const auto spec = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& p) { return p.name == s.tolerance_parameter; });
    if (spec == specs.end())
      c.fail(child(path, "tolerances"), fmt::format("integrator '{}' has no parameter '{}'", entry.name, s.tolerance_parameter),
             "tolerance_parameter = one of its real parameters");
    for (std::size_t i = 0; i < s.tolerances.size(); ++i) try {
        spec->validate(fmt::format("{}", s.tolerances[i]));
      } catch (const InputError& e) {
        c.fail(element(child(path, "tolerances"), i), e.what(), spec->range_text());
      }
  }
  read_tolerance_divisors(c, j, path, entry, s);
  return s;
}

bool no_sweep(const FileSweep& s) { return s.steps.empty() && s.stable_fractions.empty() && s.tolerances.empty(); }

// Where an integrator (at `path`) gives no sweep of its own on a problem, the problem's steps
// (with the integrator's parameters); neither: an error.
void sweep_from_problems(const Checker& c, FileIntegrator& it, const std::string& path, const std::vector<FileProblem>& problems) {
  for (const FileProblem& p : problems) {
    if (!no_sweep(it.sweep_for(p.label))) continue;
    if (p.steps.empty() && p.stable_fractions.empty())
      c.fail(path, fmt::format("no sweep on problem '{}'", p.label),
             "steps = [dt, ...], stable_steps = [fraction, ...] or tolerances = [tol, ...] with dt, here or as the problem's steps");
    FileSweep s = it.sweep_for(p.label);
    s.steps = p.steps;
    s.full_steps = p.full_steps;
    s.stable_fractions = p.stable_fractions;
    it.per_problem[p.label] = s;
  }
}

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
                      const std::string& label, const std::string& detail = "", const std::string& instead = "problems = [...]") {
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
  // The closed form each problem must have.
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
  const std::string o = m.observable;
  m.label = kind == "impact-ratio" ? (m.law.empty()   ? fmt::format("{} ratio at impact {}", o, m.impact)
                                      : m.count > 0   ? fmt::format("{} ratio err {}, impacts 1..{}", o, m.law, m.count)
                                                      : fmt::format("{} ratio err {} at impact {}", o, m.law, m.impact))
            : kind == "amplitude"  ? fmt::format("{}amplitude of {} after impact {}", m.exact ? "rel err " : "", o, m.impact)
            : kind == "impact-count" ? std::string("impacts per contact")
            : kind == "rest-time"  ? fmt::format("{} time |{}| <= {:g}", m.exact ? "err rest" : "rest", o, m.threshold)
            : kind == "peak-time"  ? fmt::format("{}time of max {}", m.exact ? "err " : "", o)
            : kind == "summary"    ? m.summary
                                   : fmt::format("{} {}", o, m.norm);
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

// A problem's grid = { key = [values], ... }: one problem per point of the product of the
// lists (keys in alphabetical order, the last varying fastest), each with the base parameters
// and its point's, labelled "label, key = value, ..."; no grid: the problem itself.
constexpr std::size_t kMaxGridPoints = 1000;

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
  for (const auto& [key, values] : grid->items()) {
    const std::string key_path = child(at, key);
    c.expect(values, key_path, values.is_array() && !values.empty(), "an array of one or more values");
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
    if (next.size() > kMaxGridPoints)
      c.fail(at, fmt::format("{} problems or more in the grid", next.size()), fmt::format("at most {} points", kMaxGridPoints));
    points = std::move(next);
  }
  return points;
}

bool is_file_stem(const std::string& id) {
  return !id.empty() && std::all_of(id.begin(), id.end(), [](char ch) {
    return std::islower(static_cast<unsigned char>(ch)) || std::isdigit(static_cast<unsigned char>(ch)) || ch == '_';
  });
}

// An optional array of tables [[key]], each checked to be a table; empty when absent.
const Json& optional_tables(const Checker& c, const Json& root, const char* key) {
  static const Json none = Json::array();
  const Json* list = c.find(root, key);
  if (!list) return none;
  c.expect(*list, key, list->is_array(), fmt::format("one or more [[{}]] tables", key));
  for (std::size_t i = 0; i < list->size(); ++i) c.expect((*list)[i], element(key, i), (*list)[i].is_object(), "a table");
  return *list;
}

// [[figure]]: drawn from the work-precision table, its columns named by their headers.
std::vector<FileFigure> read_figures(const Checker& c, const Json& root, const StudySpec& spec) {
  const std::vector<FileMeasure>& measures = spec.measures;
  const bool declared_only = spec.declared_figures_only;
  // A figure of a history or samples table: any of their columns (its table's checked with the tables).
  std::vector<std::string> table_columns = history_column_names();
  for (const auto* more : {&samples_column_names(), &periodic_column_names(), &trajectory_column_names(), &flights_column_names()})
    for (const auto& name : *more)
      if (std::find(table_columns.begin(), table_columns.end(), name) == table_columns.end()) table_columns.push_back(name);
  const auto parameters = parameter_column_names(spec);
  table_columns.insert(table_columns.end(), parameters.begin(), parameters.end());
  std::vector<FileFigure> figures;
  const Json* list = c.find(root, "figure");
  if (!list) return figures;
  c.expect(*list, "figure", list->is_array(), "one or more [[figure]] tables");
  std::vector<std::string> run_columns{"problem", "integrator", "dt", "tol"};
  for (const auto& m : measures) run_columns.push_back(m.label);
  run_columns.insert(run_columns.end(), {"CPU", "steps", "F_int evals"});
  run_columns.insert(run_columns.end(), parameters.begin(), parameters.end());  // a problem parameter: e.g. a panel per mass model
  // Drawn from a declared case table: any column it may show too (e.g. a panel per "problem name").
  if (c.find(root, "table"))
    for (const auto& name : run_column_names())
      if (std::find(run_columns.begin(), run_columns.end(), name) == run_columns.end()) run_columns.push_back(name);
  for (std::size_t i = 0; i < list->size(); ++i) {
    const Json& j = (*list)[i];
    const std::string path = element("figure", i);
    c.expect(j, path, j.is_object(), "a table");
    c.keys(j, path, {"id", "title", "x", "y", "series", "panels", "log_x", "log_y", "slopes", "table", "small_multiples", "deviation",
                     "caption", "value_label"});
    FileFigure f;
    if (const Json* v = c.find(j, "table")) f.table = c.string(*v, child(path, "table"));
    const std::vector<std::string>& columns = f.table.empty() ? run_columns : table_columns;
    f.id = c.string(c.require(j, path, "id"), child(path, "id"));
    if (!is_file_stem(f.id))
      c.fail(child(path, "id"), fmt::format("'{}' is not a file name of a-z, 0-9 and _", f.id), "[a-z0-9_]+");
    for (const auto& g : figures)
      if (g.id == f.id) c.fail(child(path, "id"), fmt::format("id '{}' used twice", f.id), "distinct ids");
    if (!declared_only &&
        (f.id == "work_precision" || f.id == "work_precision_evals" || f.id == "energy_history" || f.id.rfind("convergence_", 0) == 0))
      c.fail(child(path, "id"), fmt::format("'{}' is the id of a figure the study draws itself", f.id),
             "another id than work_precision, work_precision_evals, energy_history, convergence_* (or study.figures = \"declared\")");
    f.title = c.string(c.require(j, path, "title"), child(path, "title"));
    if (const Json* v = c.find(j, "x"); v || f.table.empty()) f.x = c.choice(c.require(j, path, "x"), child(path, "x"), columns);  // a field table's figure: none
    // Of a named table: checked against that table's columns (a pivot's spread column by its header).
    f.y = f.table.empty() ? c.choice(c.require(j, path, "y"), child(path, "y"), columns) : c.string(c.require(j, path, "y"), child(path, "y"));
    const auto names = [&](const char* key, std::vector<std::string>& out) {
      if (const Json* v = c.find(j, key)) {
        const std::string at = child(path, key);
        c.expect(*v, at, v->is_array(), "an array of column names");
        out.clear();
        for (std::size_t k = 0; k < v->size(); ++k) out.push_back(c.choice((*v)[k], element(at, k), columns));
      }
    };
    names("series", f.series);
    names("panels", f.panels);
    if (const Json* v = c.find(j, "log_x")) f.log_x = c.boolean(*v, child(path, "log_x"));
    if (const Json* v = c.find(j, "log_y")) f.log_y = c.boolean(*v, child(path, "log_y"));
    if (const Json* v = c.find(j, "small_multiples")) f.small_multiples = c.boolean(*v, child(path, "small_multiples"));
    if (const Json* v = c.find(j, "deviation")) f.deviation = c.boolean(*v, child(path, "deviation"));
    if (const Json* v = c.find(j, "caption")) f.caption = c.string(*v, child(path, "caption"));
    if (const Json* v = c.find(j, "value_label")) f.value_label = c.string(*v, child(path, "value_label"));
    if (const Json* v = c.find(j, "slopes")) {
      const std::string at = child(path, "slopes");
      c.expect(*v, at, v->is_array(), "an array of numbers");
      for (std::size_t k = 0; k < v->size(); ++k) {
        c.expect((*v)[k], element(at, k), (*v)[k].is_number(), "a number");
        f.slopes.push_back((*v)[k].get<double>());
      }
    }
    figures.push_back(f);
  }
  return figures;
}

// The columns a declared table of `rows` may show, by source name.
std::vector<std::string> table_sources(const std::string& rows, const StudySpec& spec) {
  const std::vector<FileMeasure>& measures = spec.measures;
  std::vector<std::string> sources{"problem", "integrator"};
  if (rows == "case") {
    sources.insert(sources.end(), {"dt", "tol"});
    for (const auto& m : measures) sources.push_back(m.label);
    sources.insert(sources.end(), {"CPU", "steps", "F_int evals", "status", "factorizations", "LCP its"});
    for (const auto& m : measures)
      if (measure_converges(m)) sources.push_back("pairwise order of " + m.label);
    const auto& run = run_column_names();
    sources.insert(sources.end(), run.begin(), run.end());
    sources.insert(sources.end(), spec.counters.begin(), spec.counters.end());
    const auto work = sweep_work_column_names(spec);
    sources.insert(sources.end(), work.begin(), work.end());
  } else if (rows == "group") {
    for (const auto& m : measures)
      if (measure_converges(m))
        for (const char* what : {"order", "CI low", "CI high", "points"}) sources.push_back(fmt::format("{} of {}", what, m.label));
    sources.push_back("note");  // why a group's fits are n/a (group_note, study_file.cpp)
  } else if (rows == "history" || rows == "samples") {
    sources = rows == "history" ? history_column_names() : samples_column_names();
  } else if (rows == "periodic" || rows == "trajectory" || rows == "flights") {
    sources = rows == "periodic" ? periodic_column_names() : rows == "flights" ? flights_column_names() : trajectory_column_names();
  } else if (rows == "impulses" || rows == "field") {
    sources = rows == "impulses" ? impulses_column_names() : field_column_names();
  } else if (rows == "pivot") {
    return table_sources("case", spec);
  }
  const auto parameters = parameter_column_names(spec);
  sources.insert(sources.end(), parameters.begin(), parameters.end());
  return sources;
}

std::optional<std::string> optional_string(const Checker& c, const Json& j, const std::string& path, const char* key) {
  if (const Json* v = c.find(j, key)) return c.string(*v, child(path, key));
  return std::nullopt;
}

// A number format given at `path`: a fmt format of one number, or "" (shortest round trip).
void check_number_format(const Checker& c, const std::optional<std::string>& format, const std::string& path) {
  if (format && !format->empty()) try {
      (void)fmt::format(fmt::runtime(*format), 1.0);
    } catch (const fmt::format_error& e) {
      c.fail(path, fmt::format("'{}' is no number format ({})", *format, e.what()),
             "a fmt format of one number, e.g. {:.2e}, or \"\" (shortest round-trip)");
    }
}

FileColumn read_column(const Checker& c, const Json& j, const std::string& path, const std::vector<std::string>& sources) {
  FileColumn col;
  if (j.is_string()) {
    col.of = c.choice(j, path, sources);
    return col;
  }
  c.expect(j, path, j.is_object(), "a column name or a table { of = NAME, header, unit, format, description }");
  c.keys(j, path, {"of", "header", "unit", "format", "description", "missing"});
  col.of = c.choice(c.require(j, path, "of"), child(path, "of"), sources);
  col.missing = optional_string(c, j, path, "missing");
  col.header = optional_string(c, j, path, "header");
  col.unit = optional_string(c, j, path, "unit");
  col.format = optional_string(c, j, path, "format");
  col.description = optional_string(c, j, path, "description");
  check_number_format(c, col.format, child(path, "format"));
  return col;
}

// The keys of a table of some runs (FileTable::of_some_runs) into `t`: where, drop_above (a
// case-table column each; a case table takes them too), a pivot's across, a periodic or flights
// table's measure, a trajectory's observable, exact, last, points, spacing and relative (its
// observables checked against the problems later: check_trajectory_observables); refused on the
// other tables.
void read_some_runs(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const std::vector<std::string> runs = table_sources("case", spec);
  const std::map<std::string, std::vector<std::string>> own = {
      {"across", {"pivot"}}, {"measure", {"periodic", "flights"}}, {"observable", {"trajectory"}}, {"exact", {"trajectory", "impulses"}},
      {"last", {"trajectory"}}, {"points", {"trajectory"}}, {"spacing", {"trajectory"}}, {"relative", {"trajectory"}}};
  for (const char* key : {"where", "drop_above", "across", "measure", "observable", "exact", "last", "points", "spacing", "relative"}) {
    const auto whose = own.find(key);
    const bool taken = whose == own.end() ? t.of_some_runs() || t.rows == "case"
                                          : std::find(whose->second.begin(), whose->second.end(), t.rows) != whose->second.end();
    if (c.find(j, key) && !taken)
      c.fail(child(path, key), fmt::format("a table of rows = \"{}\" has no {}", t.rows, key),
             whose == own.end() ? "rows = \"case\", \"pivot\", \"periodic\", \"trajectory\" or \"flights\""
                                : fmt::format("rows = \"{}\"", fmt::join(whose->second, "\" or \"")));
  }
  const auto conditions = [&](const char* key, const auto& read) {
    const Json* v = c.find(j, key);
    if (!v) return;
    const std::string at = child(path, key);
    c.expect(*v, at, v->is_object() && !v->empty(), "a table of case-table column = value");
    for (const auto& [name, value] : v->items()) read(c.choice(Json(name), child(at, name), runs), value, child(at, name));
  };
  conditions("where", [&](const std::string& name, const Json& value, const std::string& at) {
    c.expect(value, at, value.is_number() || value.is_string(), "a number or a text");
    t.where.emplace_back(name, value.is_number() ? Cell{value.get<double>()} : Cell{value.get<std::string>()});
  });
  conditions("drop_above", [&](const std::string& name, const Json& value, const std::string& at) {
    t.drop_above.emplace_back(name, c.positive(value, at));
  });
  if (t.rows == "pivot") t.across = c.choice(c.require(j, path, "across"), child(path, "across"), runs);
  if (t.rows == "periodic") {
    std::vector<std::string> sampled;
    for (const auto& m : spec.measures)
      if (m.kind == MeasureKind::Energy && m.every > 0.0) sampled.push_back(m.label);
    if (sampled.empty()) c.fail(child(path, "rows"), "the study has no energy measure sampled every period", "an energy [[measure]] with every");
    t.measure = c.choice(c.require(j, path, "measure"), child(path, "measure"), sampled);
  }
  if (t.rows == "flights") {
    std::vector<std::string> flights;
    for (const auto& m : spec.measures)
      if (m.kind == MeasureKind::FlightEnergy) flights.push_back(m.label);
    if (flights.empty()) c.fail(child(path, "rows"), "the study has no flight-energy measure", "a [[measure]] with kind = \"flight-energy\"");
    t.measure = c.choice(c.require(j, path, "measure"), child(path, "measure"), flights);
  }
  if (t.rows == "trajectory") {
    t.observable = c.string(c.require(j, path, "observable"), child(path, "observable"));
    if (const Json* v = c.find(j, "exact")) t.exact = c.string(*v, child(path, "exact"));
    if (const Json* v = c.find(j, "spacing")) t.step_spacing = c.choice(*v, child(path, "spacing"), {"times", "steps"}) == "steps";
    if (t.step_spacing && c.find(j, "last"))
      c.fail(child(path, "last"), "a trajectory of spacing = \"steps\" spans the whole run", "no last (or spacing = \"times\")");
    if (!t.step_spacing) t.last = c.positive(c.require(j, path, "last"), child(path, "last"));
    if (const Json* v = c.find(j, "points")) t.points = static_cast<int>(c.integer(*v, child(path, "points"), 1, 100000));
    if (const Json* v = c.find(j, "relative")) t.relative = c.boolean(*v, child(path, "relative"));
  }
}

// A group table's fit_against = "1/KEY" (FileTable::fit_against): KEY a numeric parameter of
// every problem it shows.
void read_group_fit(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const Json* v = c.find(j, "fit_against");
  if (!v) return;
  const std::string at = child(path, "fit_against");
  if (t.rows != "group") c.fail(at, "only a table of fitted orders fits", "rows = \"group\"");
  t.fit_against = c.string(*v, at);
  const std::string key = t.fit_against.rfind("1/", 0) == 0 ? t.fit_against.substr(2) : "";
  for (const FileProblem& p : spec.problems) {
    if (!t.applies_to(p.label) && !t.applies_to(p.family_label())) continue;
    std::vector<std::string> numeric;
    for (const ParamSpec& s : find_problem(p.name).parameters())
      if (s.kind != ParamSpec::Kind::Choice) numeric.push_back("1/" + s.name);
    if (std::find(numeric.begin(), numeric.end(), "1/" + key) == numeric.end() || key.empty())
      c.fail(at, fmt::format("'{}' is not 1/KEY, KEY a numeric parameter of problem '{}'", t.fit_against, p.label),
             fmt::format("{}", fmt::join(numeric, ", ")));
  }
}

// The columns of a group table with fit_against: its fits of every measure, the sweep's stable
// steps (its first run's) and the parameters.
std::vector<std::string> fitted_group_sources(const StudySpec& spec) {
  std::vector<std::string> sources{"problem", "integrator", "stable steps"};
  for (const auto& m : spec.measures)
    for (const char* what : {"order", "CI low", "CI high", "points"}) sources.push_back(fmt::format("{} of {}", what, m.label));
  const auto parameters = parameter_column_names(spec);
  sources.insert(sources.end(), parameters.begin(), parameters.end());
  return sources;
}

// except = { column = value, ... } (a case table or a table of some runs: the runs left out) and
// a pivot's order = { of = COLUMN, header, unit, format, description } (FileTable::except, order).
void read_except_and_order(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const std::vector<std::string> runs = table_sources("case", spec);
  if (const Json* v = c.find(j, "except")) {
    const std::string at = child(path, "except");
    if (!t.of_some_runs() && t.rows != "case")
      c.fail(at, fmt::format("a table of rows = \"{}\" has no except", t.rows), "rows = \"case\", \"pivot\", \"periodic\", \"trajectory\" or \"flights\"");
    c.expect(*v, at, v->is_object() && !v->empty(), "a table of case-table column = value");
    for (const auto& [name, value] : v->items()) {
      const std::string column = c.choice(Json(name), child(at, name), runs);
      c.expect(value, child(at, name), value.is_number() || value.is_string(), "a number or a text");
      t.except.emplace_back(column, value.is_number() ? Cell{value.get<double>()} : Cell{value.get<std::string>()});
    }
  }
  if (const Json* v = c.find(j, "order")) {
    const std::string at = child(path, "order");
    if (t.rows != "pivot") c.fail(at, "only a pivot fits the values of its rows", "rows = \"pivot\"");
    c.expect(*v, at, v->is_object(), "a table { of = COLUMN, header, unit, format, description }");
    if (v->contains("missing")) c.fail(child(at, "missing"), "an order is fitted, never missing", "of, header, unit, format, description");
    t.order = read_column(c, *v, at, runs);
  }
}

// A case table's not_ok = "outcome" (FileTable::outcome_columns: the measures it shows) or
// "values" (the default: the values a run reports).
void read_not_ok(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const Json* v = c.find(j, "not_ok");
  if (!v) return;
  const std::string at = child(path, "not_ok");
  if (t.rows != "case") c.fail(at, "only a table of one row per run shows a run's outcome", "rows = \"case\"");
  if (c.choice(*v, at, {"values", "outcome"}) == "values") return;
  for (const FileColumn& col : t.columns)
    if (std::any_of(spec.measures.begin(), spec.measures.end(), [&](const FileMeasure& m) { return m.label == col.of; }))
      t.outcome_columns.push_back(col.of);
  if (t.outcome_columns.empty()) c.fail(at, "the table shows no measure's column", "a measure's label among its columns, or no not_ok");
}

// A trajectory table's observable and exact: observables of the state of every problem it shows.
void check_trajectory_observables(const Checker& c, const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances) {
  for (std::size_t i = 0; i < spec.tables.size(); ++i) {
    const FileTable& t = spec.tables[i];
    if (t.rows != "trajectory") continue;
    for (std::size_t p = 0; p < spec.problems.size(); ++p) {
      if (!t.applies_to(spec.problems[p].label)) continue;
      const std::vector<std::string> names = state_observable_names(*instances[p]);
      for (const auto& [key, name] : {std::pair{"observable", t.observable}, std::pair{"exact", t.exact}})
        if (!name.empty()) check_observable(c, child(element("table", i), key), name, names, spec.problems[p].label);
    }
  }
}

// A text that goes on one line of a report (a metadata line's name or value): no control character.
void check_one_line(const Checker& c, const std::string& text, const std::string& path) {
  const auto control = std::find_if(text.begin(), text.end(), [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; });
  if (control != text.end())
    c.fail(path, fmt::format("holds the control character 0x{:02x}", static_cast<unsigned char>(*control)), "a text of one line");
}

// metadata = [{ line = NAME, of = COLUMN }, { line = NAME, text = TEXT }, ...] (MetadataLine):
// `of` a column of the case table; each name once.
std::vector<MetadataLine> read_metadata_lines(const Checker& c, const Json& v, const std::string& path, const StudySpec& spec) {
  c.expect(v, path, v.is_array() && !v.empty(), "an array of one or more { line, of } or { line, text }");
  std::vector<MetadataLine> lines;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string at = element(path, k);
    const Json& j = v[k];
    c.expect(j, at, j.is_object(), "a table { line, of } or { line, text }");
    c.keys(j, at, {"line", "of", "text"});
    MetadataLine m;
    m.line = c.string(c.require(j, at, "line"), child(at, "line"));
    if (m.line.empty()) c.fail(child(at, "line"), "an empty name", "the name of the line, e.g. N");
    check_one_line(c, m.line, child(at, "line"));
    for (const auto& other : lines)
      if (other.line == m.line) c.fail(child(at, "line"), fmt::format("line '{}' given twice", m.line), "each name once");
    if (!c.find(j, "of") == !c.find(j, "text")) c.fail(at, "give one of of = COLUMN (its values over the runs) or text = TEXT");
    if (const Json* o = c.find(j, "of")) m.of = c.choice(*o, child(at, "of"), table_sources("case", spec));
    if (const Json* t = c.find(j, "text")) {
      m.text = c.string(*t, child(at, "text"));
      check_one_line(c, m.text, child(at, "text"));
    }
    lines.push_back(m);
  }
  return lines;
}

// The keys of an impulses table (scale, exact, exact_per, exact_in) and of a field table
// (component, exact_times) into `t`, refused on the other tables; what they name in the
// problems is checked once the problems exist (check_impulses_and_fields).
void read_impulses_and_field(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const std::vector<std::pair<std::string, std::string>> own = {
      {"scale", "impulses"}, {"exact_per", "impulses"}, {"exact_in", "impulses"}, {"component", "field"}, {"exact_times", "field"}};
  for (const auto& [key, rows] : own)
    if (c.find(j, key) && t.rows != rows)
      c.fail(child(path, key), fmt::format("a table of rows = \"{}\" has no {}", t.rows, key), fmt::format("rows = \"{}\"", rows));
  if (t.rows == "impulses") {
    if (const Json* v = c.find(j, "scale")) t.scale = c.positive(*v, child(path, "scale"));
    if (const Json* v = c.find(j, "exact")) t.exact = c.string(*v, child(path, "exact"));
    std::vector<std::string> columns = table_sources("impulses", spec);  // of one run: not its values
    columns.erase(std::remove_if(columns.begin(), columns.end(), [](const std::string& n) { return n == "t" || n == "value"; }), columns.end());
    for (const char* key : {"exact_per", "exact_in"})
      if (const Json* v = c.find(j, key)) {
        if (t.exact.empty()) c.fail(child(path, key), "where the exact rows go, without exact rows", "exact = OBSERVABLE beside it");
        (std::string(key) == "exact_per" ? t.exact_per : t.exact_in) = c.choice(*v, child(path, key), columns);
      }
  }
  if (t.rows == "field") {
    if (const Json* v = c.find(j, "component")) t.component = c.string(*v, child(path, "component"));
    if (const Json* v = c.find(j, "exact_times")) t.exact_times = static_cast<int>(c.integer(*v, child(path, "exact_times"), 1, 100000));
  }
}

// Impulses and field tables against the problems they show: an impulses table's problems have
// contacts (and, with exact, an exact solution with that observable); a field table's have one
// 1D mesh of bar elements with the stress component (each cell's header naming its position:
// {} in a field column's header) and, with exact_times, the first of them an exact field.
void check_impulses_and_fields(const Checker& c, const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances) {
  for (std::size_t i = 0; i < spec.tables.size(); ++i) {
    const FileTable& t = spec.tables[i];
    const std::string path = element("table", i);
    if (t.rows != "impulses" && t.rows != "field") continue;
    std::vector<double> centres;  // of the first problem shown
    std::string first;
    for (std::size_t p = 0; p < spec.problems.size(); ++p) {
      const std::string& label = spec.problems[p].label;
      const Problem& problem = *instances[p];
      if (!t.applies_to(label)) continue;
      if (t.rows == "impulses") {
        if (problem.ncontacts() == 0)
          c.fail(child(path, "rows"), fmt::format("problem '{}' has no contacts, hence no impulses", label), "problems with contacts (or problems = [...])");
        if (!t.exact.empty() && !problem.exact())
          c.fail(child(path, "exact"), fmt::format("problem '{}' has no exact solution", label), "problems with one (or problems = [...])");
        if (!t.exact.empty()) check_observable(c, child(path, "exact"), t.exact, state_observable_names(problem), label);
        continue;
      }
      const std::optional<FieldMesh> mesh = problem.field_mesh();
      bool bars = mesh && mesh->dimension == 1 && !mesh->stress_components.empty() && mesh->ncells() > 0;
      for (Index e = 0; bars && e < mesh->ncells(); ++e) bars = mesh->cell_size(e) == 2;
      if (!bars)
        c.fail(child(path, "rows"), fmt::format("problem '{}' has no 1D field mesh of bar elements with a stress", label),
               "problems of bar elements, e.g. signorini-bar (or problems = [...])");
      const auto& names = mesh->stress_components;
      if (!t.component.empty() && std::find(names.begin(), names.end(), t.component) == names.end())
        c.fail(child(path, "component"), fmt::format("'{}' is not a stress component of problem '{}'", t.component, label),
               fmt::format("{}", fmt::join(names, ", ")));
      std::vector<double> own;
      for (Index e = 0; e < mesh->ncells(); ++e) own.push_back(0.5 * (mesh->points(mesh->cells(e, 0), 0) + mesh->points(mesh->cells(e, 1), 0)));
      if (first.empty()) {
        first = label;
        centres = own;
        Eigen::MatrixXd stress(mesh->ncells(), static_cast<Index>(names.size()));
        if (t.exact_times > 0 && !(problem.exact() && problem.exact()->exact_cell_stress(0.0, stress)))
          c.fail(child(path, "exact_times"), fmt::format("problem '{}' has no exact field", label),
                 "a first problem whose exact solution gives its element stresses (signorini-bar with g = 0), or no exact_times");
      } else if (own != centres) {
        c.fail(child(path, "problems"), fmt::format("problems '{}' and '{}' have different field meshes ({} and {} cells)", first, label,
                                                    centres.size(), own.size()),
               "problems of one mesh: problems = [...]");
      }
    }
    for (std::size_t k = 0; k < t.columns.size(); ++k)
      if (t.columns[k].of == "field" && t.columns[k].header && t.columns[k].header->find("{}") == std::string::npos)
        c.fail(child(element(child(path, "columns"), k), "header"), fmt::format("'{}' does not name the cell", *t.columns[k].header),
               "a header with {} where each cell's centre x goes, e.g. sigma(x = {})");
  }
}

// A figure of a field table is a space-time picture (no x); the others have an x and no colour scale.
void check_field_figure(const Checker& c, const std::string& path, const FileFigure& f, const FileTable& table) {
  if (table.rows == "field") {
    if (!f.x.empty()) c.fail(child(path, "x"), "a space-time picture's horizontal axis is the cells' position", "no x with a table of rows = \"field\"");
    if (std::none_of(table.columns.begin(), table.columns.end(), [](const FileColumn& col) { return col.of == "field"; }))
      c.fail(child(path, "table"), fmt::format("table '{}' shows no field to draw", table.id), "a table whose columns hold \"field\"");
    return;
  }
  if (f.x.empty()) c.fail(path, "missing key 'x'");
  if (!f.value_label.empty())
    c.fail(child(path, "value_label"), "only a space-time picture has a colour scale", "table = a table of rows = \"field\"");
}

// A figure of a pivot table draws one of its spread columns: y is its header, the value
// column's header with "{}" replaced by a value of `across` (no "{}": the header, ", ", the value).
void check_pivot_figure_y(const Checker& c, const std::string& at, const std::string& y, const FileTable& pivot) {
  const FileColumn& value = pivot.columns.back();
  std::string header = value.header.value_or(value.of);
  if (header.find("{}") == std::string::npos) header += ", {}";
  const std::size_t hole = header.find("{}");
  const std::string before = header.substr(0, hole), after = header.substr(hole + 2);
  const bool spread = y.size() > before.size() + after.size() && y.starts_with(before) && y.ends_with(after);
  if (!spread)
    c.fail(at, fmt::format("'{}' is not a spread column of pivot table '{}'", y, pivot.id),
           fmt::format("'{}' with {{}} a value of '{}'", header, pivot.across));
}

// A case table's integrators = [labels]: the runs of those integrators only.
void read_table_integrators(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const Json* v = c.find(j, "integrators");
  if (!v) return;
  const std::string at = child(path, "integrators");
  if (t.rows != "case" && t.rows != "impulses" && t.rows != "field")
    c.fail(at, "only a table of one row per run, or of its impulses or field, picks its integrators' runs", "rows = \"case\", \"impulses\" or \"field\"");
  c.expect(*v, at, v->is_array() && !v->empty(), "an array of one or more integrator labels");
  std::vector<std::string> labels;
  for (const auto& it : spec.integrators) labels.push_back(it.label);
  for (std::size_t k = 0; k < v->size(); ++k) t.integrators.push_back(c.choice((*v)[k], element(at, k), labels));
}

// A declared table's caption: each ${COLUMN} in it names a case-table column (the engine puts
// that column's values over the table's runs in its place: FileTable::caption).
void check_caption_placeholders(const Checker& c, const std::string& caption, const std::string& path, const StudySpec& spec) {
  const std::vector<std::string> columns = table_sources("case", spec);
  for (const CaptionPlaceholder& p : caption_placeholders(caption)) {
    if (p.size == std::string::npos)
      c.fail(path, fmt::format("'${{{}' has no closing }}", p.column), "${COLUMN} with COLUMN a case-table column");
    if (std::find(columns.begin(), columns.end(), p.column) == columns.end())
      c.fail(path, fmt::format("'${{{}}}' names no case-table column (nearest: {})", p.column, nearest_name(p.column, columns)),
             fmt::format("${{COLUMN}} with COLUMN one of {}", fmt::join(columns, ", ")));
  }
}

// [[table]]: the tables the study writes instead of the engine's own.
std::vector<FileTable> read_tables(const Checker& c, const Json& root, const StudySpec& spec) {
  std::vector<FileTable> tables;
  if (!c.find(root, "table")) return tables;  // the engine's own tables, their figures unchecked here
  const Json& list = optional_tables(c, root, "table");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Json& j = list[i];
    const std::string path = element("table", i);
    c.keys(j, path, {"id", "title", "caption", "rows", "columns", "error", "runs_format", "problems", "declined", "declined_reason", "integrators",
                     "where", "drop_above", "across", "measure", "observable", "exact", "last", "points", "spacing", "relative",
                     "not_ok", "fit_against", "except", "order", "scale", "exact_per", "exact_in", "component", "exact_times", "metadata"});
    FileTable t;
    t.id = c.string(c.require(j, path, "id"), child(path, "id"));
    if (!is_file_stem(t.id)) c.fail(child(path, "id"), fmt::format("'{}' is not a file name of a-z, 0-9 and _", t.id), "[a-z0-9_]+");
    for (const auto& u : tables)
      if (u.id == t.id) c.fail(child(path, "id"), fmt::format("id '{}' used twice", t.id), "distinct ids");
    t.title = c.string(c.require(j, path, "title"), child(path, "title"));
    t.caption = optional_string(c, j, path, "caption");
    if (t.caption) check_caption_placeholders(c, *t.caption, child(path, "caption"), spec);
    if (const Json* v = c.find(j, "rows")) t.rows = c.choice(*v, child(path, "rows"), {"case", "group", "ranking", "history", "samples", "pivot", "periodic", "trajectory", "flights", "impulses", "field"});
    read_some_runs(c, j, path, spec, t);
    read_impulses_and_field(c, j, path, spec, t);
    if (const Json* v = c.find(j, "metadata")) t.metadata = read_metadata_lines(c, *v, child(path, "metadata"), spec);
    if (const Json* v = c.find(j, "declined")) {
      if (t.rows != "case") c.fail(child(path, "declined"), "only a table of one row per run shows declined runs", "rows = \"case\"");
      const std::string shown = c.choice(*v, child(path, "declined"), {"as run", "n/a", "empty"});
      t.declined_blank = shown != "as run";
      t.declined_empty = shown == "empty";
    }
    if (const Json* v = c.find(j, "problems")) {
      const std::string at = child(path, "problems");
      if (t.rows == "ranking") c.fail(at, "a ranking ranks every problem of its measure", "rows = \"case\", \"group\", \"history\" or \"samples\"");
      c.expect(*v, at, v->is_array() && !v->empty(), "an array of one or more problem labels");
      std::vector<std::string> labels;  // a group's problem: a joint refinement's family label too
      for (const auto& p : spec.problems) labels.push_back(p.label);
      for (const auto& p : spec.problems)
        if (t.rows == "group" && !p.family.empty() && std::find(labels.begin(), labels.end(), p.family) == labels.end()) labels.push_back(p.family);
      for (std::size_t k = 0; k < v->size(); ++k) t.problems.push_back(c.choice((*v)[k], element(at, k), labels));
    }
    read_table_integrators(c, j, path, spec, t);
    read_group_fit(c, j, path, spec, t);
    read_except_and_order(c, j, path, spec, t);
    if (t.rows == "ranking") {
      if (c.find(j, "columns")) c.fail(child(path, "columns"), "a ranking's columns are fixed", "no columns key with rows = \"ranking\"");
      if (spec.ranked >= spec.measures.size()) c.fail(child(path, "rows"), "the study has no measure to rank by", "case, group");
      const bool first = std::none_of(tables.begin(), tables.end(), [](const FileTable& u) { return u.rows == "ranking"; });
      if (const Json* v = c.find(j, "error")) {
        const std::string at = child(path, "error");
        if (!first) c.fail(at, "the first ranking table sets the error column of every ranking", "no error key here");
        c.expect(*v, at, v->is_object(), "a table { header, unit, format, description }");
        c.keys(*v, at, {"header", "unit", "format", "description"});
        FileColumn col;
        col.header = optional_string(c, *v, at, "header");
        col.unit = optional_string(c, *v, at, "unit");
        col.format = optional_string(c, *v, at, "format");
        col.description = optional_string(c, *v, at, "description");
        check_number_format(c, col.format, child(at, "format"));
        t.error = col;
      }
      if (const Json* v = c.find(j, "runs_format")) {
        const std::string at = child(path, "runs_format");
        if (!first) c.fail(at, "the first ranking table sets the runs' format of every ranking", "no runs_format key here");
        t.runs_format = c.string(*v, at);
        if (t.runs_format->empty()) c.fail(at, "an empty format", "a fmt format of one number, e.g. {:.1e}");
        check_number_format(c, t.runs_format, at);
      }
    } else {
      for (const char* key : {"error", "runs_format"})
        if (c.find(j, key)) c.fail(child(path, key), fmt::format("only a ranking has {}", key), "rows = \"ranking\"");
      const std::string at = child(path, "columns");
      const Json& cols = c.require(j, path, "columns");
      c.expect(cols, at, cols.is_array() && !cols.empty(), "a non-empty array of columns");
      const auto sources = t.fit_against.empty() ? table_sources(t.rows, spec) : fitted_group_sources(spec);
      for (std::size_t k = 0; k < cols.size(); ++k) {
        t.columns.push_back(read_column(c, cols[k], element(at, k), sources));
        if (t.columns.back().missing && t.rows != "case" && !(t.rows == "pivot" && k + 1 == cols.size()))
          c.fail(child(element(at, k), "missing"), "only a table of one row per run shows its missing cells otherwise",
                 "rows = \"case\", or a pivot's value column (the last)");
      }
      read_not_ok(c, j, path, spec, t);
      if (t.rows == "pivot" && cols.size() < 2)
        c.fail(at, "a pivot needs the columns naming a row and the value column last", "two or more columns");
    }
    if (const Json* v = c.find(j, "declined_reason")) {
      const std::string at = child(path, "declined_reason");
      if (!t.declined_blank) c.fail(at, "a declined run's reason replaces one of its blanked cells", "declined = \"n/a\" or \"empty\"");
      std::vector<std::string> measured;
      for (const FileColumn& col : t.columns)
        if (!asked_column(col.of)) measured.push_back(col.of);
      t.declined_reason = c.choice(*v, at, measured);
    }
    tables.push_back(t);
  }
  // The figures are drawn from the first table of one row per run (or the history table they
  // name): it shows their columns.
  const auto first_runs = std::find_if(tables.begin(), tables.end(), [](const FileTable& t) { return t.rows == "case"; });
  for (std::size_t i = 0; i < spec.figures.size(); ++i) {
    const std::string path = element("figure", i);
    auto runs = first_runs;
    if (!spec.figures[i].table.empty()) {
      runs = std::find_if(tables.begin(), tables.end(), [&](const FileTable& t) { return t.id == spec.figures[i].table; });
      const auto series = [](const FileTable& t) { return t.rows == "history" || t.rows == "samples" || t.of_some_runs(); };
      if (runs == tables.end() || !series(*runs)) {
        std::vector<std::string> histories;
        for (const auto& t : tables)
          if (series(t)) histories.push_back(t.id);
        c.fail(child(path, "table"), fmt::format("'{}' is no declared table a figure names (rows = history, samples, periodic, trajectory, flights, impulses, field or pivot)",
                                                 spec.figures[i].table),
               histories.empty() ? "a [[table]] with rows = \"history\", \"samples\", \"periodic\", \"trajectory\", \"flights\", \"impulses\", \"field\" or \"pivot\""
                                 : fmt::format("{}", fmt::join(histories, ", ")));
      }
    }
    if (runs == tables.end()) c.fail(path, "declared tables hold no table of one row per run to draw it from", "a [[table]] with rows = \"case\"");
    std::vector<std::string> shown;
    for (const auto& col : runs->columns) shown.push_back(col.of);
    if (runs->rows == "pivot") shown.pop_back();  // its value column is drawn by a spread column's header
    const FileFigure& f = spec.figures[i];
    check_field_figure(c, path, f, *runs);
    std::vector<std::pair<std::string, std::string>> used;
    if (!f.x.empty()) used.emplace_back("x", f.x);
    used.emplace_back("y", f.y);
    for (const auto& s : f.series) used.emplace_back("series", s);
    for (const auto& s : f.panels) used.emplace_back("panels", s);
    for (const auto& [key, name] : used) {
      if (runs->rows == "pivot" && key == "y") {
        check_pivot_figure_y(c, child(path, key), name, *runs);
        continue;
      }
      if (std::find(shown.begin(), shown.end(), name) == shown.end())
        c.fail(child(path, key), fmt::format("'{}' is not a column of table '{}'", name, runs->id), fmt::format("{}", fmt::join(shown, ", ")));
    }
  }
  return tables;
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

// study.counters: names of integrators' work counters (Work::extra), each once.
std::vector<std::string> counter_names(const Checker& c, const Json& j, const std::string& path) {
  c.expect(j, path, j.is_array() && !j.empty(), "an array of one or more counter names");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < j.size(); ++i) {
    const std::string name = c.string(j[i], element(path, i));
    if (name.empty() || std::find(names.begin(), names.end(), name) != names.end() ||
        std::find(run_column_names().begin(), run_column_names().end(), name) != run_column_names().end())
      c.fail(element(path, i), fmt::format("'{}' is empty, given twice or the name of a run column", name),
             "distinct names of the integrators' work counters (Work::extra, e.g. energy_iterations)");
    names.push_back(name);
  }
  return names;
}

// An integrator joins the study under a label no other has.
void add_integrator(const Checker& c, std::vector<FileIntegrator>& integrators, FileIntegrator it, const std::string& path) {
  for (const auto& q : integrators)
    if (q.label == it.label) c.fail(child(path, "label"), fmt::format("label '{}' used twice", it.label), "distinct labels");
  integrators.push_back(std::move(it));
}

// The end time of the longest run: the bound of the series held in memory.
double longest_t_end(const StudySpec& spec) {
  double t = spec.t_end;
  for (const auto& p : spec.problems) t = std::max(t, spec.t_end_of(p));
  return t;
}

std::string stem_name(const std::string& file) {
  std::string name;
  for (char ch : std::filesystem::path(file).stem().string())
    name += std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::tolower(ch)) : '_';
  return name.empty() ? "study" : name;
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

// study.case_order and study.max_force_evaluations_per_step (a budget per nominal step: a run's
// is floor(k t_end / dt); (0, 1e6], beside no max_force_evaluations).
void read_study_order_and_budget(const Checker& c, const Json& study, StudySpec& spec) {
  if (const Json* v = c.find(study, "measure_over_budget")) spec.measure_over_budget = c.boolean(*v, "study.measure_over_budget");
  if (const Json* v = c.find(study, "case_order"))
  {
    const std::string order = c.choice(*v, "study.case_order", {"problem", "integrator", "sweep"});
    spec.integrator_major = order == "integrator";
    spec.sweep_major = order == "sweep";
  }
  if (const Json* v = c.find(study, "max_force_evaluations_per_step")) {
    const std::string at = "study.max_force_evaluations_per_step";
    if (c.find(study, "max_force_evaluations")) c.fail(at, "given beside study.max_force_evaluations", "one of the two budgets");
    spec.force_evaluations_per_step = c.positive(*v, at);
    if (spec.force_evaluations_per_step > 1e6)
      c.fail(at, fmt::format("{} F_int evaluations per step is no budget", spec.force_evaluations_per_step), "(0, 1e6]");
  }
}

// [[exclude]] rules (study_file.hpp, FileExclusion), checked against the problems: `above`
// names a numeric parameter of one or more of them, stable_steps_except a sweep of stable steps.
std::vector<FileExclusion> read_exclusions(const Checker& c, const Json& root, const StudySpec& spec) {
  std::vector<FileExclusion> rules;
  const Json& list = optional_tables(c, root, "exclude");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const Json& j = list[i];
    const std::string path = element("exclude", i);
    c.keys(j, path, {"integrators", "above", "stable_steps_except", "default_only", "full_only"});
    FileExclusion x;
    x.integrators = c.choice(c.require(j, path, "integrators"), child(path, "integrators"), {"schemes", "peers", "references"});
    if (const Json* v = c.find(j, "above")) {
      const std::string at = child(path, "above");
      c.expect(*v, at, v->is_object() && !v->empty(), "a table of parameter = number");
      for (const auto& [name, value] : v->items()) {
        c.expect(value, child(at, name), value.is_number(), "a number");
        const auto has = [&](const FileProblem& p, bool numeric) {
          const ParamSpecs specs = find_problem(p.name).parameters();
          const auto s = std::find_if(specs.begin(), specs.end(), [&](const ParamSpec& q) { return q.name == name; });
          return s != specs.end() && (s->kind != ParamSpec::Kind::Choice) == numeric;
        };
        if (std::none_of(spec.problems.begin(), spec.problems.end(), [&](const FileProblem& p) { return has(p, true); }) ||
            std::any_of(spec.problems.begin(), spec.problems.end(), [&](const FileProblem& p) { return has(p, false); }))
          c.fail(child(at, name), fmt::format("'{}' is no numeric parameter of the study's problems", name),
                 "a real or integer parameter of one or more problems (the rule applies to those)");
        x.above[name] = value.get<double>();
      }
    }
    if (const Json* v = c.find(j, "stable_steps_except")) x.stable_steps_except = stable_fractions(c, *v, child(path, "stable_steps_except"));
    if (const Json* v = c.find(j, "default_only")) x.default_only = c.boolean(*v, child(path, "default_only"));
    if (const Json* v = c.find(j, "full_only")) x.full_only = c.boolean(*v, child(path, "full_only"));
    if (x.default_only && x.full_only) c.fail(child(path, "full_only"), "full_only and default_only both: the rule would never apply", "at most one of them true");
    if (x.above.empty() && x.stable_steps_except.empty())
      c.fail(path, "no condition: the rule would exclude every run of its integrators", "above = { PARAMETER = number } and/or stable_steps_except = [...]");
    rules.push_back(std::move(x));
  }
  return rules;
}
}  // namespace

bool FileMeasure::applies_to(const std::string& problem_label) const {
  return problems.empty() || std::find(problems.begin(), problems.end(), problem_label) != problems.end();
}

const std::string& FileMeasure::observable_for(const std::string& problem_label) const {
  const auto it = problem_observables.find(problem_label);
  return it == problem_observables.end() ? observable : it->second;
}

std::pair<double, double> FileMeasure::window_for(const std::string& problem_label) const {
  const auto it = problem_windows.find(problem_label);
  if (it != problem_windows.end()) return it->second;
  return problem_windows.empty() ? std::pair{window_start, window_end} : std::pair{0.0, std::numeric_limits<double>::infinity()};
}

bool FileMeasure::rankable() const {
  if (kind >= MeasureKind::ImpactRatio || kind == MeasureKind::RestStart) return !law.empty() || exact;  // a difference from a closed form, not a value
  if (kind == MeasureKind::Hausdorff) return norm != "value scale";  // a scale, not an error
  if (kind == MeasureKind::ContactDuration) return exact;
  return (kind != MeasureKind::Energy && kind != MeasureKind::FlightEnergy && kind != MeasureKind::ImpactTime) || norm == "max";
}

const FileSweep& FileIntegrator::sweep_for(const std::string& problem_label) const {
  const auto it = per_problem.find(problem_label);
  return it == per_problem.end() ? sweep : it->second;
}

StudySpec parse_study_text(const std::string& text, const std::string& file, bool json) {
  Json root;
  Lines lines;
  if (json) {
    try {
      root = Json::parse(text, duplicate_key_check(text, file));
    } catch (const Json::parse_error& e) {
      throw InputError(fmt::format("{}: not valid JSON: {}", file, e.what()));
    } catch (const Json::out_of_range& e) {  // a number beyond a double's range (406)
      throw InputError(fmt::format("{}: a number beyond the range of a double (1.8e308): {}", file, e.what()));
    }
  } else {
    try {
      toml_to_json(toml::parse(text, file), "", root, lines);
    } catch (const toml::parse_error& e) {
      throw InputError(fmt::format("{}:{}: not valid TOML: {}", file, e.source().begin.line, e.description()));
    }
  }
  const Checker c(file, lines, json ? &text : nullptr);
  c.expect(root, "(file)", root.is_object(), "a table");
  c.keys(root, "", {"study", "problem", "integrator", "reference", "measure", "figure", "table", "exclude"});

  StudySpec spec;
  spec.file = file;
  spec.name = stem_name(file);
  spec.text = text;
  spec.hash = fnv1a64(text);

  const Json& study = c.require(root, "", "study");
  c.expect(study, "study", study.is_object(), "a table");
  c.keys(study, "study", {"title", "t_end", "sample_every", "check_every", "cpu_repeats", "max_force_evaluations", "targets",
                          "rank_by", "energy_blow_up", "max_penetration", "integrators", "figures", "case_order",
                          "max_force_evaluations_per_step", "measure_over_budget", "history_intervals", "counters", "metadata"});
  spec.title = c.string(c.require(study, "study", "title"), "study.title");
  spec.t_end = c.positive(c.require(study, "study", "t_end"), "study.t_end");
  if (const Json* v = c.find(study, "sample_every")) spec.sample_every = c.integer(*v, "study.sample_every", 1, 1L << 40);
  if (const Json* v = c.find(study, "check_every")) spec.check_every = c.integer(*v, "study.check_every", 1, 1L << 40);
  if (const Json* v = c.find(study, "history_intervals"))
    spec.history_intervals = static_cast<int>(c.integer(*v, "study.history_intervals", 1, 100000));
  if (const Json* v = c.find(study, "counters")) spec.counters = counter_names(c, *v, "study.counters");
  if (const Json* v = c.find(study, "cpu_repeats")) spec.cpu_repeats = static_cast<int>(c.integer(*v, "study.cpu_repeats", 0, 100));
  if (const Json* v = c.find(study, "max_force_evaluations"))  // >= 1: no budget (0) would let a case run 2e8 steps
    spec.max_force_evaluations = c.integer(*v, "study.max_force_evaluations", 1, 1L << 50);
  read_study_order_and_budget(c, study, spec);
  if (const Json* v = c.find(study, "targets")) spec.targets = c.positive_list(*v, "study.targets");
  if (const Json* v = c.find(study, "energy_blow_up")) {  // inf (TOML): no such status
    c.expect(*v, "study.energy_blow_up", v->is_number(), "a number");
    spec.energy_blow_up = v->get<double>();
    if (!(spec.energy_blow_up > 0.0))
      c.fail("study.energy_blow_up", fmt::format("{} is not positive", spec.energy_blow_up), "(0, inf]; inf: no energy blow-up status");
  }
  if (const Json* v = c.find(study, "max_penetration")) spec.max_penetration = c.positive(*v, "study.max_penetration");
  // study.integrators = "all": every registered integrator; "schemes": those not peers and not references.
  const std::string registered_integrators =
      c.find(study, "integrators") ? c.choice(study["integrators"], "study.integrators", {"all", "schemes"}) : "";
  const bool all_integrators = !registered_integrators.empty();
  if (const Json* v = c.find(study, "figures")) spec.declared_figures_only = c.choice(*v, "study.figures", {"all", "declared"}) == "declared";

  const auto list = [&](const char* key) -> const Json& {
    const Json& a = c.require(root, "", key);
    c.expect(a, key, a.is_array() && !a.empty(), fmt::format("one or more [[{}]] tables", key));
    for (std::size_t i = 0; i < a.size(); ++i) c.expect(a[i], element(key, i), a[i].is_object(), "a table");
    return a;
  };
  std::vector<std::unique_ptr<Problem>> instances;
  const Json& problems = list("problem");
  for (std::size_t i = 0; i < problems.size(); ++i) {
    const Json& j = problems[i];
    const std::string path = element("problem", i);
    c.keys(j, path, {"name", "label", "parameters", "grid", "refine", "t_end", "max_force_evaluations", "steps", "full_steps", "stable_steps",
                     "reference", "energy_blow_up", "max_penetration", "energy_scale", "full_only", "default_only", "full_t_end",
                     "end_at_impact", "t_end_exact", "min_flight"});
    FileProblem p;
    p.name = c.registered(c.require(j, path, "name"), child(path, "name"), names_of(problem_registry()), "problem");
    p.label = c.find(j, "label") ? c.string(j["label"], child(path, "label")) : p.name;
    const auto& entry = find_problem(p.name);
    if (const Json* v = c.find(j, "parameters")) p.parameters = c.parameters(*v, child(path, "parameters"), entry.parameters());
    if (const Json* v = c.find(j, "t_end")) p.t_end = c.positive(*v, child(path, "t_end"));
    if (const Json* v = c.find(j, "max_force_evaluations"))
      p.max_force_evaluations = c.integer(*v, child(path, "max_force_evaluations"), 1, 1L << 50);
    read_problem_outcome(c, j, path, p);
    read_problem_steps(c, j, path, spec, p);
    const std::size_t first = spec.problems.size();
    for (FileProblem q : grid_points(c, j, path, p, entry.parameters())) {
      for (const auto& r : spec.problems)
        if (r.label == q.label) c.fail(child(path, "label"), fmt::format("label '{}' used twice", q.label), "distinct labels");
      try {
        instances.push_back(make_problem(q.name, q.parameters));
      } catch (const InputError& e) {
        c.fail(child(path, c.find(j, "grid") ? "grid" : "parameters"), e.what());
      }
      read_end_at_impact(c, j, path, *instances.back(), q);
      read_t_end_exact(c, j, path, *instances.back(), q);
      FileSweep own_steps;  // its stable steps against its end time
      own_steps.stable_fractions = q.stable_fractions;
      check_steps(c, own_steps, path, spec, q, instances.back()->stable_step());
      spec.problems.push_back(q);
    }
    if (const Json* r = c.find(j, "reference")) {
      std::vector<std::size_t> points(spec.problems.size() - first);
      std::iota(points.begin(), points.end(), first);
      const FileReference own = read_reference(c, *r, child(path, "reference"), spec, points, instances);
      for (const std::size_t q : points) spec.problems[q].reference = own;
    }
  }

  // study.integrators = "all": each registered one, with the problems' steps, but those the
  // [[integrator]] tables name: in its place, the tables' variants, in their order.
  std::vector<FileIntegrator> declared;
  const Json& integrators = all_integrators && !c.find(root, "integrator") ? Json::array() : list("integrator");
  const std::vector<std::string> sweep_keys{"parameters", "steps", "full_steps", "stable_steps", "tolerances", "tolerance_parameter",
                                           "tolerance_divisors", "dt"};
  for (std::size_t i = 0; i < integrators.size(); ++i) {
    const Json& j = integrators[i];
    const std::string path = element("integrator", i);
    auto keys = sweep_keys;
    keys.insert(keys.end(), {"name", "label", "per_problem", "optional"});
    c.keys(j, path, keys);
    // optional = true: left out of a build that does not register it (a peer whose package is
    // absent), so that the file still runs there; a name no build knows is still an error there.
    if (const Json* o = c.find(j, "optional"); o && c.boolean(*o, child(path, "optional"))) {
      const Json& name = c.require(j, path, "name");
      const auto names = names_of(integrator_registry());
      if (name.is_string() && std::find(names.begin(), names.end(), name.get<std::string>()) == names.end()) continue;
    }
    FileIntegrator it;
    it.name = c.registered(c.require(j, path, "name"), child(path, "name"), names_of(integrator_registry()), "integrator");
    it.label = c.find(j, "label") ? c.string(j["label"], child(path, "label")) : it.name;
    const auto& entry = find_integrator(it.name);
    it.sweep = read_sweep(c, j, path, entry, nullptr);
    if (const Json* pp = c.find(j, "per_problem")) {
      const std::string pp_path = child(path, "per_problem");
      c.expect(*pp, pp_path, pp->is_object(), "a table keyed by problem label");
      std::vector<std::string> labels;
      for (const auto& p : spec.problems) labels.push_back(p.label);
      c.keys(*pp, pp_path, labels);
      for (const auto& [label, o] : pp->items()) {
        c.expect(o, child(pp_path, label), o.is_object(), "a table");
        c.keys(o, child(pp_path, label), sweep_keys);
        it.per_problem[label] = read_sweep(c, o, child(pp_path, label), entry, &it.sweep);
      }
    }
    sweep_from_problems(c, it, path, spec.problems);
    for (std::size_t p = 0; p < spec.problems.size(); ++p) {
      const std::string& label = spec.problems[p].label;
      const bool own = it.per_problem.count(label) > 0;
      check_steps(c, it.sweep_for(label), own ? child(child(path, "per_problem"), label) : path, spec, spec.problems[p],
                  instances[p]->stable_step());
    }
    add_integrator(c, declared, std::move(it), path);
  }
  if (!all_integrators) spec.integrators = std::move(declared);
  for (const auto& entry : integrator_registry()) {
    if (!all_integrators) break;
    if (registered_integrators == "schemes" && (entry.reference || entry.peer)) continue;
    const auto named = [&](const FileIntegrator& it) { return it.name == entry.name; };
    if (std::any_of(declared.begin(), declared.end(), named)) {
      std::copy_if(declared.begin(), declared.end(), std::back_inserter(spec.integrators), named);
      continue;
    }
    FileIntegrator it{entry.name, entry.name, {}, {}};
    sweep_from_problems(c, it, "study.integrators", spec.problems);
    add_integrator(c, spec.integrators, std::move(it), "study.integrators");
  }

  if (const Json* r = c.find(root, "reference")) {
    std::vector<std::size_t> served;  // the problems without a reference of their own
    for (std::size_t p = 0; p < spec.problems.size(); ++p)
      if (!spec.problems[p].reference) served.push_back(p);
    spec.reference = read_reference(c, *r, "reference", spec, served, instances);
    spec.has_reference = true;
  }

  // A study of declared tables may show its runs' own figures alone (outcome, steps, histories).
  const Json& measures = c.find(root, "measure") || !c.find(root, "table") ? list("measure") : Json::array();
  const std::vector<std::string> kinds{"error",        "impact-time", "energy",      "momentum",     "penetration",
                                       "hausdorff",    "stop-time",   "onset-time",  "flight-energy", "rest-start", "estimate", "chatter",
                                       "zero-steps",   "contact-duration", "impact-ratio",
                                       "amplitude",    "impact-count", "rest-time",  "peak-time",    "value",
                                       "summary"};
  std::vector<std::string> problem_labels;
  for (const auto& p : spec.problems) problem_labels.push_back(p.label);
  for (std::size_t i = 0; i < measures.size(); ++i) {
    const Json& j = measures[i];
    const std::string path = element("measure", i);
    FileMeasure m;
    const std::string kind = c.choice(c.require(j, path, "kind"), child(path, "kind"), kinds);
    m.kind = static_cast<MeasureKind>(std::find(kinds.begin(), kinds.end(), kind) - kinds.begin());
    if (const Json* v = c.find(j, "problems")) {
      const std::string at = child(path, "problems");
      c.expect(*v, at, v->is_array() && !v->empty(), "an array of one or more problem labels");
      for (std::size_t k = 0; k < v->size(); ++k) m.problems.push_back(c.choice((*v)[k], element(at, k), problem_labels));
    }
    // The keys every kind takes, and its own.
    const auto keys = [&](std::vector<std::string> own) {
      own.insert(own.end(), {"kind", "label", "problems"});
      c.keys(j, path, own);
    };
    // The problems it is measured on: their index in spec.problems.
    std::vector<std::size_t> on;
    for (std::size_t p = 0; p < instances.size(); ++p)
      if (m.applies_to(spec.problems[p].label)) on.push_back(p);
    if (m.kind >= MeasureKind::ImpactRatio) {
      read_event_measure(c, j, path, kind, m, spec, instances, on);
    } else if (m.kind == MeasureKind::Error || m.kind == MeasureKind::Hausdorff) {
      const bool hausdorff = m.kind == MeasureKind::Hausdorff;
      if (hausdorff) {
        keys({"observable", "time_scale", "value_scale", "norm"});
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
      } else {
        keys({"observable", "norm", "window", "relative_to", "against", "scale", "inside", "semi_discrete", "dof", "per_nominal_step"});
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
    } else if (m.kind == MeasureKind::ImpactTime) {
      keys({"count", "located", "min_flight_steps", "norm"});
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
    } else if (m.kind == MeasureKind::StopTime || m.kind == MeasureKind::OnsetTime) {
      keys({});
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
    } else if (m.kind == MeasureKind::Energy) {
      keys({"norm", "history", "window", "every", "from", "relative_to"});
      if (const Json* v = c.find(j, "relative_to"))
        m.from_first_step = c.choice(*v, child(path, "relative_to"), {"initial", "first step"}) == "first step";
      read_energy_sampling(c, j, path, m);
      if (m.from_first_step && m.norm == "offset")
        c.fail(child(path, "relative_to"), "the offset is E_1 - E0 relative to E0's scale", "relative_to = \"initial\" with norm = \"offset\"");
    } else if (m.kind == MeasureKind::Chatter || m.kind == MeasureKind::ZeroSteps || m.kind == MeasureKind::ContactDuration) {
      keys(m.kind == MeasureKind::ContactDuration ? std::vector<std::string>{"exact"} : std::vector<std::string>{"observable", "scale", "inside"});
      read_step_values_measure(c, j, path, kind, m, spec, instances, on);
    } else if (m.kind == MeasureKind::Estimate) {
      keys({"observable", "order"});
      read_next_run_estimate(c, j, path, m, spec, instances, on);
    } else if (m.kind == MeasureKind::RestStart) {
      read_rest_start(c, j, path, m, spec, instances, on);
    } else if (m.kind == MeasureKind::FlightEnergy) {
      read_flight_energy(c, j, path, spec, on, instances, m);
      keys({"count", "norm", "min_flight_steps", "at"});
    } else {
      keys(kind == "momentum" ? std::vector<std::string>{"window", "relative_to", "component"} : std::vector<std::string>{});
      if (const Json* v = c.find(j, "relative_to"))
        m.initial_speeds_scale = c.choice(*v, child(path, "relative_to"), {"momentum", "initial speeds"}) == "initial speeds";
      m.label = kind == "momentum" ? "momentum residual" : "penetration";
      if (const Json* v = c.find(j, "component")) read_momentum_component(c, j, path, *v, m, spec, instances, on);
    }
    if (const Json* v = c.find(j, "window")) {
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
    if (const Json* v = c.find(j, "label")) m.label = c.string(*v, child(path, "label"));
    for (const auto& q : spec.measures)
      if (q.label == m.label) c.fail(path, fmt::format("a second measure labelled '{}'", m.label), "distinct labels (label = ...)");
    spec.measures.push_back(m);
  }
  spec.exclusions = read_exclusions(c, root, spec);
  spec.ranked = ranked_measure(c, study, spec.measures);
  spec.figures = read_figures(c, root, spec);
  spec.tables = read_tables(c, root, spec);
  check_trajectory_observables(c, spec, instances);
  check_impulses_and_fields(c, spec, instances);
  if (const Json* v = c.find(study, "metadata")) {
    if (!c.find(root, "table")) c.fail("study.metadata", "metadata lines are written on declared tables", "[[table]]s, or no metadata");
    spec.metadata = read_metadata_lines(c, *v, "study.metadata", spec);
  }
  if (std::any_of(spec.measures.begin(), spec.measures.end(), [](const FileMeasure& m) { return m.kind == MeasureKind::Hausdorff; }))
    for (std::size_t i = 0; i < spec.integrators.size(); ++i) {
      const auto held = [&](const FileSweep& sweep, const std::string& path) {
        for (std::size_t k = 0; k < sweep.steps.size(); ++k)
          check_held_samples(c, sweep.steps[k], spec.sample_every, longest_t_end(spec), element(child(path, "steps"), k),
                             "a run's graph for a Hausdorff distance", "study.sample_every");
        for (std::size_t k = 0; k < sweep.stable_fractions.size(); ++k)
          for (const auto& problem : instances)
            check_held_samples(c, sweep.stable_fractions[k] * problem->stable_step(), spec.sample_every, longest_t_end(spec),
                               element(child(path, "stable_steps"), k), "a run's graph for a Hausdorff distance", "study.sample_every");
        if (!sweep.tolerances.empty())
          check_held_samples(c, sweep.dt, spec.sample_every, longest_t_end(spec), child(path, "dt"), "a run's graph for a Hausdorff distance",
                             "study.sample_every");
      };
      const std::string path = element("integrator", i);
      held(spec.integrators[i].sweep, path);
      for (const auto& [label, sweep] : spec.integrators[i].per_problem) held(sweep, child(child(path, "per_problem"), label));
    }
  return spec;
}

StudySpec read_study_file(const std::filesystem::path& path) {
  // The name goes into the reports' metadata lines and headings, one line each.
  const std::string name = path.string();
  const auto control = std::find_if(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
  if (control != name.end())
    throw InputError(fmt::format("study file '{}': its name holds the control character 0x{:02x}; valid: a name without "
                                 "control characters (newlines, tabs, escapes)",
                                 one_line(name), static_cast<unsigned char>(*control)));
  return parse_study_text(read_file_bounded(path, kMaxStudyFileBytes, "study file"), path.string(),
                          path.extension() == ".json");
}

StudySpec reduced_study(StudySpec spec, double t_scale, std::size_t max_runs, long budget) {
  spec.t_end *= t_scale;
  spec.reference.t_end *= t_scale;  // a reference's own end stays past its problems' (0: theirs)
  for (auto& p : spec.problems) {
    p.t_end *= t_scale;
    if (p.reference) p.reference->t_end *= t_scale;
    if (p.max_force_evaluations > 0) p.max_force_evaluations = std::min(p.max_force_evaluations, budget);
  }
  spec.cpu_repeats = 0;
  spec.max_force_evaluations = budget;
  spec.force_evaluations_per_step = 0.0;  // the budget above, whatever the step
  const auto cut = [&](FileSweep& s) {
    if (s.steps.size() > max_runs) s.steps.resize(max_runs);
    if (s.stable_fractions.size() > max_runs) s.stable_fractions.resize(max_runs);
    if (s.tolerances.size() > max_runs) s.tolerances.resize(max_runs);
  };
  for (auto& it : spec.integrators) {
    cut(it.sweep);
    for (auto& [label, s] : it.per_problem) cut(s);
  }
  return spec;
}

}  // namespace nsb
