#include "studies/shard.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <regex>

#include "core/build_info.hpp"
#include "core/json.hpp"
#include "core/output.hpp"
#include "core/plugin.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace fs = std::filesystem;

namespace {

// A shard holds cases' figures and histories, not series: far below this.
constexpr std::size_t kMaxShardBytes = std::size_t{1} << 30;

// A decimal integer in [lo, hi]; nullopt for anything else (sign, overflow, other characters).
std::optional<long> decimal(const std::string& text, long lo, long hi) {
  long v = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc() || end != text.data() + text.size() || v < lo || v > hi) return std::nullopt;
  return v;
}

// The keys the studies' results share, where present: "status" one of the run statuses
// (status_name) or of kStudyStatuses, "message" a string, "steps" and "force_evaluations"
// whole numbers >= 0. Empty when they hold, else why not.
std::string result_damage(const Json& r) {
  if (!r.is_object()) return "not an object";
  if (r.contains("status")) {
    const Json& status = r["status"];
    bool known = false;
    for (const std::string_view s : kStudyStatuses) known = known || (status.is_string() && status.get_ref<const std::string&>() == s);
    for (const RunStatus s : {RunStatus::Ok, RunStatus::Diverged, RunStatus::OverBudget, RunStatus::Interrupted})
      known = known || status == status_name(s);
    if (!known) return fmt::format("status {} is not a run status", status.dump());
  }
  if (r.contains("message") && !r["message"].is_string()) return "message is not a string";
  for (const char* key : {"steps", "force_evaluations"})
    if (r.contains(key) && !(r[key].is_number_integer() && r[key].get<long>() >= 0))
      return fmt::format("{} {} is not a whole number >= 0", key, r[key].dump());
  return {};
}

// JSON has no inf or NaN (nlohmann writes them as null), but a result may hold them (a run
// whose energy overflowed: its energy growth is inf, a table cell "inf"). A shard writes each
// as {"non_finite": "inf" | "-inf" | "nan"} and the merge reads it back, so that merged reports
// equal a single machine's.
constexpr const char* kNonFinite = "non_finite";

// j with each element `replace` gives a value for replaced by it, recursively.
Json replaced(const Json& j, const std::function<std::optional<Json>(const Json&)>& replace) {
  if (auto r = replace(j)) return *r;
  if (!j.is_structured()) return j;
  Json out = j.is_array() ? Json::array() : Json::object();
  if (j.is_array())
    for (const Json& e : j) out.push_back(replaced(e, replace));
  else
    for (const auto& [k, e] : j.items()) out[k] = replaced(e, replace);
  return out;
}

Json portable(const Json& j) {
  return replaced(j, [](const Json& x) -> std::optional<Json> {
    if (!x.is_number_float() || std::isfinite(x.get<double>())) return std::nullopt;
    const double v = x.get<double>();
    return Json{{kNonFinite, std::isnan(v) ? "nan" : v > 0 ? "inf" : "-inf"}};
  });
}

Json restored(const Json& j) {
  return replaced(j, [](const Json& x) -> std::optional<Json> {
    if (!x.is_object() || x.size() != 1 || !x.contains(kNonFinite) || !x[kNonFinite].is_string()) return std::nullopt;
    const std::string& v = x[kNonFinite].get_ref<const std::string&>();
    if (v == "inf") return Json(std::numeric_limits<double>::infinity());
    if (v == "-inf") return Json(-std::numeric_limits<double>::infinity());
    if (v == "nan") return Json(std::numeric_limits<double>::quiet_NaN());
    return std::nullopt;
  });
}

// What computed a shard's results: nsbench's version and revision, its build, and each loaded
// plugin's file, hash and build. A merge takes only shards of its own code (an -O0 plugin's
// shard beside an optimised one's was merged into a report stamped as the latter).
Json code_identity() {
  const BuildInfo& b = build_info();
  Json plugins = Json::array();
  for (const auto& p : loaded_plugins()) plugins.push_back({{"file", p.file}, {"hash", p.hash}, {"build", p.build_text()}});
  return {{"nsbench", b.version}, {"git_revision", b.git_revision}, {"build_type", b.build_type}, {"compiler", b.compiler},
          {"plugins", plugins}};
}

std::string content_hash(Json file) {
  file.erase("content_fnv1a64");
  return fnv1a64(file.dump());
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  if (slash != std::string::npos) {
    const auto n = decimal(text.substr(slash + 1), 1, kMaxShards);
    const auto i = n ? decimal(text.substr(0, slash), 1, *n) : std::nullopt;
    if (i) return {*i, *n};
  }
  throw InputError(fmt::format("--shard '{}': expected I/N with 1 <= I <= N <= {}", text, kMaxShards));
}

