#pragma once
// The study-file reader's own functions shared between its files (studies/study_file/read_*.cpp,
// studies/study_file_reader.cpp): the Checker every value is read through, and the readers of
// each part of the file. Not part of the library's interface (studies/study_file.hpp is).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/parameters.hpp"
#include "core/plugin.hpp"
#include "integrators/registry.hpp"
#include "problems/problem.hpp"
#include "studies/study.hpp"
#include "studies/study_file.hpp"

namespace nsb::study_files {

using Lines = std::map<std::string, long>;

inline std::string child(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

inline std::string element(const std::string& path, std::size_t i) { return fmt::format("{}[{}]", path, i); }

// read_tree.cpp
// The file's text as one JSON tree (TOML converted), with the line of each key path in `lines`
// (TOML; JSON's lines are found in its text by json_line).
Json read_tree(const std::string& text, const std::string& file, bool json, Lines& lines);
long json_line(const std::string& text, const std::string& path);
std::string type_name(const Json& j);

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

// read_sweeps.cpp
void check_step(const Checker& c, double dt, const std::string& path, double t_end, const std::string& whose = "study.t_end");
void check_held_samples(const Checker& c, double dt, long sample_every, double t_end, const std::string& path,
                        const std::string& what, const std::string& sample_key);
void check_steps(const Checker& c, const FileSweep& s, const std::string& path, const StudySpec& spec, const FileProblem& p,
                 double stable);
std::vector<double> stable_fractions(const Checker& c, const Json& j, const std::string& path);
FileSweep read_sweep(const Checker& c, const Json& j, const std::string& path, const IntegratorEntry& entry,
                     const FileSweep* base);
void sweep_from_problems(const Checker& c, FileIntegrator& it, const std::string& path, const std::vector<FileProblem>& problems);
void add_integrator(const Checker& c, std::vector<FileIntegrator>& integrators, FileIntegrator it, const std::string& path);

// read_problems.cpp
void read_problem_steps(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileProblem& p);
FileReference read_reference(const Checker& c, const Json& r, const std::string& path, const StudySpec& spec,
                             const std::vector<std::size_t>& served, const std::vector<std::unique_ptr<Problem>>& instances);
std::pair<double, double> read_window(const Checker& c, const Json& v, const std::string& at, const StudySpec& spec,
                                      const std::vector<std::size_t>& on);
std::vector<FileProblem> grid_points(const Checker& c, const Json& j, const std::string& path, const FileProblem& base,
                                     const ParamSpecs& specs);
void read_problem_outcome(const Checker& c, const Json& j, const std::string& path, FileProblem& p);
void read_end_at_impact(const Checker& c, const Json& j, const std::string& path, const Problem& instance, FileProblem& p);
void read_t_end_exact(const Checker& c, const Json& j, const std::string& path, const Problem& instance, FileProblem& p);
double longest_t_end(const StudySpec& spec);

// read_measure_list.cpp: the [[measure]] list into spec.measures.
void read_measures(const Checker& c, const Json& root, StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances);

// read_measures.cpp
void read_min_flight_steps(const Checker& c, const Json& j, const std::string& path, FileMeasure& m);
void read_flight_energy(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec,
                        const std::vector<std::size_t>& on, const std::vector<std::unique_ptr<Problem>>& instances, FileMeasure& m);
void read_momentum_component(const Checker& c, const Json& j, const std::string& path, const Json& v, FileMeasure& m,
                             const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                             const std::vector<std::size_t>& on);
void check_observable(const Checker& c, const std::string& at, const std::string& name, const std::vector<std::string>& valid,
                      const std::string& label, const std::string& detail = "", const std::string& instead = "problems = [...]");
std::vector<std::string> state_observable_names(const Problem& problem);
void read_next_run_estimate(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                            const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on);
void check_against(const Checker& c, const std::string& path, const FileMeasure& m, const std::vector<std::string>& names,
                   const std::string& label);
void read_inside_phase(const Checker& c, const Json& v, const std::string& path, FileMeasure& m, const StudySpec& spec,
                       const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on);
void read_step_values_measure(const Checker& c, const Json& j, const std::string& path, const std::string& kind, FileMeasure& m,
                              const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                              const std::vector<std::size_t>& on);
void read_rest_start(const Checker& c, const Json& j, const std::string& path, FileMeasure& m, const StudySpec& spec,
                     const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on);
void read_event_measure(const Checker& c, const Json& j, const std::string& path, const std::string& kind, FileMeasure& m,
                        const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances,
                        const std::vector<std::size_t>& on);
void read_semi_discrete(const Checker& c, const Json& j, const std::string& path, FileMeasure& m,
                        const std::vector<std::unique_ptr<Problem>>& instances, const std::vector<std::size_t>& on);
std::size_t ranked_measure(const Checker& c, const Json& study, const std::vector<FileMeasure>& measures);
void read_energy_sampling(const Checker& c, const Json& j, const std::string& path, FileMeasure& m);

// read_figures.cpp
bool is_file_stem(const std::string& id);
const Json& optional_tables(const Checker& c, const Json& root, const char* key);
std::vector<FileFigure> read_figures(const Checker& c, const Json& root, const StudySpec& spec);
void check_field_figure(const Checker& c, const std::string& path, const FileFigure& f, const FileTable& table);
void check_pivot_figure_y(const Checker& c, const std::string& at, const std::string& y, const FileTable& pivot);
void check_table_figures(const Checker& c, const StudySpec& spec, const std::vector<FileTable>& tables);

// read_tables.cpp
std::vector<std::string> table_sources(const std::string& rows, const StudySpec& spec);
FileColumn read_column(const Checker& c, const Json& j, const std::string& path, const std::vector<std::string>& sources);
std::vector<FileTable> read_tables(const Checker& c, const Json& root, const StudySpec& spec);

// read_table_kinds.cpp
void read_some_runs(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t);
void read_group_fit(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t);
std::vector<std::string> fitted_group_sources(const StudySpec& spec);
void read_except_and_order(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t);
void read_not_ok(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t);
void check_trajectory_observables(const Checker& c, const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances);
std::vector<MetadataLine> read_metadata_lines(const Checker& c, const Json& v, const std::string& path, const StudySpec& spec);
void read_impulses_and_field(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t);
void check_impulses_and_fields(const Checker& c, const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances);

// study_file_reader.cpp: [[KEY]], one or more tables.
const Json& required_tables(const Checker& c, const Json& root, const char* key);

}  // namespace nsb::study_files
