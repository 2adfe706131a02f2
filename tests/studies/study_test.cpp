#include <catch2/catch.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "integrators/registry.hpp"
#include "studies/parallel.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"

using Catch::Detail::Approx;

namespace {
nsb::Table sample_table() {
  nsb::Table t;
  t.id = "sample";
  t.title = "A_title with 50% & more";
  t.caption = "caption";
  t.columns = {{"name", "", "", ""}, {"err", "m", "{:.2e}", "error"}, {"n", "", "", ""}};
  t.metadata = {{"study", "test"}};
  t.add_row({std::string("a,b"), 1.5e-3, 7L});
  t.add_row({std::string("diverged"), std::numeric_limits<double>::quiet_NaN(), nsb::Cell{}});
  t.figures = {{"fig", "Fig", "n", "err", {"name"}, {}, true, true}};
  t.headline = true;
  return t;
}
}  // namespace

TEST_CASE("tables: CSV keeps full precision, quotes, stamps; Markdown and LaTeX format and escape", "[studies]") {
  const auto t = sample_table();
  const std::string csv = nsb::to_csv(t);
  // The release beside the revision, as CMake's project VERSION names it.
  CHECK_THAT(csv, Catch::Contains("# study: test\n") &&
                      Catch::Contains("# nsbench_version: " NSBENCH_VERSION "\n# git_revision: ") &&
                      Catch::Contains("name,err [m],n\n") && Catch::Contains("\"a,b\",0.0015,7\n") &&
                      Catch::Contains("diverged,n/a,n/a\n"));
  const std::string md = nsb::to_markdown(t);
  CHECK_THAT(md, Catch::Contains("| a,b | 1.50e-03 | 7 |") && Catch::Contains("| diverged | n/a | n/a |"));
  const std::string tex = nsb::to_latex(t);
  CHECK_THAT(tex, Catch::Contains("A\\_title with 50\\% \\& more") && Catch::Contains("\\toprule") &&
                      Catch::Contains("\\label{tab:sample}") && Catch::Contains("nsbench " NSBENCH_VERSION ", revision "));
  nsb::Table bad = t;
  CHECK_THROWS_AS(bad.add_row({1.0}), std::logic_error);
}

TEST_CASE("tables: the JSON form round-trips every cell type, NaN included", "[studies]") {
  auto t = sample_table();
  t.lead_figures = true;  // the first page's figures: lost in the parallel runner's round trip once
  const auto back = nsb::table_from_json_text(nsb::table_to_json_text(t));
  CHECK(nsb::to_csv(back) == nsb::to_csv(t));
  CHECK(back.figures.size() == 1);
  CHECK(back.headline);
  CHECK(back.lead_figures);
  CHECK_FALSE(back.lead);
  CHECK(nsb::figures_to_json({back}) == nsb::figures_to_json({t}));
}

TEST_CASE("convergence: observed and fitted orders recover a known power law", "[studies]") {
  const std::vector<double> h = {1e-1, 5e-2, 2.5e-2, 1.25e-2};
  std::vector<double> e;
  for (double x : h) e.push_back(3.0 * x * x);
  CHECK(nsb::observed_order(h[0], e[0], h[1], e[1]) == Approx(2.0).epsilon(1e-12));
  CHECK(nsb::fitted_order(h, e) == Approx(2.0).epsilon(1e-12));
  e[1] = std::numeric_limits<double>::quiet_NaN();  // a diverged point is left out
  CHECK(nsb::fitted_order(h, e) == Approx(2.0).epsilon(1e-12));
  CHECK(std::isnan(nsb::observed_order(h[0], 0.0, h[1], 1.0)));
  CHECK(std::isnan(nsb::fitted_order({1.0}, {1.0})));
}

TEST_CASE("parallel: results come back in case order, and a failing case is reported", "[studies]") {
  const auto squares = nsb::parallel_map<long>(200, [](std::size_t i) { return static_cast<long>(i * i); }, "test");
  for (std::size_t i = 0; i < squares.size(); ++i) REQUIRE(squares[i] == static_cast<long>(i * i));
  CHECK_THROWS_WITH(nsb::parallel_for(50, [](std::size_t i) {
    if (i == 17) throw std::runtime_error("case 17 failed");
  }, "test"), "case 17 failed");
}

