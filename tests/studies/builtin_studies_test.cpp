// The built-in study files (studies/builtin/): each parses, and its case list is the one of the C++
// study it replaced. Checked against the C++ study (the same list, default and --full) before
// the C++ was deleted; now against what stays: the C++ study's recorded sweep sizes, and some of
// each study's runs made here against the committed reports' rows. Those reports are one run of
// the landed code (scripts/report_revisions.py, the report_revisions test, fails otherwise),
// so these are partial --verify checks of what this build writes; the peers' rows are left out
// (their own libraries round differently from machine to machine).
#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

#include "integrators/registry.hpp"
#include "problems/bouncing_bar.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/exact_solution.hpp"
#include "problems/registry.hpp"
#include "studies/hausdorff.hpp"
#include "studies/registry.hpp"
#include "studies/study_file.hpp"
#include "studies/table.hpp"
#include "studies/verify.hpp"

namespace {

using CaseKey = std::tuple<std::string, std::string, double>;  // problem label, integrator, dt

nsb::StudySpec builtin_spec(const std::string& path) {
  const nsb::EmbeddedStudyFile* file = nsb::builtin_study_file(path);
  REQUIRE(file != nullptr);
  return nsb::parse_study_text(std::string(file->text), path, false);
}

std::vector<CaseKey> file_case_keys(const nsb::StudySpec& spec, bool full) {
  std::vector<CaseKey> keys;
  for (const auto& c : nsb::study_cases(nsb::file_study(spec), {full})) {
    CHECK(c["tol"].is_null());
    keys.emplace_back(spec.problems[c["problem"].get<std::size_t>()].label, spec.integrators[c["integrator"].get<std::size_t>()].name,
                      c["dt"].get<double>());
  }
  return keys;
}

bool registered(const std::string& integrator) {
  for (const auto& e : nsb::integrator_registry())
    if (e.name == integrator) return true;
  return false;
}

// Registered and computed by nsbench itself: a peer's rows come from its own library (Siconos'
// OpenBLAS kernels round differently from machine to machine, the one documented exception to
// bit-identical results), so tests compare them against a committed report to no round-off.
bool ours(const std::string& integrator) {
  for (const auto& e : nsb::integrator_registry())
    if (e.name == integrator) return !e.peer;
  return false;
}

// The (problem, integrator, dt) of each row of a committed report, of the integrators this
// build has (the peers are optional).
std::vector<CaseKey> report_rows(const std::string& id) {
  std::ifstream in(std::filesystem::path(NSBENCH_SOURCE_DIR) / "reports" / (id + ".csv"));
  std::stringstream text;
  text << in.rdbuf();
  const auto records = nsb::parse_csv(text.str());
  REQUIRE(records.size() > 1);
  CHECK(records[0][0] == "problem");
  CHECK(records[0][1] == "integrator");
  CHECK(records[0][2] == "dt [s]");
  std::vector<CaseKey> rows;
  for (std::size_t r = 1; r < records.size(); ++r)
    if (registered(records[r][1])) rows.emplace_back(records[r][0], records[r][1], std::stod(records[r][2]));
  return rows;
}

}  // namespace

TEST_CASE("builtin precision.toml: the cases of the committed report; --full the C++ study's longer sweeps", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/precision.toml");
  const auto rows = report_rows("work_precision");
  // The file's cases of the integrators the report holds (this test binary registers test
  // integrators of its own, which integrators = "all" includes).
  std::vector<CaseKey> cases;
  for (const auto& c : file_case_keys(spec, false))
    if (std::any_of(rows.begin(), rows.end(), [&](const CaseKey& r) { return std::get<1>(r) == std::get<1>(c); })) cases.push_back(c);
  REQUIRE(cases.size() == rows.size());
  for (std::size_t k = 0; k < cases.size(); ++k) {
    INFO("case " << k << ": " << std::get<0>(cases[k]) << ", " << std::get<1>(cases[k]) << ", dt " << std::get<2>(cases[k]));
    CHECK(cases[k] == rows[k]);
  }
  // --full: the C++ study's 9, 8 and 8 steps per integrator, each sweep the default one continued.
  const auto full = file_case_keys(spec, true);
  CHECK(full.size() == 25 * nsb::integrator_registry().size());
  const std::vector<std::size_t> sizes{9, 8, 8};
  for (std::size_t p = 0; p < spec.problems.size(); ++p) {
    const auto& sweep = spec.integrators.front().sweep_for(spec.problems[p].label);
    CHECK(sweep.full_steps.size() == sizes[p]);
    CHECK(std::equal(sweep.steps.begin(), sweep.steps.end(), sweep.full_steps.begin()));
  }
}

// hard.toml says what the hard study promises: each case (a [[problem]], in its order) run by
// every registered integrator, in the registry's order, at the case's own step; the 10^4
// impacts with --full only. Its reports verify at --rtol 0 against those of the C++ study it
// replaced (studies/hard_cases.cpp, whose case list this file's equalled before it was deleted:
// commit 85de2c9): nsbench-study hard --verify reports --rtol 0.
TEST_CASE("built-in study hard: every case run by every registered integrator at its own step; 10^4 impacts with --full only",
          "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/hard.toml");
  const auto& registry = nsb::integrator_registry();
  REQUIRE(spec.problems.size() == 18);
  REQUIRE(spec.integrators.size() == registry.size());
  const auto& hard = *std::find_if(nsb::study_registry().begin(), nsb::study_registry().end(),
                                   [](const nsb::StudyEntry& e) { return e.name == "hard"; });
  CHECK(hard.source == "studies/builtin/hard.toml");
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto cases = nsb::study_cases(hard, {full});
    REQUIRE(cases.size() == (full ? 18 : 17) * registry.size());
    std::size_t k = 0;
    for (std::size_t p = 0; p < spec.problems.size(); ++p) {
      if (spec.problems[p].full_only && !full) continue;
      const auto own = nsb::make_problem(spec.problems[p].name, spec.problems[p].parameters)->stable_step();
      for (std::size_t i = 0; i < registry.size(); ++i, ++k) {
        CHECK(cases[k]["problem"] == p);
        CHECK(spec.integrators[cases[k]["integrator"].get<std::size_t>()].name == registry[i].name);
        const nsb::FileSweep& sweep = spec.integrators[i].sweep_for(spec.problems[p].label);
        REQUIRE(sweep.steps.size() + sweep.stable_fractions.size() == 1);  // one run per case
        const double dt = sweep.steps.empty() ? sweep.stable_fractions[0] * own : sweep.steps[0];
        CHECK(cases[k]["dt"].get<double>() == dt);
      }
    }
  }
  // Only the 10^4 impacts is --full only.
  CHECK(std::count_if(spec.problems.begin(), spec.problems.end(), [](const nsb::FileProblem& p) { return p.full_only; }) == 1);
  CHECK(spec.problems[2].label == "10^4 impacts, e = 1");
  CHECK(spec.problems[2].full_only);
}