fs::path shard_path(const fs::path& out, const std::string& study, long i, long n) {
  return out / "shards" / fmt::format("{}-{}-of-{}.json", study, i, n);
}

std::string shard_text(const std::string& study, bool full, const Shard& shard, const std::vector<Json>& cases,
                       const std::vector<std::size_t>& mine, const std::vector<Json>& results) {
  Json file = {{"study", study}, {"full", full}, {"shard", shard.index}, {"of", shard.count}, {"code", code_identity()},
               {"cases", cases}, {"results", Json::object()}};
  for (std::size_t j = 0; j < mine.size(); ++j) file["results"][std::to_string(mine[j])] = portable(results[j]);
  file["content_fnv1a64"] = content_hash(file);
  return file.dump() + "\n";
}

std::vector<Json> merge_shards(const std::string& study, const std::vector<Json>& cases, const fs::path& out, bool full,
                               const std::function<std::string(const Json&, const Json&)>& check) {
  const std::regex name(study + R"(-(\d+)-of-(\d+)\.json)");
  long count = 0;
  if (fs::is_directory(out / "shards"))
    for (const auto& f : fs::directory_iterator(out / "shards")) {
      std::smatch m;
      const std::string fname = f.path().filename().string();
      if (!std::regex_match(fname, m, name)) continue;
      const auto n = decimal(m[2], 1, kMaxShards);
      if (!n) throw InputError(fmt::format("--merge: {}: not a shard file name (at most {} shards)", f.path().string(), kMaxShards));
      count = std::max(count, *n);
    }
  if (count == 0) throw InputError(fmt::format("--merge: no shard files for study {} in {}", study, (out / "shards").string()));
  std::vector<Json> results(cases.size());
  for (long i = 1; i <= count; ++i) {
    const fs::path path = shard_path(out, study, i, count);
    if (!fs::exists(path)) throw InputError(fmt::format("--merge: shard {} of {} of study {} is missing", i, count, study));
    const auto refuse = [&](const std::string& why) {
      return InputError(fmt::format("--merge: {}: {}; rerun this shard (--shard {}/{})", path.string(), why, i, count));
    };
    const Json shard = parse_json_bounded(read_file_bounded(path, kMaxShardBytes, "--merge: shard"));
    if (shard.is_discarded() || !shard.is_object())
      throw refuse(fmt::format("not a JSON object (damaged, cut short or nested deeper than {})", kMaxJsonDepth));
    for (const char* key : {"study", "full", "shard", "of", "code", "cases", "results", "content_fnv1a64"})
      if (!shard.contains(key)) throw refuse(fmt::format("no key '{}'", key));
    if (!shard["content_fnv1a64"].is_string() || shard["content_fnv1a64"] != content_hash(shard))
      throw refuse("its content does not match its content_fnv1a64 hash (edited or damaged)");
    if (shard["study"] != study || shard["shard"] != i || shard["of"] != count)
      throw refuse(fmt::format("it names study {} shard {} of {}", shard["study"].dump(), shard["shard"].dump(), shard["of"].dump()));
    if (const Json own = code_identity(); shard["code"] != own)
      throw refuse(fmt::format("computed by other code ({}), not this merge's ({})", shard["code"].dump(), own.dump()));
    if (shard["cases"] != Json(cases) || shard["full"] != full)
      throw refuse("made by other study definitions (stale)");
    if (!shard["results"].is_object()) throw refuse("'results' is not an object");
    for (const auto& [k, written] : shard["results"].items()) {
      const Json r = restored(written);
      const auto index = decimal(k, 0, static_cast<long>(cases.size()) - 1);
      if (!index || *index % count != i - 1)
        throw refuse(fmt::format("results key '{}' is not a case of this shard (cases 0 to {}, k % {} = {})", k,
                                 cases.size() - 1, count, i - 1));
      if (!r.is_object()) throw refuse(fmt::format("result {} is not an object", k));
      std::string damage = result_damage(r);
      if (damage.empty() && check) damage = check(cases[static_cast<std::size_t>(*index)], r);
      if (!damage.empty()) throw refuse(fmt::format("result {}: {}", k, damage));
      results[static_cast<std::size_t>(*index)] = r;
    }
  }
  for (std::size_t k = 0; k < results.size(); ++k)
    if (results[k].is_null()) throw InputError(fmt::format("--merge: case {} of study {} is in no shard", k, study));
  return results;
}

}  // namespace nsb