namespace {
// Runs n tasks on 4 threads (more than the cases need on any machine), task i holding locks[i]
// for 5 ms; the most tasks that held each lock at once.
std::map<std::string, int> most_at_once(std::size_t n, const std::vector<std::string>& locks) {
  setenv("NSBENCH_JOBS", "4", 1);
  std::mutex mutex;
  std::map<std::string, int> holding, most;
  std::vector<int> runs(n, 0);
  nsb::parallel_for(n, [&](std::size_t i) {
    {
      const std::lock_guard lock(mutex);
      ++runs[i];
      most[locks[i]] = std::max(most[locks[i]], ++holding[locks[i]]);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    const std::lock_guard lock(mutex);
    --holding[locks[i]];
  }, "test", locks);
  unsetenv("NSBENCH_JOBS");
  CHECK(std::all_of(runs.begin(), runs.end(), [](int r) { return r == 1; }));
  return most;
}
}  // namespace

TEST_CASE("parallel: cases naming the same lock never run at once; the others do not wait for them", "[studies]") {
  std::vector<std::string> locks(60);
  for (std::size_t i = 0; i < locks.size(); ++i) locks[i] = i % 3 == 0 ? "A" : i % 5 == 0 ? "B" : "";
  const auto most = most_at_once(locks.size(), locks);
  CHECK(most.at("A") == 1);
  CHECK(most.at("B") == 1);
  CHECK(most.at("") > 1);  // 4 threads, 5 ms each: lock-free cases overlap
  // Every case left waiting for the one lock: run one by one, no thread stuck.
  CHECK(most_at_once(12, std::vector<std::string>(12, "A")).at("A") == 1);
  // A failing case holding a lock: reported, the others stop, no thread waits for ever.
  setenv("NSBENCH_JOBS", "4", 1);
  CHECK_THROWS_WITH(nsb::parallel_for(30, [](std::size_t i) {
    if (i == 4) throw std::runtime_error("case 4 failed");
  }, "test", std::vector<std::string>(30, "A")), "case 4 failed");
  unsetenv("NSBENCH_JOBS");
  CHECK_THROWS_AS(nsb::parallel_for(3, [](std::size_t) {}, "test", {"A"}), std::logic_error);
}

TEST_CASE("studies: a case's lock is the one its integrators declare", "[studies]") {
  nsb::StudyEntry study;
  study.case_integrators = &nsb::integrators_named;
  CHECK(nsb::case_lock(study, {{"integrator", "cd-lagrange"}}).empty());
  CHECK(nsb::case_lock(study, {{"integrators", {"moreau-jean", "nsga"}}}).empty());
  for (const auto& entry : nsb::integrator_registry())
    if (entry.name.rfind("siconos-", 0) == 0) {  // built with the Siconos peers
      CHECK(entry.shared_lock == "Siconos (BLAS)");
      CHECK(nsb::case_lock(study, {{"integrators", {"moreau-jean", entry.name}}}) == entry.shared_lock);
    }
  study.case_integrators = nullptr;  // a study that names none: its cases take no lock
  CHECK(nsb::case_lock(study, {{"integrator", "siconos-moreau-jean"}}).empty());
}

TEST_CASE("studies: a bad study definition fails with the study, the case and the reason", "[studies][bad-input]") {
  nsb::StudyEntry bad;
  bad.name = "broken";
  bad.cases = [](const nsb::StudyOptions&) { return std::vector<nsb::Json>{{{"integrator", "no-such-scheme"}}}; };
  bad.run_case = [](const nsb::Json& c) -> nsb::Json {
    nsb::make_integrator(c["integrator"]);
    return {};
  };
  const auto cases = nsb::study_cases(bad, {});
  CHECK_THROWS_WITH(nsb::run_study_case(bad, cases[0], {}),
                    Catch::Contains("study broken, case {\"integrator\":\"no-such-scheme\"}") &&
                        Catch::Contains("unknown integrator (nearest: ") && Catch::Contains("valid: cd-lagrange"));
}

TEST_CASE("studies: NaN and overflowing numbers travel through JSON as null and come back as n/a", "[studies]") {
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const nsb::Json j = nsb::Json::parse(nsb::reals({1.5, nan, inf}).dump());
  CHECK(nsb::real(j[0]) == 1.5);
  CHECK(std::isnan(nsb::real(j[1])));
  CHECK(std::isnan(nsb::real(j[2])));
  CHECK(std::holds_alternative<std::monostate>(nsb::number_cell(j[2])));
}

TEST_CASE("interval histories: the largest value of each interval at its last step, a partial last interval closed", "[studies]") {
  nsb::IntervalMax h(1.0, 4, 2);  // intervals end at 0.25, 0.5, 0.75, 1
  const std::vector<double> t = {0.1, 0.2, 0.3, 0.6, 0.7};
  const std::vector<double> a = {1.0, 3.0, 2.0, 5.0, 4.0};
  for (std::size_t i = 0; i < t.size(); ++i) h.add(t[i], {a[i], 10.0 * a[i]});
  h.finish();  // stopped at 0.7: the third interval is partial
  CHECK(h.times() == std::vector<double>{0.3, 0.6, 0.7});
  CHECK(h.largest(0) == std::vector<double>{3.0, 5.0, 4.0});
  CHECK(h.largest(1) == std::vector<double>{30.0, 50.0, 40.0});
  h.finish();  // nothing open: nothing added
  CHECK(h.times().size() == 3);
  const nsb::IntervalMax none;  // a run that never started (n/a)
  CHECK(none.times().empty());
  CHECK(none.largest(1).empty());
}

TEST_CASE("registry: each built-in study names the file that defines it, and the file exists", "[studies]") {
  for (const auto& s : nsb::study_registry()) {
    INFO(s.name);
    REQUIRE_FALSE(s.source.empty());
    CHECK(std::filesystem::exists(std::filesystem::path(NSBENCH_SOURCE_DIR) / s.source));
  }
}

TEST_CASE("registry: every file of studies/builtin/ is embedded as it is and is one built-in study", "[studies]") {
  const std::filesystem::path dir = std::filesystem::path(NSBENCH_SOURCE_DIR) / "studies" / "builtin";
  std::size_t on_disk = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".toml" && f.path().extension() != ".py") continue;
    ++on_disk;
    const std::string path = "studies/builtin/" + f.path().filename().string();
    INFO(path);
    const nsb::EmbeddedStudyFile* embedded = nsb::builtin_study_file(path);
    REQUIRE(embedded != nullptr);
    std::ifstream in(f.path(), std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(embedded->text == text);  // the build embeds the file's bytes: the same hash
    const auto& r = nsb::study_registry();
    CHECK(std::count_if(r.begin(), r.end(), [&](const nsb::StudyEntry& s) { return s.source == path; }) == 1);
  }
  CHECK(nsb::builtin_study_files().size() == on_disk);
  for (const auto& s : nsb::study_registry())  // a Python study is its script, which the C++ side never runs
    if (!s.script.empty()) CHECK_THROWS_WITH(nsb::study_cases(s, {}), Catch::Contains("written in Python (" + s.source + ")"));
  CHECK(nsb::builtin_study_file("studies/builtin/no-such-study.toml") == nullptr);
}