// energy.toml's cases are those of the C++ study it replaced (studies/energy.cpp, whose case list
// this file's equalled, default and --full, before it was deleted: commit dd90fe1): per problem
// in its order, every registered integrator in the registry's order at its defaults but
// cd-lagrange-adaptive, in its place in its four variants; the problems' parameters, steps and
// end times below are the C++ study's (kProblems). The energy-target case (bouncing mass,
// e = 0.9) ends at its exact 11th impact (end_at_impact). Its reports verify at --rtol 0 against
// the C++ study's but for its declined rows' table: nsbench-study energy --verify reports --rtol 0.
TEST_CASE("built-in study energy: energy.toml's cases are the C++ study's, default and --full", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/energy.toml");
  const auto& energy = *std::find_if(nsb::study_registry().begin(), nsb::study_registry().end(),
                                     [](const nsb::StudyEntry& e) { return e.name == "energy"; });
  CHECK(energy.source == "studies/builtin/energy.toml");
  struct Expected {
    std::map<std::string, std::string> parameters;
    double dt, t_end;
  };
  const double target_end = nsb::make_problem("bouncing-mass", {{"e", "0.9"}})->exact()->impact_times(1e9).at(10);
  const std::vector<Expected> problems = {{{{"e", "1"}}, 1e-3, 904.0},
                                          {{{"wall", "both"}, {"gap", "0.5"}}, 0.02, 40.0},
                                          {{{"e", "0.9"}}, 1e-3, target_end},
                                          {{{"g", "0.25"}, {"mass", "lumped"}, {"N", "50"}}, 0.01, 210.0},
                                          {{{"g", "0.25"}, {"mass", "singular"}, {"N", "50"}}, 0.01, 210.0}};
  const std::vector<Expected> full = {{{{"e", "1"}}, 1e-3, 9031.0},
                                      {{{"wall", "both"}, {"gap", "0.5"}}, 0.02, 400.0},
                                      {{{"e", "0.9"}}, 1e-3, target_end},
                                      {{{"g", "0.25"}, {"mass", "lumped"}, {"N", "100"}}, 0.005, 2100.0},
                                      {{{"g", "0.25"}, {"mass", "singular"}, {"N", "100"}}, 0.005, 2100.0}};
  const std::vector<std::map<std::string, std::string>> variants = {{{"momentum", "variational"}, {"energy_target", "impact-law"}},
                                                                    {{"momentum", "variational"}, {"energy_target", "no-work"}},
                                                                    {{"momentum", "talk"}, {"energy_target", "impact-law"}},
                                                                    {{"momentum", "talk"}, {"energy_target", "no-work"}}};
  for (const bool is_full : {false, true}) {
    INFO("full " << is_full);
    const auto cases = nsb::study_cases(energy, {is_full});
    std::size_t k = 0;
    for (const Expected& want : is_full ? full : problems)
      for (const auto& entry : nsb::integrator_registry()) {
        const bool adaptive = entry.name == "cd-lagrange-adaptive";
        for (const auto& variant : adaptive ? variants : std::vector<std::map<std::string, std::string>>{{}}) {
          REQUIRE(k < cases.size());
          INFO("case " << k << ": " << cases[k].dump());
          const nsb::FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
          const nsb::FileIntegrator& it = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
          CHECK(p.parameters == want.parameters);
          CHECK(it.name == entry.name);
          CHECK(it.sweep_for(p.label).parameters == variant);
          CHECK(cases[k]["dt"].get<double>() == want.dt);
          CHECK((cases[k].contains("t_end") ? cases[k]["t_end"].get<double>() : spec.t_end_of(p)) == want.t_end);
          ++k;
        }
      }
    CHECK(k == cases.size());
  }
}

namespace {

// The cases of the C++ study bouncing-bar (studies/bouncing_bar.cpp, deleted once
// bouncing-bar.toml's case list equalled it, default and --full): every registered integrator x
// mass lumped | consistent | singular x (N, alpha): default N in {50, 100, 200, 400} at alpha =
// 0.9 then N = 100 at alpha = 0.5, --full N in {50, ..., 800} x alpha in {0.25, 0.5, 0.9};
// peers at N <= 50 and references at alpha = 0.9 and N <= 100 in the default grid, references at
// alpha = 0.9 under --full; K = 20 periods (--full: 50).
struct BouncingBarCase {
  std::string integrator, mass;
  long N;
  double alpha;
  int periods;
};

std::vector<BouncingBarCase> cpp_bouncing_bar_cases(bool full) {
  std::vector<std::pair<long, double>> grid;
  if (full) {
    for (long N : {50, 100, 200, 400, 800})
      for (double alpha : {0.25, 0.5, 0.9}) grid.emplace_back(N, alpha);
  } else {
    for (long N : {50, 100, 200, 400}) grid.emplace_back(N, 0.9);
    grid.emplace_back(100, 0.5);
  }
  std::vector<BouncingBarCase> cases;
  for (const auto& entry : nsb::integrator_registry())
    for (const char* mass : {"lumped", "consistent", "singular"})
      for (const auto& [N, alpha] : grid)
        if ((!entry.reference && (!entry.peer || full || N <= 50)) || (entry.reference && alpha == 0.9 && (full || N <= 100)))
          cases.push_back({entry.name, mass, N, alpha, full ? 50 : 20});
  return cases;
}

const nsb::StudyEntry& bouncing_bar_entry() {
  const auto& registry = nsb::study_registry();
  const auto entry = std::find_if(registry.begin(), registry.end(), [](const nsb::StudyEntry& e) { return e.name == "bouncing-bar"; });
  REQUIRE(entry != registry.end());
  return *entry;
}

std::vector<std::vector<std::string>> report_csv(const std::string& id) {
  std::ifstream in(std::filesystem::path(NSBENCH_SOURCE_DIR) / "reports" / (id + ".csv"));
  std::stringstream text;
  text << in.rdbuf();
  auto records = nsb::parse_csv(text.str());
  REQUIRE(records.size() > 1);
  return records;
}

}  // namespace

