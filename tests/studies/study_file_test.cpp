#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "integrators/registry.hpp"
#include "problems/bouncing_bar.hpp"
#include "problems/registry.hpp"
#include "problems/signorini_bar.hpp"
#include "run/run.hpp"
#include "studies/study.hpp"
#include "studies/study_file.hpp"
#include "tests/app/run_cli.hpp"
#include "tests/support/files.hpp"

using Catch::Detail::Approx;
namespace fs = std::filesystem;

namespace {

const std::string kMinimal = R"([study]
title = "t"
t_end = 0.6

[[problem]]
name = "bouncing-mass"
parameters = { e = 0.5 }

[[integrator]]
name = "cd-lagrange"
steps = [1e-2, 5e-3]

[reference]
solution = "exact"

[[measure]]
kind = "error"
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

std::string study_error_of(const std::string& text, bool json = false) {
  try {
    nsb::parse_study_text(text, "f.toml", json);
  } catch (const nsb::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

const fs::path kExamples = fs::path(NSBENCH_SOURCE_DIR) / "studies" / "examples";

// The reference cache of these tests: a fresh directory, not the user's.
struct TempCache {
  fs::path dir = fs::temp_directory_path() / fmt::format("nsbench-study-file-test-{}", ::getpid());
  TempCache() { setenv("NSBENCH_REFERENCE_CACHE", dir.c_str(), 1); }
  ~TempCache() {
    unsetenv("NSBENCH_REFERENCE_CACHE");
    fs::remove_all(dir);
  }
};

// A [study] table of one CPU run and one target error, 1e-2.
std::string quick_study(const std::string& t_end, const std::string& more = "") {
  return "[study]\ntitle = \"t\"\nt_end = " + t_end + "\ncpu_repeats = 0\ntargets = [1e-2]\n" + more;
}

// Runs every case of a study in this thread and builds its tables.
std::vector<nsb::Table> run_all(const nsb::StudySpec& spec, std::vector<nsb::Json>* results_out = nullptr) {
  const nsb::StudyEntry entry = nsb::file_study(spec);
  const auto cases = nsb::study_cases(entry, {});
  std::vector<nsb::Json> results;
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {}));
  if (results_out) *results_out = results;
  return nsb::study_tables(entry, cases, results, {});
}

const nsb::Table& table_ending(const std::vector<nsb::Table>& tables, const std::string& suffix) {
  for (const auto& t : tables)
    if (t.id.size() >= suffix.size() && t.id.compare(t.id.size() - suffix.size(), suffix.size(), suffix) == 0) return t;
  FAIL("no table " << suffix);
  throw;
}

std::size_t column(const nsb::Table& t, const std::string& name) {
  for (std::size_t i = 0; i < t.columns.size(); ++i)
    if (t.columns[i].name == name) return i;
  FAIL("no column " << name);
  throw;
}

}  // namespace

TEST_CASE("fit_order: slope and 95% interval by hand on three points and t quantiles", "[studies][study_file]") {
  // x = log h = 0, 1, 2; y = 2x + (0, 0.1, 0): slope 2, SSR = 1/150, SE = sqrt(SSR / 1 / 2).
  const std::vector<double> h{1.0, std::exp(1.0), std::exp(2.0)};
  const std::vector<double> e{1.0, std::exp(2.1), std::exp(4.0)};
  const nsb::OrderFit fit = nsb::fit_order(h, e);
  CHECK(fit.points == 3);
  CHECK(fit.order == Approx(2.0).epsilon(1e-12));
  const double half = 12.7062047 * std::sqrt(1.0 / 150.0 / 2.0);
  CHECK(fit.low == Approx(2.0 - half).epsilon(1e-9));
  CHECK(fit.high == Approx(2.0 + half).epsilon(1e-9));
  CHECK(nsb::fitted_order(h, e) == Approx(2.0).epsilon(1e-12));
  // Exact power law: a zero-width interval; two points: no interval.
  const nsb::OrderFit exact = nsb::fit_order({1e-3, 2e-3, 4e-3, 8e-3}, {3e-6, 12e-6, 48e-6, 192e-6});
  CHECK(exact.order == Approx(2.0).epsilon(1e-12));
  CHECK(exact.high - exact.low < 1e-9);
  CHECK(std::isnan(nsb::fit_order({1.0, 2.0}, {1.0, 2.0}).low));
  CHECK(nsb::student_t975(1) == Approx(12.7062047));
  CHECK(nsb::student_t975(10) == Approx(2.2281389));
  CHECK(nsb::student_t975(60) == Approx(2.0002978).epsilon(1e-6));
  CHECK(nsb::student_t975(1000) == Approx(1.9623391).epsilon(1e-6));
}

// Issue 30, finding 8: steps = [1e-2, 1e-2, 1e-3] gave order 1.2505 with an interval 3e-15
// wide, status ok: a repeated step is not a new point of the fit.
TEST_CASE("fit_order: a repeated abscissa counts once; a study file refuses repeated steps", "[studies][study_file]") {
  const nsb::OrderFit fit = nsb::fit_order({1e-2, 1e-2, 1e-3}, {1e-2, 1e-2, 1e-4});
  CHECK(fit.points == 2);
  CHECK(fit.order == Approx(2.0).epsilon(1e-12));
  CHECK(std::isnan(fit.low));  // two distinct points: no interval
  CHECK(std::isnan(fit.high));
  const nsb::OrderFit same = nsb::fit_order({1e-3, 2e-3, 2e-3, 4e-3}, {1e-6, 4e-6, 4e-6, 16e-6});
  CHECK(same.points == 3);
  CHECK(same.order == Approx(2.0).epsilon(1e-12));
  CHECK(nsb::fit_order({1e-2, 1e-2}, {1e-2, 2e-2}).points == 1);
  CHECK(std::isnan(nsb::fit_order({1e-2, 1e-2}, {1e-2, 2e-2}).order));
  CHECK(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-2, 1e-2, 1e-3]")) ==
        "f.toml:11: integrator[0].steps[1]: 0.01 repeats steps[0]; valid: distinct values");
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "tolerances = [1e-4, 1e-6, 1e-4]\ndt = 1e-2")),
             Catch::EndsWith("integrator[0].tolerances[2]: 0.0001 repeats tolerances[0]; valid: distinct values"));
}

TEST_CASE("fit_order: the 95% interval covers a known slope in about 95% of noisy samples", "[studies][study_file]") {
  std::mt19937_64 rng(12345);
  std::normal_distribution<double> noise(0.0, 0.2);
  const std::vector<double> h{1e-3, 2e-3, 4e-3, 8e-3, 1.6e-2};
  int covered = 0;
  const int trials = 4000;
  for (int k = 0; k < trials; ++k) {
    std::vector<double> e;
    for (double x : h) e.push_back(0.7 * std::pow(x, 1.5) * std::exp(noise(rng)));
    const nsb::OrderFit fit = nsb::fit_order(h, e);
    covered += fit.low <= 1.5 && 1.5 <= fit.high;
  }
  // Binomial standard deviation at 95%: 0.34% of 4000 trials; 4 of them either side.
  CHECK(covered / double(trials) == Approx(0.95).margin(0.014));
}

TEST_CASE("study file: a minimal TOML file reads and so does JSON with the same schema too", "[studies][study_file]") {
  const nsb::StudySpec s = nsb::parse_study_text(kMinimal, "min.toml", false);
  CHECK(s.name == "min");
  CHECK(s.t_end == 0.6);
  REQUIRE(s.problems.size() == 1);
  CHECK(s.problems[0].label == "bouncing-mass");
  CHECK(s.problems[0].parameters.at("e") == "0.5");
  CHECK(s.integrators[0].sweep.steps == std::vector<double>{1e-2, 5e-3});
  CHECK(s.reference.exact);
  CHECK(s.measures[0].label == "err u max");
  const std::string json = R"({"study": {"title": "t", "t_end": 0.6},
  "problem": [{"name": "bouncing-mass", "parameters": {"e": 0.5}}],
  "integrator": [{"name": "cd-lagrange", "steps": [0.01, 0.005]}],
  "reference": {"solution": "exact"},
  "measure": [{"kind": "error"}]})";
  const nsb::StudySpec j = nsb::parse_study_text(json, "min.json", true);
  CHECK(j.integrators[0].sweep.steps == s.integrators[0].sweep.steps);
  CHECK(j.problems[0].parameters == s.problems[0].parameters);
  CHECK_THAT(study_error_of(replaced(json, "\"t_end\"", "\"t_ned\""), true),
             Catch::StartsWith("f.toml:1: study.t_ned: unknown key (nearest valid key: t_end)"));
  CHECK_THAT(study_error_of(replaced(json, "[0.01, 0.005]", "[]"), true), Catch::StartsWith("f.toml:3: integrator[0].steps: empty list"));
}

TEST_CASE("study file: errors name FILE:LINE and the key path and what is wrong and the valid choices", "[studies][study_file]") {
  using Catch::Contains;
  using Catch::StartsWith;
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end", "t_ned")),
             StartsWith("f.toml:3: study.t_ned: unknown key (nearest valid key: t_end); valid: title, t_end,"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = \"0.6\"")),
             StartsWith("f.toml:3: study.t_end: expected a number, got a string"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "\"bouncing-mass\"", "\"bouncing-mas\"")),
             StartsWith("f.toml:6: problem[0].name: 'bouncing-mas' is not valid (nearest: bouncing-mass); valid: ") &&
                 Contains("spring-chain"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "\"cd-lagrange\"", "\"cd-lagrang\"")),
             StartsWith("f.toml:10: integrator[0].name: 'cd-lagrang' is not valid (nearest: cd-lagrange); valid: ") &&
                 Contains("moreau-jean"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "{ e = 0.5 }", "{ ee = 0.5 }")),
             StartsWith("f.toml:7: problem[0].parameters.ee: unknown parameter (nearest: e); valid: m, g, e, h0, v0"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "{ e = 0.5 }", "{ e = 1.5 }")),
             StartsWith("f.toml:7: problem[0].parameters.e: ") && Contains("valid: [0, 1]"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "[1e-2, 5e-3]", "[]")),
             StartsWith("f.toml:11: integrator[0].steps: empty list; valid: one or more positive numbers"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "[1e-2, 5e-3]", "[1e-2, -5e-3]")),
             StartsWith("f.toml:11: integrator[0].steps[1]: -0.005 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "[1e-2, 5e-3]", "[1e-2, 0]")),
             StartsWith("f.toml:11: integrator[0].steps[1]: 0 is not positive and finite"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "kind = \"error\"", "kind = \"eror\"")),
             StartsWith("f.toml:17: measure[0].kind: 'eror' is not valid (nearest: error); valid: error, impact-time, energy,"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "kind = \"error\"", "kind = \"error\"\nobservable = \"w\"")),
             StartsWith("f.toml:18: measure[0].observable: 'w' is not an observable of problem 'bouncing-mass'; valid: u, q, v,"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "solution = \"exact\"", "integrator = \"event-driven\"")),
             StartsWith("f.toml:13: reference: missing key 'dt'"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "name = \"bouncing-mass\"", "name = \"spring-chain\"")),
             StartsWith("f.toml:14: reference.solution: problem 'spring-chain' (spring-chain) has no exact solution"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "tolerances = [1e-6]")),
             StartsWith("f.toml:9: integrator[0]: a tolerance sweep needs its step: dt = ..."));
  CHECK_THAT(study_error_of(replaced(kMinimal, "[study]", "[studdy]")),
             StartsWith("f.toml:1: studdy: unknown key (nearest valid key: study)"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = ")), StartsWith("f.toml:3: not valid TOML: "));
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-2]\nper_problem = { chain = { steps = [1e-3] } }")),
             StartsWith("f.toml:12: integrator[0].per_problem.chain: unknown key (nearest valid key: bouncing-mass)"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "kind = \"error\"", "kind = \"energy\"\nnorm = \"l2\"")),
             StartsWith("f.toml:18: measure[0].norm: 'l2' is not valid") && Contains("valid: max, final, final abs, drift, offset"));
  CHECK_THAT(study_error_of("[study]\ntitle = 1\n"), StartsWith("f.toml:2: study.title: expected a string, got an integer"));
}

TEST_CASE("study file: per-problem overrides replace the sweep and merge the parameters", "[studies][study_file]") {
  const std::string text = replaced(kMinimal, "steps = [1e-2, 5e-3]",
                                    "steps = [1e-2, 5e-3]\nparameters = { lcp_tol = 1e-10 }\n"
                                    "[integrator.per_problem.bouncing-mass]\nsteps = [2e-3]\nparameters = { lcp_max_iter = 50 }\n");
  const nsb::StudySpec s = nsb::parse_study_text(text, "o.toml", false);
  const nsb::FileSweep& sw = s.integrators[0].sweep_for("bouncing-mass");
  CHECK(sw.steps == std::vector<double>{2e-3});
  CHECK(sw.parameters.at("lcp_tol") == "1e-10");
  CHECK(sw.parameters.at("lcp_max_iter") == "50");
  CHECK(s.integrators[0].sweep_for("other").steps.size() == 2);
}

TEST_CASE("study file: a per-problem override shows in the rows; an energy blow-up is no 'ok', is not ranked, and "
          "the empty ranking cell names it", "[studies][study_file]") {
  TempCache cache;
  // moreau-jean at theta = 1 on the spring chain only; cd-lagrange at dt = 0.2 on the chain,
  // above its stable step 0.14: its energy grows ten times a step (1.6e6 E0 after 5 steps).
  // No run reaches the second target.
  const std::string text = R"([study]
title = "t"
t_end = 1.0
targets = [1e-2, 1e-14]

[[problem]]
name = "spring-chain"

[[integrator]]
name = "moreau-jean"
steps = [0.1, 0.05]
[integrator.per_problem.spring-chain]
parameters = { theta = 1 }

[[integrator]]
name = "cd-lagrange"
steps = [0.2, 0.01]

[reference]
integrator = "modal-exact"
dt = 1e-3

[[measure]]
kind = "error"
observable = "kinetic"

[[measure]]
kind = "energy"
)";
  const auto tables = run_all(nsb::parse_study_text(text, "o.toml", false));
  const nsb::Table& wp = table_ending(tables, "_work_precision");
  const std::size_t status = column(wp, "status");
  REQUIRE(wp.rows.size() == 4);
  CHECK(std::get<std::string>(wp.rows[0][1]) == "moreau-jean [theta=1]");
  CHECK(std::get<std::string>(wp.rows[0][status]) == "ok");
  CHECK_THAT(std::get<std::string>(wp.rows[2][status]), Catch::StartsWith("energy blow-up: max (E - E0 - W) / E scale = "));
  CHECK(std::get<std::string>(wp.rows[3][status]) == "ok");
  const nsb::Table& rank = table_ending(tables, "_ranking");
  REQUIRE(rank.rows.size() == 2);
  for (const auto& row : rank.rows)  // the runs a cost is read between
    for (std::size_t col : {4, 7})
      if (const auto* runs = std::get_if<std::string>(&row[col])) CHECK_THAT(*runs, !Catch::Contains("dt = 2.00e-01"));
  CHECK(std::get<std::string>(rank.rows[1][2]) == "none (removed: energy blow-up: cd-lagrange dt = 2.00e-01)");
  CHECK(std::get<std::string>(rank.rows[1][5]) == "none (removed: energy blow-up: cd-lagrange dt = 2.00e-01)");
}

TEST_CASE("study file: energy lost to friction is no blow-up; a real blow-up is, and the empty ranking cell names it",
          "[studies][study_file]") {
  // The mass slides down the 30 deg slope against mu = 0.3 for 2 s: E (gravity's potential
  // included) falls from 2 J to about -20 J. cd-lagrange at dt = 0.2 on the spring chain is
  // above its stable step 0.14 (its energy grows ten times a step).
  const std::string text = quick_study("2.0") + R"(
[[problem]]
name = "sliding-mass"
label = "slide"
parameters = { alpha = 30, mu = 0.3, v0 = 2 }

[[problem]]
name = "spring-chain"
label = "chain"

[[integrator]]
name = "moreau-jean"
steps = [1e-2, 1e-3]

[[integrator]]
name = "cd-lagrange"
steps = [1e-2, 1e-3]
[integrator.per_problem.chain]
steps = [0.2, 0.3]

[[measure]]
kind = "energy"
norm = "final"
)";
  const auto tables = run_all(nsb::parse_study_text(text, "e.toml", false));
  const nsb::Table& wp = table_ending(tables, "_work_precision");
  const std::size_t status = column(wp, "status");
  REQUIRE(wp.rows.size() == 8);
  for (std::size_t i = 0; i < 8; ++i) {
    const std::string problem = std::get<std::string>(wp.rows[i][0]), integrator = std::get<std::string>(wp.rows[i][1]);
    INFO(problem << ", " << integrator << ": " << std::get<std::string>(wp.rows[i][status]));
    if (problem == "slide") {
      CHECK(std::get<std::string>(wp.rows[i][status]) == "ok");
      CHECK(std::get<double>(wp.rows[i][4]) < -2.0);  // (E - E0) / |E0| at the end: energy lost, not gained
    } else if (integrator == "cd-lagrange") {
      CHECK_THAT(std::get<std::string>(wp.rows[i][status]), Catch::StartsWith("energy blow-up: max (E - E0 - W) / E scale = "));
    } else {
      CHECK(std::get<std::string>(wp.rows[i][status]) == "ok");
    }
  }
}

