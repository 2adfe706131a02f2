#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include "core/parameters.hpp"
#include "studies/performance.hpp"
#include "studies/study.hpp"

namespace {

namespace fs = std::filesystem;

// A benchmark entry as Google Benchmark writes it (the fields the table reads).
nsb::Json entry(const std::string& run_name, const std::string& run_type, const std::string& aggregate, double time,
                const std::string& unit, double threads) {
  nsb::Json b = {{"name", run_name}, {"run_name", run_name}, {"run_type", run_type}, {"real_time", time},
                 {"cpu_time", time}, {"time_unit", unit}, {"units", 1000.0}, {"limit_ns", 250.0},
                 {"threads", 1}, {"run_threads", threads}, {"label", "limit: triad over N+1 doubles"}};
  if (!aggregate.empty()) b["aggregate_name"] = aggregate;
  return b;
}

fs::path write_json(const std::string& name, const nsb::Json& j) {
  const fs::path p = fs::temp_directory_path() / name;
  std::ofstream(p) << j.dump();
  return p;
}

nsb::Json output(double threads, double scale) {
  return {{"context", {{"executable", "/x/build/studies/nsbench-bench-bar"}, {"host_name", "h"}, {"num_cpus", 2}}},
          {"benchmarks",
           {entry("BM_Step/a/1000", "iteration", "", 1.2 * scale, "us", threads),
            entry("BM_Step/a/1000", "iteration", "", 1.0 * scale, "us", threads),
            entry("BM_Step/a/1000", "aggregate", "mean", 1.1 * scale, "us", threads),
            entry("BM_Step/a/1000", "aggregate", "min", 1.0 * scale, "us", threads),
            entry("BM_Step/b/1000/real_time", "iteration", "", 3000.0 * scale, "ns", threads),
            entry("BM_Step/b/1000/real_time", "iteration", "", 2000.0 * scale, "ns", threads)}}};
}

}  // namespace

TEST_CASE("performance: the min aggregate or the least repetition, the ratio to the limit, the speed-up",
          "[studies][performance]") {
  const auto one = write_json("nsbench_perf_1.json", output(1, 1.0));
  const auto two = write_json("nsbench_perf_2.json", output(2, 0.5));
  const nsb::Table t = nsb::performance_table({one, two});
  REQUIRE(t.rows.size() == 4);
  CHECK(std::get<std::string>(t.rows[0][0]) == "bar");
  CHECK(std::get<std::string>(t.rows[0][1]) == "Step/a/1000");
  CHECK(std::get<double>(t.rows[0][4]) == Approx(1.0));         // us: the min aggregate, not the mean
  CHECK(std::get<double>(t.rows[0][8]) == Approx(1000.0 / 250.0));
  CHECK(std::get<std::string>(t.rows[1][1]) == "Step/b/1000");  // /real_time dropped
  CHECK(std::get<double>(t.rows[1][4]) == Approx(2.0));         // no aggregate: the least repetition
  CHECK(std::get<double>(t.rows[1][5]) == Approx(2.0));         // ns per unit
  CHECK(std::holds_alternative<std::monostate>(t.rows[0][9]));  // one thread: no speed-up
  CHECK(std::get<double>(t.rows[2][9]) == Approx(2.0));         // the 2-thread rows against the 1-thread ones
  CHECK(std::get<double>(t.rows[3][9]) == Approx(2.0));
  CHECK(std::holds_alternative<std::monostate>(t.rows[0][10]));  // no peak_rss_mb counter
}

TEST_CASE("performance: the memory benchmark's peak RSS in its own column", "[studies][performance]") {
  nsb::Json j = {{"context", {{"executable", "/x/build/studies/nsbench-bench-memory"}}},
                 {"benchmarks", {entry("BM_PeakRss/bouncing-mass/2000000/real_time", "iteration", "", 5.0, "s", 1)}}};
  j["benchmarks"][0]["peak_rss_mb"] = 16.8;
  const nsb::Table t = nsb::performance_table({write_json("nsbench_perf_memory.json", j)});
  REQUIRE(t.rows.size() == 1);
  CHECK(std::get<std::string>(t.rows[0][0]) == "memory");
  CHECK(std::get<std::string>(t.rows[0][1]) == "PeakRss/bouncing-mass/2000000");
  CHECK(std::get<double>(t.rows[0][10]) == 16.8);
  CHECK(std::holds_alternative<std::monostate>(t.rows[0][11]));  // no bytes_per_element counter
}

TEST_CASE("performance: the hex8 bar's bytes per element in their own column", "[studies][performance]") {
  nsb::Json j = {{"context", {{"executable", "/x/build/studies/nsbench-bench-bar3d"}}},
                 {"benchmarks", {entry("BM_Bar3d/internal-force/16/real_time", "iteration", "", 80.0, "us", 1)}}};
  j["benchmarks"][0]["bytes_per_element"] = 28.5;
  const nsb::Table t = nsb::performance_table({write_json("nsbench_perf_bar3d.json", j)});
  REQUIRE(t.rows.size() == 1);
  CHECK(t.columns.at(11).name == "bytes per unit");
  CHECK(std::get<double>(t.rows[0][11]) == 28.5);
}

TEST_CASE("performance: a file that is missing, not JSON or not benchmark output is named in the error",
          "[studies][performance]") {
  const auto not_json = fs::temp_directory_path() / "nsbench_perf_bad.json";
  std::ofstream(not_json) << "{ not json";
  const auto not_bench = write_json("nsbench_perf_other.json", {{"cases", 1}});
  nsb::Json bad_unit = output(1, 1.0);
  bad_unit["benchmarks"][0]["time_unit"] = "fortnights";
  const auto unit = write_json("nsbench_perf_unit.json", bad_unit);
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(nsb::performance_table({fs::temp_directory_path() / "nsbench_perf_missing.json"}),
                    Contains("nsbench_perf_missing.json") && Contains("cannot read"));
  CHECK_THROWS_WITH(nsb::performance_table({not_json}), Contains("nsbench_perf_bad.json") && Contains("not JSON"));
  CHECK_THROWS_WITH(nsb::performance_table({not_bench}), Contains("nsbench_perf_other.json") && Contains("--benchmark_out"));
  CHECK_THROWS_WITH(nsb::performance_table({unit}), Contains("fortnights") && Contains("valid: ns, us, ms, s"));
  CHECK_THROWS_AS(nsb::performance_table({}), nsb::InputError);
}