// bouncing-bar.toml's runs are the C++ study's, default and --full: in its order (integrator,
// mass model, N, alpha = dt / stable step), each with its dt, end time t1 + K P and budget of 4
// F_int evaluations per nominal step. A run added, removed or moved fails here.
TEST_CASE("built-in study bouncing-bar: bouncing-bar.toml's cases are the C++ study's, default and --full", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bouncing-bar.toml");
  CHECK(bouncing_bar_entry().source == "studies/builtin/bouncing-bar.toml");
  const nsb::ParamSpecs bar = nsb::find_problem("bouncing-bar").parameters();
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto expected = cpp_bouncing_bar_cases(full);
    const auto cases = nsb::study_cases(bouncing_bar_entry(), {full});
    REQUIRE(cases.size() == expected.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const BouncingBarCase& e = expected[k];
      INFO("case " << k << ": " << e.integrator << " " << e.mass << " N " << e.N << " alpha " << e.alpha);
      const nsb::FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
      const nsb::Params params(bar, p.parameters);
      CHECK(p.name == "bouncing-bar");
      CHECK(spec.integrators[cases[k]["integrator"].get<std::size_t>()].name == e.integrator);
      CHECK(params.choice("mass") == e.mass);
      CHECK(params.integer("N") == e.N);
      CHECK(cases[k]["stable_steps"].get<double>() == e.alpha);
      const auto problem = nsb::make_problem("bouncing-bar", p.parameters);
      const double dt = e.alpha * problem->stable_step();
      CHECK(cases[k]["dt"].get<double>() == dt);
      const nsb::BouncingBarExact fall(params, 0.0);
      const double t_end = fall.impact_time() + e.periods * (16.0 * fall.wave_time());
      CHECK(spec.t_end_of(p, full) == t_end);
      CHECK(spec.budget_of(p, dt, t_end) == static_cast<long>(4.0 * t_end / dt));
    }
  }
}

// Its tables against the committed report: cd-lagrange's runs at
// N = 100, alpha = 0.9 (lumped, consistent: declined, singular) and at N = 50 (lumped, consistent)
// as the file measures them: table bouncing_bar's header and rows (every cell but the CPU time,
// and the drift to round-off: the one fit_line sums x / n where the C++ study summed and
// divided), and cd-lagrange's rows of bouncing_bar_dep, bouncing_bar_energy and
// bouncing_bar_trajectory (with the exact rows that follow them) cell for cell.
TEST_CASE("built-in study bouncing-bar: its tables' cd-lagrange rows equal the committed report's", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bouncing-bar.toml");
  const nsb::StudyEntry& entry = bouncing_bar_entry();
  std::vector<nsb::Json> cases, results;
  for (const auto& c : nsb::study_cases(entry, {})) {
    const nsb::Overrides& p = spec.problems[c["problem"].get<std::size_t>()].parameters;
    const bool n50 = p.at("N") == "50" && p.at("mass") != "singular", n100 = p.at("N") == "100";
    if (spec.integrators[c["integrator"].get<std::size_t>()].name == "cd-lagrange" && c["stable_steps"].get<double>() == 0.9 && (n50 || n100)) {
      cases.push_back(c);
      results.push_back(nsb::run_study_case(entry, c, {}));
    }
  }
  REQUIRE(cases.size() == 5);
  const auto tables = nsb::study_tables(entry, cases, results, {});
  const auto fresh_csv = [&](const std::string& id) {
    const auto table = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& t) { return t.id == id; });
    REQUIRE(table != tables.end());
    return nsb::parse_csv(nsb::to_csv(*table));
  };
  const auto report = report_csv("bouncing_bar");
  const auto fresh = fresh_csv("bouncing_bar");
  REQUIRE(fresh.size() == 6);
  CHECK(fresh[0] == report[0]);
  for (std::size_t r = 1; r < fresh.size(); ++r) {
    const auto row = std::find_if(report.begin() + 1, report.end(), [&](const std::vector<std::string>& was) {
      return std::equal(was.begin(), was.begin() + 4, fresh[r].begin());
    });
    REQUIRE(row != report.end());
    REQUIRE(row->size() == fresh[r].size());
    for (std::size_t c = 0; c < row->size(); ++c) {
      INFO("row " << r << ", column " << report[0][c]);
      if (report[0][c] == "CPU [s]") continue;
      if (report[0][c] == "drift [1/period]" && !(*row)[c].empty())
        CHECK(std::stod(fresh[r][c]) == Catch::Detail::Approx(std::stod((*row)[c])).epsilon(1e-15));
      else
        CHECK(fresh[r][c] == (*row)[c]);
    }
  }
  // The other tables: the report's rows of cd-lagrange (and the exact rows after them: the
  // first run of each mass in the report is cd-lagrange's but for the consistent mass it
  // declines) in their order.
  for (const char* id : {"bouncing_bar_dep", "bouncing_bar_energy", "bouncing_bar_trajectory"}) {
    INFO(id);
    const auto was = report_csv(id);
    std::vector<std::vector<std::string>> expected = {was[0]};
    for (std::size_t r = 1; r < was.size(); ++r)
      if (was[r][0] == "cd-lagrange" || (was[r][0] == "exact" && was[r][1] != "consistent")) expected.push_back(was[r]);
    const auto now = fresh_csv(id);
    CHECK(expected.size() == (std::string(id) == "bouncing_bar_dep" ? 2u : std::string(id) == "bouncing_bar_energy" ? 41u : 1605u));
    CHECK(now == expected);
  }
}

