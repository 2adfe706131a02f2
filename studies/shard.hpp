#pragma once
// Shards of a study (--shard I/N, --merge): the results of the cases k with k % N == I - 1,
// written to <out>/shards/<study>-I-of-N.json and merged back into the study's results.
//
// A shard file is checked against its schema before any of it is used: the keys study, full,
// shard, of, code, cases, results and content_fnv1a64 (FNV-1a 64 of the file's JSON without
// that key, as nlohmann::json dumps it); `code` names what computed it (nsbench's version and
// git revision, build type, compiler, every loaded plugin's file, hash and build) and must be
// the merging process's own; `results` maps the decimal index of each case of this shard (and
// only those) to an object. A file cut short, damaged, from another study definition or
// another build is refused with an InputError naming it. The hash detects accidents, not
// intent: a hand edit that recomputes it passes the hash, and is refused only where a result
// breaks its schema (the checks below).
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "studies/study.hpp"

namespace nsb {

struct Shard {
  long index = 0, count = 0;  // 1-based; count 0: not sharded
};

// "I/N" with 1 <= I <= N <= kMaxShards; InputError otherwise.
Shard parse_shard(const std::string& text);
inline constexpr long kMaxShards = 1'000'000;

std::filesystem::path shard_path(const std::filesystem::path& out, const std::string& study, long i, long n);

// The text of shard `shard` of `study`: `results[j]` is the result of case `mine[j]`.
std::string shard_text(const std::string& study, bool full, const Shard& shard, const std::vector<Json>& cases,
                       const std::vector<std::size_t>& mine, const std::vector<Json>& results);

// Results of every case of a study, read back from its shard files in out/shards. Each file
// is parsed only when nested at most kMaxJsonDepth deep (core/json.hpp), and each result
// must pass the checks of the keys every study's results share ("status" a run status,
// "message" a string, "steps" and "force_evaluations" whole numbers >= 0, where present) and
// `check` (when set: a study's own schema, e.g. file_result_damage of studies/study_file.hpp),
// which returns why a result is not one the study's run_case returns, or "".
std::vector<Json> merge_shards(const std::string& study, const std::vector<Json>& cases,
                               const std::filesystem::path& out, bool full,
                               const std::function<std::string(const Json&, const Json&)>& check = {});

}  // namespace nsb
