#include "studies/case_run.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <optional>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "run/run_case.hpp"
#include "studies/run_measure.hpp"
#include "studies/study_file.hpp"

namespace nsb {

namespace {

const Json& required(const Json& c, const char* key) {
  if (!c.is_object() || !c.contains(key)) throw InputError(fmt::format("case: key '{}' is missing", key));
  return c[key];
}

std::string text_key(const Json& c, const char* key) {
  const Json& j = required(c, key);
  if (!j.is_string()) throw InputError(fmt::format("case {} {}: must be a string", key, j.dump()));
  return j.get<std::string>();
}

// A number as the text a run option is parsed from: the shortest text that reads back as it.
std::string number_text(const Json& c, const char* key, const std::string& fallback) {
  if (!c.contains(key)) return fallback;
  const Json& j = c[key];
  if (!j.is_number() || j.is_boolean()) throw InputError(fmt::format("case {} {}: must be a number", key, j.dump()));
  return j.dump();
}

std::vector<std::string> assignments_of(const Json& c) {
  if (!c.contains("set")) return {};
  const Json& s = c["set"];
  std::vector<std::string> items;
  if (s.is_array())
    for (const auto& item : s)
      if (item.is_string()) items.push_back(item.get<std::string>());
  if (!s.is_array() || items.size() != s.size()) throw InputError(fmt::format("case set {}: must be a list of \"key=value\" strings", s.dump()));
  return items;
}

long count_key(const Json& c, const char* key, long fallback) {
  if (!c.contains(key)) return fallback;
  const Json& j = c[key];
  if (!j.is_number_integer() || j.get<long>() < 0) throw InputError(fmt::format("case {} {}: must be an integer >= 0", key, j.dump()));
  return j.get<long>();
}

// The step: dt as given, or cfl times the stable step; when cfl meets a problem without a finite
// one, `declined` gets the reason.
std::string step_text(const Json& c, const Problem& p, std::string& declined) {
  if (c.contains("dt") == c.contains("cfl")) throw InputError("case: give one of 'dt' and 'cfl'");
  if (c.contains("dt")) return number_text(c, "dt", "");
  const double cfl = parse_real(number_text(c, "cfl", ""), "cfl");
  if (!(cfl > 0.0 && std::isfinite(cfl))) throw InputError(fmt::format("case cfl {}: must be a finite number > 0", cfl));
  const double stable = p.stable_step();
  if (!(stable > 0.0 && std::isfinite(stable))) {
    declined = fmt::format("cfl {}: the problem's stable step is {}, not a finite step to take a fraction of", cfl, stable);
    return "1";
  }
  return Json(cfl * stable).dump();
}

// An array of a run as JSON: {"shape": [...], "float64": the base64 of its little-endian doubles,
// row after row}, a non-finite value NaN (as reals() makes it null). A long run's numbers then
// cost 8 bytes each to hold and to hand to Python (NumPy reads them as they are), not a JSON
// value and its decimal text each.
Json packed(const std::vector<double>& values, const std::vector<std::size_t>& shape) {
  static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  static_assert(std::endian::native == std::endian::little, "packed: little-endian doubles");
  std::string bytes(values.size() * sizeof(double), '\0');
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double x = std::isfinite(values[i]) ? values[i] : std::numeric_limits<double>::quiet_NaN();
    std::memcpy(bytes.data() + i * sizeof(double), &x, sizeof(double));
  }
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t word = 0;
    for (std::size_t k = 0; k < 3; ++k) word = word << 8 | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    for (std::size_t k = 0; k < 4; ++k) text += k <= n ? kDigits[(word >> (18 - 6 * k)) & 63u] : '=';
  }
  return {{"shape", shape}, {"float64", std::move(text)}};
}

const std::vector<std::string> kStateArrays = {"u", "v", "impulses", "tangential_impulses", "tangential_impulses2"};

// The names a case keeps of what a run records (`states`: its arrays, `series`: its columns):
// every one when the key is absent or true, else those listed, each one of `valid`.
std::vector<std::string> kept(const Json& c, const char* key, const std::vector<std::string>& valid) {
  if (!c.contains(key) || c[key] == Json(true)) return valid;
  const Json& j = c[key];
  std::vector<std::string> names;
  for (const auto& name : j.is_array() ? j : Json::array({j})) {
    if (!name.is_string() || std::find(valid.begin(), valid.end(), name.get<std::string>()) == valid.end())
      throw InputError(fmt::format("case {} {}: {} is not one of {}", key, j.dump(), name.dump(), fmt::join(valid, ", ")));
    names.push_back(name.get<std::string>());
  }
  return names;
}