// reference.toml's runs are those of the C++ study it replaced (studies/reference.cpp, whose case
// list this file's equalled, default and --full, before it was deleted: commit ef9a78a), rebuilt
// here as that study built them (kTolerances, kStiffness; atol = rtol / 100 formatted as it did),
// and the rows of the committed reports. Its reports verify at --rtol 0 against the C++ study's:
// nsbench-study reference --verify reports --rtol 0.
TEST_CASE("built-in study reference: reference.toml's runs are the C++ study's and the committed reports' rows", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/reference.toml");
  const auto& registry = nsb::study_registry();
  const auto study = std::find_if(registry.begin(), registry.end(), [](const nsb::StudyEntry& e) { return e.name == "reference"; });
  REQUIRE(study != registry.end());
  CHECK(study->source == "studies/builtin/reference.toml");
  struct Run {
    std::string integrator, label;
    std::map<std::string, std::string> parameters;
    double x;
  };
  const auto text = [](double x) { return fmt::format("{}", x); };
  const std::vector<double> tolerances = {1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10};
  std::vector<Run> expected;
  for (const char* method : {"bdf", "adams"})
    for (double tol : tolerances)
      expected.push_back({"event-driven", fmt::format("event-driven {}", method), {{"method", method}, {"rtol", text(tol)}, {"atol", text(tol / 100)}}, tol});
  for (double tol : tolerances) expected.push_back({"penalty-bdf", "penalty-bdf k=1e10", {{"rtol", text(tol)}, {"atol", text(tol / 100)}}, tol});
  for (double k : {1e6, 1e7, 1e8, 1e9, 1e10})
    expected.push_back({"penalty-bdf", "penalty-bdf", {{"stiffness", text(k)}, {"rtol", "1e-10"}, {"atol", "1e-14"}}, k});
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto cases = nsb::study_cases(*study, {full});
    REQUIRE(cases.size() == expected.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      INFO("case " << k << ": " << expected[k].label << " " << expected[k].x);
      const nsb::FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
      const nsb::FileIntegrator& it = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
      CHECK(p.name == "bouncing-mass");
      CHECK(p.parameters == std::map<std::string, std::string>{{"e", "0.9"}});
      CHECK(spec.t_end_of(p) == 3.0);
      CHECK(it.name == expected[k].integrator);
      CHECK(it.label == expected[k].label);
      CHECK(nsb::file_case_parameters(spec, cases[k]) == expected[k].parameters);
      CHECK(cases[k]["tol"].get<double>() == expected[k].x);
      CHECK(cases[k]["dt"].get<double>() == 1e-3);
    }
  }
  // The committed reports: 24 rows of the tolerance sweeps (integrator, rtol), 5 of the penalty's (k).
  const auto records = [](const std::string& id) {
    std::ifstream in(std::filesystem::path(NSBENCH_SOURCE_DIR) / "reports" / (id + ".csv"));
    std::stringstream csv;
    csv << in.rdbuf();
    return nsb::parse_csv(csv.str());
  };
  const auto tolerance = records("reference_tolerance"), penalty = records("reference_penalty");
  REQUIRE(tolerance.size() == 25);
  REQUIRE(penalty.size() == 6);
  for (std::size_t r = 1; r < tolerance.size(); ++r) {
    CHECK(tolerance[r][0] == expected[r - 1].label);
    CHECK(std::stod(tolerance[r][1]) == expected[r - 1].x);
  }
  for (std::size_t r = 1; r < penalty.size(); ++r) CHECK(std::stod(penalty[r][0]) == expected[24 + r - 1].x);
}

// bouncing.toml's runs are those of the C++ study it replaced (studies/bouncing.cpp, whose case
// list and tables this file's equalled, default and --full, before it was deleted), rebuilt here
// by that study's rule: every registered integrator in the registry's order, then e in {1, 0.9,
// 0.5}, then dt in {1e-2, 1e-3, 1e-4, 1e-5} (and 1e-6 with --full), each to e < 1: the exact
// Zeno time + 0.5 s, e = 1: the 6th exact impact + 0.1 s. A run added, removed or moved fails here.
TEST_CASE("built-in study bouncing: bouncing.toml's runs are the C++ study's, in its order, with its steps and end times", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bouncing.toml");
  const auto& registry = nsb::study_registry();
  const auto study = std::find_if(registry.begin(), registry.end(), [](const nsb::StudyEntry& e) { return e.name == "bouncing"; });
  REQUIRE(study != registry.end());
  CHECK(study->source == "studies/builtin/bouncing.toml");
  for (const bool full : {false, true}) {
    INFO("full " << full);
    std::vector<double> steps = {1e-2, 1e-3, 1e-4, 1e-5};
    if (full) steps.push_back(1e-6);
    std::vector<std::tuple<std::string, double, double>> expected;  // integrator, e, dt
    for (const auto& entry : nsb::integrator_registry())
      for (double e : {1.0, 0.9, 0.5})
        for (double dt : steps) expected.emplace_back(entry.name, e, dt);
    const auto cases = nsb::study_cases(*study, {full});
    REQUIRE(cases.size() == expected.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const auto& [name, e, dt] = expected[k];
      INFO("case " << k << ": " << name << " e " << e << " dt " << dt);
      const nsb::FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
      const nsb::FileIntegrator& it = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
      CHECK(it.name == name);
      CHECK(it.sweep_for(p.label).parameters.empty());
      CHECK(p.name == "bouncing-mass");
      CHECK(p.parameters == std::map<std::string, std::string>{{"e", fmt::format("{}", e)}});
      CHECK(cases[k]["dt"].get<double>() == dt);
      const auto problem = nsb::make_problem("bouncing-mass", p.parameters);
      const auto& mass = dynamic_cast<const nsb::BouncingMass&>(*problem);
      CHECK(spec.t_end_of(p, full) == (e < 1.0 ? mass.zeno_time() + 0.5 : mass.impact_time(6) + 0.1));
    }
  }
}

