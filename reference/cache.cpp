#include "reference/cache.hpp"

#include <fmt/format.h>
#include <sundials/sundials_config.h>

#include <algorithm>
#include <cstdint>
#include <mutex>
#include <set>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <thread>

#include "core/json.hpp"
#include "core/output.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"

namespace nsb {

namespace {

// Far above any reference series a study asks for (500,001 rows of a few columns: ~50 MB).
constexpr std::size_t kMaxCacheFileBytes = std::size_t{4} << 30;

// A missing, unreadable or oversized file reads as empty: the run is regenerated.
std::string read_text(const std::filesystem::path& path) {
  try {
    return read_file_bounded(path, kMaxCacheFileBytes, "reference cache");
  } catch (const InputError&) {
    return {};
  }
}

// Written beside and renamed: a reader never sees half a file, and concurrent writers of
// the same run (parallel study cases) each rename a whole file of the same content. The
// error, empty when written.
std::string write_text(const std::filesystem::path& path, const std::string& text) {
  const auto tmp = std::filesystem::path(
      fmt::format("{}.{}.tmp", path.string(), std::hash<std::thread::id>()(std::this_thread::get_id())));
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out) return fmt::format("cannot write {}", tmp.string());
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (!ec) return {};
  std::filesystem::remove(tmp, ec);
  return fmt::format("cannot write {}", path.string());
}

// Why a stored entry cannot be used as the summary of a run; empty when it can. The
// metadata is compared by the caller.
std::string damage(const nlohmann::json& stored) {
  if (stored.is_discarded()) return "not JSON, or nested too deep";
  if (!stored.is_object()) return "not a JSON object";
  for (const char* key : {"metadata", "summary", "series_fnv1a64"})
    if (!stored.contains(key)) return fmt::format("no key '{}'", key);
  if (!stored["series_fnv1a64"].is_string()) return "series_fnv1a64 is not a string";
  const auto& s = stored["summary"];
  if (!s.is_object()) return "summary is not an object";
  if (!s.contains("status") || (s["status"] != "ok" && s["status"] != "diverged")) return "summary.status is not \"ok\" or \"diverged\"";
  if (!s.contains("message") || !s["message"].is_string()) return "summary.message is not a string";
  if (!s.contains("steps") || !s["steps"].is_number_integer() || s["steps"].get<long>() < 0) return "summary.steps is not a count";
  if (!s.contains("cpu_seconds") || !s["cpu_seconds"].is_number()) return "summary.cpu_seconds is not a number";
  if (!s.contains("work") || !s["work"].is_object()) return "summary.work is not an object";
  for (const char* key : {"steps", "force_evaluations", "tangent_evaluations", "factorizations", "linear_solves"})
    if (!s["work"].contains(key) || !s["work"][key].is_number_integer() || s["work"][key].get<long>() < 0)
      return fmt::format("summary.work.{} is not a count", key);
  for (const auto& [key, value] : s["work"].items())
    if (!value.is_number()) return fmt::format("summary.work.{} is not a number", key);
  return {};
}

// One warning line per cache location and kind of trouble, not one per run of a study.
void warn_once(const std::string& line) {
  static std::mutex mutex;
  static std::set<std::string> said;
  const std::lock_guard lock(mutex);
  if (said.insert(line).second) fmt::print(stderr, "nsbench: warning: {}\n", line);
}

// Inverse of series_to_csv; nullopt when the text is not a well-formed series.
std::optional<Series> parse_series(const std::string& text) {
  std::istringstream in(text);
  std::string line;
  Series s;
  if (!std::getline(in, line) || line.empty()) return std::nullopt;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');) s.columns.push_back(name);
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::size_t count = 0;
    for (std::string cell; std::getline(row, cell, ','); ++count) {
      char* end = nullptr;
      s.values.push_back(std::strtod(cell.c_str(), &end));
      if (end != cell.c_str() + cell.size()) return std::nullopt;
    }
    if (count != s.columns.size()) return std::nullopt;
  }
  return s;
}

// Whether a stored series has a column for each of the problem's observables: one stored before
// the problem gained an observable (the metadata names no observables) is stale.
bool records_observables(const Series& series, const Problem& problem) {
  const auto names = problem.observable_names();
  return std::all_of(names.begin(), names.end(), [&](const std::string& name) {
    return std::find(series.columns.begin(), series.columns.end(), name) != series.columns.end();
  });
}

