// Damaged shard files (issue 20): every one is refused with an InputError naming the file,
// never a crash, an uncaught exception or edited numbers in the tables.
#include "studies/shard.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>

#include "core/output.hpp"
#include "studies/study.hpp"
#include "tests/support/files.hpp"
#include "../app/run_cli.hpp"

namespace fs = std::filesystem;
using nsb::Json;

namespace {

const std::vector<Json> kCases = {{{"dt", 0.1}}, {{"dt", 0.05}}, {{"dt", 0.025}}};

Json result(double value) { return {{"status", "ok"}, {"steps", 10}, {"values", {value}}}; }

void write_shards(const fs::path& out) {
  fs::create_directories(out / "shards");
  nsb::write_file_atomic(nsb::shard_path(out, "s", 1, 2),
                         nsb::shard_text("s", false, {1, 2}, kCases, {0, 2}, {result(0.0714), result(0.03)}));
  nsb::write_file_atomic(nsb::shard_path(out, "s", 2, 2), nsb::shard_text("s", false, {2, 2}, kCases, {1}, {result(0.05)}));
}

Json read_json(const fs::path& p) { return Json::parse(std::ifstream(p)); }

// Writes `j` with its content hash recomputed, as a careful forger would: the schema still holds.
void write_rehashed(const fs::path& p, Json j) {
  j.erase("content_fnv1a64");
  j["content_fnv1a64"] = nsb::fnv1a64(j.dump());
  std::ofstream(p, std::ios::trunc) << j.dump();
}

}  // namespace

TEST_CASE("shards: --shard I/N parsed without overflow", "[studies][shard]") {
  CHECK(nsb::parse_shard("3/8").index == 3);
  CHECK(nsb::parse_shard("3/8").count == 8);
  for (const char* bad : {"99999999999999999999/2", "1/99999999999999999999", "0/2", "3/2", "-1/2", "1/-2", "1/2x", "/2",
                          "1/", "1/2000000"})
    CHECK_THROWS_WITH(nsb::parse_shard(bad), Catch::StartsWith(std::string("--shard '") + bad + "': expected I/N"));
}

TEST_CASE("shards: written and merged back whole", "[studies][shard]") {
  const nsb::test::TempDir dir("shard_test");
  write_shards(dir.path);
  const auto merged = nsb::merge_shards("s", kCases, dir.path, false);
  REQUIRE(merged.size() == 3);
  CHECK(merged[0]["values"][0] == 0.0714);
  CHECK(merged[1]["values"][0] == 0.05);
  CHECK(merged[2]["values"][0] == 0.03);
}

// Found by the Slurm round trip on `hard`: a study file's outcome statuses were refused.
TEST_CASE("shards: every status a study's result may carry merges back", "[studies][shard]") {
  std::vector<std::string> statuses(nsb::kStudyStatuses.begin(), nsb::kStudyStatuses.end());
  for (const nsb::RunStatus s : {nsb::RunStatus::Ok, nsb::RunStatus::Diverged, nsb::RunStatus::OverBudget,
                                 nsb::RunStatus::Interrupted})
    statuses.emplace_back(nsb::status_name(s));
  for (const std::string& status : statuses) {
    const nsb::test::TempDir dir("shard_test");
    fs::create_directories(dir.path / "shards");
    Json r = result(0.5);
    r["status"] = status;
    nsb::write_file_atomic(nsb::shard_path(dir.path, "s", 1, 1),
                           nsb::shard_text("s", false, {1, 1}, kCases, {0, 1, 2}, {result(0.1), r, result(0.2)}));
    CAPTURE(status);
    CHECK(nsb::merge_shards("s", kCases, dir.path, false)[1]["status"] == status);
  }
}

// Found by the Slurm round trip on `hard`: JSON has no inf, and a diverged run's energy
// growth (inf in the single-machine report) came back from its shard as null (n/a).
TEST_CASE("shards: inf, -inf and NaN in a result merge back as they were", "[studies][shard]") {
  const nsb::test::TempDir dir("shard_test");
  fs::create_directories(dir.path / "shards");
  const double inf = std::numeric_limits<double>::infinity();
  Json r = result(inf);
  r["nested"] = {{"growth", -inf}, {"values", {1.0, std::numeric_limits<double>::quiet_NaN()}}};
  r["lookalike"] = {{"non_finite", "infinite"}};  // not one of the three: kept as written
  nsb::write_file_atomic(nsb::shard_path(dir.path, "s", 1, 1),
                         nsb::shard_text("s", false, {1, 1}, kCases, {0, 1, 2}, {result(0.1), r, result(0.2)}));
  const Json merged = nsb::merge_shards("s", kCases, dir.path, false)[1];
  CHECK(merged["values"][0].get<double>() == inf);
  CHECK(merged["nested"]["growth"].get<double>() == -inf);
  CHECK(merged["nested"]["values"][0] == 1.0);
  CHECK(std::isnan(merged["nested"]["values"][1].get<double>()));
  CHECK(merged["lookalike"] == r["lookalike"]);
}