// Its tables against the committed report: the runs at dt = 1e-2 and
// 1e-3 of cd-lagrange, moreau-jean and schatzman-paoli as the file measures them: their rows of
// bouncing_mass (impact times, flight energies, Zeno times, penetration, steps; every cell but
// the CPU time), of bouncing_mass_energy (each flight of the dt = 1e-3 runs) and of
// bouncing_mass_energy_history (E / E0 every (steps / 400)-th step), cell for cell.
TEST_CASE("built-in study bouncing: its tables' rows of three schemes equal the committed report's", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bouncing.toml");
  const auto& registry = nsb::study_registry();
  const auto study = std::find_if(registry.begin(), registry.end(), [](const nsb::StudyEntry& e) { return e.name == "bouncing"; });
  REQUIRE(study != registry.end());
  const std::vector<std::string> schemes = {"cd-lagrange", "moreau-jean", "schatzman-paoli"};
  const auto shown = [&](const std::string& name) { return std::find(schemes.begin(), schemes.end(), name) != schemes.end(); };
  std::vector<nsb::Json> cases, results;
  for (const auto& c : nsb::study_cases(*study, {}))
    if (shown(spec.integrators[c["integrator"].get<std::size_t>()].name) && c["dt"].get<double>() >= 1e-3) {
      cases.push_back(c);
      results.push_back(nsb::run_study_case(*study, c, {}));
    }
  REQUIRE(cases.size() == 3 * 3 * 2);
  const auto tables = nsb::study_tables(*study, cases, results, {});
  const auto fresh_csv = [&](const std::string& id) {
    const auto table = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& t) { return t.id == id; });
    REQUIRE(table != tables.end());
    return nsb::parse_csv(nsb::to_csv(*table));
  };
  const auto report = report_csv("bouncing_mass");
  const auto fresh = fresh_csv("bouncing_mass");
  REQUIRE(fresh.size() == 1 + cases.size());
  CHECK(fresh[0] == report[0]);
  for (std::size_t r = 1; r < fresh.size(); ++r) {
    const auto row = std::find_if(report.begin() + 1, report.end(), [&](const std::vector<std::string>& was) {
      return std::equal(was.begin(), was.begin() + 3, fresh[r].begin());
    });
    REQUIRE(row != report.end());
    REQUIRE(row->size() == fresh[r].size());
    for (std::size_t c = 0; c < row->size(); ++c) {
      INFO("row " << r << ", column " << report[0][c]);
      if (report[0][c] != "CPU [s]") CHECK(fresh[r][c] == (*row)[c]);
    }
  }
  for (const char* id : {"bouncing_mass_energy", "bouncing_mass_energy_history"}) {
    INFO(id);
    const auto was = report_csv(id);
    std::vector<std::vector<std::string>> expected = {was[0]};
    for (std::size_t r = 1; r < was.size(); ++r)
      if (shown(was[r][0])) expected.push_back(was[r]);
    CHECK(expected.size() > 3 * 3);
    CHECK(fresh_csv(id) == expected);
  }
}

// hausdorff.toml's runs are those of the C++ study it replaced (studies/hausdorff_study.cpp,
// whose case list, default and --full, this file's equalled run for run before it was deleted),
// rebuilt here by that study's rule: six problems in its order, each over the schemes (peers and
// references aside) in the registry's order, each over four levels: 4 ms / 2^level, the bars N =
// 25 2^level at 0.9 of their stable step; each to its end from the exact events (the spring
// chain: 2 s, against modal-exact at output step 2e-5 s). The same with --full (the C++ study had
// one grid). A run added, removed or moved fails here.
TEST_CASE("built-in study hausdorff: hausdorff.toml's runs are the C++ study's, in its order, with its steps and end times", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/hausdorff.toml");
  const auto& registry = nsb::study_registry();
  const auto study = std::find_if(registry.begin(), registry.end(), [](const nsb::StudyEntry& e) { return e.name == "hausdorff"; });
  REQUIRE(study != registry.end());
  using Overrides = std::map<std::string, std::string>;
  const std::vector<std::pair<std::string, Overrides>> subjects = {
      {"bouncing-mass", {{"e", "0.9"}, {"h0", "1"}}},
      {"signorini-bar", {{"mass", "lumped"}}},
      {"bouncing-bar", {{"mass", "lumped"}}},
      {"spring-chain", {{"n", "3"}, {"wall", "left"}}},
      {"sliding-mass", {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "2"}}},
      {"rolling-disk", {{"h0", "0.05"}, {"omega0", "20"}, {"e", "0.5"}, {"mu", "0.3"}}},
  };
  std::vector<std::tuple<std::size_t, std::string, int>> expected;  // subject, integrator, level
  for (std::size_t s = 0; s < subjects.size(); ++s)
    for (const auto& entry : nsb::integrator_registry())
      if (!entry.reference && !entry.peer)
        for (int level = 0; level < 4; ++level) expected.emplace_back(s, entry.name, level);
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto cases = nsb::study_cases(nsb::file_study(spec), {full});
    REQUIRE(cases.size() == expected.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const auto& [s, integrator, level] = expected[k];
      const auto& [name, parameters] = subjects[s];
      INFO("case " << k << ": " << name << " " << integrator << " level " << level);
      const bool bar = name == "signorini-bar" || name == "bouncing-bar";
      Overrides want = parameters;
      if (bar) want["N"] = fmt::format("{}", 25L << level);
      const nsb::FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
      const nsb::FileIntegrator& it = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
      CHECK(p.name == name);
      CHECK(p.parameters == want);
      CHECK(it.name == integrator);
      CHECK(it.sweep_for(p.label).parameters.empty());
      const auto problem = nsb::make_problem(name, want);
      CHECK(cases[k]["dt"].get<double>() == (bar ? 0.9 * problem->stable_step() : 4e-3 / std::pow(2.0, level)));
      const nsb::ExactSolution* exact = problem->exact();
      double t_end = 2.0;
      if (name == "bouncing-mass") t_end = exact->impact_times(1e3).at(2) + 0.2;
      if (name == "signorini-bar")
        t_end = exact->event_time(nsb::ExactEvent::contact_start).value() + 1.5 * exact->value(nsb::ExactValue::contact_duration).value();
      if (name == "bouncing-bar") {
        const nsb::BouncingBarExact fall(problem->parameters(), 0.0);
        t_end = fall.impact_time() + 16.0 * fall.wave_time();
      }
      if (name == "sliding-mass") t_end = 1.5 * exact->event_time(nsb::ExactEvent::slip_stop).value();
      if (name == "rolling-disk") t_end = 1.2 * exact->event_time(nsb::ExactEvent::rest).value();
      CHECK(spec.t_end_of(p, full) == t_end);
      const nsb::FileReference& ref = *spec.reference_of(p);
      CHECK(ref.exact == (name != "spring-chain"));
      if (name == "spring-chain") {
        CHECK(ref.integrator == "modal-exact");
        CHECK(ref.dt == 2e-5);
        CHECK(ref.sample_every == 1);
        CHECK(ref.parameters.empty());
      }
    }
  }
  CHECK(study->source == "studies/builtin/hausdorff.toml");
}

