// The cases of a study file: one per problem, integrator and step (or tolerance, or stable-step
// fraction), in the study's case order, less those an [[exclude]] rule removes.
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "core/parameters.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "studies/measures.hpp"

namespace nsb::study_files {

namespace {

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


}  // namespace

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

// The end time of a case: its problem's, or its full_t_end under --full.
double case_t_end(const StudySpec& spec, const FileProblem& p, const Json& c) {
  return c.contains("t_end") ? c["t_end"].get<double>() : spec.t_end_of(p);
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

}  // namespace nsb::study_files

namespace nsb {

Overrides file_case_parameters(const StudySpec& spec, const Json& c) {
  const FileProblem& fp = spec.problems[c["problem"].get<std::size_t>()];
  const FileSweep& sweep = spec.integrators[c["integrator"].get<std::size_t>()].sweep_for(fp.label);
  Overrides params = sweep.parameters;
  if (c["tol"].is_null()) return params;
  params[sweep.tolerance_parameter] = fmt::format("{}", c["tol"].get<double>());
  for (const auto& [name, divisor] : sweep.tolerance_divisors) params[name] = fmt::format("{}", c["tol"].get<double>() / divisor);
  return params;
}

}  // namespace nsb