TEST_CASE("study file: measures name their problems; stop and onset times are the friction study's; rank_by picks the ranking",
          "[studies][study_file]") {
  // The friction study's sliding mass that stops (t_s = 0.6 s) and its disk (rolling from 0.113 s).
  const std::string text = quick_study("2.0", "rank_by = \"stop time err\"\n") + R"(
[[problem]]
name = "sliding-mass"
label = "slide"
parameters = { alpha = 30, mu = 0.8, v0 = 2 }

[[problem]]
name = "rolling-disk"
label = "disk"
parameters = { h0 = 0, v0 = 1, omega0 = 0, mu = 0.3, kappa = 0.5 }

[[integrator]]
name = "moreau-jean"
steps = [1e-2, 1e-3]

[reference]
solution = "exact"

[[measure]]
kind = "error"
observable = "omega"
problems = ["disk"]

[[measure]]
kind = "stop-time"
problems = ["slide"]

[[measure]]
kind = "onset-time"
problems = ["disk"]
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "m.toml", false);
  REQUIRE(spec.ranked == 1);
  const auto tables = run_all(spec);
  const nsb::Table& wp = table_ending(tables, "_work_precision");
  REQUIRE(wp.rows.size() == 4);
  const std::size_t omega = column(wp, "err omega max"), stop = column(wp, "stop time err"), onset = column(wp, "onset time err");
  CHECK(wp.columns[stop].unit == "s");
  const auto value = [&](std::size_t row, std::size_t col) { return std::get<double>(wp.rows[row][col]); };
  const auto not_measured = [&](std::size_t row, std::size_t col) { return std::holds_alternative<std::monostate>(wp.rows[row][col]); };
  for (std::size_t i = 0; i < 2; ++i) {  // slide: only the stop time
    CHECK(not_measured(i, omega));
    CHECK(not_measured(i, onset));
    CHECK(value(i, stop) < 1e-2);
  }
  for (std::size_t i = 2; i < 4; ++i) {  // disk: the other two
    CHECK(value(i, omega) < 1.0);
    CHECK(value(i, onset) < 1e-2);
    CHECK(not_measured(i, stop));
  }
  CHECK_THAT(wp.caption, Catch::Contains("err omega max: measured on disk only (n/a on the other problems)."));
  // The friction study's rule (studies/builtin/friction.py, slip_stop.hpp's in NumPy): the stop-time
  // error of its committed report (friction_sliding, moreau-jean, mu 0.8, dt = 1e-3), to the bit.
  CHECK(value(1, stop) == 0.0006757762464599804);
  // The ranking is by the stop time, on the problem it is measured on only.
  const nsb::Table& rank = table_ending(tables, "_ranking");
  REQUIRE(rank.rows.size() == 1);
  CHECK(std::get<std::string>(rank.rows[0][0]) == "slide");
  CHECK(rank.columns[1].name == "target stop time err");
  CHECK(rank.columns[1].unit == "s");
}

TEST_CASE("study file: a measure's problems, rank_by and the new kinds are checked; an unknown name hints at a plugin",
          "[studies][study_file][bad-input]") {
  using Catch::Contains;
  const std::string two = replaced(kMinimal, "[[integrator]]", "[[problem]]\nname = \"spring-chain\"\n\n[[integrator]]");
  // Without `problems`, an observable of one problem alone is refused naming the other.
  CHECK_THAT(study_error_of(replaced(replaced(two, "solution = \"exact\"", "integrator = \"modal-exact\"\ndt = 1e-3"),
                               "kind = \"error\"", "kind = \"error\"\nobservable = \"q\"")),
             Contains("'q' is not an observable of problem 'spring-chain' recorded by its reference run") &&
                 Contains("or name the problems it is measured on: problems = [...]"));
  CHECK_THAT(study_error_of(kMinimal + "problems = [\"nope\"]\n"),
             Contains("measure[0].problems[0]: 'nope' is not valid (nearest: bouncing-mass); valid: bouncing-mass"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nrank_by = \"err u mx\"")),
             Contains("study.rank_by: 'err u mx' names no measure (nearest: err u max); valid: the label of a measure: err u max"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nrank_by = \"energy err drift\"") +
                      "[[measure]]\nkind = \"energy\"\nnorm = \"drift\"\n"),
             Contains("study.rank_by: measure 'energy err drift' is signed"));
  CHECK_THAT(study_error_of(kMinimal + "[[measure]]\nkind = \"stop-time\"\n"),
             Contains("measure[1].kind: problem 'bouncing-mass' has no exact stop time by t_end"));
  CHECK_THAT(study_error_of(replaced(replaced(kMinimal, "name = \"bouncing-mass\"", "name = \"sliding-mass\""), "parameters = { e = 0.5 }",
                               "parameters = { mu = 0.3 }") + "[[measure]]\nkind = \"stop-time\"\n"),
             Contains("problem 'sliding-mass' has no exact stop time by t_end"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "name = \"cd-lagrange\"", "name = \"my-scheme\"")),
             Contains("integrator[0].name: 'my-scheme' is not valid") &&
                 Contains("a plugin's integrator? load its file with --plugin FILE or NSBENCH_PLUGINS"));
}

TEST_CASE("study file: the example in docs/study_files.md is a valid study file", "[studies][study_file]") {
  const std::string readme = nsb::test::read_text(fs::path(NSBENCH_SOURCE_DIR) / "docs" / "study_files.md");
  const auto begin = readme.find("```toml\n"), end = readme.find("```\n", begin + 8);
  REQUIRE(begin != std::string::npos);
  const nsb::StudySpec spec = nsb::parse_study_text(readme.substr(begin + 8, end - begin - 8), "docs/study_files.md", false);
  CHECK(spec.measures[spec.ranked].label == "err u max");
  CHECK(spec.measures[1].problems == std::vector<std::string>{"bouncing mass"});
  CHECK(spec.tables.size() == 1);
}

TEST_CASE("study file examples: the quick bouncing-mass comparison runs (reduced)", "[studies][study_file]") {
  const nsb::StudySpec spec = nsb::reduced_study(nsb::read_study_file(kExamples / "bouncing_quick.toml"), 0.5, 3, 200000);
  std::vector<nsb::Json> results;
  const auto tables = run_all(spec, &results);
  const nsb::Table& wp = table_ending(tables, "_work_precision");
  CHECK(wp.rows.size() == 3 * 3 + 3);
  const std::size_t err = column(wp, "err u max"), impact = column(wp, "impact time err"), pen = column(wp, "penetration");
  for (const auto& row : wp.rows) {
    REQUIRE(std::holds_alternative<double>(row[err]));
    CHECK(std::get<double>(row[err]) < 0.5);  // against the exact solution, all runs track it
    CHECK(std::get<double>(row[impact]) < 2e-2);
    CHECK(std::get<double>(row[pen]) >= 0.0);
  }
  // Time-stepping: first order with impacts; the fitted interval holds the fit.
  const nsb::Table& orders = table_ending(tables, "_orders");
  const std::size_t order = column(orders, "order"), low = column(orders, "CI low"), high = column(orders, "CI high");
  for (const auto& row : orders.rows)
    if (std::get<std::string>(row[1]) == "CD-Lagrange" && std::get<std::string>(row[2]) == "err u max") {
      CHECK(std::get<double>(row[order]) == Approx(1.0).margin(0.3));
      CHECK(std::get<double>(row[low]) <= std::get<double>(row[order]));
      CHECK(std::get<double>(row[order]) <= std::get<double>(row[high]));
    }
  CHECK(table_ending(tables, "_ranking").headline);
  CHECK(wp.figures.size() == 2 + 3);  // work-precision (CPU, F_int), convergence of 2 errors and the impact time
}

TEST_CASE("study file examples: spring-chain orders against the cached modal-exact reference (reduced)", "[studies][study_file]") {
  TempCache cache;
  // Up to t = 0.1: before the first impact (0.133), both chains are smooth: CD-Lagrange is of order 2.
  nsb::StudySpec spec = nsb::reduced_study(nsb::read_study_file(kExamples / "chain_orders.toml"), 0.1, 3, 200000);
  const auto tables = run_all(spec);
  const nsb::Table& orders = table_ending(tables, "_orders");
  int checked = 0;
  for (const auto& row : orders.rows)
    if (std::get<std::string>(row[1]) == "CD-Lagrange" && std::get<std::string>(row[2]) == "err min_gap max") {
      CHECK(std::get<double>(row[column(orders, "order")]) == Approx(2.0).margin(0.15));
      ++checked;
    }
  CHECK(checked == 2);
  const nsb::Table& wp = table_ending(tables, "_work_precision");
  for (const auto& row : wp.rows) CHECK(std::get<double>(row[column(wp, "momentum residual")]) < 1e-9);
}

TEST_CASE("study file examples: bar energy study runs (reduced) and an over-budget run is a row with its reason", "[studies][study_file]") {
  const nsb::StudySpec spec = nsb::reduced_study(nsb::read_study_file(kExamples / "bar_energy.toml"), 0.2, 1, 20000);
  const auto tables = run_all(spec);
  const nsb::Table& wp = table_ending(tables, "_work_precision");
  CHECK(wp.rows.size() == 4);
  int over = 0;
  for (const auto& row : wp.rows) {
    const std::string status = std::get<std::string>(row.back());
    if (status.rfind("over budget", 0) == 0) {
      ++over;
      CHECK(std::holds_alternative<std::monostate>(row[column(wp, "energy err max")]));
    } else {
      CHECK(status == "ok");
    }
  }
  CHECK(over == 1);
  const nsb::Table& h = table_ending(tables, "_energy_history");
  CHECK(h.csv_only);
  CHECK(h.rows.size() >= 3 * 100);
}

TEST_CASE("study file: fuzz over mutated example files: each reads and runs or fails as an InputError", "[studies][study_file]") {
  TempCache cache;
  std::vector<std::string> texts;
  for (const char* f : {"bouncing_quick.toml", "chain_orders.toml", "bar_energy.toml"}) texts.push_back(nsb::test::read_text(kExamples / f));
  const std::vector<std::string> values{"0", "-1", "1e-300", "1e300", "\"x\"", "nan", "inf", "true", "[]", "{}", "[1e-3, 0]", "\"exact\""};
  std::mt19937 rng(2026);
  int ran = 0, rejected = 0;
  for (int k = 0; k < 120; ++k) {
    std::string text = texts[rng() % texts.size()];
    std::vector<std::string> lines;
    std::stringstream in(text);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    const std::size_t i = rng() % lines.size();
    switch (rng() % 5) {
      case 0: lines.erase(lines.begin() + static_cast<long>(i)); break;
      case 1: lines.insert(lines.begin() + static_cast<long>(i), lines[i]); break;
      case 2:
        if (const auto eq = lines[i].find("= "); eq != std::string::npos) lines[i] = lines[i].substr(0, eq + 2) + values[rng() % values.size()];
        break;
      case 3:
        if (!lines[i].empty()) lines[i][rng() % lines[i].size()] = "x_=[]\"{}.1"[rng() % 10];
        break;
      default: lines.resize(i); break;
    }
    std::string mutated;
    for (const auto& l : lines) mutated += l + "\n";
    INFO(mutated);
    try {
      nsb::StudySpec spec = nsb::reduced_study(nsb::parse_study_text(mutated, "fuzz.toml", false), 1.0, 1, 5000);
      spec.t_end = std::min(spec.t_end, 0.05);  // bounded runs whatever t_end says
      run_all(spec);
      ++ran;
    } catch (const nsb::InputError& e) {
      CHECK_THAT(e.what(), Catch::StartsWith("fuzz.toml") || Catch::StartsWith("study "));
      ++rejected;
    }
  }
  CHECK(ran > 10);
  CHECK(rejected > 10);
}

TEST_CASE("nsbench-study run writes the tables and the file and its hash and merges shards and exits 2 on a bad file", "[studies][study_file]") {
  TempCache cache;
  const fs::path dir = cache.dir / "cli";
  fs::create_directories(dir);
  const fs::path file = dir / "mini.toml";
  std::ofstream(file) << replaced(kMinimal, "[[measure]]", "[[measure]]\nkind = \"penetration\"\n[[measure]]");
  const auto study = [&](const std::string& args) {
    return std::system(fmt::format("NSBENCH_JOBS=2 '{}' run '{}' --out '{}' {} 2>'{}'", NSBENCH_STUDY_CLI, file.string(),
                                   (dir / "out").string(), args, (dir / "stderr").string()).c_str());
  };
  REQUIRE(study("") == 0);
  CHECK_THAT(nsb::test::read_text(dir / "out" / "mini_work_precision.md"), Catch::Contains("| bouncing-mass | cd-lagrange | 1.00e-02 |") &&
                                                               Catch::Contains("libraries = Eigen ") && Catch::Contains("command = "));
  CHECK(nsb::test::read_text(dir / "out" / "mini.study.toml") == nsb::test::read_text(file));
  CHECK_THAT(nsb::test::read_text(dir / "out" / "mini.study.hash"), Catch::StartsWith("FNV-1a 64 "));
  CHECK_THAT(nsb::test::read_text(dir / "out" / "index.md"), Catch::Contains("This index last written by `") && Catch::Contains(" run "));
  CHECK_THAT(nsb::test::read_text(dir / "stderr"), Catch::Contains("mini: case 2/2"));
  fs::remove(dir / "out" / "mini_work_precision.md");
  REQUIRE(study("--shard 1/2") == 0);
  REQUIRE(study("--shard 2/2") == 0);
  REQUIRE(study("--merge") == 0);
  CHECK(fs::exists(dir / "out" / "mini_work_precision.md"));
  std::ofstream(file) << replaced(kMinimal, "t_end", "tend");
  CHECK(WEXITSTATUS(study("")) == 2);
  CHECK_THAT(nsb::test::read_text(dir / "stderr"), Catch::Contains("mini.toml:3: study.tend: unknown key (nearest valid key: t_end)"));
}

// Issue 20's hostile study files: each refused at its line, before any run or file.
TEST_CASE("study file: duplicate JSON keys, overflowing numbers and impossible step counts are refused with FILE:LINE",
          "[studies][study_file]") {
  const std::string json = R"({"study": {"title": "t", "t_end": 0.6},
  "problem": [{"name": "bouncing-mass", "parameters": {"e": 0.5}}],
  "integrator": [{"name": "cd-lagrange", "steps": [0.01, 0.005]}],
  "reference": {"solution": "exact"},
  "measure": [{"kind": "error"}]})";
  CHECK(study_error_of(replaced(json, "\"t_end\": 0.6}", "\"t_end\": 0.6,\n \"t_end\": 5}"), true) ==
        "f.toml:2: key 't_end' given twice in one table; valid: each key once");
  // The same key in two tables is fine.
  CHECK(study_error_of(replaced(json, "\"e\": 0.5}", "\"e\": 0.5, \"h0\": 1}"), true) == "(no error)");
  const std::string digits(400, '7');
  CHECK_THAT(study_error_of(replaced(json, "0.6}", digits + "}"), true),
             Catch::StartsWith("f.toml: a number beyond the range of a double (1.8e308)"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 1e30")),
             Catch::StartsWith("f.toml:11: integrator[0].steps[0]: study.t_end / dt = 1e+30 / 0.01 = 1e+32 steps, more than a "
                               "run's limit of 200000000; valid: dt >= t_end / 200000000"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-300]")),
             Catch::StartsWith("f.toml:11: integrator[0].steps[0]: study.t_end / dt = 0.6 / 1e-300"));
  CHECK(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-2, 16]")) ==
        "f.toml:11: integrator[0].steps[1]: dt = 16 is larger than study.t_end = 0.6; valid: dt <= t_end");
}

TEST_CASE("study file: a series held in memory whole is bounded before any work", "[studies][study_file]") {
  // A reference run's samples and a run's graph for a Hausdorff distance are kept whole: more
  // than 1e7 samples is refused at the file's line, with the sample_every that fits.
  const std::string reference = replaced(replaced(kMinimal, "solution = \"exact\"", "integrator = \"event-driven\"\ndt = 1e-8"),
                                         "kind = \"error\"\n", "kind = \"error\"\nobservable = \"q\"\n");
  CHECK_THAT(study_error_of(reference),
             Catch::StartsWith("f.toml:15: reference.dt: the reference run holds t_end / dt / sample_every = 0.6 / 1e-08 / 1 = 6e+07 "
                               "samples in memory, more than the limit of 1e+07; valid: reference.sample_every >= "));
  const std::string least = study_error_of(reference).substr(study_error_of(reference).rfind(">= ") + 3);
  CHECK((least == "6" || least == "7"));  // 6e7 / 1e7, up to the rounding of t_end / dt
  CHECK(study_error_of(replaced(reference, "dt = 1e-8", "dt = 1e-8\nsample_every = " + least)) == "(no error)");
  const std::string hausdorff =
      replaced(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-2, 1e-8]"), "kind = \"error\"\n",
               "kind = \"hausdorff\"\nobservable = \"v\"\n");
  CHECK_THAT(study_error_of(hausdorff), Catch::StartsWith("f.toml:11: integrator[0].steps[1]: a run's graph for a Hausdorff distance holds"));
  CHECK(study_error_of(replaced(hausdorff, "t_end = 0.6", "t_end = 0.6\nsample_every = 7")) == "(no error)");
  CHECK(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-2, 1e-8]")) == "(no error)");  // streamed measures
}

TEST_CASE("study file: a hausdorff measure converges where the max-norm velocity error does not", "[studies][study_file]") {
  // Three impacts: the third is computed a step late at every step here (the first two land in
  // the step that holds them), an O(1) max-norm error.
  std::string text = replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [4e-3, 2e-3, 1e-3, 5e-4]");
  text = replaced(text, "parameters = { e = 0.5 }", "parameters = { e = 0.9 }");
  text = replaced(text, "t_end = 0.6", "t_end = 2.2\ncpu_repeats = 0");
  text = replaced(text, "kind = \"error\"\n", "kind = \"error\"\nobservable = \"v\"\n\n[[measure]]\nkind = \"hausdorff\"\nobservable = \"v\"\n");
  const nsb::StudySpec spec = nsb::parse_study_text(text, "h.toml", false);
  REQUIRE(spec.measures.size() == 2);
  CHECK(spec.measures[1].label == "hausdorff v");
  const auto tables = run_all(spec, nullptr);
  const nsb::Table& orders = table_ending(tables, "_orders");
  const std::size_t order = column(orders, "order");
  double max_norm = NAN, hausdorff = NAN;
  for (const auto& row : orders.rows)
    (std::get<std::string>(row[2]) == "hausdorff v" ? hausdorff : max_norm) = std::get<double>(row[order]);
  CHECK(std::abs(max_norm) < 0.3);
  CHECK(hausdorff == Approx(1.0).margin(0.45));
  // Errors in the definition: the observable is required, the scales positive.
  CHECK_THAT(study_error_of(replaced(text, "kind = \"hausdorff\"\nobservable = \"v\"\n", "kind = \"hausdorff\"\n")),
             Catch::Contains("missing key 'observable'"));
  CHECK_THAT(study_error_of(replaced(text, "kind = \"hausdorff\"\n", "kind = \"hausdorff\"\ntime_scale = -1\n")),
             Catch::Contains("measure[1].time_scale"));
  CHECK_THAT(study_error_of(replaced(text, "kind = \"hausdorff\"\nobservable = \"v\"\n", "kind = \"hausdorff\"\nobservable = \"u\"\n")),
             Catch::Contains("not an observable"));
}

