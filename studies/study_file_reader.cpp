// Reading and checking a study file (schema: studies/study_file.hpp, README.md): the study's own
// keys, its problems, integrators, reference and measures in turn (studies/study_file/read_*.cpp
// read each part), every error "FILE:LINE: key.path: what; valid: ...".
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <iterator>
#include <memory>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

#include "core/output.hpp"
#include "problems/registry.hpp"
#include "studies/report_text.hpp"

namespace nsb::study_files {

namespace {

// A study file is a page of text; anything larger is not one (/dev/zero, a data file given by mistake).
constexpr std::size_t kMaxStudyFileBytes = 1 << 20;

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

std::string stem_name(const std::string& file) {
  std::string name;
  for (char ch : std::filesystem::path(file).stem().string())
    name += std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::tolower(ch)) : '_';
  return name.empty() ? "study" : name;
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

// [study]'s keys into spec; returns study.integrators: "all" (every registered integrator),
// "schemes" (those not peers and not references) or "" (the [[integrator]] tables').
std::string read_study_keys(const Checker& c, const Json& study, StudySpec& spec) {
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
  const std::string registered_integrators =
      c.find(study, "integrators") ? c.choice(study["integrators"], "study.integrators", {"all", "schemes"}) : "";
  if (const Json* v = c.find(study, "figures")) spec.declared_figures_only = c.choice(*v, "study.figures", {"all", "declared"}) == "declared";
  return registered_integrators;
}

// [[problem]] j into spec.problems (each point of its grid a problem), an instance of each into `instances`.
void read_problem(const Checker& c, const Json& j, const std::string& path, StudySpec& spec,
                  std::vector<std::unique_ptr<Problem>>& instances) {
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

// [[integrator]] j into `declared` (nothing for an optional one this build does not register).
void read_integrator(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec,
                     const std::vector<std::unique_ptr<Problem>>& instances, std::vector<FileIntegrator>& declared) {
  const std::vector<std::string> sweep_keys{"parameters", "steps", "full_steps", "stable_steps", "tolerances", "tolerance_parameter",
                                           "tolerance_divisors", "dt"};
  auto keys = sweep_keys;
  keys.insert(keys.end(), {"name", "label", "per_problem", "optional"});
  c.keys(j, path, keys);
  // optional = true: left out of a build that does not register it (a peer whose package is
  // absent), so that the file still runs there; a name no build knows is still an error there.
  if (const Json* o = c.find(j, "optional"); o && c.boolean(*o, child(path, "optional"))) {
    const Json& name = c.require(j, path, "name");
    const auto names = names_of(integrator_registry());
    if (name.is_string() && std::find(names.begin(), names.end(), name.get<std::string>()) == names.end()) return;
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

// The study's integrators: the [[integrator]] tables', or with study.integrators = "all" (or
// "schemes") each registered one, with the problems' steps, but those the [[integrator]] tables
// name: in its place, the tables' variants, in their order.
void read_integrators(const Checker& c, const Json& root, const std::string& registered_integrators, StudySpec& spec,
                      const std::vector<std::unique_ptr<Problem>>& instances) {
  const bool all_integrators = !registered_integrators.empty();
  std::vector<FileIntegrator> declared;
  const Json& integrators = all_integrators && !c.find(root, "integrator") ? Json::array() : required_tables(c, root, "integrator");
  for (std::size_t i = 0; i < integrators.size(); ++i) read_integrator(c, integrators[i], element("integrator", i), spec, instances, declared);
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
}

// A Hausdorff distance compares a run's whole graph: the samples each run holds for it stay
// within the limit (check_held_samples).
void check_hausdorff_samples(const Checker& c, const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances) {
  if (std::none_of(spec.measures.begin(), spec.measures.end(), [](const FileMeasure& m) { return m.kind == MeasureKind::Hausdorff; })) return;
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
}

}  // namespace

// [[KEY]]: one or more tables.
const Json& required_tables(const Checker& c, const Json& root, const char* key) {
  const Json& a = c.require(root, "", key);
  c.expect(a, key, a.is_array() && !a.empty(), fmt::format("one or more [[{}]] tables", key));
  for (std::size_t i = 0; i < a.size(); ++i) c.expect(a[i], element(key, i), a[i].is_object(), "a table");
  return a;
}

}  // namespace nsb::study_files

namespace nsb {

StudySpec parse_study_text(const std::string& text, const std::string& file, bool json) {
  using namespace study_files;  // the reader's own functions, here alone
  Lines lines;
  const Json root = read_tree(text, file, json, lines);
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
  const std::string registered_integrators = read_study_keys(c, study, spec);
  std::vector<std::unique_ptr<Problem>> instances;
  const Json& problems = required_tables(c, root, "problem");
  for (std::size_t i = 0; i < problems.size(); ++i) read_problem(c, problems[i], element("problem", i), spec, instances);
  read_integrators(c, root, registered_integrators, spec, instances);
  if (const Json* r = c.find(root, "reference")) {
    std::vector<std::size_t> served;  // the problems without a reference of their own
    for (std::size_t p = 0; p < spec.problems.size(); ++p)
      if (!spec.problems[p].reference) served.push_back(p);
    spec.reference = read_reference(c, *r, "reference", spec, served, instances);
    spec.has_reference = true;
  }
  read_measures(c, root, spec, instances);
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
  check_hausdorff_samples(c, spec, instances);
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
  return parse_study_text(read_file_bounded(path, study_files::kMaxStudyFileBytes, "study file"), path.string(),
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