// u, v and the step's impulses at every sample, row after row: the arrays named in `keep`.
class StateRows final : public StateSink {
 public:
  explicit StateRows(const std::vector<std::string>& keep) {
    for (const auto& name : keep) rows[name] = {};
  }
  void state(const State& s, const Vec& normal, const Vec& tangential, const Vec& tangential2) override {
    t.push_back(s.t);
    const Vec* arrays[] = {&s.u, &s.v, &normal, &tangential, &tangential2};
    for (std::size_t k = 0; k < kStateArrays.size(); ++k)
      if (const auto it = rows.find(kStateArrays[k]); it != rows.end()) {
        it->second.width = static_cast<std::size_t>(arrays[k]->size());
        it->second.values.insert(it->second.values.end(), arrays[k]->begin(), arrays[k]->end());
      }
  }
  struct Rows {
    std::size_t width = 0;
    std::vector<double> values;
  };
  std::vector<double> t;
  std::map<std::string, Rows> rows;
};

// The columns named in `keep`, in that order (each one of the series').
Json series_json(const Series& s, const std::vector<std::string>& keep) {
  Json columns = Json::array();
  for (const auto& name : keep) {
    const std::size_t j = s.column(name);
    std::vector<double> column(s.rows());
    for (std::size_t i = 0; i < s.rows(); ++i) column[i] = s.at(i, j);
    columns.push_back(packed(column, {column.size()}));
  }
  return columns;
}

Json declined_result(const std::string& reason) { return {{"status", kDeclinedStatus}, {"message", reason}}; }

// A case with measures: the run as the one case of a study file (studies/study_file.hpp) whose
// [[measure]] tables are the case's `measures` and whose [reference] is its `reference`, so that
// every measure kind of the language is measured by the same code as in a study file.
Json measured_run(const Json& c, const std::string& problem, const std::string& integrator, const RoutedOverrides& routed,
                  const RunOptions& o, long repeats) {
  Json study = {{"title", "nsbench.study case"}, {"t_end", o.t_end}, {"sample_every", o.sample_every}, {"cpu_repeats", repeats}};
  if (o.max_force_evaluations > 0) study["max_force_evaluations"] = o.max_force_evaluations;
  Json file = {{"study", study},
               {"problem", Json::array({{{"name", problem}, {"label", problem}, {"parameters", routed.problem}}})},
               {"integrator", Json::array({{{"name", integrator}, {"label", integrator}, {"parameters", routed.integrator},
                                            {"steps", Json::array({o.dt})}}})},
               {"measure", c["measures"]}};
  if (c.contains("reference")) file["reference"] = c["reference"];
  const StudyEntry entry = file_study(parse_study_text(file.dump(), "case", true));
  const std::vector<Json> cases = study_cases(entry, {});
  if (cases.size() != 1) throw std::logic_error("a measured case is one case of its study file");
  return run_study_case(entry, cases.front(), {});
}

// The observers a case names (`observe`), their kinds and parameters checked before the run.
struct Observer {
  const RunMeasureEntry* kind;
  Params params;
};

std::vector<Observer> observers_of(const Json& c) {
  std::vector<Observer> observers;
  if (!c.contains("observe")) return observers;
  if (!c["observe"].is_array()) throw InputError(fmt::format("case observe {}: must be a list of tables", c["observe"].dump()));
  for (std::size_t k = 0; k < c["observe"].size(); ++k) {
    const Json& o = c["observe"][k];
    if (!o.is_object() || !o.contains("kind") || !o["kind"].is_string())
      throw InputError(fmt::format("case observe[{}] {}: a table with a kind (valid kinds: see nsbench.study.run_measures())", k, o.dump()));
    const RunMeasureEntry& kind = find_run_measure(o["kind"].get<std::string>());
    std::map<std::string, std::string> overrides;
    for (const auto& [key, value] : o.items())
      if (key != "kind") overrides[key] = value.is_string() ? value.get<std::string>() : value.dump();
    observers.push_back({&kind, Params(kind.parameters(), overrides)});
  }
  return observers;
}

// The observed run: each observer fed after every step, its figures under "observed" in order.
// An observer that does not apply to the problem or the scheme declines the case.
Json observed_run(const std::vector<Observer>& observers, RunCase& rc, const RunOptions& o) {
  std::vector<std::unique_ptr<RunMeasure>> running;
  try {
    for (const auto& ob : observers) running.push_back(ob.kind->make(ob.params, *rc.problem, *rc.integrator));
  } catch (const InputError& e) {
    return declined_result(e.what());
  }
  const RunResult r = run(*rc.problem, *rc.integrator, o, [&](const Integrator& it, const StepInfo& step) {
    for (auto& m : running) m->add(it, step);
  });
  Json observed = Json::array();
  for (const auto& m : running) observed.push_back(m->result());
  return {{"status", status_name(r.status)}, {"message", r.message}, {"dt", o.dt}, {"steps", r.steps},
          {"force_evaluations", r.work.force_evaluations},
          {"summary", Json::parse(summary_to_json(*rc.problem, *rc.integrator, o, r))}, {"observed", std::move(observed)}};
}

}  // namespace