// The pieces the hausdorff study's file needs (studies/builtin/drafts/hausdorff.toml): the
// graph errors of a Hausdorff measure (norm), an observable per problem, an end time from the
// exact solution's events (t_end_exact), the schemes alone (integrators = "schemes") and the runs
// of a joint refinement together (case_order = "sweep").
TEST_CASE("study file: Hausdorff norms, observables per problem, t_end_exact, schemes, sweep order", "[studies][study_file]") {
  const std::string text = R"([study]
title = "t"
t_end = 1.0
cpu_repeats = 0
[[problem]]
name = "bouncing-mass"
parameters = { e = 0.9, h0 = 1 }
t_end_exact = { impact_2 = 1.0, plus = 0.1 }
steps = [1e-3]
[[problem]]
name = "sliding-mass"
parameters = { alpha = 30, mu = 0.8, v0 = 2 }
t_end_exact = { slip_stop = 1.5 }
steps = [1e-3]
[[integrator]]
name = "moreau-jean"
[reference]
solution = "exact"
[[measure]]
kind = "hausdorff"
observable = { "bouncing-mass" = "v", "sliding-mass" = "v" }
[[measure]]
kind = "hausdorff"
observable = "v"
norm = "to reference"
[[measure]]
kind = "hausdorff"
observable = "v"
norm = "from reference"
[[measure]]
kind = "hausdorff"
observable = "v"
norm = "max error"
[[measure]]
kind = "hausdorff"
observable = "v"
norm = "value scale"
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "f.toml", false);
  const auto mass = nsb::make_problem("bouncing-mass", spec.problems[0].parameters);
  const auto slide = nsb::make_problem("sliding-mass", spec.problems[1].parameters);
  CHECK(spec.problems[0].t_end == mass->exact()->impact_times(10.0).at(1) + 0.1);
  CHECK(spec.problems[1].t_end == 1.5 * slide->exact()->event_time(nsb::ExactEvent::slip_stop).value());
  CHECK(spec.measures[0].label == "hausdorff");
  CHECK(spec.measures[1].label == "hausdorff v to reference");
  CHECK(spec.measures[4].label == "hausdorff v value scale");
  CHECK_FALSE(spec.measures[4].rankable());
  CHECK_FALSE(nsb::measure_converges(spec.measures[4]));
  std::vector<nsb::Json> results;
  run_all(spec, &results);
  REQUIRE(results.size() == 2);
  for (const auto& r : results) {
    INFO(r.dump());
    REQUIRE(r["status"] == "ok");
    const auto& v = r["values"];
    CHECK(v[0].get<double>() == std::max(v[1].get<double>(), v[2].get<double>()));  // H: the larger directed distance
    CHECK(v[1].get<double>() > 0.0);
    CHECK(v[3].get<double>() >= 0.0);
  }
  // The largest |v| of the bouncing mass is its impact speed sqrt(2 g h0) (both sides of each
  // impact are vertices of the exact graph, at the impact times' round-off); the sliding mass's
  // its initial speed, 2.
  CHECK(results[0]["values"][4].get<double>() == Approx(std::sqrt(2.0 * 9.81)).epsilon(1e-8));
  CHECK(results[1]["values"][4].get<double>() == 2.0);

  // integrators = "schemes": the registered integrators but peers and references, in order.
  const nsb::StudySpec schemes = nsb::parse_study_text(replaced(replaced(text, "[[integrator]]\nname = \"moreau-jean\"\n", ""),
                                                                 "cpu_repeats = 0", "cpu_repeats = 0\nintegrators = \"schemes\""),
                                                        "f.toml", false);
  std::vector<std::string> want, got;
  for (const auto& e : nsb::integrator_registry())
    if (!e.reference && !e.peer) want.push_back(e.name);
  for (const auto& it : schemes.integrators) got.push_back(it.name);
  CHECK(got == want);

  // case_order = "sweep": a joint refinement's runs of one integrator together, then the next integrator's.
  const std::string bar = R"([study]
title = "t"
t_end = 1.0
case_order = "sweep"
[[problem]]
name = "signorini-bar"
grid = { N = [10, 20] }
refine = "N"
stable_steps = [0.9]
[[problem]]
name = "bouncing-mass"
steps = [1e-3, 5e-4]
[[integrator]]
name = "cd-lagrange"
[[integrator]]
name = "moreau-jean"
[reference]
solution = "exact"
[[measure]]
kind = "error"
)";
  const nsb::StudySpec sweeps = nsb::parse_study_text(bar, "f.toml", false);
  std::vector<std::string> order;
  for (const auto& c : nsb::study_cases(nsb::file_study(sweeps), {false}))
    order.push_back(fmt::format("{} {} {}", sweeps.problems[c["problem"].get<std::size_t>()].label,
                                sweeps.integrators[c["integrator"].get<std::size_t>()].name, c["dt"].get<double>()));
  CHECK(order == std::vector<std::string>{"signorini-bar, N = 10 cd-lagrange " + order[0].substr(order[0].rfind(' ') + 1),
                                          "signorini-bar, N = 20 cd-lagrange " + order[1].substr(order[1].rfind(' ') + 1),
                                          "signorini-bar, N = 10 moreau-jean " + order[0].substr(order[0].rfind(' ') + 1),
                                          "signorini-bar, N = 20 moreau-jean " + order[1].substr(order[1].rfind(' ') + 1),
                                          "bouncing-mass cd-lagrange 0.001", "bouncing-mass cd-lagrange 0.0005",
                                          "bouncing-mass moreau-jean 0.001", "bouncing-mass moreau-jean 0.0005"});

  // Bad input: one line naming file, line, key and what is valid.
  using Catch::StartsWith;
  using Catch::Contains;
  const auto at_slide = [&](const std::string& to) { return replaced(text, "t_end_exact = { slip_stop = 1.5 }", to); };
  CHECK_THAT(study_error_of(at_slide("t_end_exact = { rest = 1.5 }")),
             StartsWith("f.toml:13: problem[1].t_end_exact.rest: problem 'sliding-mass' has no exact time or value 'rest'; valid: "
                        "slip_stop, stop_distance, plus"));
  CHECK_THAT(study_error_of(at_slide("t_end_exact = { slip_stop = \"x\" }")),
             StartsWith("f.toml:13: problem[1].t_end_exact.slip_stop: expected a number (the factor)"));
  CHECK_THAT(study_error_of(at_slide("t_end_exact = { slip_stop = 1.0, plus = -5.0 }")),
             StartsWith("f.toml:13: problem[1].t_end_exact: t_end = ") && Contains("valid: a sum > 0"));
  CHECK_THAT(study_error_of(at_slide("t_end_exact = 1.5")),
             StartsWith("f.toml:13: problem[1].t_end_exact: expected a table of exact time or value = factor"));
  CHECK_THAT(study_error_of(at_slide("t_end_exact = { slip_stop = 1.5 }\nt_end = 2")),
             StartsWith("f.toml:13: problem[1].t_end_exact: the run's end given twice"));
  CHECK_THAT(study_error_of(replaced(text, "impact_2 = 1.0", "impact_900 = 1.0")),
             StartsWith("f.toml:8: problem[0].t_end_exact.impact_900: problem 'bouncing-mass' has no exact time or value 'impact_900'; "
                        "valid: impact_1 .. impact_"));
  CHECK_THAT(study_error_of(replaced(text, "impact_2 = 1.0", "impact_99999999999999999999999 = 1.0")),
             StartsWith("f.toml:8: problem[0].t_end_exact.impact_99999999999999999999999: problem 'bouncing-mass' has no exact time"));
  CHECK_THAT(study_error_of(replaced(text, "cpu_repeats = 0", "cpu_repeats = 0\nintegrators = \"peers\"")),
             StartsWith("f.toml:5: study.integrators: 'peers' is not valid") && Contains("valid: all, schemes"));
  CHECK_THAT(study_error_of(replaced(bar, "case_order = \"sweep\"", "case_order = \"sweeps\"")),
             StartsWith("f.toml:4: study.case_order: 'sweeps' is not valid (nearest: sweep); valid: problem, integrator, sweep"));
  CHECK_THAT(study_error_of(replaced(text, "norm = \"max error\"", "norm = \"max\"")),
             StartsWith("f.toml:33: measure[3].norm: 'max' is not valid") &&
                 Contains("valid: distance, to reference, from reference, max error, value scale"));
  CHECK_THAT(study_error_of(replaced(text, "{ \"bouncing-mass\" = \"v\", \"sliding-mass\" = \"v\" }", "{ \"bouncing-mass\" = \"v\" }")),
             StartsWith("f.toml:21: measure[0].observable: missing key 'sliding-mass'"));
  CHECK_THAT(study_error_of(replaced(text, "\"sliding-mass\" = \"v\" }", "\"sliding-mass\" = \"v\", slide = \"v\" }")),
             StartsWith("f.toml:21: measure[0].observable.slide: unknown key") && Contains("valid: bouncing-mass, sliding-mass"));
  CHECK_THAT(study_error_of(replaced(text, "\"sliding-mass\" = \"v\" }", "\"sliding-mass\" = \"v_contact\" }")),
             StartsWith("f.toml:21: measure[0].observable.sliding-mass: 'v_contact' is not an observable of problem 'sliding-mass'"));
}

// Issue 30, finding 9: a newline in a study file's name broke the reports' metadata lines.
TEST_CASE("study file: a name with a control character is refused in one line", "[studies][study_file]") {
  const fs::path dir = fs::temp_directory_path() / fmt::format("nsbench_study_name_{}", ::getpid());
  fs::create_directories(dir);
  const fs::path file = dir / "two\nlines.toml";
  std::ofstream(file) << kMinimal;
  try {
    nsb::read_study_file(file);
    FAIL("accepted");
  } catch (const nsb::InputError& e) {
    const std::string what = e.what();
    CHECK(what == "study file '" + (dir / "two lines.toml").string() + "': its name holds the control character 0x0a; "
                  "valid: a name without control characters (newlines, tabs, escapes)");
  }
  fs::remove_all(dir);
}

// Issue 30, finding 10: floor = inf was accepted, and max_force_evaluations = 0 (no budget)
// let each case run up to 2e8 steps.
TEST_CASE("study file: an infinite floor and a zero budget are refused", "[studies][study_file]") {
  CHECK_THAT(study_error_of(replaced(kMinimal, "solution = \"exact\"", "solution = \"exact\"\nfloor = inf")),
             Catch::EndsWith("reference.floor: inf is not a finite number >= 0; valid: [0, inf)"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nmax_force_evaluations = 0")),
             Catch::EndsWith("study.max_force_evaluations: 0 is out of range; valid: [1, 1125899906842624]"));
  CHECK(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nmax_force_evaluations = 1")) == "(no error)");
}

TEST_CASE("study file: per-problem end times and budgets, stable-step sweeps and outcome thresholds: bad input named",
          "[studies][study_file]") {
  using Catch::StartsWith;
  CHECK_THAT(study_error_of(replaced(kMinimal, "parameters = { e = 0.5 }", "parameters = { e = 0.5 }\nt_end = -1")),
             StartsWith("f.toml:8: problem[0].t_end: -1 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "parameters = { e = 0.5 }", "parameters = { e = 0.5 }\nt_end = 0.005")),
             StartsWith("f.toml:12: integrator[0].steps[0]: dt = 0.01 is larger than the t_end of problem 'bouncing-mass' = 0.005; "
                        "valid: dt <= t_end"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "parameters = { e = 0.5 }", "parameters = { e = 0.5 }\nmax_force_evaluations = 0")),
             StartsWith("f.toml:8: problem[0].max_force_evaluations: 0 is out of range; valid: [1, "));
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-2]\nstable_steps = [0.5]")),
             StartsWith("f.toml:9: integrator[0]: give one of steps, stable_steps or tolerances; valid: one sweep per integrator"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "stable_steps = [0.5, 2000]")),
             StartsWith("f.toml:11: integrator[0].stable_steps[1]: 2000 stable steps is no step of a study; valid: (0, 1000]"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "stable_steps = [0.5, 0.5]")),
             StartsWith("f.toml:11: integrator[0].stable_steps[1]: 0.5 repeats stable_steps[0]; valid: distinct values"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nenergy_blow_up = 0")),
             StartsWith("f.toml:4: study.energy_blow_up: 0 is not positive; valid: (0, inf]; inf: no energy blow-up status"));
  CHECK(nsb::parse_study_text(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nenergy_blow_up = inf"), "f.toml", false).energy_blow_up ==
        std::numeric_limits<double>::infinity());  // never
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nenergy_blow_up = -inf")),
             StartsWith("f.toml:4: study.energy_blow_up: -inf is not positive; valid: (0, inf]"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nmax_penetration = \"1e-3\"")),
             StartsWith("f.toml:4: study.max_penetration: expected a number, got a string"));
  // The bouncing mass has no stiffness: its stable step is no finite step.
  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "stable_steps = [0.5]")),
             StartsWith("f.toml:11: integrator[0].stable_steps[0]: dt = inf is larger than study.t_end (problem 'bouncing-mass', "
                        "stable step inf) = 0.6"));
}

TEST_CASE("study file: a problem's own end time and budget, dt from the stable step, and a penetration threshold run",
          "[studies][study_file]") {
  const std::string text = quick_study("0.6", "max_penetration = 1e-12\n") + R"(
[[problem]]
name = "bouncing-mass"
label = "short"
t_end = 0.3

[[problem]]
name = "bouncing-mass"
label = "budget"
max_force_evaluations = 5

[[problem]]
name = "signorini-bar"
label = "bar"
parameters = { N = 10 }
t_end = 0.05

[[integrator]]
name = "cd-lagrange"
steps = [1e-2]
[integrator.per_problem.bar]
stable_steps = [0.5, 0.25]

[[measure]]
kind = "penetration"
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "w.toml", false);
  CHECK(spec.t_end_of(spec.problems[0]) == 0.3);
  CHECK(spec.t_end_of(spec.problems[1]) == 0.6);
  CHECK(spec.budget_of(spec.problems[1], 1e-2, spec.t_end_of(spec.problems[1])) == 5);
  CHECK(spec.budget_of(spec.problems[0], 1e-2, spec.t_end_of(spec.problems[0])) == spec.max_force_evaluations);
  const auto cases = nsb::study_cases(nsb::file_study(spec), {});
  REQUIRE(cases.size() == 4);
  const double stable = nsb::make_problem("signorini-bar", {{"N", "10"}})->stable_step();
  CHECK(cases[2]["dt"].get<double>() == 0.5 * stable);
  CHECK(cases[3]["dt"].get<double>() == 0.25 * stable);
  std::vector<nsb::Json> results;
  const auto tables = run_all(spec, &results);
  CHECK(results[0]["steps"] == 30);                                    // 0.3 s at 1e-2: before the impact at 0.45 s
  CHECK(results[0]["status"] == "ok");                                 // no contact, no penetration
  CHECK(results[1]["status"] == "over budget");                        // 5 F_int evaluations
  CHECK(results[2]["steps"] == static_cast<long>(std::ceil(0.05 / (0.5 * stable) - 1e-9)));
  // CD-Lagrange's velocity-level contact lets the mass through the floor by O(dt v): above 1e-12.
  const std::string text2 = replaced(text, "t_end = 0.3", "t_end = 0.6");
  std::vector<nsb::Json> results2;
  run_all(nsb::parse_study_text(text2, "w.toml", false), &results2);
  CHECK(results2[0]["status"] == "penetration");
  CHECK_THAT(results2[0]["message"].get<std::string>(), Catch::StartsWith("max penetration "));
}

TEST_CASE("study file: a grid of problem parameters and a measure's time window", "[studies][study_file]") {
  using Catch::StartsWith;
  const std::string grid = replaced(kMinimal, "parameters = { e = 0.5 }", "label = \"mass\"\ngrid = { e = [0.5, 0.9], h0 = [1, 2] }");
  const nsb::StudySpec s = nsb::parse_study_text(grid, "g.toml", false);
  REQUIRE(s.problems.size() == 4);  // keys in alphabetical order, the last varying fastest
  CHECK(s.problems[0].label == "mass, e = 0.5, h0 = 1");
  CHECK(s.problems[1].label == "mass, e = 0.5, h0 = 2");
  CHECK(s.problems[3].label == "mass, e = 0.9, h0 = 2");
  CHECK(s.problems[3].parameters.at("e") == "0.9");
  CHECK(s.problems[3].parameters.at("h0") == "2");
  CHECK_THAT(study_error_of(replaced(kMinimal, "parameters = { e = 0.5 }", "grid = { e = [0.5, 1.5] }")),
             StartsWith("f.toml:7: problem[0].grid.e: ") && Catch::Contains("valid: [0, 1]"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "parameters = { e = 0.5 }", "parameters = { e = 0.5 }\ngrid = { e = [0.9] }")),
             StartsWith("f.toml:8: problem[0].grid.e: also given in parameters"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "parameters = { e = 0.5 }", "grid = { e = [] }")),
             StartsWith("f.toml:7: problem[0].grid.e: expected an array of one or more values"));
  // The product's size from the lists' lengths, before any point is built (issue 56: a 1,000 x
  // 4,000 grid ended in std::bad_alloc at 1.5 GB).
  std::string forty = "0.5";
  for (int i = 1; i < 40; ++i) forty += ", 0.5";
  CHECK_THAT(study_error_of(replaced(kMinimal, "parameters = { e = 0.5 }", "grid = { e = [" + forty + "], h0 = [" + forty + "] }")),
             StartsWith("f.toml:7: problem[0].grid: 1600 problems in the grid (the product of its lists' lengths); valid: at most 1000 points"));

  // Before the first impact (0.4515 s) Moreau-Jean and the exact solution are both free flight.
  const std::string window = quick_study("0.6") + R"(
