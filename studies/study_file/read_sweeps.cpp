// Reading an integrator's sweeps (steps, stable-step fractions, tolerances), checked against the
// run driver's limits.
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "run/run.hpp"

namespace nsb::study_files {

namespace {

// A series held in memory whole (a reference run's samples; a run's graph for a Hausdorff
// distance) is bounded before any work: at most kMaxHeldSamples samples (1e7: 160 MB as a
// Hausdorff graph, 80 MB a column of a reference).
constexpr double kMaxHeldSamples = 1e7;

// A stiff part's stable step can be far below the step an implicit scheme takes (the hard
// study's 900 x CFL): a multiple up to 1000.
constexpr double kMaxStableFraction = 1000.0;

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

bool no_sweep(const FileSweep& s) { return s.steps.empty() && s.stable_fractions.empty() && s.tolerances.empty(); }

}  // namespace

// The run driver's limits (run/run.cpp), checked here so that a study stops at its
// file's line before any run or any file is written.
void check_step(const Checker& c, double dt, const std::string& path, double t_end, const std::string& whose) {
  const long limit = RunOptions{}.max_steps;
  if (dt > t_end) c.fail(path, fmt::format("dt = {:g} is larger than {} = {:g}", dt, whose, t_end), "dt <= t_end");
  if (t_end / dt > static_cast<double>(limit))
    c.fail(path, fmt::format("{} / dt = {:g} / {:g} = {:.3g} steps, more than a run's limit of {}", whose, t_end, dt, t_end / dt, limit),
           fmt::format("dt >= t_end / {} = {:g}", limit, t_end / static_cast<double>(limit)));
}

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
  if (!s.stable_fractions.empty() && !(stable > 0.0))  // NaN or <= 0: a plugin's problem breaking its contract (inf: no stiffness)
    c.fail(child(path, "stable_steps"), fmt::format("problem '{}' ({}) reports the stable step {}", p.label, p.name, stable),
           "a problem whose stable_step() is > 0 (inf without stiffness)");
  for (std::size_t i = 0; i < s.stable_fractions.size(); ++i)
    check_step(c, s.stable_fractions[i] * stable, element(child(path, "stable_steps"), i), t_end,
               fmt::format("{} (problem '{}', stable step {:g})", whose, p.label, stable));
  if (!s.tolerances.empty()) check_step(c, s.dt, child(path, "dt"), t_end, whose);
}

// stable_steps: dt as a multiple of the problem's stable step, (0, 1000].
std::vector<double> stable_fractions(const Checker& c, const Json& j, const std::string& path) {
  std::vector<double> v = c.distinct_list(j, path);
  for (std::size_t i = 0; i < v.size(); ++i)
    if (v[i] > kMaxStableFraction)
      c.fail(element(path, i), fmt::format("{} stable steps is no step of a study", v[i]),
             fmt::format("(0, {:g}]: dt as a multiple of the problem's stable step 2 / omega_max", kMaxStableFraction));
  return v;
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

// An integrator joins the study under a label no other has.
void add_integrator(const Checker& c, std::vector<FileIntegrator>& integrators, FileIntegrator it, const std::string& path) {
  for (const auto& q : integrators)
    if (q.label == it.label) c.fail(child(path, "label"), fmt::format("label '{}' used twice", it.label), "distinct labels");
  integrators.push_back(std::move(it));
}

}  // namespace nsb::study_files