TEST_CASE("shards: a damaged shard is refused naming the file", "[studies][shard]") {
  const nsb::test::TempDir dir("shard_test");
  write_shards(dir.path);
  const fs::path first = nsb::shard_path(dir.path, "s", 1, 2);
  Json j = read_json(first);
  std::string expected = "its content does not match its content_fnv1a64 hash";

  SECTION("a value edited by hand") {
    std::string text = j.dump();
    std::ofstream(first, std::ios::trunc) << text.replace(text.find("0.0714"), 6, "0.5000");
  }
  SECTION("steps edited") {
    j["results"]["0"]["steps"] = -5;
    std::ofstream(first, std::ios::trunc) << j.dump();
  }
  SECTION("cut short") {
    const std::string text = j.dump();
    std::ofstream(first, std::ios::trunc) << text.substr(0, text.size() / 2);
    expected = "not a JSON object";
  }
  SECTION("an empty file") {
    std::ofstream(first, std::ios::trunc);
    expected = "not a JSON object";
  }
  SECTION("hash missing") {
    j.erase("content_fnv1a64");
    std::ofstream(first, std::ios::trunc) << j.dump();
    expected = "no key 'content_fnv1a64'";
  }
  SECTION("results key -1, rehashed") {
    j["results"]["-1"] = result(1.0);
    write_rehashed(first, j);
    expected = "results key '-1' is not a case of this shard";
  }
  SECTION("results key 99999999999999999999, rehashed") {
    j["results"]["99999999999999999999"] = result(1.0);
    write_rehashed(first, j);
    expected = "results key '99999999999999999999' is not a case of this shard";
  }
  SECTION("a case of the other shard (overlapping results), rehashed") {
    j["results"]["1"] = result(1.0);
    write_rehashed(first, j);
    expected = "results key '1' is not a case of this shard";
  }
  SECTION("a result not an object, rehashed") {
    j["results"]["0"] = Json::array();
    write_rehashed(first, j);
    expected = "result 0 is not an object";
  }
  // Issue 30, finding 7: these were accepted (and a values array too short read past its end).
  SECTION("a bogus status, rehashed") {
    j["results"]["0"]["status"] = "fine";
    write_rehashed(first, j);
    expected = "result 0: status \"fine\" is not a run status";
  }
  SECTION("fractional steps, rehashed") {
    j["results"]["2"]["steps"] = 2.5;
    write_rehashed(first, j);
    expected = "result 2: steps 2.5 is not a whole number >= 0";
  }
  SECTION("negative steps, rehashed") {
    j["results"]["2"]["steps"] = -3;
    write_rehashed(first, j);
    expected = "result 2: steps -3 is not a whole number >= 0";
  }
  SECTION("an array nested 100,000 deep") {
    std::string text = j.dump();
    text.insert(text.size() - 1, ",\"deep\":" + std::string(100000, '[') + std::string(100000, ']'));
    std::ofstream(first, std::ios::trunc) << text;
    expected = "not a JSON object (damaged, cut short or nested deeper than 64)";
  }
  SECTION("another revision's or build's shard, rehashed (issue 56: shards carried no code identity)") {
    REQUIRE(j["code"]["git_revision"].is_string());
    j["code"]["git_revision"] = "0000000";
    write_rehashed(first, j);
    expected = "computed by other code ({\"build_type\"";
  }
  SECTION("another study definition, rehashed") {
    j["cases"][0]["dt"] = 0.2;
    write_rehashed(first, j);
    expected = "made by other study definitions (stale)";
  }
  CHECK_THROWS_WITH(nsb::merge_shards("s", kCases, dir.path, false),
                    Catch::StartsWith("--merge: " + first.string() + ": ") && Catch::Contains(expected));
}