namespace {

// The runs of the C++ study bar (studies/bar.cpp, deleted once bar.toml's case list equalled
// it, default and --full): every registered integrator x mass lumped | consistent | singular x
// alpha = dt / stable step in {0.25, 0.5, 0.9, 1} (references, whose accuracy is their
// tolerance, at alpha = 1 only) x N in {50, 100, 200, 400, 800} (--full: also 1600, 3200, 6400);
// since, N = 800 runs under --full only (bar.toml's header says why).
struct BarCase {
  std::string integrator, mass;
  double alpha;
  long N;
};

std::vector<BarCase> cpp_bar_cases(bool full) {
  std::vector<long> meshes = {50, 100, 200, 400};
  if (full) meshes.insert(meshes.end(), {800, 1600, 3200, 6400});
  std::vector<BarCase> cases;
  for (const auto& entry : nsb::integrator_registry())
    for (const char* mass : {"lumped", "consistent", "singular"})
      for (double alpha : {0.25, 0.5, 0.9, 1.0})
        if (!entry.reference || alpha == 1.0)
          for (long N : meshes) cases.push_back({entry.name, mass, alpha, N});
  return cases;
}

const nsb::StudyEntry& bar_entry() {
  const auto& registry = nsb::study_registry();
  const auto entry = std::find_if(registry.begin(), registry.end(), [](const nsb::StudyEntry& e) { return e.name == "bar"; });
  REQUIRE(entry != registry.end());
  return *entry;
}

}  // namespace

// bar.toml's runs are the C++ study's, default and --full: in its order (integrator, mass,
// alpha, N), each of the signorini-bar at its defaults but mass and N, with dt = alpha * stable
// step, to t0 + 1.5 T (the contact and half its length after). A run added, removed or moved
// fails here.
TEST_CASE("built-in study bar: bar.toml's runs are the C++ study's, in its order, with its steps and end time", "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bar.toml");
  CHECK(bar_entry().source == "studies/builtin/bar.toml");
  const nsb::ParamSpecs bar = nsb::find_problem("signorini-bar").parameters();
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto expected = cpp_bar_cases(full);
    const auto cases = nsb::study_cases(bar_entry(), {full});
    REQUIRE(cases.size() == expected.size());
    for (std::size_t k = 0; k < cases.size(); ++k) {
      const BarCase& e = expected[k];
      INFO("case " << k << ": " << e.integrator << " " << e.mass << " alpha " << e.alpha << " N " << e.N);
      const nsb::FileProblem& p = spec.problems[cases[k]["problem"].get<std::size_t>()];
      const nsb::Params params(bar, p.parameters);
      const nsb::FileIntegrator& it = spec.integrators[cases[k]["integrator"].get<std::size_t>()];
      CHECK(p.name == "signorini-bar");
      CHECK(it.name == e.integrator);
      CHECK(it.sweep_for(p.label).parameters.empty());
      CHECK(p.parameters.size() == 2);  // mass and N: the rest the defaults
      CHECK(params.choice("mass") == e.mass);
      CHECK(params.integer("N") == e.N);
      CHECK(cases[k]["stable_steps"].get<double>() == e.alpha);
      const auto problem = nsb::make_problem("signorini-bar", p.parameters);
      CHECK(cases[k]["dt"].get<double>() == e.alpha * problem->stable_step());
      const auto* exact = problem->exact();
      REQUIRE(exact != nullptr);
      CHECK(spec.t_end_of(p, full) ==
            exact->event_time(nsb::ExactEvent::contact_start).value() + 1.5 * exact->value(nsb::ExactValue::contact_duration).value());
    }
  }
}

// --full's finer meshes pass modal-exact's max_dofs (2000) at N = 3200: its own run there
// declined with the reason, and a scheme's run measured but its time error against the
// semi-discrete bar n/a, the reason in its note (the note column of table bar).
TEST_CASE("built-in study bar: with --full, modal-exact declines N = 3200 and a scheme's time error there is n/a with the reason",
          "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bar.toml");
  const auto time_error = std::find_if(spec.measures.begin(), spec.measures.end(), [](const nsb::FileMeasure& m) { return m.label == "u time err"; });
  REQUIRE(time_error != spec.measures.end());
  const auto run = [&](const std::string& integrator) {
    for (const auto& c : nsb::study_cases(bar_entry(), {true})) {
      const nsb::FileProblem& p = spec.problems[c["problem"].get<std::size_t>()];
      if (spec.integrators[c["integrator"].get<std::size_t>()].name == integrator && p.parameters.at("N") == "3200" &&
          p.parameters.at("mass") == "lumped" && c["stable_steps"].get<double>() == 1.0)
        return nsb::run_study_case(bar_entry(), c, {true});
    }
    FAIL("no --full run of " << integrator << " at N = 3200, lumped, alpha = 1");
    return nsb::Json();
  };
  const nsb::Json own = run("modal-exact");
  CHECK(own["status"] == "n/a");
  CHECK_THAT(own["message"].get<std::string>(), Catch::Contains("max_dofs = 2000") && Catch::Contains("3201 dofs"));
  const nsb::Json scheme = run("cd-lagrange");
  CHECK(scheme["status"] == "ok");
  CHECK(scheme["values"][static_cast<std::size_t>(time_error - spec.measures.begin())].is_null());
  CHECK_THAT(scheme["run"]["note"].get<std::string>(),
             Catch::StartsWith("u time err n/a: integrator modal-exact needs at most max_dofs = 2000 dofs") && Catch::Contains("3201 dofs"));
}