[[problem]]
name = "bouncing-mass"
[[integrator]]
name = "moreau-jean"
steps = [1e-2]
[reference]
solution = "exact"
[[measure]]
kind = "error"
window = [0.0, 0.4]
[[measure]]
kind = "error"
)";
  const nsb::StudySpec w = nsb::parse_study_text(window, "w.toml", false);
  CHECK(w.measures[0].label == "err u max, t in [0, 0.4]");
  std::vector<nsb::Json> results;
  run_all(w, &results);
  const double in_window = results[0]["values"][0], whole = results[0]["values"][1];
  CHECK(in_window < 0.2 * whole);  // the impact's error is outside the window
  CHECK(in_window > 0.0);
  CHECK_THAT(study_error_of(replaced(kMinimal, "kind = \"error\"", "kind = \"error\"\nwindow = [0.5, 0.2]")),
             StartsWith("f.toml:18: measure[0].window: [0.5, 0.2] is no time window; valid: 0 <= t0 < t1, finite"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "kind = \"error\"", "kind = \"error\"\nwindow = [0.7, 0.9]")),
             StartsWith("f.toml:18: measure[0].window: the window starts at 0.7 s, not before the end of problem 'bouncing-mass'"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "kind = \"error\"", "kind = \"penetration\"\nwindow = [0, 0.1]")),
             StartsWith("f.toml:18: measure[0].window: unknown key"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "kind = \"error\"", "kind = \"error\"\nwindow = 0.4")),
             StartsWith("f.toml:18: measure[0].window: expected an array [t0, t1] of two numbers"));
}

TEST_CASE("study file: figures declared in the file are drawn from the work-precision table; bad ones named",
          "[studies][study_file]") {
  using Catch::StartsWith;
  const std::string fig = kMinimal + "\n[[figure]]\nid = \"steps\"\ntitle = \"Steps\"\nx = \"dt\"\ny = \"steps\"\nslopes = [-1]\n";
  std::vector<nsb::Json> results;
  const auto tables = run_all(nsb::reduced_study(nsb::parse_study_text(fig, "min.toml", false), 1.0, 2, 100000), &results);
  const nsb::Table& wp = table_ending(tables, "_work_precision");
  const auto f = std::find_if(wp.figures.begin(), wp.figures.end(), [](const nsb::Figure& g) { return g.id == "min_steps"; });
  REQUIRE(f != wp.figures.end());
  CHECK(f->x == "dt");
  CHECK(f->y == "steps");
  CHECK(f->series == std::vector<std::string>{"integrator"});
  CHECK(f->slopes == std::vector<double>{-1.0});
  CHECK_THAT(study_error_of(replaced(fig, "y = \"steps\"", "y = \"stpes\"")),
             StartsWith("f.toml:23: figure[0].y: 'stpes' is not valid (nearest: steps); valid: problem, integrator, dt, tol, err u max, CPU,"));
  CHECK_THAT(study_error_of(replaced(fig, "id = \"steps\"", "id = \"Steps!\"")),
             StartsWith("f.toml:20: figure[0].id: 'Steps!' is not a file name of a-z, 0-9 and _; valid: [a-z0-9_]+"));
  CHECK_THAT(study_error_of(replaced(fig, "id = \"steps\"", "id = \"work_precision\"")),
             StartsWith("f.toml:20: figure[0].id: 'work_precision' is the id of a figure the study draws itself"));
  CHECK_THAT(study_error_of(replaced(fig, "title = \"Steps\"\n", "")), StartsWith("f.toml:19: figure[0]: missing key 'title'"));
}

TEST_CASE("study file: declared tables pick, order and rename the columns of the runs and of the fitted orders; bad ones named",
          "[studies][study_file]") {
  using Catch::StartsWith;
  const std::string declared = kMinimal + R"(
[[table]]
id = "runs"
title = "Runs"
caption = "What the rows are."
columns = ["problem", "integrator", { of = "dt", header = "step", format = "{:.1e}" }, { of = "err u max", header = "err" }, "steps", "factorizations",
           { of = "pairwise order of err u max", header = "order" }]

[[table]]
id = "fits"
title = "Orders"
rows = "group"
columns = ["problem", "integrator", { of = "order of err u max", header = "order" }, "points of err u max"]

[[table]]
id = "best"
title = "Cheapest"
rows = "ranking"
)";
  const auto tables = run_all(nsb::reduced_study(nsb::parse_study_text(declared, "min.toml", false), 1.0, 2, 100000));
  REQUIRE(tables.size() == 3);  // the declared tables only, in their order
  const nsb::Table& runs = tables[0];
  CHECK(runs.id == "runs");
  CHECK(runs.title == "Runs");
  CHECK(runs.caption == "What the rows are.");
  REQUIRE(runs.columns.size() == 7);
  CHECK(runs.columns[2].name == "step");
  CHECK(runs.columns[2].unit == "s");  // the source's unit
  CHECK(runs.columns[2].format == "{:.1e}");
  CHECK(runs.columns[3].name == "err");
  CHECK(runs.columns[3].format == "{:.3e}");
  REQUIRE(runs.rows.size() == 2);
  CHECK(std::get<std::string>(runs.rows[0][1]) == "cd-lagrange");
  CHECK(std::get<double>(runs.rows[1][2]) == 5e-3);
  CHECK(std::get<double>(runs.rows[1][3]) > 0.0);
  CHECK(std::get<long>(runs.rows[1][5]) == 0);  // CD-Lagrange factorizes nothing
  // The order against the run before: none for the first, that of the two errors for the second.
  CHECK(std::holds_alternative<std::monostate>(runs.rows[0][6]));
  CHECK(std::get<double>(runs.rows[1][6]) == Approx(std::log(std::get<double>(runs.rows[0][3]) / std::get<double>(runs.rows[1][3])) / std::log(2.0)));
  CHECK(runs.columns[6].format == nsb::kOrderFormat);
  // The engine's figures whose columns the table shows, under its headers: CPU is not shown.
  REQUIRE(runs.figures.size() == 1);
  CHECK(runs.figures[0].x == "step");
  CHECK(runs.figures[0].y == "err");
  const nsb::Table& fits = tables[1];
  CHECK(fits.id == "fits");
  REQUIRE(fits.rows.size() == 1);
  CHECK(fits.columns[2].name == "order");
  CHECK(std::get<double>(fits.rows[0][2]) > 0.5);
  CHECK(std::get<long>(fits.rows[0][3]) == 2);
  CHECK(tables[2].id == "best");
  CHECK(tables[2].title == "Cheapest");
  CHECK(std::any_of(tables[2].columns.begin(), tables[2].columns.end(),
                    [](const nsb::Column& c) { return c.description == "err u max of runs"; }));

  // Each edit of the file and the start of the error it gives.
  const std::vector<std::array<std::string, 3>> bad = {
      {"\"steps\", \"fact", "\"stpes\", \"fact",
       "f.toml:23: table[0].columns[4]: 'stpes' is not valid (nearest: steps); valid: problem, integrator, dt, tol, err u max, "
       "CPU, steps, F_int evals, status, factorizations, LCP its, pairwise order of err u max"},
      {"\"points of err u max\"", "\"dt\"",
       "f.toml:30: table[1].columns[3]: 'dt' is not valid (nearest: "},
      {"format = \"{:.1e}\"", "format = \"{:.1q}\"",
       "f.toml:23: table[0].columns[2].format: '{:.1q}' is no number format"},
      {"header = \"step\"", "heading = \"step\"",
       "f.toml:23: table[0].columns[2].heading: unknown key (nearest valid key: header); valid: of, header, unit, format, "
       "description"},
      {"id = \"fits\"", "id = \"runs\"",
       "f.toml:27: table[1].id: id 'runs' used twice; valid: distinct ids"},
      {"id = \"runs\"", "id = \"Runs\"",
       "f.toml:20: table[0].id: 'Runs' is not a file name of a-z, 0-9 and _; valid: [a-z0-9_]+"},
      {"rows = \"group\"", "rows = \"groups\"",
       "f.toml:29: table[1].rows: 'groups' is not valid (nearest: group); valid: case, group, ranking"},
      {"rows = \"ranking\"", "rows = \"ranking\"\ncolumns = [\"problem\"]",
       "f.toml:36: table[2].columns: a ranking's columns are fixed"},
      {"title = \"Orders\"\n", "",
       "f.toml:26: table[1]: missing key 'title'"},
  };
  for (const auto& [from, to, error] : bad) CHECK_THAT(study_error_of(replaced(declared, from, to)), StartsWith(error));
  CHECK_THAT(study_error_of(declared + "\n[[figure]]\nid = \"cost\"\ntitle = \"Cost\"\nx = \"CPU\"\ny = \"err u max\"\n"),
             StartsWith("f.toml:40: figure[0].x: 'CPU' is not a column of table 'runs'; valid: problem, integrator, dt, err u max, "
                        "steps, factorizations, pairwise order of err u max"));
}

TEST_CASE("study file: a lockstep reference steps with each run; the reference itself is n/a; bad input named",
          "[studies][study_file]") {
  using Catch::Contains;
  using Catch::StartsWith;
  const std::string lockstep = quick_study("1.0") + R"(
[[problem]]
name = "spring-chain"
parameters = { n = 10, wall = "left" }

[[integrator]]
name = "cd-lagrange"
steps = [1e-2, 5e-3]

[[integrator]]
name = "modal-exact"
steps = [1e-2]

[reference]
integrator = "modal-exact"
lockstep = true

[[measure]]
kind = "error"
window = [0.0, 0.12]

[[measure]]
kind = "error"
window = [0.0, 0.12]
relative_to = "run"
label = "err over the run's scale"
)";
  std::vector<nsb::Json> results;
  const auto tables = run_all(nsb::parse_study_text(lockstep, "lock.toml", false), &results);
  REQUIRE(results.size() == 3);
  // Before the first impact (t = 0.133) CD-Lagrange is of order 2 against the exact semi-discrete chain.
  const double coarse = results[0]["values"][0], fine = results[1]["values"][0];
  CHECK(coarse > 0.0);
  CHECK(std::log2(coarse / fine) == Approx(2.0).margin(0.3));
  // The same error relative to the chain's largest displacement over the run, not over the
  // window alone: smaller, as the chain drifts away from the wall.
  const double over_run = results[0]["values"][1];
  CHECK(over_run > 0.0);
  CHECK(over_run < 0.5 * coarse);
  CHECK(results[2]["status"] == "n/a");
  CHECK(results[2]["message"] == "the reference of this problem");
  CHECK_THAT(table_ending(tables, "_work_precision").caption, Contains("modal-exact stepped with each run (lockstep)"));

  CHECK_THAT(study_error_of(replaced(lockstep, "lockstep = true", "lockstep = true\ndt = 1e-3")),
             StartsWith("f.toml:22: reference.dt: a lockstep reference steps with each run, at its steps"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "solution = \"exact\"", "solution = \"exact\"\nlockstep = true")),
             Contains("reference.lockstep: only a reference integrator steps with the runs"));
  CHECK_THAT(study_error_of(replaced(lockstep, "relative_to = \"run\"", "relative_to = \"all\"")),
             Contains("measure[1].relative_to: 'all' is not valid (nearest: "));
  CHECK_THAT(study_error_of(replaced(lockstep, "kind = \"error\"\nwindow = [0.0, 0.12]\n\n", "kind = \"hausdorff\"\nobservable = \"q\"\n\n")),
             Contains("a Hausdorff distance needs the reference's whole graph"));
}

TEST_CASE("study file: the ranking marks another code's integrator as a peer", "[studies][study_file]") {
  const auto& registry = nsb::integrator_registry();
  const auto peer = std::find_if(registry.begin(), registry.end(), [](const nsb::IntegratorEntry& e) { return e.peer; });
  if (peer == registry.end()) {  // the peers are optional (CMake option NSBENCH_ENGINES, Siconos)
    WARN("no peer integrator in this build: nothing to check");
    return;
  }
  const std::string text = replaced(kMinimal, "name = \"cd-lagrange\"", "name = \"" + peer->name + "\"");
  const auto tables = run_all(nsb::reduced_study(nsb::parse_study_text(text, "peer.toml", false), 1.0, 2, 100000));
  bool marked = false;
  for (const auto& row : table_ending(tables, "_ranking").rows)
    for (const auto& cell : row)
      if (const auto* s = std::get_if<std::string>(&cell)) marked = marked || s->find(peer->name + " (peer)") != std::string::npos;
  CHECK(marked);
}

namespace {

// The signorini bar (N = 100, lumped) at twice its stable step: cd-lagrange's energy grows by
// 1e220 within 100 steps and its state overflows at step 139.
std::string unstable_bar(const std::string& check_every, const std::string& budget) {
  return quick_study("3.0", "check_every = " + check_every + "\n") + R"(
[[problem]]
name = "signorini-bar"
label = "bar"
parameters = { N = 100, mass = "lumped" }
stable_steps = [2.0]
energy_blow_up = 0.1
max_force_evaluations = )" + budget + R"(

[[integrator]]
name = "cd-lagrange"

[[table]]
id = "runs"
title = "runs"
columns = ["problem name", "stable steps", "outcome", "steps", "t reached", "energy growth", "energy blow-up limit", "budget", "note"]

[[table]]
id = "history"
title = "history"
rows = "history"
columns = ["problem", "integrator", "t", "energy deviation", "penetration"]

[[figure]]
id = "deviation"
title = "deviation"
table = "history"
x = "t"
y = "energy deviation"
log_x = false
)";
}

}  // namespace

TEST_CASE("study file: a problem's own stable steps and thresholds, full_only, check_every, run figures and history tables",
          "[studies][study_file]") {
  // The driver checks the state every check_every steps: a run that overflows at step 139 is
  // found diverged there, or at the end (150) when checked every 1000 steps.
  for (const auto& [every, steps] : {std::pair{"1", 139L}, {"1000", 150L}}) {
    const auto tables = run_all(nsb::parse_study_text(unstable_bar(every, "1000000"), "f.toml", false));
    const nsb::Table& runs = table_ending(tables, "runs");
    REQUIRE(runs.rows.size() == 1);
    const auto& row = runs.rows[0];
    CHECK(std::get<std::string>(row[0]) == "signorini-bar");
    CHECK(std::get<double>(row[1]) == 2.0);
    CHECK(std::get<std::string>(row[2]) == "diverged");
    CHECK(std::get<long>(row[3]) == steps);
    CHECK(std::get<double>(row[6]) == 0.1);
    CHECK(std::get<long>(row[7]) == 1000000);
    CHECK_THAT(std::get<std::string>(row[8]), Catch::StartsWith("non-finite state"));
  }
  // A blow-up seen before the budget ran out is the outcome, the driver's message the note.
  const auto tables = run_all(nsb::parse_study_text(unstable_bar("1", "100"), "f.toml", false));
  const auto& row = table_ending(tables, "runs").rows.at(0);
  CHECK(std::get<std::string>(row[2]) == "energy blow-up");
  CHECK(std::get<double>(row[5]) > 1e200);
  CHECK_THAT(std::get<std::string>(row[8]), Catch::StartsWith("budget of 100 F_int evaluations exceeded"));
  // The history: the largest deviation of each of 200 intervals of [0, 3] up to the stop at
  // t = 2 (step 100), growing; its figure by the history table's columns.
  const nsb::Table& history = table_ending(tables, "history");
  CHECK(history.csv_only);
  REQUIRE(history.rows.size() == 100);  // a step (0.02 s) is longer than an interval (0.015 s): one row each
  CHECK(std::get<double>(history.rows.back()[2]) == Approx(2.0));
  CHECK(std::get<double>(history.rows.back()[3]) > std::get<double>(history.rows.front()[3]));
  REQUIRE(history.figures.size() == 1);
  CHECK(history.figures[0].id == "f_deviation");
  CHECK(history.figures[0].panels == std::vector<std::string>{"problem"});
  CHECK(table_ending(tables, "runs").figures.empty());

  // A problem's own stable_steps serve every integrator without a sweep of its own; a full_only
  // problem runs with --full only.
  const std::string every = quick_study("0.6", "integrators = \"all\"\n") + R"(
[[problem]]
name = "bouncing-mass"
label = "own"
steps = [1e-2]
[[problem]]
name = "signorini-bar"
label = "long"
stable_steps = [0.5]
full_only = true
[[table]]
id = "runs"
title = "runs"
columns = ["problem", "integrator", "dt"]
)";
  const nsb::StudySpec spec = nsb::parse_study_text(every, "f.toml", false);
  const auto& registry = nsb::integrator_registry();
  REQUIRE(spec.integrators.size() == registry.size());
  for (std::size_t i = 0; i < registry.size(); ++i)
    CHECK(spec.integrators[i].sweep_for("long").stable_fractions == std::vector<double>{0.5});
  const nsb::StudyEntry entry = nsb::file_study(spec);
  CHECK(nsb::study_cases(entry, {false}).size() == registry.size());
  const auto full = nsb::study_cases(entry, {true});
  REQUIRE(full.size() == 2 * registry.size());
  const double stable = nsb::make_problem("signorini-bar", {})->stable_step();
  CHECK(full.back()["dt"].get<double>() == 0.5 * stable);
  CHECK(full.back()["stable_steps"].get<double>() == 0.5);
}