TEST_CASE("shards: a missing case or an absurd shard count in a file name is an input error", "[studies][shard]") {
  const nsb::test::TempDir dir("shard_test");
  write_shards(dir.path);
  fs::remove(nsb::shard_path(dir.path, "s", 2, 2));
  CHECK_THROWS_WITH(nsb::merge_shards("s", kCases, dir.path, false), Catch::Contains("shard 2 of 2 of study s is missing"));
  std::ofstream(dir.path / "shards" / "s-1-of-99999999999999999999.json") << "{}";
  CHECK_THROWS_WITH(nsb::merge_shards("s", kCases, dir.path, false), Catch::Contains("not a shard file name"));
}

TEST_CASE("nsbench-study: /dev/zero as a study file and a huge --shard are one line and exit 2", "[studies][shard][cli]") {
  auto r = nsb::test::run_command(fmt::format("'{}' run /dev/zero --out /tmp/nsbench_never_written", NSBENCH_STUDY_CLI));
  CHECK(r.code == 2);
  CHECK(r.output == "nsbench-study: error: study file '/dev/zero': not a regular file\n");
  {
    const fs::path big = fs::temp_directory_path() / fmt::format("nsbench_big_{}.toml", ::getpid());
    std::ofstream(big) << "#";
    fs::resize_file(big, 2 << 20);  // sparse: a comment sign, then zeros to 2 MiB
    r = nsb::test::run_command(fmt::format("'{}' run '{}' --out /tmp/nsbench_never_written", NSBENCH_STUDY_CLI, big.string()));
    fs::remove(big);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Contains("2097152 bytes, larger than the limit of 1048576 bytes"));
  }
  r = nsb::test::run_command(fmt::format("'{}' bouncing --shard 99999999999999999999/2 --out /tmp/nsbench_never_written", NSBENCH_STUDY_CLI));
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::StartsWith("nsbench-study: error: --shard '99999999999999999999/2': expected I/N"));
  CHECK_FALSE(fs::exists("/tmp/nsbench_never_written"));
}

// Issue 30, finding 7: a study file's result whose values array is empty (its hash
// recomputed) segfaulted in the tables; null values, a missing key, a bad history are refused
// by the study's own schema (StudyEntry::check_result).
TEST_CASE("nsbench-study --merge: a result against its study's schema, one line and exit 2", "[studies][shard][cli]") {
  const nsb::test::TempDir dir("shard_test");
  const std::string study = fmt::format("{}/studies/examples/bouncing_quick.toml", NSBENCH_SOURCE_DIR);
  const auto cli = [&](const std::string& args) {
    return nsb::test::run_command(fmt::format("'{}' run {} --out {} {}", NSBENCH_STUDY_CLI, study, dir.path.string(), args));
  };
  // A one-shard run of the quick study takes seconds; its shard file is then damaged.
  REQUIRE(cli("--shard 1/1").code == 0);
  const fs::path file = nsb::shard_path(dir.path, "bouncing_quick", 1, 1);
  const Json whole = read_json(file);
  REQUIRE(whole["results"]["0"]["status"] == "ok");
  const std::vector<std::pair<std::function<void(Json&)>, std::string>> damages = {
      {[](Json& r) { r["values"] = Json::array(); }, "values is not an array of"},
      {[](Json& r) { r["values"] = nullptr; }, "values is not an array of"},
      {[](Json& r) { r.erase("message"); }, "no key 'message'"},
      {[](Json& r) { r["history"] = {{"t", {0.1, 0.2}}, {"e", {0.1}}}; }, "history is not two arrays"},
      {[](Json& r) { r["cpu"] = "fast"; }, "cpu is not a number"},
      // Issue 56: accepted before, a hand edit with its hash recomputed.
      {[](Json& r) { r["values"][0] = -5; }, "values[0] (err u max) is -5, not >= 0"},
      {[](Json& r) { r["run"] = Json::object(); }, "run is not a table with t_reached and max_penetration"},
      {[](Json& r) { r["run"].erase("counters"); }, "run.counters is not an array of the study's 0 counters"},
      {[](Json& r) { r["lcp_iterations"] = -1; }, "lcp_iterations -1 is not a whole number >= 0"},
  };
  for (const auto& [damage, expected] : damages) {
    Json j = whole;
    damage(j["results"]["0"]);
    write_rehashed(file, j);
    const auto merged = cli("--merge");
    INFO(expected << ": " << merged.output);
    CHECK(merged.code == 2);
    CHECK(std::count(merged.output.begin(), merged.output.end(), '\n') == 1);
    CHECK_THAT(merged.output, Catch::StartsWith("nsbench-study: error: --merge: " + file.string() + ": result 0: " + expected));
  }
}