Json run_described_case(const Json& c) {
  const std::string problem = text_key(c, "problem"), integrator = text_key(c, "integrator");
  const std::vector<std::string> sets = assignments_of(c);
  RunCase rc = make_run_case(problem, integrator, sets);
  std::string declined;
  RunOptions o = parse_run_options(step_text(c, *rc.problem, declined), number_text(c, "t_end", ""),
                                   number_text(c, "sample_every", "1"), OptionStyle::Python);
  o.max_force_evaluations = count_key(c, "max_force_evaluations", 0);
  const long repeats = count_key(c, "cpu_repeats", 0);
  const bool states = c.contains("states") && c["states"] != Json(false);
  const std::vector<std::string> state_arrays = states ? kept(c, "states", kStateArrays) : std::vector<std::string>{};
  if (!declined.empty()) return declined_result(declined);
  if (c.contains("measures") || c.contains("reference")) {
    if (states) throw InputError("case: states and measures: give one of them (a measured run records no series)");
    return measured_run(c, problem, integrator,
                        route_overrides(sets, find_problem(problem).parameters(), find_integrator(integrator).parameters()), o,
                        repeats);
  }
  const std::vector<Observer> observers = observers_of(c);
  if (const auto reason = init_or_decline(*rc.integrator, *rc.problem)) return declined_result(*reason);
  if (!observers.empty()) {
    if (states || repeats > 0) throw InputError("case: observe with states or cpu_repeats: give observe alone (its run is observed)");
    o.record_series = false;
    return observed_run(observers, rc, o);
  }
  StateRows rows(state_arrays);
  if (states) o.state_sink = &rows;
  const RunResult r = run(*rc.problem, *rc.integrator, o);
  const std::vector<std::string> columns = kept(c, "series", r.series.columns);  // checked once the columns are known
  Json result = {{"status", status_name(r.status)}, {"message", r.message}, {"dt", o.dt}, {"steps", r.steps},
                 {"force_evaluations", r.work.force_evaluations},
                 {"summary", Json::parse(summary_to_json(*rc.problem, *rc.integrator, o, r))},
                 {"columns", columns}, {"series", series_json(r.series, columns)}};
  if (states) {
    result["state_t"] = packed(rows.t, {rows.t.size()});
    for (const auto& [name, r] : rows.rows) result[name] = packed(r.values, {rows.t.size(), r.width});
  }
  if (repeats > 0) {
    const auto routed = route_overrides(sets, find_problem(problem).parameters(), find_integrator(integrator).parameters());
    o.state_sink = nullptr;
    const CpuCost cost = cpu_cost(*rc.problem, integrator, routed.integrator, o, static_cast<int>(repeats));
    result["cpu"] = real(cost.median);
    result["cpu_spread"] = real(cost.spread);
  }
  return result;
}

namespace {

bool reals_or_nulls(const Json& a) {
  return a.is_array() && std::all_of(a.begin(), a.end(), [](const Json& x) { return x.is_number() || x.is_null(); });
}

// A measured run's result is a study-file case's (studies/study_file.hpp): one value per measure.
std::string measured_result_damage(const Json& c, const Json& r) {
  const std::size_t measures = c.contains("measures") && c["measures"].is_array() ? c["measures"].size() : 0;
  if (!r.contains("values") || !reals_or_nulls(r["values"]) || r["values"].size() != measures)
    return fmt::format("'values' is not a list of {} numbers (or null), one per measure", measures);
  return "";
}

std::string observed_result_damage(const Json& c, const Json& r) {
  if (!r.contains("summary")) return "no 'summary'";
  if (!r.contains("observed") || !r["observed"].is_array() || r["observed"].size() != c["observe"].size())
    return fmt::format("'observed' is not a list of {} results, one per observer", c["observe"].size());
  return "";
}

}  // namespace

std::string described_result_damage(const Json& c, const Json& r) {
  if (!r.is_object() || !r.contains("status") || !r["status"].is_string()) return "no status";
  if (r["status"] == kDeclinedStatus) return r.contains("message") && r["message"].is_string() ? "" : "a declined run without its reason";
  if (c.contains("measures") || c.contains("reference")) return measured_result_damage(c, r);
  if (c.contains("observe") && c["observe"].is_array()) return observed_result_damage(c, r);
  for (const char* key : {"summary", "columns", "series"})
    if (!r.contains(key)) return fmt::format("no '{}'", key);
  if (!r["columns"].is_array() || !r["series"].is_array() || r["columns"].size() != r["series"].size())
    return "'columns' and 'series' are not lists of the same length";
  for (const auto& column : r["series"])
    if (!column.is_object() || !column.contains("shape") || !column.contains("float64") || !column["float64"].is_string())
      return "a series column is not a packed array";
  return "";
}

}  // namespace nsb