TEST_CASE("study file: a problem's own stable steps and thresholds, full_only, check_every and history tables: bad input named",
          "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const auto with_problem = [](const std::string& line) { return replaced(kMinimal, "parameters = { e = 0.5 }", "parameters = { e = 0.5 }\n" + line); };
  for (const char* key : {"energy_blow_up", "max_penetration", "energy_scale"})
    CHECK_THAT(study_error_of(with_problem(std::string(key) + " = 0")),
               StartsWith(fmt::format("f.toml:8: problem[0].{}: 0 is not positive and finite; valid: (0, inf)", key)));
  CHECK_THAT(study_error_of(with_problem("full_only = 1")), StartsWith("f.toml:8: problem[0].full_only: expected a boolean, got an integer"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\ncheck_every = 0")),
             StartsWith("f.toml:4: study.check_every: 0 is out of range; valid: [1, "));
  CHECK_THAT(study_error_of(with_problem("steps = [1e-2]\nstable_steps = [0.5]")),
             StartsWith("f.toml:5: problem[0]: give one of steps or stable_steps; valid: one sweep per problem"));
  CHECK_THAT(study_error_of(with_problem("stable_steps = [2000]")),
             StartsWith("f.toml:8: problem[0].stable_steps[0]: 2000 stable steps is no step of a study; valid: (0, 1000]"));
  // A problem's stable steps against its end time, with its stable step named.
  CHECK_THAT(study_error_of(with_problem("stable_steps = [900]\nt_end = 1e-3")),
             StartsWith("f.toml:8: problem[0].stable_steps[0]: dt = ") && Catch::Contains("is larger than the t_end of problem"));
  // History tables: their problems and columns; a figure drawn from one names it.
  const std::string history = kMinimal + "[[table]]\nid = \"h\"\ntitle = \"h\"\nrows = \"history\"\ncolumns = [\"t\", \"penetration\"]\n";
  CHECK(nsb::parse_study_text(history, "f.toml", false).tables.at(0).rows == "history");
  CHECK_THAT(study_error_of(history + "problems = [\"nope\"]\n"),
             StartsWith("f.toml:23: table[0].problems[0]: 'nope' is not valid (nearest: bouncing-mass); valid: bouncing-mass"));
  CHECK_THAT(study_error_of(replaced(history, "rows = \"history\"", "rows = \"ranking\"\nproblems = [\"bouncing-mass\"]")),
             StartsWith("f.toml:22: table[0].problems: a ranking ranks every problem of its measure; valid: rows = \"case\", \"group\", \"history\" or \"samples\""));
  CHECK_THAT(study_error_of(replaced(history, "\"penetration\"]", "\"steps\"]")),
             StartsWith("f.toml:22: table[0].columns[1]: 'steps' is not valid (nearest: "));
  const std::string figure = "[[figure]]\nid = \"d\"\ntitle = \"d\"\nx = \"t\"\ny = \"energy deviation\"\ntable = ";
  CHECK_THAT(study_error_of(history + figure + "\"runs\"\n"),
             StartsWith("f.toml:28: figure[0].table: 'runs' is no declared table a figure names (rows = history, samples, periodic, trajectory, "
                        "flights, impulses, field or pivot); valid: h"));
  CHECK_THAT(study_error_of(history + figure + "\"h\"\n"),
             StartsWith("f.toml:27: figure[0].y: 'energy deviation' is not a column of table 'h'; valid: t, penetration"));
  CHECK_THAT(study_error_of(history + replaced(figure, "\"energy deviation\"", "\"err\"") + "\"h\"\n"),
             StartsWith("f.toml:27: figure[0].y: 'err' is not a column of table 'h'; valid: t, penetration"));
}

TEST_CASE("study file: a problem's steps serve integrators without a sweep of their own, full_steps under --full; "
          "integrators = \"all\" runs every registered one; bad ones named", "[studies][study_file]") {
  using Catch::StartsWith;
  const std::string all = R"([study]
title = "t"
t_end = 0.6
integrators = "all"

[[problem]]
name = "bouncing-mass"
steps = [1e-2, 5e-3]
full_steps = [1e-2, 5e-3, 2e-3]

[reference]
solution = "exact"

[[measure]]
kind = "error"
)";
  const nsb::StudySpec spec = nsb::parse_study_text(all, "f.toml", false);
  const auto& registry = nsb::integrator_registry();
  REQUIRE(spec.integrators.size() == registry.size());
  for (std::size_t i = 0; i < registry.size(); ++i) CHECK(spec.integrators[i].name == registry[i].name);
  const nsb::StudyEntry entry = nsb::file_study(spec);
  CHECK(nsb::study_cases(entry, {false}).size() == 2 * registry.size());
  const auto full = nsb::study_cases(entry, {true});
  REQUIRE(full.size() == 3 * registry.size());
  CHECK(full[2]["dt"].get<double>() == 2e-3);
  // An integrator's own sweep wins over the problem's; one without takes the problem's.
  const std::string listed = replaced(all, "integrators = \"all\"\n", "") +
                             "\n[[integrator]]\nname = \"cd-lagrange\"\n\n[[integrator]]\nname = \"moreau-jean\"\nsteps = [2e-2]\n";
  const auto cases = nsb::study_cases(nsb::file_study(nsb::parse_study_text(listed, "f.toml", false)), {false});
  REQUIRE(cases.size() == 3);
  CHECK(cases[1]["dt"].get<double>() == 5e-3);
  CHECK(cases[2]["dt"].get<double>() == 2e-2);
  CHECK_THAT(study_error_of(replaced(listed, "steps = [1e-2, 5e-3]\nfull_steps = [1e-2, 5e-3, 2e-3]\n", "")),
             StartsWith("f.toml:14: integrator[0]: no sweep on problem 'bouncing-mass'; valid: steps = [dt, ...]"));
  CHECK_THAT(study_error_of(replaced(all, "steps = [1e-2, 5e-3]\n", "")),
             StartsWith("f.toml:8: problem[0].full_steps: full_steps without steps; valid: steps = [dt, ...] beside it"));
  CHECK_THAT(study_error_of(replaced(all, "steps = [1e-2, 5e-3]", "steps = [1e-2, 0.7]")),
             StartsWith("f.toml:8: problem[0].steps[1]: dt = 0.7 is larger than study.t_end = 0.6; valid: dt <= t_end"));
  CHECK_THAT(study_error_of(replaced(all, "\"all\"", "\"some\"")), StartsWith("f.toml:4: study.integrators: 'some' is not valid (nearest: "));
  // [[integrator]] tables beside "all" are variants in the place of the one they name; a label
  // of another registered integrator is taken.
  CHECK_THAT(study_error_of(all + "\n[[integrator]]\nname = \"cd-lagrange\"\nlabel = \"moreau-jean\"\n"),
             StartsWith("f.toml:4: study.integrators.label: label 'moreau-jean' used twice; valid: distinct labels"));
  CHECK_THAT(study_error_of(replaced(listed, "steps = [2e-2]", "full_steps = [2e-2]")),
             StartsWith("f.toml:21: integrator[1].full_steps: full_steps without steps; valid: steps = [dt, ...] beside it"));
}

TEST_CASE("study file: a problem's own reference, its floor and what it is against; a window per problem; bad ones named",
          "[studies][study_file]") {
  using Catch::Contains;
  using Catch::StartsWith;
  TempCache cache;
  const std::string text = quick_study("0.3") + R"(
[[problem]]
name = "bouncing-mass"
label = "mass"

[[problem]]
name = "spring-chain"
label = "chain"
parameters = { n = 3, wall = "left" }
reference = { integrator = "modal-exact", lockstep = true, floor = 1e-13, against = "the chain solved exactly" }

[[integrator]]
name = "cd-lagrange"
steps = [1e-2, 5e-3]

[[integrator]]
name = "modal-exact"
steps = [1e-2]

[reference]
solution = "exact"

[[measure]]
kind = "error"
label = "windowed"
window = { mass = [0.0, 0.1] }

[[measure]]
kind = "error"
label = "mass only"
window = [0.0, 0.1]
problems = ["mass"]

[[measure]]
kind = "error"
label = "whole"
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "f.toml", false);
  REQUIRE(spec.problems[1].reference);
  CHECK(spec.reference_of(spec.problems[0]) == &spec.reference);
  CHECK(spec.reference_of(spec.problems[1])->lockstep);
  std::vector<nsb::Json> results;
  const auto tables = run_all(spec, &results);
  REQUIRE(results.size() == 6);
  for (std::size_t k : {0, 1}) {  // the mass: the window's error, as the measure with that window
    REQUIRE(results[k]["values"][0].is_number());
    CHECK(results[k]["values"][0] == results[k]["values"][1]);
    CHECK(results[k]["values"][0].get<double>() < results[k]["values"][2].get<double>());
  }
  for (std::size_t k : {3, 4}) {  // the chain: no window of its own, the whole run
    REQUIRE(results[k]["values"][0].is_number());
    CHECK(results[k]["values"][0] == results[k]["values"][2]);
    CHECK(results[k]["values"][1].is_null());
  }
  CHECK(results[2]["status"] == "ok");  // modal-exact on the mass, against its exact solution
  CHECK(results[5]["status"] == "n/a");  // modal-exact on the chain is its reference
  CHECK(results[5]["message"] == "the reference of this problem");
  const nsb::Table& rank = table_ending(tables, "_ranking");
  CHECK_THAT(rank.caption, Contains("mass: against the exact solution; chain: against the chain solved exactly (its own error 1.0e-13)"));
  CHECK_THAT(table_ending(tables, "_work_precision").caption,
             Contains("Errors against mass: the exact solution; chain: the chain solved exactly;"));
  CHECK_THAT(study_error_of(replaced(text, "reference = { integrator = \"modal-exact\", lockstep = true,", "reference = { solution = \"exact\",")),
             StartsWith("f.toml:15: problem[1].reference.solution: problem 'chain' (spring-chain) has no exact solution"));
  CHECK_THAT(study_error_of(replaced(text, "lockstep = true,", "lockstep = true, dt = 1e-3,")),
             StartsWith("f.toml:15: problem[1].reference.dt: a lockstep reference steps with each run"));
  CHECK_THAT(study_error_of(replaced(text, "against = \"the chain solved exactly\"", "against = 3")),
             StartsWith("f.toml:15: problem[1].reference.against: expected a string, got an integer"));
  CHECK_THAT(study_error_of(replaced(text, "window = { mass = [0.0, 0.1] }", "window = { mas = [0.0, 0.1] }")),
             StartsWith("f.toml:31: measure[0].window.mas: unknown key (nearest valid key: mass); valid: mass, chain"));
  CHECK_THAT(study_error_of(replaced(text, "window = { mass = [0.0, 0.1] }", "window = { mass = [0.0, 0.1] }\nproblems = [\"chain\"]")),
             StartsWith("f.toml:31: measure[0].window.mass: the measure is not measured on problem 'mass'"));
  CHECK_THAT(study_error_of(replaced(text, "window = { mass = [0.0, 0.1] }", "window = { mass = [0.4, 0.5] }")),
             StartsWith("f.toml:31: measure[0].window.mass: the window starts at 0.4 s, not before the end of problem 'mass' (0.3 s)"));
}

TEST_CASE("study file: figures = \"declared\" draws the declared figures alone, ids as given; a ranking's error column and "
          "runs' format; bad ones named", "[studies][study_file]") {
  using Catch::StartsWith;
  const std::string text = replaced(kMinimal, "t_end = 0.6\n", "t_end = 0.6\nfigures = \"declared\"\ntargets = [1]\n") + R"(
[[figure]]
id = "work_precision"
title = "Error against CPU"
x = "CPU"
y = "err u max"

[[table]]
id = "runs"
title = "Runs"
columns = ["problem", "integrator", "dt", "err u max", "CPU", { of = "status", description = "" }]

[[table]]
id = "best"
title = "Cheapest"
rows = "ranking"
error = { header = "err", format = "", description = "err u max of runs" }
runs_format = "{:.1e}"
)";
  const auto tables = run_all(nsb::reduced_study(nsb::parse_study_text(text, "min.toml", false), 1.0, 2, 100000));
  REQUIRE(tables.size() == 2);
  REQUIRE(tables[0].figures.size() == 1);  // not the engine's work-precision and convergence figures
  CHECK(tables[0].figures[0].id == "work_precision");
  CHECK(tables[0].columns.back().description.empty());
  const nsb::Table& rank = tables[1];
  CHECK(rank.columns[1].name == "target err");
  CHECK(rank.columns[1].description == "err u max of runs");
  const std::string runs = std::get<std::string>(rank.rows[0][4]);
  CHECK_THAT(runs, StartsWith("dt = 5.0e-03") || StartsWith("dt = 1.0e-02"));
  CHECK_THAT(study_error_of(replaced(text, "figures = \"declared\"", "figures = \"mine\"")),
             StartsWith("f.toml:4: study.figures: 'mine' is not valid (nearest: "));
  CHECK_THAT(study_error_of(replaced(text, "runs_format = \"{:.1e}\"", "runs_format = \"{:q}\"")),
             StartsWith("f.toml:37: table[1].runs_format: '{:q}' is no number format"));
  CHECK_THAT(study_error_of(replaced(text, "runs_format = \"{:.1e}\"", "runs_format = \"\"")),
             StartsWith("f.toml:37: table[1].runs_format: an empty format; valid: a fmt format of one number"));
  CHECK_THAT(study_error_of(replaced(text, "header = \"err\"", "heder = \"err\"")),
             StartsWith("f.toml:36: table[1].error.heder: unknown key (nearest valid key: header)"));
  CHECK_THAT(study_error_of(replaced(text, "title = \"Runs\"", "title = \"Runs\"\nruns_format = \"{:.1e}\"")),
             StartsWith("f.toml:30: table[0].runs_format: only a ranking has runs_format; valid: rows = \"ranking\""));
  CHECK_THAT(study_error_of(text + "\n[[table]]\nid = \"again\"\ntitle = \"Again\"\nrows = \"ranking\"\nruns_format = \"{:.2e}\"\n"),
             StartsWith("f.toml:43: table[2].runs_format: the first ranking table sets the runs' format of every ranking"));
  // Without figures = "declared", the engine's figure ids stay reserved.
  CHECK_THAT(study_error_of(replaced(text, "figures = \"declared\"\n", "")),
             StartsWith("f.toml:21: figure[0].id: 'work_precision' is the id of a figure the study draws itself"));
}

TEST_CASE("study file: a run without an error (over budget) is not reached, not 'removed' by a rule", "[studies][study_file]") {
  const std::string text = replaced(kMinimal, "t_end = 0.6\n", "t_end = 0.6\ncpu_repeats = 0\nmax_force_evaluations = 10\n");
  const auto tables = run_all(nsb::parse_study_text(text, "f.toml", false));
  const nsb::Table& rank = table_ending(tables, "_ranking");
  CHECK(std::get<std::string>(rank.rows[0][2]) == "none");
}

namespace {

const std::string kLongTime = quick_study("1.0", "history_intervals = 10\ncounters = [\"no_root_steps\"]\n") + R"(
[[problem]]
name = "bouncing-mass"
label = "target"
parameters = { e = 0.9 }
steps = [1e-3]
end_at_impact = 3
[[problem]]
name = "spring-chain"
label = "chain"
parameters = { wall = "both", gap = 0.5 }
steps = [0.02]
min_flight = 0.5
[[integrator]]
name = "moreau-jean"
[[integrator]]
name = "newmark-lm"
[[measure]]
kind = "energy"
norm = "offset"
label = "offset"
[[measure]]
kind = "energy"
norm = "final abs"
relative_to = "first step"
label = "final"
[[measure]]
kind = "momentum"
relative_to = "initial speeds"
problems = ["chain"]
label = "momentum"
[[measure]]
kind = "flight-energy"
count = 2
problems = ["target"]
label = "flight"
[[measure]]
kind = "flight-energy"
count = 2
norm = "count"
problems = ["target"]
label = "flights"
[[table]]
id = "runs"
title = "runs"
problems = ["target"]
declined = "n/a"
declined_reason = "final"
columns = ["problem", "integrator name", "parameters", "t_end", "steps", "min step", "max step", "offset", "final", "flight",
           "flights", "no_root_steps", "parameter e", "status"]
[[table]]
id = "fits"
title = "fits"
rows = "group"
problems = ["target"]
columns = ["integrator", "parameter e", "order of flight"]
[[table]]
id = "momentum"
title = "momentum"
rows = "history"
problems = ["chain"]
columns = ["integrator", "t", "momentum residual"]
[[table]]
id = "ratio"
title = "ratio"
rows = "samples"
problems = ["chain"]
columns = ["integrator", "t", "energy ratio", "parameter wall"]
)";

}  // namespace

