#include "reference/cache.hpp"
#include "core/output.hpp"
#include "tests/support/files.hpp"

#include <unistd.h>

#include <catch2/catch.hpp>
#include <algorithm>
#include <fstream>
#include <thread>

namespace fs = std::filesystem;

namespace {

nsb::ReferenceRequest request() {
  nsb::ReferenceRequest r;
  r.problem = "bouncing-mass";
  r.problem_parameters = {{"e", "0.9"}};
  r.integrator = "event-driven";
  r.dt = 0.01;
  r.t_end = 1.0;
  return r;
}

}  // namespace

TEST_CASE("reference cache: stored, reused, regenerated when missing, stale or corrupt", "[reference][cache]") {
  const nsb::test::TempDir dir("cache_test");
  const auto first = nsb::cached_reference(dir.path, request());
  CHECK_FALSE(first.from_cache);
  REQUIRE(first.summary["status"] == "ok");
  const std::string key = nsb::reference_key(first.metadata);
  REQUIRE(fs::exists(dir.path / (key + ".json")));
  REQUIRE(fs::exists(dir.path / (key + ".csv")));
  // Defaults are part of the metadata, so the key names the run completely.
  CHECK(first.metadata["integrator_parameters"]["rtol"] == "1e-11");

  const auto again = nsb::cached_reference(dir.path, request());
  CHECK(again.from_cache);
  CHECK(again.series.columns == first.series.columns);
  CHECK(again.series.values == first.series.values);  // round-trip exact

  // Another parameter is another run.
  auto other = request();
  other.integrator_parameters = {{"rtol", "1e-9"}};
  CHECK_FALSE(nsb::cached_reference(dir.path, other).from_cache);

  // Stale metadata (as left by an older version) and a truncated series are regenerated.
  {
    auto stored = nlohmann::json::parse(std::ifstream(dir.path / (key + ".json")));
    stored["metadata"]["cache_version"] = 0;
    std::ofstream(dir.path / (key + ".json")) << stored.dump();
  }
  CHECK_FALSE(nsb::cached_reference(dir.path, request()).from_cache);
  CHECK(nsb::cached_reference(dir.path, request()).from_cache);
  std::ofstream(dir.path / (key + ".csv")) << "t,dt\n1,2,3\n";
  const auto rebuilt = nsb::cached_reference(dir.path, request());
  CHECK_FALSE(rebuilt.from_cache);
  CHECK(rebuilt.series.values == first.series.values);
}

// A study's cases run in parallel and read their reference when they start: the first computes
// it, the others wait and load it (without the lock, each would find no file and compute it).
TEST_CASE("reference cache: threads asking for the same run compute it once", "[reference][cache]") {
  const nsb::test::TempDir dir("cache_threads_test");
  std::vector<nsb::CachedReference> got(4);
  {
    std::vector<std::jthread> threads;
    for (auto& g : got) threads.emplace_back([&dir, &slot = g] { slot = nsb::cached_reference(dir.path, request()); });
  }
  CHECK(std::count_if(got.begin(), got.end(), [](const auto& g) { return !g.from_cache; }) == 1);
  for (const auto& g : got) CHECK(g.series.values == got.front().series.values);
}

TEST_CASE("reference cache: unknown names and bad values are input errors", "[reference][cache]") {
  auto r = request();
  r.integrator = "no-such";
  CHECK_THROWS_AS(nsb::reference_metadata(r), nsb::InputError);
  r = request();
  r.integrator_parameters = {{"rtol", "-1"}};
  CHECK_THROWS_AS(nsb::reference_metadata(r), nsb::InputError);
}

