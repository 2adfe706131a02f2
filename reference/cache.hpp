#pragma once
// Reference runs cached as files, so that studies reuse them instead of recomputing.
//
// A run is identified by its metadata: problem and its full parameter list (defaults
// included), integrator and its full parameter list, dt, t_end, sample_every, the cache
// format version and the SUNDIALS version. key = FNV-1a 64-bit hash of that JSON (sorted
// keys), and the run is stored as <dir>/<key>.json (metadata + the run's figures and work
// counters) and <dir>/<key>.csv (the series, shortest round-trip numbers: reloads exactly).
// The .json also holds the FNV-1a 64 of the .csv's bytes (series_fnv1a64). A run is
// regenerated when a file is missing or unreadable, when the .csv does not match that hash
// (edited or cut short), when the stored metadata differs from the requested one (stale: e.g. a parameter default changed),
// or when the series lacks a column of the problem's observables (stored before the problem gained it). Bump
// kReferenceCacheVersion when the reference integrators change their results.
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "run/run.hpp"

namespace nsb {

inline constexpr int kReferenceCacheVersion = 4;

struct ReferenceRequest {
  std::string problem;
  std::map<std::string, std::string> problem_parameters;  // overrides of the defaults
  std::string integrator;
  std::map<std::string, std::string> integrator_parameters;
  double dt = 0.0;
  double t_end = 0.0;
  long sample_every = 1;
};

struct CachedReference {
  nlohmann::json metadata;
  nlohmann::json summary;  // status, message, steps, cpu_seconds, work counters
  Series series;
  bool from_cache = false;
};

// The canonical metadata of a request (throws InputError for unknown names or bad values).
nlohmann::json reference_metadata(const ReferenceRequest& request);
std::string reference_key(const nlohmann::json& metadata);

// Where studies keep reference runs: $NSBENCH_REFERENCE_CACHE, default .nsbench-cache/reference.
std::filesystem::path reference_cache_dir();

// Loads the run from `dir` when present and current, otherwise runs it and stores it. Callers in
// several threads asking for the same run wait for one computation of it.
CachedReference cached_reference(const std::filesystem::path& dir, const ReferenceRequest& request);

}  // namespace nsb