TEST_CASE("study file: errors from the first step, flight energies, a momentum scale, end_at_impact, counters, declined rows, "
          "momentum histories and samples", "[studies][study_file]") {
  const nsb::StudySpec spec = nsb::parse_study_text(kLongTime, "f.toml", false);
  const auto target = nsb::make_problem("bouncing-mass", {{"e", "0.9"}});
  CHECK(spec.problems[0].t_end == target->exact()->impact_times(10.0).at(2));  // end_at_impact = 3
  std::vector<nsb::Json> results;
  const auto tables = run_all(spec, &results);
  const nsb::Table& runs = table_ending(tables, "runs");
  REQUIRE(runs.rows.size() == 2);  // the target problem's alone
  const auto cell = [&](std::size_t row, const std::string& header) { return runs.rows[row][column(runs, header)]; };
  // Moreau-Jean: the offset is its first step's energy change, relative to E0.
  auto mj = nsb::make_integrator("moreau-jean");
  mj->init(*target, target->initial_state());
  const double e0 = mj->energy().total();
  mj->step(1e-3);
  CHECK(std::get<double>(cell(0, "offset")) == (mj->energy().total() - e0) / std::abs(e0));
  CHECK(std::get<double>(cell(0, "final")) >= 0.0);
  CHECK(std::get<double>(cell(0, "flights")) == 2.0);  // two flights compared ...
  CHECK(std::get<double>(cell(0, "flight")) < 1e-2);   // ... close to E0 e^(2i)
  CHECK(std::get<double>(cell(0, "min step")) == 1e-3);
  CHECK(std::get<double>(cell(0, "max step")) == 1e-3);
  CHECK(std::holds_alternative<std::monostate>(cell(0, "no_root_steps")));  // moreau-jean counts none
  CHECK(std::get<std::string>(cell(0, "integrator name")) == "moreau-jean");
  CHECK(std::get<std::string>(cell(0, "parameters")) == "default");
  // newmark-lm declines e = 0.9: what was asked kept, its reason in the column declined_reason names.
  CHECK(std::get<std::string>(cell(1, "integrator name")) == "newmark-lm");
  CHECK_THAT(std::get<std::string>(cell(1, "final")), Catch::StartsWith("integrator newmark-lm needs e = 0 on contacts with mass (it has no velocity-level impact law); "
                                                                                 "problem bouncing-mass has restitution e = 0.9"));
  CHECK(std::holds_alternative<std::monostate>(cell(1, "offset")));
  CHECK(std::holds_alternative<std::monostate>(cell(1, "flight")));
  // A group table shows its problem's parameters beside the fits (one step: no order).
  const nsb::Table& fits = table_ending(tables, "fits");
  REQUIRE(fits.rows.size() == 2);
  CHECK(fits.rows[0][0] == nsb::Cell{std::string("moreau-jean")});
  CHECK(std::get<double>(fits.rows[0][1]) == 0.9);
  CHECK(std::holds_alternative<std::monostate>(fits.rows[0][2]));
  CHECK(std::get<double>(cell(0, "parameter e")) == 0.9);  // a real parameter: a number
  // newmark-lm declines e = 0.9: what was asked kept, what a run measures n/a (not 0 steps).
  CHECK_THAT(std::get<std::string>(cell(1, "status")), Catch::StartsWith("n/a: "));
  CHECK(std::get<double>(cell(1, "t_end")) == spec.problems[0].t_end);
  CHECK(std::holds_alternative<std::monostate>(cell(1, "steps")));
  CHECK(std::holds_alternative<std::monostate>(cell(1, "flights")));
  // The chain (no external force): Moreau-Jean balances momentum; 10 intervals; 11 samples (the
  // first step's, then at or after each k t_end / 10, k = 1..10: the last step reaches t_end).
  const nsb::Table& momentum = table_ending(tables, "momentum");
  REQUIRE(momentum.rows.size() == 10);  // moreau-jean's (newmark-lm declines the chain too)
  for (const auto& row : momentum.rows) CHECK(std::get<double>(row[2]) < 1e-12);
  const nsb::Table& ratio = table_ending(tables, "ratio");
  REQUIRE(ratio.rows.size() == 11);
  CHECK(std::get<double>(ratio.rows[0][1]) == Approx(0.02));  // the first step's
  CHECK(std::get<double>(ratio.rows[1][1]) >= 0.1);           // then at or after k t_end / 10
  CHECK(std::get<double>(ratio.rows[0][2]) == Approx(1.0).epsilon(1e-2));
  CHECK(std::get<std::string>(ratio.rows[0][3]) == "both");
  // The chain's momentum measure, by its scale sum_i m_i |v0_i|.
  const auto chain = std::find_if(results.begin(), results.end(), [](const nsb::Json& r) { return r.contains("values") && !r["values"][2].is_null(); });
  REQUIRE(chain != results.end());
  CHECK((*chain)["values"][2].get<double>() < 1e-12);
}

TEST_CASE("study file: integrators = \"all\" with variants in place; full_t_end, default_only; the new keys' bad input named",
          "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const std::string all = quick_study("0.6", "integrators = \"all\"\n") + R"(
[[problem]]
name = "bouncing-mass"
steps = [1e-2]
full_t_end = 1.2
[[problem]]
name = "spring-chain"
steps = [1e-2]
default_only = true
[[integrator]]
name = "cd-lagrange-adaptive"
label = "talk"
parameters = { momentum = "talk" }
[[integrator]]
name = "cd-lagrange-adaptive"
label = "variational"
parameters = { momentum = "variational" }
[[measure]]
kind = "energy"
)";
  const nsb::StudySpec spec = nsb::parse_study_text(all, "f.toml", false);
  const auto& registry = nsb::integrator_registry();
  REQUIRE(spec.integrators.size() == registry.size() + 1);
  std::size_t k = 0;
  for (const auto& entry : registry) {
    if (entry.name != "cd-lagrange-adaptive") {
      CHECK(spec.integrators[k++].label == entry.name);
      continue;
    }
    CHECK(spec.integrators[k++].label == "talk");
    CHECK(spec.integrators[k++].label == "variational");
  }
  const nsb::StudyEntry entry = nsb::file_study(spec);
  const auto plain = nsb::study_cases(entry, {false}), full = nsb::study_cases(entry, {true});
  CHECK(plain.size() == 2 * spec.integrators.size());
  REQUIRE(full.size() == spec.integrators.size());  // the chain is default_only
  CHECK(full.front()["t_end"].get<double>() == 1.2);
  CHECK_FALSE(plain.front().contains("t_end"));

  const auto with_problem = [](const std::string& line) { return replaced(kMinimal, "parameters = { e = 0.5 }", "parameters = { e = 0.5 }\n" + line); };
  CHECK_THAT(study_error_of(with_problem("full_only = true\ndefault_only = true")),
             StartsWith("f.toml:9: problem[0].default_only: full_only and default_only both: the problem would never run; valid: at most one"));
  CHECK_THAT(study_error_of(with_problem("full_t_end = 0")), StartsWith("f.toml:8: problem[0].full_t_end: 0 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(with_problem("min_flight = -1")), StartsWith("f.toml:8: problem[0].min_flight: -1 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(with_problem("end_at_impact = 0")), StartsWith("f.toml:8: problem[0].end_at_impact: 0 is out of range; valid: [1, 1000]"));
  CHECK_THAT(study_error_of(with_problem("end_at_impact = 900")),
             StartsWith("f.toml:8: problem[0].end_at_impact: problem 'bouncing-mass' knows ") && Catch::Contains("exact impact times; valid: [1, "));
  CHECK_THAT(study_error_of(with_problem("end_at_impact = 2\nt_end = 1")),
             StartsWith("f.toml:8: problem[0].end_at_impact: the run's end given twice; valid: one of t_end (with full_t_end) or end_at_impact"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\ncounters = [\"impacts\"]")),
             StartsWith("f.toml:4: study.counters[0]: 'impacts' is empty, given twice or the name of a run column; valid: distinct names"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nhistory_intervals = 0")),
             StartsWith("f.toml:4: study.history_intervals: 0 is out of range; valid: [1, 100000]"));
  const auto with_measure = [](const std::string& lines) { return replaced(kMinimal, "kind = \"error\"", lines); };
  CHECK_THAT(study_error_of(with_measure("kind = \"energy\"\nrelative_to = \"start\"")),
             StartsWith("f.toml:18: measure[0].relative_to: 'start' is not valid (nearest: ") && Catch::Contains("valid: initial, first step"));
  CHECK_THAT(study_error_of(with_measure("kind = \"energy\"\nnorm = \"offset\"\nrelative_to = \"first step\"")),
             StartsWith("f.toml:19: measure[0].relative_to: the offset is E_1 - E0 relative to E0's scale"));
  CHECK_THAT(study_error_of(with_measure("kind = \"momentum\"\nrelative_to = \"speeds\"")),
             StartsWith("f.toml:18: measure[0].relative_to: 'speeds' is not valid (nearest: ") && Catch::Contains("valid: momentum, initial speeds"));
  CHECK_THAT(study_error_of(with_measure("kind = \"flight-energy\"")), StartsWith("f.toml:16: measure[0]: missing key 'count'"));
  CHECK_THAT(study_error_of(with_measure("kind = \"flight-energy\"\ncount = 3")),  // t_end 0.6: one impact, at 0.45 s
             StartsWith("f.toml:18: measure[0].count: problem 'bouncing-mass' knows 1 exact impacts and energies by t_end, not count + 1 = 4"));
  CHECK_THAT(study_error_of(with_measure("kind = \"flight-energy\"\ncount = 1\nnorm = \"l2\"")),
             StartsWith("f.toml:19: measure[0].norm: 'l2' is not valid (nearest: ") && Catch::Contains("valid: max, count"));
  // The impacts compared (min_flight_steps), their count, and flight energies at the mid-flight step.
  CHECK_THAT(study_error_of(with_measure("kind = \"impact-time\"\nmin_flight_steps = 0")),
             StartsWith("f.toml:18: measure[0].min_flight_steps: 0 is out of range; valid: [1, 1000000]"));
  CHECK_THAT(study_error_of(with_measure("kind = \"impact-time\"\nmin_flight_steps = 2.5")),
             StartsWith("f.toml:18: measure[0].min_flight_steps: expected an integer, got a number"));
  CHECK_THAT(study_error_of(with_measure("kind = \"impact-time\"\nnorm = \"first\"")),
             StartsWith("f.toml:18: measure[0].norm: 'first' is not valid (nearest: ") && Catch::Contains("valid: max, count"));
  CHECK_THAT(study_error_of(with_measure("kind = \"impact-time\"\nlocated = true\nnorm = \"count\"")),
             StartsWith("f.toml:18: measure[0].located: located impacts are compared by rank, all of the first count; valid: located = true "
                        "without min_flight_steps and norm = \"count\""));
  CHECK_THAT(study_error_of(with_measure("kind = \"flight-energy\"\ncount = 1\nmin_flight_steps = -3")),
             StartsWith("f.toml:19: measure[0].min_flight_steps: -3 is out of range; valid: [1, 1000000]"));
  CHECK_THAT(study_error_of(with_measure("kind = \"flight-energy\"\ncount = 1\nat = \"middle\"")),
             StartsWith("f.toml:19: measure[0].at: 'middle' is not valid (nearest: ") && Catch::Contains("valid: exact mid-flight, mid-flight step"));
  // The start of the final rest: its bounds, min_rest and exact time.
  const std::string bound = "kind = \"rest-start\"\nrest = [{ observable = \"v\", abs = true, at_most = 19.62, dt_power = 1 }]\n";
  CHECK_THAT(study_error_of(with_measure("kind = \"rest-start\"")), StartsWith("f.toml:16: measure[0]: missing key 'rest'"));
  CHECK_THAT(study_error_of(with_measure("kind = \"rest-start\"\nrest = []")),
             StartsWith("f.toml:18: measure[0].rest: expected an array of one or more { observable, abs, at_most, dt_power }"));
  CHECK_THAT(study_error_of(with_measure("kind = \"rest-start\"\nrest = [{ observable = \"w\", at_most = 1 }]")),
             StartsWith("f.toml:18: measure[0].rest[0].observable: 'w' is not an observable of problem 'bouncing-mass'; valid: q, v, "));
  CHECK_THAT(study_error_of(with_measure("kind = \"rest-start\"\nrest = [{ observable = \"v\", at_most = 0 }]")),
             StartsWith("f.toml:18: measure[0].rest[0].at_most: 0 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(with_measure("kind = \"rest-start\"\nrest = [{ observable = \"v\", at_most = 1, dt_power = 5 }]")),
             StartsWith("f.toml:18: measure[0].rest[0].dt_power: 5 is out of range; valid: [0, 4]"));
  CHECK_THAT(study_error_of(with_measure("kind = \"rest-start\"\nrest = [{ observable = \"v\", at_most = 1, below = 2 }]")),
             StartsWith("f.toml:18: measure[0].rest[0].below: unknown key"));
  CHECK_THAT(study_error_of(with_measure(bound + "min_rest = -0.25")),
             StartsWith("f.toml:19: measure[0].min_rest: -0.25 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(with_measure(bound + "exact = true")),
             StartsWith("f.toml:19: measure[0].exact: the exact start of a rest is a summary value of the problem; valid: summary = NAME"));
  CHECK_THAT(study_error_of(with_measure(bound + "exact = true\nsummary = \"t_roll_exact\"")),
             StartsWith("f.toml:20: measure[0].summary: 't_roll_exact' is not a summary value of problem 'bouncing-mass'; valid: t_zeno_exact"));
  const std::string declared = kMinimal + "[[table]]\nid = \"t\"\ntitle = \"t\"\ncolumns = [\"problem\"]\n";
  CHECK_THAT(study_error_of(declared + "declined_reason = \"problem\"\n"),
             StartsWith("f.toml:22: table[0].declined_reason: a declined run's reason replaces one of its blanked cells; valid: declined = \"n/a\" or \"empty\""));
  CHECK_THAT(study_error_of(replaced(declared, "columns = [\"problem\"]", "columns = [\"problem\", \"err u max\"]") +
                            "declined = \"n/a\"\ndeclined_reason = \"problem\"\n"),
             StartsWith("f.toml:23: table[0].declined_reason: 'problem' is not valid (nearest: err u max); valid: err u max"));
  CHECK_THAT(study_error_of(declared + "declined = \"zero\"\n"),
             StartsWith("f.toml:22: table[0].declined: 'zero' is not valid (nearest: ") && Catch::Contains("valid: as run, n/a"));
  CHECK_THAT(study_error_of(declared + "rows = \"group\"\ndeclined = \"n/a\"\n"),
             StartsWith("f.toml:23: table[0].declined: only a table of one row per run shows declined runs; valid: rows = \"case\""));
  CHECK_THAT(study_error_of(declared + "rows = \"ranking\"\nproblems = [\"bouncing-mass\"]\n"),
             StartsWith("f.toml:23: table[0].problems: a ranking ranks every problem of its measure"));
  CHECK(nsb::parse_study_text(declared + "rows = \"group\"\nproblems = [\"bouncing-mass\"]\n", "f.toml", false).tables.at(0).problems ==
        std::vector<std::string>{"bouncing-mass"});  // a group table picks its problems
  CHECK_THAT(study_error_of(replaced(declared, "columns = [\"problem\"]", "columns = [\"parameter wall\"]")),
             StartsWith("f.toml:21: table[0].columns[0]: 'parameter wall' is not valid (nearest: parameter "));
  const std::string figure = "[[figure]]\nid = \"f\"\ntitle = \"f\"\nx = \"dt\"\ny = \"steps\"\nsmall_multiples = 1\n";
  CHECK_THAT(study_error_of(kMinimal + figure), StartsWith("f.toml:23: figure[0].small_multiples: expected a boolean, got an integer"));
  CHECK_THAT(study_error_of(kMinimal + replaced(figure, "small_multiples", "deviation")),
             StartsWith("f.toml:23: figure[0].deviation: expected a boolean, got an integer"));
}

TEST_CASE("study file: an optional integrator is left out where this build does not register it; bad input named",
          "[studies][study_file][bad-input]") {
  const std::string text = quick_study("0.6", "integrators = \"all\"\n") + R"(
[[problem]]
name = "bouncing-mass"
steps = [1e-2]
[[integrator]]
name = "peer-of-another-build"
optional = true
[[integrator]]
name = "moreau-jean"
label = "MJ, theta = 1"
parameters = { theta = 1.0 }
optional = true
[[measure]]
kind = "energy"
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "f.toml", false);
  const auto labelled = [&](const std::string& label) {
    return std::count_if(spec.integrators.begin(), spec.integrators.end(), [&](const auto& it) { return it.label == label; });
  };
  CHECK(spec.integrators.size() == nsb::integrator_registry().size());  // moreau-jean's variant in its place
  CHECK(labelled("MJ, theta = 1") == 1);
  CHECK(labelled("moreau-jean") == 0);
  CHECK(labelled("peer-of-another-build") == 0);
  // Without optional an unknown name is an error; optional takes a boolean.
  CHECK_THAT(study_error_of(replaced(text, "optional = true\n[[integrator]]", "[[integrator]]")),
             Catch::StartsWith("f.toml:12: integrator[0].name: 'peer-of-another-build' is not"));
  CHECK_THAT(study_error_of(replaced(text, "optional = true\n[[integrator]]", "optional = 1\n[[integrator]]")),
             Catch::StartsWith("f.toml:13: integrator[0].optional: expected a boolean, got an integer"));
}

TEST_CASE("study file: case_order, default_only, [[exclude]] rules by kind, parameter and stable step, a budget per step",
          "[studies][study_file]") {
  const std::string text = quick_study("0.6", "integrators = \"all\"\ncase_order = \"integrator\"\nmax_force_evaluations_per_step = 4\n") + R"(
[[problem]]
name = "bouncing-mass"
label = "mass"
steps = [1e-2]
default_only = true
[[problem]]
name = "signorini-bar"
label = "bar"
grid = { N = [10, 20] }
stable_steps = [0.5, 0.9]
[[exclude]]
integrators = "peers"
above = { N = 10 }
[[exclude]]
integrators = "references"
stable_steps_except = [0.9]
full_only = true
[[table]]
id = "runs"
title = "runs"
columns = ["problem", "integrator", "dt", "budget"]
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "f.toml", false);
  CHECK(spec.integrator_major);
  const auto& registry = nsb::integrator_registry();
  const nsb::StudyEntry entry = nsb::file_study(spec);
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto cases = nsb::study_cases(entry, {full});
    // Integrator by integrator, each over the problems in their order and its sweep; the mass
    // without --full only; peers not above N = 10; references at 0.9 stable steps only under --full.
    std::vector<std::pair<std::size_t, std::string>> expected;  // (integrator, problem label)
    for (std::size_t i = 0; i < registry.size(); ++i)
      for (const auto& p : spec.problems) {
        if (p.label == "mass") {
          if (!full) expected.emplace_back(i, p.label);
          continue;
        }
        if (registry[i].peer && p.label == "bar, N = 20") continue;
        if (!(registry[i].reference && full)) expected.emplace_back(i, p.label);  // at 0.5 stable steps
        expected.emplace_back(i, p.label);                                         // at 0.9
      }
    REQUIRE(cases.size() == expected.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const nsb::FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
      CHECK(cases[k]["integrator"].get<std::size_t>() == expected[k].first);
      CHECK(p.label == expected[k].second);
      const double dt = cases[k]["dt"];
      CHECK(spec.budget_of(p, dt, 0.6) == static_cast<long>(4.0 * 0.6 / dt));  // floor(4 t_end / dt)
    }
  }
  // The budget holds: at 0.5 evaluations per step, a run of 60 steps stops over budget past 30.
  const std::string short_budget = quick_study("0.6", "max_force_evaluations_per_step = 0.5\n") + R"(