// bar.toml's tables against the committed reports, cell for cell but
// the CPU time: the runs of cd-lagrange (lumped: every alpha and N, its time error against
// modal-exact; consistent: declined, every measured cell n/a) and of modal-exact (lumped, alpha
// = 1: its own time error n/a), their rows of bar, bar_n100, bar_orders (fitted against
// log(1/N), the energy and chatter errors' too) and bar_time_orders (modal-exact's left out), in
// the report's order.
TEST_CASE("built-in study bar: cd-lagrange's and modal-exact's rows of bar, bar_n100, bar_orders and bar_time_orders are the "
          "committed report's",
          "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bar.toml");
  const nsb::StudyEntry entry = nsb::file_study(spec);
  std::vector<nsb::Json> cases, results;
  for (const auto& c : nsb::study_cases(entry, {})) {
    const std::string& integrator = spec.integrators[c["integrator"].get<std::size_t>()].name;
    const std::string& mass = spec.problems[c["problem"].get<std::size_t>()].parameters.at("mass");
    if ((integrator == "cd-lagrange" && mass != "singular") || (integrator == "modal-exact" && mass == "lumped")) {
      cases.push_back(c);
      results.push_back(nsb::run_study_case(entry, c, {}));
    }
  }
  REQUIRE(cases.size() == 36);  // 2 masses x 4 alphas x 4 meshes, and 4 meshes
  const auto tables = nsb::study_tables(entry, cases, results, {});
  const std::vector<std::pair<std::string, std::size_t>> ids = {{"bar", 4}, {"bar_n100", 2}, {"bar_orders", 3}, {"bar_time_orders", 3}};
  const std::vector<std::size_t> rows = {36, 2, 9, 8};
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto& [id, keys] = ids[i];
    INFO(id);
    const auto table = std::find_if(tables.begin(), tables.end(), [&, &id = id](const nsb::Table& t) { return t.id == id; });
    REQUIRE(table != tables.end());
    const auto fresh = nsb::parse_csv(nsb::to_csv(*table));
    const auto report = report_csv(id);
    REQUIRE(fresh.size() == rows[i] + 1);
    CHECK(fresh[0] == report[0]);
    auto from = report.begin() + 1;
    for (std::size_t r = 1; r < fresh.size(); ++r) {
      const auto row = std::find_if(from, report.end(), [&, keys = keys](const std::vector<std::string>& was) {
        return std::equal(was.begin(), was.begin() + static_cast<long>(keys), fresh[r].begin());
      });
      INFO("row " << r << ": " << fresh[r][0] << ", " << fresh[r][1] << ", " << fresh[r][2]);
      REQUIRE(row != report.end());  // in the report, after the rows before it
      from = row + 1;
      REQUIRE(row->size() == fresh[r].size());
      for (std::size_t c = 0; c < row->size(); ++c) {
        INFO("column " << report[0][c]);
        if (report[0][c] != "CPU [s]") CHECK(fresh[r][c] == (*row)[c]);
      }
    }
  }
}

// bar.toml's tables bar_contact_force_history (rows = "impulses") and bar_space_time (rows =
// "field") against the committed report: the runs they show (N = 100 and 50
// at alpha = 0.9, lumped and singular mass) of nsbench's own integrators (peers aside), every other
// run of the study's list a placeholder that did not run (n/a). Each table equals the
// report's rows of those integrators cell for cell at rtol 0; its metadata lines N, alpha,
// mass (and the space-time schemes) the report's; the figures.json entries of the file's
// figures the report's.
TEST_CASE("built-in study bar: its contact-force history and space-time tables, metadata and figures equal the committed report's",
          "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bar.toml");
  const nsb::StudyEntry entry = nsb::file_study(spec);
  const auto cases = nsb::study_cases(entry, {false});
  const auto report_text = [](const std::string& name) {
    std::ifstream in(std::filesystem::path(NSBENCH_SOURCE_DIR) / "reports" / name);
    std::stringstream text;
    text << in.rdbuf();
    REQUIRE(!text.str().empty());
    return text.str();
  };
  // A report's lines less the rows of the peers (optional, and rounded by their own libraries).
  const auto of_this_build = [&](const std::string& id) {
    std::stringstream in(report_text(id + ".csv"));
    std::string out, line;
    for (bool header = true; std::getline(in, line); header = header && line[0] == '#') {
      const std::string first = line.substr(0, line.find(','));
      if (header || line[0] == '#' || first == "exact" || ours(first)) out += line + "\n";
    }
    return out;
  };
  const std::vector<std::string> shown = {"lumped, alpha = 0.9, N = 100", "singular, alpha = 0.9, N = 100",
                                          "lumped, alpha = 0.9, N = 50", "singular, alpha = 0.9, N = 50"};
  const std::string history = of_this_build("bar_contact_force_history");
  const nsb::Json not_run = {{"status", "n/a"}, {"message", "not run by this test"}, {"steps", 0}, {"force_evaluations", 0},
                             {"run", {{"t_reached", 0.0}, {"impacts", 0}, {"note", "not run by this test"}}}};
  std::vector<nsb::Json> results;
  std::size_t ran = 0;
  for (const auto& c : cases) {
    const std::string& problem = spec.problems[c["problem"].get<std::size_t>()].label;
    const std::string& integrator = spec.integrators[c["integrator"].get<std::size_t>()].name;
    const bool in_report = history.find("\n" + integrator + ",") != std::string::npos ||
                           std::find(spec.tables.back().integrators.begin(), spec.tables.back().integrators.end(), integrator) !=
                               spec.tables.back().integrators.end();
    const bool run = in_report && std::find(shown.begin(), shown.end(), problem) != shown.end();
    ran += run;
    results.push_back(run ? nsb::run_study_case(entry, c, {}) : not_run);
  }
  CHECK(ran >= 2 * 5 + 2 * 8);  // the space-time schemes at N = 50, the history's schemes at N = 100
  const auto tables = nsb::study_tables(entry, cases, results, {});
  const auto table = [&](const std::string& id) -> const nsb::Table& {
    const auto t = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& u) { return u.id == id; });
    REQUIRE(t != tables.end());
    return *t;
  };
  for (const std::string id : {"bar_contact_force_history", "bar_space_time"}) {
    INFO(id);
    const nsb::VerifyResult v = nsb::verify_table(table(id), of_this_build(id), nsb::VerifyTolerance{0.0, 0.0});
    for (const auto& d : v.differences) INFO(d);
    CHECK(v.differences.empty());
    CHECK(v.cells_compared > (id == "bar_space_time" ? 1300 * 53 : 6000 * 4));
    // The report's metadata lines (its first lines, before the build stamp) are the table's:
    // the parameters shown (N, alpha, mass; the space-time schemes) and the study file's stamp.
    std::stringstream in(report_text(id + ".csv"));
    std::vector<std::pair<std::string, std::string>> expected;
    for (std::string line; std::getline(in, line) && line.rfind("# nsbench_version", 0) != 0;)
      expected.emplace_back(line.substr(2, line.find(": ") - 2), line.substr(line.find(": ") + 2));
    for (const std::string key : {"study", "N", "alpha", "mass", "study_file", "study_file_fnv1a64"}) {
      INFO(key);
      CHECK(std::any_of(expected.begin(), expected.end(), [&](const auto& line) { return line.first == key; }));
    }
    CHECK(expected.size() == table(id).metadata.size());
    for (const auto& line : expected) {
      INFO(line.first);
      CHECK(std::find(table(id).metadata.begin(), table(id).metadata.end(), line) != table(id).metadata.end());
    }
  }
  // figures.json: the report's entries of the file's figures.
  const nsb::Json fresh = nsb::Json::parse(nsb::figures_to_json(tables));
  const nsb::Json report = nsb::Json::parse(report_text("figures.json"));
  for (const std::string id : {"bar_convergence", "bar_energy", "bar_force_oscillation", "bar_time_error", "bar_contact_force", "bar_space_time"}) {
    INFO(id);
    const auto by_id = [&](const nsb::Json& all) {
      const auto f = std::find_if(all.begin(), all.end(), [&](const nsb::Json& e) { return e["id"] == id; });
      REQUIRE(f != all.end());
      return *f;
    };
    CHECK(by_id(fresh) == by_id(report));
  }
}