// Stores a computed run; a location that takes no files (NSBENCH_REFERENCE_CACHE=/proc/x,
// a regular file, a read-only directory, a <key>.csv that is a directory) leaves the run
// unstored, with a warning: the cache only saves time, a study's results are the same
// without it, so it is no reason to stop one.
void store(const std::filesystem::path& dir, const CachedReference& ref) {
  const std::string key = reference_key(ref.metadata);
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir)) {
    warn_once(fmt::format("reference cache {}: cannot create the directory{}; the reference runs are computed and "
                          "not stored (NSBENCH_REFERENCE_CACHE sets the location)",
                          dir.string(), ec ? ": " + ec.message() : ""));
    return;
  }
  const std::string csv = series_to_csv(ref.series);
  std::string error = write_text(dir / (key + ".csv"), csv);
  if (error.empty())
    error = write_text(dir / (key + ".json"),
                       nlohmann::json{{"metadata", ref.metadata}, {"summary", ref.summary}, {"series_fnv1a64", fnv1a64(csv)}}.dump(2) + "\n");
  if (!error.empty())
    warn_once(fmt::format("reference cache {}: {}; the reference runs are computed and not stored "
                          "(NSBENCH_REFERENCE_CACHE sets the location)", dir.string(), error));
}

}  // namespace

nlohmann::json reference_metadata(const ReferenceRequest& r) {
  const auto& problem = find_problem(r.problem);
  const auto& integrator = find_integrator(r.integrator);
  return {{"cache_version", kReferenceCacheVersion},
          {"sundials_version", SUNDIALS_VERSION},
          {"problem", r.problem},
          {"problem_parameters", Params(problem.parameters(), r.problem_parameters).values()},
          {"integrator", r.integrator},
          {"integrator_parameters", Params(integrator.parameters(), r.integrator_parameters).values()},
          {"dt", r.dt},
          {"t_end", r.t_end},
          {"sample_every", r.sample_every}};
}

std::string reference_key(const nlohmann::json& metadata) {
  return fnv1a64(metadata.dump());
}

std::filesystem::path reference_cache_dir() {
  const char* env = std::getenv("NSBENCH_REFERENCE_CACHE");
  return env && *env ? std::filesystem::path(env) : std::filesystem::path(".nsbench-cache/reference");
}

// One lock per cached run: the cases of a study that read the same reference, run in parallel,
// wait for the first to compute it and then load it, instead of each computing it.
std::mutex& key_mutex(const std::string& key) {
  static std::mutex guard;
  static std::map<std::string, std::mutex> mutexes;  // node-based: the references stay valid
  const std::lock_guard lock(guard);
  return mutexes[key];
}

CachedReference cached_reference(const std::filesystem::path& dir, const ReferenceRequest& request) {
  CachedReference ref;
  ref.metadata = reference_metadata(request);
  const std::string key = reference_key(ref.metadata);
  const std::lock_guard lock(key_mutex(key));
  const auto json_path = dir / (key + ".json"), csv_path = dir / (key + ".csv");

  const std::string text = read_text(json_path);
  const auto stored = parse_json_bounded(text);
  const std::string damaged = text.empty() ? "" : damage(stored);
  if (!damaged.empty())
    fmt::print(stderr, "nsbench: warning: reference cache {}: damaged ({}), rebuilt\n", json_path.string(), damaged);
  auto problem = make_problem(request.problem, request.problem_parameters);
  if (!text.empty() && damaged.empty() && stored["metadata"] == ref.metadata) {
    const std::string csv = read_text(csv_path);
    const auto series = stored["series_fnv1a64"] == fnv1a64(csv) ? parse_series(csv) : std::nullopt;
    if (series && records_observables(*series, *problem)) {
      ref.summary = stored["summary"];
      ref.series = std::move(*series);
      ref.from_cache = true;
      return ref;
    }
  }

  auto integrator = make_integrator(request.integrator, request.integrator_parameters);
  integrator->init(*problem, problem->initial_state());
  RunOptions options;
  options.dt = request.dt;
  options.t_end = request.t_end;
  options.sample_every = request.sample_every;
  const RunResult r = run(*problem, *integrator, options);
  nlohmann::json work = {{"steps", r.work.steps},
                         {"force_evaluations", r.work.force_evaluations},
                         {"tangent_evaluations", r.work.tangent_evaluations},
                         {"factorizations", r.work.factorizations},
                         {"linear_solves", r.work.linear_solves}};
  for (const auto& [k, v] : r.work.extra) work[k] = v;
  ref.summary = {{"status", r.status == RunStatus::Ok ? "ok" : "diverged"},
                 {"message", r.message},
                 {"steps", r.steps},
                 {"cpu_seconds", r.cpu_seconds},
                 {"work", work}};
  ref.series = r.series;
  store(dir, ref);
  return ref;
}

}  // namespace nsb