[[problem]]
name = "bouncing-mass"
[[problem]]
name = "signorini-bar"
parameters = { N = 10 }
[[integrator]]
name = "cd-lagrange"
steps = [1e-2]
[[table]]
id = "runs"
title = "runs"
columns = ["status", "budget", "F_int evals", "parameter h0", "parameter N", { of = "parameter mass", header = "mass" }]
)";
  const auto tables = run_all(nsb::parse_study_text(short_budget, "f.toml", false));
  const nsb::Table& runs = table_ending(tables, "runs");
  REQUIRE(runs.rows.size() == 2);
  const auto& row = runs.rows[0];
  CHECK_THAT(std::get<std::string>(row[0]), Catch::StartsWith("over budget"));
  CHECK(std::get<long>(row[1]) == 30);  // floor(0.5 x 0.6 / 0.01)
  CHECK(std::get<long>(row[2]) == 31);  // the run stops at the evaluation past the budget
  // A problem's parameters as columns: reals and integers as numbers (defaults included),
  // choices as text, empty where the problem has no such parameter.
  CHECK(std::get<double>(row[3]) == 1.0);
  CHECK(std::holds_alternative<std::monostate>(row[4]));
  CHECK(std::holds_alternative<std::monostate>(row[5]));
  CHECK(std::holds_alternative<std::monostate>(runs.rows[1][3]));
  CHECK(std::get<long>(runs.rows[1][4]) == 10);
  CHECK(std::get<std::string>(runs.rows[1][5]) == "lumped");
  CHECK(runs.columns[5].name == "mass");
}

TEST_CASE("study file: case_order, default_only, [[exclude]] and a budget per step: bad input named", "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const auto with_study = [](const std::string& line) { return replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\n" + line); };
  CHECK_THAT(study_error_of(with_study("case_order = \"integrators\"")),
             StartsWith("f.toml:4: study.case_order: 'integrators' is not valid (nearest: integrator); valid: problem, integrator"));
  CHECK_THAT(study_error_of(with_study("max_force_evaluations_per_step = 0")),
             StartsWith("f.toml:4: study.max_force_evaluations_per_step: 0 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(with_study("max_force_evaluations_per_step = 2e6")),
             StartsWith("f.toml:4: study.max_force_evaluations_per_step: 2000000 F_int evaluations per step is no budget; valid: (0, 1e6]"));
  CHECK_THAT(study_error_of(with_study("max_force_evaluations = 10\nmax_force_evaluations_per_step = 4")),
             StartsWith("f.toml:5: study.max_force_evaluations_per_step: given beside study.max_force_evaluations; valid: one of the two budgets"));
  const auto with_problem = [](const std::string& line) { return replaced(kMinimal, "parameters = { e = 0.5 }", "parameters = { e = 0.5 }\n" + line); };
  CHECK_THAT(study_error_of(with_problem("default_only = true\nfull_only = true")),
             StartsWith("f.toml:8: problem[0].default_only: full_only and default_only both: the problem would never run; valid: at most one of them true"));
  const auto with_rule = [](const std::string& lines) { return kMinimal + "[[exclude]]\nintegrators = \"peers\"\n" + lines; };
  CHECK(nsb::parse_study_text(with_rule("above = { e = 0.5 }\n"), "f.toml", false).exclusions.at(0).above.at("e") == 0.5);
  CHECK_THAT(study_error_of(replaced(with_rule("above = { e = 0.5 }\n"), "\"peers\"", "\"peer\"")),
             StartsWith("f.toml:19: exclude[0].integrators: 'peer' is not valid (nearest: peers); valid: schemes, peers, references"));
  CHECK_THAT(study_error_of(with_rule("above = { N = 10 }\n")),
             StartsWith("f.toml:20: exclude[0].above.N: 'N' is no numeric parameter of the study's problems; valid: a real or integer parameter of one or more problems (the rule applies to those)"));
  CHECK_THAT(study_error_of(with_rule("above = { e = \"0.5\" }\n")), StartsWith("f.toml:20: exclude[0].above.e: expected a number, got a string"));
  CHECK_THAT(study_error_of(with_rule("stable_steps_except = [0]\n")),
             StartsWith("f.toml:20: exclude[0].stable_steps_except[0]: 0 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(with_rule("default_only = false\n")),
             StartsWith("f.toml:18: exclude[0]: no condition: the rule would exclude every run of its integrators; valid: above = "));
  CHECK_THAT(study_error_of(with_rule("above = { e = 0.5 }\ndefault_only = true\nfull_only = true\n")),
             StartsWith("f.toml:22: exclude[0].full_only: full_only and default_only both: the rule would never apply; valid: at most one of them true"));
  CHECK_THAT(study_error_of(kMinimal + "[[table]]\nid = \"r\"\ntitle = \"r\"\ncolumns = [\"parameter N\"]\n"),
             StartsWith("f.toml:21: table[0].columns[0]: 'parameter N' is not valid (nearest: parameter "));
  CHECK_THAT(study_error_of(with_rule("below = { e = 0.5 }\n")), StartsWith("f.toml:20: exclude[0].below: unknown key (nearest valid key: above)"));
}

TEST_CASE("study file: an energy error sampled every period (count, first, final, drift per period); over-budget runs measured",
          "[studies][study_file]") {
  // The bouncing mass (e = 1) to t = 1 at dt = 1e-2, sampled at 0.1 + 0.25 k: 0.35, 0.6, 0.85
  // (1.1 is past t_end). Three points at k = 1, 2, 3: the least-squares slope is (e3 - e1) / 2.
  const std::string text = quick_study("1.0") + R"(
[[problem]]
name = "bouncing-mass"
parameters = { e = 1 }
[[integrator]]
name = "moreau-jean"
steps = [1e-2]
[[measure]]
kind = "energy"
every = 0.25
from = 0.1
norm = "count"
[[measure]]
kind = "energy"
every = 0.25
from = 0.1
norm = "first"
[[measure]]
kind = "energy"
every = 0.25
from = 0.1
[[measure]]
kind = "energy"
every = 0.25
from = 0.1
norm = "drift"
label = "drift"
)";
  std::vector<nsb::Json> results;
  const nsb::StudySpec spec = nsb::parse_study_text(text, "f.toml", false);
  CHECK(spec.measures[2].label == "energy err final, every 0.25 from 0.1");
  run_all(spec, &results);
  REQUIRE(results.size() == 1);
  const nsb::Json& v = results[0]["values"];
  CHECK(v[0].get<double>() == 3.0);
  const double first = v[1], last = v[2];
  CHECK(first != last);  // moreau-jean's energy changes at the impact near t = 0.45
  CHECK(v[3].get<double>() == Approx((last - first) / 2.0).epsilon(1e-12));
  // Over budget: no measures, unless study.measure_over_budget (then those up to the stop: one
  // sample of three).
  for (const bool measured : {false, true}) {
    const std::string more = fmt::format("max_force_evaluations = 45\nmeasure_over_budget = {}\n", measured);
    std::vector<nsb::Json> stopped;
    run_all(nsb::parse_study_text(replaced(text, "targets = [1e-2]\n", "targets = [1e-2]\n" + more), "f.toml", false), &stopped);
    CHECK(stopped[0]["status"] == "over budget");
    CHECK(stopped[0].contains("values") == measured);
    if (measured) CHECK(stopped[0]["values"][0].get<double>() == 1.0);
  }
}

TEST_CASE("study file: an energy error sampled every period: bad input named", "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const std::string energy = replaced(kMinimal, "kind = \"error\"", "kind = \"energy\"");
  const auto with = [&](const std::string& lines) { return energy + lines; };
  CHECK_THAT(study_error_of(with("every = 0\n")), StartsWith("f.toml:18: measure[0].every: 0 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(with("every = 0.1\nfrom = -1\n")), StartsWith("f.toml:19: measure[0].from: -1 is no start time; valid: [0, inf)"));
  CHECK_THAT(study_error_of(with("from = 0.1\n")), StartsWith("f.toml:18: measure[0].from: from without every; valid: every = T beside it"));
  CHECK_THAT(study_error_of(with("every = 0.1\nnorm = \"max\"\n")),
             StartsWith("f.toml:19: measure[0].norm: 'max' is not valid (nearest: "));
  CHECK_THAT(study_error_of(with("every = 0.1\nhistory = true\n")),
             StartsWith("f.toml:19: measure[0].history: an energy sampled every period has no window or history; valid: one of every or window/history"));
  CHECK_THAT(study_error_of(replaced(kMinimal, "t_end = 0.6", "t_end = 0.6\nmeasure_over_budget = 1")),
             StartsWith("f.toml:4: study.measure_over_budget: expected a boolean, got an integer"));
}

namespace {

// The bouncing bar (N = 10) to t = 2 (first impact at t = 1, contact until about 1.67): a lumped
// bar that Moreau-Jean runs and a consistent one that CD-Lagrange declines.
std::string bouncing_bar_errors_study(double force_scale) {
  return quick_study("2.0") + fmt::format(R"(
[[problem]]
name = "bouncing-bar"
label = "lumped"
parameters = {{ mass = "lumped", N = 10 }}
stable_steps = [0.5]
[[problem]]
name = "bouncing-bar"
label = "consistent"
parameters = {{ mass = "consistent", N = 10 }}
stable_steps = [0.5]
[[integrator]]
name = "moreau-jean"
[[integrator]]
name = "cd-lagrange"
[[measure]]
kind = "error"
observable = "u_contact"
against = "u_contact_exact"
scale = 5.0
label = "u max"
[[measure]]
kind = "error"
observable = "u_contact"
against = "u_contact_exact"
scale = 5.0
norm = "rms"
label = "u rms"
[[measure]]
kind = "error"
observable = "contact_force"
against = "contact_force_exact"
scale = {:.17g}
norm = "step rms"
inside = "contact_force_exact"
window = [0.0, 1.9]
label = "force osc"
[[measure]]
kind = "error"
observable = "contact_force"
against = "contact_force_exact"
scale = 300.0
norm = "step rms"
inside = "contact_force_exact"
window = [0.0, 0.5]
label = "force early"
[[table]]
id = "runs"
title = "runs"
declined = "empty"
columns = ["problem", "integrator", "steps", "u max", "status", {{ of = "force early", missing = "" }}, "force early"]
)",
                                          force_scale);
}

}  // namespace

TEST_CASE("study file: errors relative to a fixed scale, rms in time and over the steps, inside the exact contact phases; "
          "declined cells empty", "[studies][study_file]") {
  // The known answer: the bouncing bar study's own formulas, by hand on one run, against a
  // freshly built exact solution: |u_0 - u_0,exact| / g0 (max, and sqrt(sum dt e^2 / t) in time),
  // and the RMS over the steps of (Lambda / dt - lambda_exact) / (rho A c V) at the steps whose
  // t - dt, t and t + dt lie inside the exact contact phase, t <= 1.9.
  const nsb::Params params(nsb::SignoriniBar::bouncing_parameters_spec(), {{"mass", "lumped"}, {"N", "10"}});
  const nsb::BouncingBarExact ex(params, 4.0);
  const double g0 = params.real("g0");
  const double force_scale = params.real("rho") * params.real("A") * std::sqrt(params.real("E") / params.real("rho")) * ex.impact_speed();
  const auto problem = nsb::make_problem("bouncing-bar", {{"mass", "lumped"}, {"N", "10"}});
  auto integrator = nsb::make_integrator("moreau-jean");
  REQUIRE_FALSE(nsb::init_or_decline(*integrator, *problem));
  nsb::RunOptions options;
  options.dt = 0.5 * problem->stable_step();
  options.t_end = 2.0;
  options.record_series = false;
  double u_max = 0.0, u_sq = 0.0, osc_sq = 0.0;
  long osc_n = 0;
  const nsb::RunResult r = nsb::run(*problem, *integrator, options, [&](const nsb::Integrator& it, const nsb::StepInfo& info) {
    const double t = it.state().t;
    const double du = std::abs(it.state().u[0] - ex.displacement(0.0, t)) / g0;
    u_max = std::max(u_max, du);
    u_sq += info.dt * du * du;
    if (t <= 1.9 && ex.contact_force(t - info.dt) > 0.0 && ex.contact_force(t) > 0.0 && ex.contact_force(t + info.dt) > 0.0) {
      const double d = (it.impulses()[0] / info.dt - ex.contact_force(t)) / force_scale;
      osc_sq += d * d;
      ++osc_n;
    }
  });
  REQUIRE(osc_n > 10);  // the contact phase [1, 1.67] holds many steps of 1/60

  const nsb::StudySpec spec = nsb::parse_study_text(bouncing_bar_errors_study(force_scale), "f.toml", false);
  std::vector<nsb::Json> results;
  const auto tables = run_all(spec, &results);
  REQUIRE(results.size() == 4);  // lumped: moreau-jean, cd-lagrange; consistent: the same
  const nsb::Json& v = results[0]["values"];
  CHECK(results[0]["steps"].get<long>() == r.steps);
  CHECK(v[0].get<double>() == u_max);  // bit for bit: the same sums in the same order
  CHECK(v[1].get<double>() == std::sqrt(u_sq / r.t_final));
  CHECK(v[2].get<double>() == std::sqrt(osc_sq / static_cast<double>(osc_n)));
  CHECK(v[2].get<double>() > 0.0);
  // CD-Lagrange declines the consistent mass: what was asked kept, its measured cells empty text.
  const nsb::Table& runs = table_ending(tables, "runs");
  REQUIRE(runs.rows.size() == 4);
  const auto& declined = runs.rows[3];
  CHECK(std::get<std::string>(declined[1]) == "cd-lagrange");
  CHECK_THAT(std::get<std::string>(declined[4]), Catch::StartsWith("n/a"));
  CHECK(std::get<std::string>(declined[2]).empty());
  CHECK(std::get<std::string>(declined[3]).empty());
  CHECK(std::get<long>(runs.rows[0][2]) == r.steps);
  // Before the first impact (t <= 0.5) no step lies inside a contact phase: no value, shown as
  // the column's missing text "" where it says one, n/a where not.
  CHECK(std::get<std::string>(runs.rows[0][5]).empty());
  CHECK(std::holds_alternative<std::monostate>(runs.rows[0][6]));
}

TEST_CASE("study file: a fixed error scale, the rms norms, inside and declined = \"empty\": bad input named",
          "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const std::string text = bouncing_bar_errors_study(300.0);
  CHECK(study_error_of(text) == "(no error)");
  CHECK_THAT(study_error_of(replaced(text, "scale = 5.0", "scale = 0")),
             StartsWith("f.toml:25: measure[0].scale: 0 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(replaced(text, "scale = 5.0", "scale = \"g0\"")),
             StartsWith("f.toml:25: measure[0].scale: expected a number, got a string"));
  CHECK_THAT(study_error_of(replaced(text, "scale = 5.0", "scale = 5.0\nrelative_to = \"run\"")),
             StartsWith("f.toml:25: measure[0].scale: a fixed scale and relative_to both say what the error is relative to; valid: one of them"));
  CHECK_THAT(study_error_of(replaced(text, "norm = \"rms\"", "norm = \"rmss\"")),
             StartsWith("f.toml:32: measure[1].norm: 'rmss' is not valid (nearest: ") && Catch::Contains("valid: final, max, l2, rms, step rms"));
  CHECK_THAT(study_error_of(replaced(text, "inside = \"contact_force_exact\"", "inside = \"force\"")),
             StartsWith("f.toml:40: measure[2].inside: 'force' is not an observable of problem 'lumped'; valid: u_contact, "));
  CHECK_THAT(study_error_of(replaced(text, "inside = \"contact_force_exact\"", "inside = 1")),
             StartsWith("f.toml:40: measure[2].inside: expected a string, got an integer"));
  CHECK_THAT(study_error_of(replaced(text, "missing = \"\"", "missing = 0")),
             StartsWith("f.toml:56: table[0].columns[5].missing: expected a string, got an integer"));
  const std::string history = replaced(replaced(text, "declined = \"empty\"", "rows = \"history\""), "\"steps\", \"u max\", \"status\", { of = \"force early\", missing = \"\" }, \"force early\"",
                                        "{ of = \"t\", missing = \"\" }");
  CHECK_THAT(study_error_of(history),
             StartsWith("f.toml:56: table[0].columns[2].missing: only a table of one row per run shows its missing cells otherwise; valid: rows = \"case\""));
  CHECK_THAT(study_error_of(replaced(text, "declined = \"empty\"", "declined = \"blank\"")),
             StartsWith("f.toml:55: table[0].declined: 'blank' is not valid (nearest: ") && Catch::Contains("valid: as run, n/a, empty"));
}

namespace {

// The nondimensional Signorini bar (N = 20, contact on [0, 2], force level 1) to t = 3, one
// scheme at 0.9 stable step: the contact node's displacement error in L2 over time, the
// contact force's chatter and zero steps inside the exact contact, and the contact duration.
std::string bar_contact_study(const std::string& integrator) {
  return quick_study("3.0") + fmt::format(R"(
[[problem]]
name = "signorini-bar"
label = "bar"
parameters = {{ mass = "lumped", N = 20 }}
stable_steps = [0.9]
[[integrator]]
name = "{}"
[[measure]]
kind = "error"
observable = "u_contact"
against = "u_contact_exact"
scale = 1.0
norm = "l2 in time"
label = "u L2"
[[measure]]
kind = "chatter"
observable = "contact_force"
inside = "contact_force_exact"
label = "chatter"
[[measure]]
kind = "zero-steps"
observable = "contact_force"
inside = "contact_force_exact"
label = "lost"
[[measure]]
kind = "contact-duration"
exact = true
label = "duration err"
[[measure]]
kind = "contact-duration"
label = "duration"
)",
                                          integrator);
}

}  // namespace