// bar.toml's orders tables say the grid that was run (their captions' ${parameter N} and
// ${stable steps}: the values over the table's runs): bar_orders the meshes N = 50..400, with
// --full to 6400, bar_time_orders the alphas. The default captions are the committed reports'
// (the line under the title of bar_orders.md and bar_time_orders.md), byte for byte. The runs
// are not made: the captions take the cases' parameters only.
TEST_CASE("built-in study bar: the orders tables' captions name the meshes and alphas run, the default's the committed reports'",
          "[studies]") {
  const nsb::StudySpec spec = builtin_spec("studies/builtin/bar.toml");
  const nsb::StudyEntry entry = nsb::file_study(spec);
  const auto report_caption = [](const std::string& id) {
    std::ifstream in(std::filesystem::path(NSBENCH_SOURCE_DIR) / "reports" / (id + ".md"));
    std::string title, blank, caption;
    std::getline(in, title);
    std::getline(in, blank);
    std::getline(in, caption);
    CHECK(title.rfind("## ", 0) == 0);
    CHECK(blank.empty());
    return caption;
  };
  const nsb::Json not_run = {{"status", "n/a"}, {"message", "not run by this test"}, {"steps", 0}, {"force_evaluations", 0},
                             {"run", {{"t_reached", 0.0}, {"impacts", 0}, {"note", "not run by this test"}}}};
  for (const bool full : {false, true}) {
    INFO("full " << full);
    const auto cases = nsb::study_cases(entry, {full});
    const auto tables = nsb::study_tables(entry, cases, std::vector<nsb::Json>(cases.size(), not_run), {full});
    const auto caption = [&](const std::string& id) {
      const auto t = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& u) { return u.id == id; });
      REQUIRE(t != tables.end());
      return t->caption;
    };
    std::string orders = report_caption("bar_orders");
    const std::string meshes = "over N = 50, 100, 200, 400 with";
    REQUIRE(orders.find(meshes) != std::string::npos);
    if (full) orders.replace(orders.find(meshes), meshes.size(), "over N = 50, 100, 200, 400, 800, 1600, 3200, 6400 with");
    CHECK(caption("bar_orders") == orders);
    const std::string time_orders = report_caption("bar_time_orders");
    CHECK(time_orders.find("over alpha = 0.25, 0.5, 0.9, 1 at each N") != std::string::npos);
    CHECK(caption("bar_time_orders") == time_orders);
  }
}

// Issue 51, item 6: every table of every built-in study file, in Markdown, within the cell
// limit and each declined run's reason said once. Its runs are not made: each says it declined,
// with a reason as long as a scheme's (studies/table.hpp: the footnote rules).
TEST_CASE("built-in study files: every Markdown table's cells within 300 characters, a declined run's reason once",
          "[studies][tables]") {
  const std::string why = "integrator x needs a diagonal mass matrix with entries >= 0; problem y has a non-diagonal mass matrix "
                          "(valid: a problem with a lumped mass, e.g. mass=lumped), not run by this test";
  const nsb::Json declined = {{"status", "n/a"}, {"message", why}, {"steps", 0}, {"force_evaluations", 0},
                              {"run", {{"t_reached", 0.0}, {"impacts", 0}, {"note", why}}}};
  std::size_t shown = 0;
  for (const auto& file : nsb::builtin_study_files()) {
    if (!file.path.ends_with(".toml")) continue;  // a Python study's tables: its own (tests/python)
    INFO(file.path);
    const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(std::string(file.text), std::string(file.path), false));
    const auto cases = nsb::study_cases(entry, {});
    for (const auto& t : nsb::study_tables(entry, cases, std::vector<nsb::Json>(cases.size(), declined), {})) {
      if (t.csv_only) continue;
      INFO(t.id);
      const std::string md = nsb::to_markdown(t);
      std::istringstream in(md);
      for (std::string line; std::getline(in, line);) {
        if (line.rfind("| ", 0) != 0) continue;
        for (std::size_t begin = 2, end; begin < line.size(); begin = end + 3) {
          end = line.find(" | ", begin);
          while (end != std::string::npos && line[end - 1] == '\\') end = line.find(" | ", end + 1);  // an escaped bar
          if (end == std::string::npos) end = line.size() - 2;
          CHECK(end - begin <= nsb::kMaxCellChars);
        }
      }
      const std::size_t said = [&] {
        std::size_t n = 0;
        for (std::size_t at = md.find(why); at != std::string::npos; at = md.find(why, at + 1)) ++n;
        return n;
      }();
      CHECK(said <= 1);
      shown += said;
    }
  }
  CHECK(shown > 0);  // the reason is shown, under some table
}