// A series edited by hand or cut short at a row boundary still parses: only the hash in the
// .json tells it from the run, and it is regenerated rather than used.
TEST_CASE("reference cache: an edited or truncated series is regenerated, not used", "[reference][cache]") {
  const nsb::test::TempDir dir("cache_test");
  const auto first = nsb::cached_reference(dir.path, request());
  const fs::path csv = dir.path / (nsb::reference_key(first.metadata) + ".csv");
  const auto read = [&] {
    std::ifstream in(csv, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string text = read();
  const auto rewrite = [&](const std::string& t) { std::ofstream(csv, std::ios::binary | std::ios::trunc) << t; };

  SECTION("truncated to whole rows") {
    const auto cut = text.find('\n', text.size() / 3);
    REQUIRE(cut != std::string::npos);
    rewrite(text.substr(0, cut + 1));
  }
  SECTION("one value edited") {
    std::string edited = text;
    const auto row = edited.find('\n', edited.size() / 2);
    edited.insert(row + 1, "5");  // a digit more in the first cell of a row: still a number
    rewrite(edited);
  }
  const auto again = nsb::cached_reference(dir.path, request());
  CHECK_FALSE(again.from_cache);
  CHECK(again.series.values == first.series.values);
  CHECK(read() == text);
  CHECK(nsb::cached_reference(dir.path, request()).from_cache);
}

// Issue 30, finding 2: "summary" renamed segfaulted, "ok" -> "nk" failed later, "[]" was
// called an unreadable shard file. Every damaged entry is rebuilt (with a warning line).
TEST_CASE("reference cache: a damaged entry is rebuilt, never used or fatal", "[reference][cache]") {
  const nsb::test::TempDir dir("cache_test");
  const auto first = nsb::cached_reference(dir.path, request());
  const fs::path json = dir.path / (nsb::reference_key(first.metadata) + ".json");
  std::ifstream in(json, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const auto at = t.find(from);
    REQUIRE(at != std::string::npos);
    return t.replace(at, from.size(), to);
  };
  const std::string damaged = GENERATE_COPY(
      replaced("\"summary\"", "\"rummary\""), replaced("\"ok\"", "\"nk\""), replaced("\"steps\": ", "\"steps\": 0.5+"),
      replaced("\"work\": {", "\"work\": {\"x\": null, "), replaced("\"series_fnv1a64\"", "\"series\""),
      std::string("[]"), std::string("null"), std::string("{}"), std::string(100000, '['));
  CAPTURE(damaged.substr(0, 60));
  std::ofstream(json, std::ios::binary | std::ios::trunc) << damaged;
  const auto rebuilt = nsb::cached_reference(dir.path, request());
  CHECK_FALSE(rebuilt.from_cache);
  CHECK(rebuilt.summary["status"] == "ok");
  CHECK(rebuilt.summary["steps"] == first.summary["steps"]);
  CHECK(rebuilt.series.values == first.series.values);
  CHECK(nsb::cached_reference(dir.path, request()).from_cache);
}

// Issue 30, finding 3: an unusable cache location threw out of the study (SIGABRT). The
// cache only saves time, so the run is computed and not stored, with a warning.
TEST_CASE("reference cache: an unusable location computes the run without storing it", "[reference][cache]") {
  const nsb::test::TempDir dir("cache_test");
  fs::create_directories(dir.path);
  const auto expected = nsb::cached_reference(dir.path / "ok", request());
  const std::string key = nsb::reference_key(expected.metadata);
  std::ofstream(dir.path / "file") << "a regular file";
  fs::create_directories(dir.path / "csv_dir" / (key + ".csv"));
  for (const fs::path& cache : {fs::path("/proc/x"), dir.path / "file", dir.path / "file" / "sub", dir.path / "csv_dir"}) {
    CAPTURE(cache);
    nsb::CachedReference ref;
    REQUIRE_NOTHROW(ref = nsb::cached_reference(cache, request()));
    CHECK_FALSE(ref.from_cache);
    CHECK(ref.series.values == expected.series.values);
  }
  CHECK(fs::is_directory(dir.path / "csv_dir" / (key + ".csv")));  // not ours to remove
}

// A series stored before its problem gained an observable (spring-chain's v_first) has no column
// for it: stale, rebuilt, though its hash and metadata still match.
TEST_CASE("reference cache: a series without a column of the problem's observables is rebuilt", "[reference][cache]") {
  const nsb::test::TempDir dir("cache_test");
  nsb::ReferenceRequest r;
  r.problem = "spring-chain";
  r.problem_parameters = {{"n", "3"}, {"wall", "left"}};
  r.integrator = "modal-exact";
  r.dt = 0.01;
  r.t_end = 0.1;
  const auto first = nsb::cached_reference(dir.path, r);
  REQUIRE(first.series.columns.back() == "v_first");
  const std::string key = nsb::reference_key(first.metadata);
  // The same run as an older build stored it: the last column dropped, the hash of that text.
  std::ifstream in(dir.path / (key + ".csv"));
  std::string text, line;
  for (bool header = true; std::getline(in, line); header = false) {
    line.erase(line.rfind(','));
    text += line + "\n";
    if (header) CHECK(line.find("v_first") == std::string::npos);
  }
  in.close();
  std::ofstream(dir.path / (key + ".csv"), std::ios::binary | std::ios::trunc) << text;
  auto stored = nlohmann::json::parse(std::ifstream(dir.path / (key + ".json")));
  stored["series_fnv1a64"] = nsb::fnv1a64(text);
  std::ofstream(dir.path / (key + ".json")) << stored.dump();
  const auto rebuilt = nsb::cached_reference(dir.path, r);
  CHECK_FALSE(rebuilt.from_cache);
  CHECK(rebuilt.series.columns == first.series.columns);
  CHECK(rebuilt.series.values == first.series.values);
  CHECK(nsb::cached_reference(dir.path, r).from_cache);
}