// The known answer: the bar study's formulas, by hand on one run: sqrt(sum dt (u_0 -
// u_0,exact)^2); over the steps whose t - dt and t + dt lie inside the exact contact (0, 2) the
// force F_k = Lambda_k / dt, the RMS of (F_{k+1} - 2 F_k + F_{k-1}) / 4 and the count of
// F_k = 0; and (t_last - t_first + dt) - 2 over the steps with an impulse.
TEST_CASE("study file: l2 in time, chatter, zero steps and contact duration against the bar study's formulas",
          "[studies][study_file]") {
  for (const char* scheme : {"moreau-jean", "schatzman-paoli"}) {
    INFO(scheme);
    const auto problem = nsb::make_problem("signorini-bar", {{"mass", "lumped"}, {"N", "20"}});
    const auto& bar = dynamic_cast<const nsb::SignoriniBar&>(*problem);
    auto integrator = nsb::make_integrator(scheme);
    REQUIRE_FALSE(nsb::init_or_decline(*integrator, *problem));
    nsb::RunOptions options;
    options.dt = 0.9 * problem->stable_step();
    options.t_end = 3.0;
    options.record_series = false;
    double u_sq = 0.0, first = NAN, last = NAN;
    std::vector<double> force;
    nsb::run(*problem, *integrator, options, [&](const nsb::Integrator& it, const nsb::StepInfo& info) {
      const double t = it.state().t, lambda = it.impulses()[0];
      const double du = it.state().u[0] - bar.exact_displacement(0.0, t);
      u_sq += info.dt * du * du;
      if (lambda > 0.0) {
        if (std::isnan(first)) first = t;
        last = t;
      }
      if (t - info.dt > 0.0 && t + info.dt < 2.0) force.push_back(lambda / info.dt);
    });
    double chatter_sq = 0.0;
    long zeros = 0;
    for (std::size_t k = 0; k < force.size(); ++k) {
      zeros += force[k] == 0.0;
      if (k > 0 && k + 1 < force.size()) {
        const double d2 = 0.25 * (force[k + 1] - 2.0 * force[k] + force[k - 1]);
        chatter_sq += d2 * d2;
      }
    }
    REQUIRE(force.size() > 30);
    const nsb::StudySpec spec = nsb::parse_study_text(bar_contact_study(scheme), "f.toml", false);
    std::vector<nsb::Json> results;
    run_all(spec, &results);
    REQUIRE(results.size() == 1);
    const nsb::Json& v = results[0]["values"];
    CHECK(v[0].get<double>() == std::sqrt(u_sq));  // bit for bit: the same sums in the same order
    CHECK(v[1].get<double>() == std::sqrt(chatter_sq / static_cast<double>(force.size() - 2)));
    CHECK(v[2].get<double>() == static_cast<double>(zeros));
    CHECK(v[3].get<double>() == std::abs(last - first + options.dt - 2.0));
    CHECK(v[4].get<double>() == last - first + options.dt);
    CHECK(v[4].get<double>() == Approx(2.0).margin(2.0 * options.dt));
  }
}

TEST_CASE("study file: chatter, zero-steps, contact-duration and the l2 in time norm: bad input named",
          "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const std::string text = bar_contact_study("moreau-jean");
  CHECK(study_error_of(text) == "(no error)");
  CHECK_THAT(study_error_of(replaced(text, "norm = \"l2 in time\"", "norm = \"l2 time\"")),
             StartsWith("f.toml:19: measure[0].norm: 'l2 time' is not valid (nearest: ") &&
                 Catch::Contains("valid: final, max, l2, rms, step rms, l2 in time"));
  CHECK_THAT(study_error_of(replaced(text, "kind = \"chatter\"\nobservable = \"contact_force\"", "kind = \"chatter\"")),
             StartsWith("f.toml:21: measure[1]: missing key 'observable'"));
  CHECK_THAT(study_error_of(replaced(text, "kind = \"chatter\"\nobservable = \"contact_force\"", "kind = \"chatter\"\nobservable = \"force\"")),
             StartsWith("f.toml:23: measure[1].observable: 'force' is not an observable of problem 'bar'; valid: u_contact, "));
  CHECK_THAT(study_error_of(replaced(text, "kind = \"zero-steps\"\nobservable = \"contact_force\"\ninside = \"contact_force_exact\"",
                                     "kind = \"zero-steps\"\nobservable = \"contact_force\"\ninside = \"gap\"")),
             StartsWith("f.toml:29: measure[2].inside: 'gap' is not an observable of problem 'bar'; valid: u_contact, "));
  CHECK_THAT(study_error_of(replaced(text, "label = \"chatter\"", "label = \"chatter\"\nscale = -1")),
             StartsWith("f.toml:26: measure[1].scale: -1 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(study_error_of(replaced(text, "label = \"lost\"", "label = \"lost\"\nwindow = [0.0, 1.0]")),
             StartsWith("f.toml:31: measure[2].window: unknown key") && Catch::Contains("valid: observable, scale, inside, kind, label, problems"));
  CHECK_THAT(study_error_of(replaced(text, "exact = true", "exact = 1")),
             StartsWith("f.toml:33: measure[3].exact: expected a boolean, got an integer"));
  CHECK_THAT(study_error_of(replaced(text, "exact = true", "exact = true\nobservable = \"u_contact\"")),
             StartsWith("f.toml:34: measure[3].observable: unknown key") && Catch::Contains("valid: exact, kind, label, problems"));
  // The bouncing mass knows its impacts, no contact duration: exact = true names it.
  const std::string mass = quick_study("1.0") + R"(
[[problem]]
name = "bouncing-mass"
[[integrator]]
name = "moreau-jean"
steps = [1e-3]
[[measure]]
kind = "contact-duration"
exact = true
)";
  CHECK_THAT(study_error_of(mass),
             StartsWith("f.toml:14: measure[0].exact: problem 'bouncing-mass' knows no exact contact duration; valid: problems that know it"));
}

// The features the built-in study reference needs (studies/builtin/reference.toml): a tolerance
// sweep that sets atol = rtol / 100, impact times the integrator locates itself, a run's own
// error estimate against the next run of its sweep (plain and under an error law x^q), the rate
// against the next run, the solver's own steps and Jacobians, a sum of work counters, and a
// table of some integrators' runs. The bouncing mass (e = 0.9, h0 = 1) to t = 1 s has one
// exact impact, at 0.4515 s.
TEST_CASE("study file: tolerance divisors, located impacts, next-run estimates and rates, solver counts, counter sums",
          "[studies][study_file]") {
  const std::string text = R"([study]
title = "t"
t_end = 1.0
cpu_repeats = 0
figures = "declared"
counters = ["root_evaluations", "events + switches"]

[[problem]]
name = "bouncing-mass"
parameters = { e = 0.9 }

[[integrator]]
name = "event-driven"
label = "ed"
tolerances = [1e-4, 1e-6]
tolerance_divisors = { atol = 100 }
dt = 1e-2

[[integrator]]
name = "cd-lagrange"
steps = [1e-2, 1e-3]

[[measure]]
kind = "impact-time"
label = "t located"
located = true

[[measure]]
kind = "estimate"
label = "est"
observable = "q"

[[measure]]
kind = "estimate"
label = "est law"
observable = "q"
order = 1

[[measure]]
kind = "error"
label = "err"
observable = "q"
against = "q_exact"
scale = 1.0

[[table]]
id = "runs"
title = "runs"
integrators = ["ed"]
columns = ["integrator", "tol", "t located", "est", "est law", "rate of err", "solver steps", "Jacobians", "root_evaluations",
           "events + switches", "err"]
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "r.toml", false);
  const auto cases = nsb::study_cases(nsb::file_study(spec), {});
  REQUIRE(cases.size() == 4);
  CHECK(nsb::file_case_parameters(spec, cases[0]) == std::map<std::string, std::string>{{"rtol", "0.0001"}, {"atol", "1e-06"}});
  CHECK(nsb::file_case_parameters(spec, cases[1]) == std::map<std::string, std::string>{{"rtol", "1e-06"}, {"atol", "1e-08"}});
  CHECK(nsb::file_case_parameters(spec, cases[2]).empty());
  std::vector<nsb::Json> results;
  const auto tables = run_all(spec, &results);
  REQUIRE(tables.size() == 1);
  const nsb::Table& t = tables[0];
  REQUIRE(t.rows.size() == 2);  // the ed runs alone
  const auto cell = [&](std::size_t row, std::size_t col) { return std::get<double>(t.rows[row][col]); };
  // The located impact: the event-driven reference finds it to its tolerance; cd-lagrange locates none (n/a).
  CHECK(cell(0, 2) < 1e-5);
  CHECK(cell(1, 2) < cell(0, 2));
  CHECK(results[2]["values"][0].is_null());
  // The estimate: max |q(1e-4) - q(1e-6)| over the 100 samples; under the law x^1 divided by 1 - 1e-2.
  const auto a = results[0]["samples"]["1"].get<std::vector<double>>(), b = results[1]["samples"]["1"].get<std::vector<double>>();
  REQUIRE(a.size() == 100);
  REQUIRE(b.size() == 100);
  double d = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) d = std::max(d, std::abs(a[k] - b[k]));
  CHECK(d > 0.0);
  CHECK(cell(0, 3) == d);
  CHECK(cell(0, 4) == d / (1.0 - 1e-2));
  // The rate of err against the next run, in 1/tol: log(e / e') / log(tol' / tol).
  CHECK(cell(0, 5) == Approx(std::log(cell(0, 10) / cell(1, 10)) / std::log(1e-6 / 1e-4)).epsilon(1e-12));
  // The last run of its sweep has no next run.
  for (std::size_t col : {3, 4, 5}) CHECK(std::holds_alternative<std::monostate>(t.rows[1][col]));
  // CVODE's own steps (not the 100 output steps), its Jacobians, roots, and the one impact as events.
  CHECK(std::get<long>(t.rows[0][6]) > 0);
  CHECK(std::get<long>(t.rows[0][6]) != 100);
  CHECK(std::get<long>(t.rows[0][7]) >= 0);
  CHECK(cell(0, 8) > 0.0);
  CHECK(cell(0, 9) == 1.0);
  // A shard's run read back (--merge): its estimate samples an array of numbers per estimate measure.
  CHECK(nsb::file_result_damage(spec, results[0]).empty());
  nsb::Json damaged = results[0];
  damaged["samples"]["2"] = "x";
  CHECK(nsb::file_result_damage(spec, damaged) == "samples has no array of numbers for measure 2");
  damaged["samples"] = nsb::Json::array();
  CHECK(nsb::file_result_damage(spec, damaged) == "samples is not a table");

  CHECK_THAT(study_error_of(replaced(kMinimal, "steps = [1e-2, 5e-3]", "steps = [1e-2, 5e-3]\ntolerance_divisors = { atol = 100 }")),
             Catch::StartsWith("f.toml:12: integrator[0].tolerance_divisors: divisors of a tolerance without a tolerance sweep"));
  CHECK_THAT(study_error_of(replaced(text, "order = 1", "order = 0")),
             Catch::StartsWith("f.toml:37: measure[2].order: 0 is no order of an error law x^q"));
  CHECK_THAT(study_error_of(replaced(text, "integrators = [\"ed\"]", "integrators = [\"ef\"]")),
             Catch::StartsWith("f.toml:49: table[0].integrators[0]: 'ef' is not valid (nearest: ed); valid: ed, cd-lagrange"));
  CHECK_THAT(study_error_of(replaced(text, "atol = 100", "atol = 1e-300")),
             Catch::StartsWith("f.toml:16: integrator[0].tolerance_divisors.atol: tolerance 0.0001 / 1e-300: parameter 'atol' = 1e+296 is outside its valid range (0, 1]; valid: (0, 1]"));
}

// The note of a group table (rows = "group", column "note"; the hausdorff study's orders): why a
// group's fits may be n/a. Known answers: a scheme that declines the problem (newmark-lm declines
// the spring chain's wall contact) "declined"; one whose second run exceeds the budget (150
// F_int evaluations: 100 steps of 1e-2 s to 1 s fit, 200 of 5e-3 s do not) "over budget"; one
// whose runs are all ok, nothing. Opt-in: a group table without it has no such column.
TEST_CASE("study file: a group table's note says declined, or the status of the group's first run that failed",
          "[studies][study_file]") {
  using Catch::StartsWith;
  const std::string text = quick_study("1.0", "max_force_evaluations = 150\n") + R"(
[[problem]]
name = "spring-chain"
parameters = { n = 3, wall = "left" }

[[integrator]]
name = "cd-lagrange"
steps = [1e-2, 5e-3]

[[integrator]]
name = "newmark-lm"
steps = [1e-2, 5e-3]

[[integrator]]
name = "moreau-jean"
steps = [2e-2, 1e-2]

[reference]
integrator = "modal-exact"
lockstep = true

[[measure]]
kind = "error"

[[table]]
id = "runs"
title = "Runs"
columns = ["problem", "integrator", "dt", "status"]

[[table]]
id = "fits"
title = "Orders"
rows = "group"
columns = ["problem", "integrator", "order of err u max", { of = "note", header = "why" }]
)";
  const auto tables = run_all(nsb::parse_study_text(text, "f.toml", false));
  REQUIRE(tables.size() == 2);
  const nsb::Table& runs = tables[0];
  REQUIRE(runs.rows.size() == 6);
  CHECK(std::get<std::string>(runs.rows[0][3]) == "ok");
  CHECK(std::get<std::string>(runs.rows[1][3]).rfind("over budget", 0) == 0);
  CHECK(std::get<std::string>(runs.rows[2][3]).rfind("n/a: ", 0) == 0);
  const nsb::Table& fits = tables[1];
  REQUIRE(fits.columns.size() == 4);
  CHECK(fits.columns[3].name == "why");
  CHECK(fits.columns[3].description == "declined (n/a), or the status of the group's first run that failed");
  REQUIRE(fits.rows.size() == 3);
  CHECK(std::get<std::string>(fits.rows[0][1]) == "cd-lagrange");
  CHECK(std::get<std::string>(fits.rows[0][3]) == "over budget");
  CHECK(std::get<std::string>(fits.rows[1][1]) == "newmark-lm");
  CHECK(std::get<std::string>(fits.rows[1][3]) == "declined");
  CHECK(std::get<std::string>(fits.rows[2][1]) == "moreau-jean");
  CHECK(std::get<std::string>(fits.rows[2][3]).empty());
  CHECK(std::get<double>(fits.rows[2][2]) > 0.0);
  // Bad input: one line naming file, line, key and what is valid (note among a group's columns,
  // not one of a ranking's or a history's).
  CHECK_THAT(study_error_of(replaced(text, "{ of = \"note\", header = \"why\" }", "\"notes\"")),
             StartsWith("f.toml:40: table[1].columns[3]: 'notes' is not valid (nearest: note); valid: problem, integrator, "
                        "order of err u max, CI low of err u max, CI high of err u max, points of err u max, note"));
  CHECK_THAT(study_error_of(replaced(text, "rows = \"group\"\ncolumns = [\"problem\", \"integrator\", \"order of err u max\", "
                                           "{ of = \"note\", header = \"why\" }]",
                                     "rows = \"history\"\ncolumns = [\"note\"]")),
             StartsWith("f.toml:40: table[1].columns[0]: 'note' is not valid"));
}

// t_end_exact's wave_time (L / c of a bar: the bouncing bar's period is 16 of them) and its
// contact_start (with gravity the fall's end t1): the hausdorff study's horizon t1 + 16 L / c.
TEST_CASE("study file: t_end_exact = { contact_start, wave_time } on the bouncing bar; wave_time elsewhere refused",
          "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const std::string text = quick_study("1.0") + R"(
[[problem]]
name = "bouncing-bar"
parameters = { N = 20 }
t_end_exact = { contact_start = 1.0, wave_time = 16.0 }
stable_steps = [0.9]

[[integrator]]
name = "cd-lagrange"

[reference]
solution = "exact"

[[measure]]
kind = "error"
observable = "v_contact"
)";
  const nsb::StudySpec spec = nsb::parse_study_text(text, "f.toml", false);
  CHECK(spec.problems[0].t_end == 1.0 + 16.0 * (10.0 / 30.0));  // DEP: t1 = 1, L / c = 1/3
  CHECK_THAT(study_error_of(replaced(replaced(text, "name = \"bouncing-bar\"\nparameters = { N = 20 }", "name = \"bouncing-mass\""),
                                     "observable = \"v_contact\"", "observable = \"v\"")),
             StartsWith("f.toml:9: problem[0].t_end_exact.contact_start: problem 'bouncing-mass' has no exact time or value "
                        "'contact_start'; valid: impact_1 .. impact_"));
  CHECK_THAT(study_error_of(replaced(text, "parameters = { N = 20 }", "parameters = { N = 20, stiff_ratio = 2 }")),
             StartsWith("f.toml:10: problem[0].t_end_exact.contact_start: problem 'bouncing-bar' has no exact time or value "
                        "'contact_start'; valid: contact_duration, plus"));
  CHECK_THAT(study_error_of(replaced(text, "contact_start = 1.0, wave_time = 16.0", "contact_start = 1.0, wave_tim = 16.0")),
             StartsWith("f.toml:10: problem[0].t_end_exact.wave_tim: problem 'bouncing-bar' has no exact time or value 'wave_tim'; "
                        "valid: contact_start, contact_duration, wave_time, plus"));
}

// Issue 56, finding 14: a plugin problem whose stable_step() is NaN in a study of fixed steps:
// the scheme that caps its steps by it is recorded as declined with the reason, the others
// run, and the study completes (exit 0).
TEST_CASE("nsbench-study: a problem whose stable step is NaN declines the scheme that reads it, the study goes on",
          "[studies][study_file][contract]") {
  const nsb::test::TempDir dir("study_file_nan_stable", true);
  const fs::path file = dir.path / "nan_stable.toml";
  std::ofstream(file) << R"([study]
title = "a plugin problem whose stable step is NaN"
t_end = 0.6

[[problem]]
name = "nan-stable-mass"

[[integrator]]
name = "cd-lagrange"
steps = [1e-2]

[[integrator]]
name = "cd-lagrange-adaptive"
steps = [1e-2]

[reference]
integrator = "cd-lagrange"
dt = 1e-3

[[measure]]
kind = "penetration"
)";
  const auto r = nsb::test::run_command(fmt::format("NSBENCH_JOBS=1 '{}' run '{}' --plugin '{}' --out '{}'", NSBENCH_STUDY_CLI, file.string(),
                                                    nsb::test::test_plugin("nan_stable_step"), (dir.path / "out").string()));
  INFO(r.output);
  REQUIRE(r.code == 0);
  const std::string table = nsb::test::read_text(dir.path / "out" / "nan_stable_work_precision.md");
  CHECK_THAT(table, Catch::Contains("| nan-stable-mass | cd-lagrange | 1.00e-02 |"));
  CHECK_THAT(table, Catch::Contains("problem nan-stable-mass reports the stable step nan, which caps its steps"));
}
