// A study's outputs do not depend on how many cases run at once (NSBENCH_JOBS), CPU
// columns aside. The reduced study: Moreau-Jean on the 32x32 block (the case issue 11 found
// changed by its neighbour: a supernodal factorisation through a BLAS without locks) at two
// steps, and every registered integrator on the bouncing mass; run as nsbench-study runs a
// study (parallel_map over the cases, then the tables) with 1 and 2 jobs, compared cell by
// cell with zero tolerance.
#include <catch2/catch.hpp>
#include <cstdlib>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "studies/parallel.hpp"
#include "studies/study.hpp"
#include "studies/verify.hpp"

namespace {

std::vector<nsb::Json> reduced_cases(const nsb::StudyOptions&) {
  std::vector<nsb::Json> cases = {
      {{"problem", "block-2d"}, {"integrator", "moreau-jean"}, {"dt", 1e-4}, {"t_end", 4e-4}},
      {{"problem", "block-2d"}, {"integrator", "moreau-jean"}, {"dt", 5e-5}, {"t_end", 2e-4}},
  };
  for (const auto& e : nsb::integrator_registry())
    cases.push_back({{"problem", "bouncing-mass"}, {"integrator", e.name}, {"dt", 1e-2}, {"t_end", 1.0}});
  return cases;
}

nsb::Json reduced_run(const nsb::Json& c) {
  std::map<std::string, std::string> mesh;
  if (c["problem"] == "block-2d") mesh = {{"nx", "32"}, {"ny", "32"}, {"vx", "0.5"}};
  const auto problem = nsb::make_problem(c["problem"], mesh);
  const auto integrator = nsb::make_integrator(c["integrator"]);
  try {
    integrator->init(*problem, problem->initial_state());
  } catch (const nsb::InputError&) {  // a scheme that declines the problem: a row all the same
    return {{"status", "declined"}, {"steps", 0}, {"series", ""}, {"energy", nullptr}, {"cpu", 0.0}};
  }
  nsb::RunOptions options;
  options.dt = c["dt"];
  options.t_end = c["t_end"];
  const nsb::RunResult r = nsb::run(*problem, *integrator, options);
  return {{"status", nsb::status_name(r.status)}, {"steps", r.steps}, {"series", nsb::series_to_csv(r.series)},
          {"energy", nsb::real(r.final_energy)}, {"cpu", r.cpu_seconds}};
}

std::vector<nsb::Table> reduced_tables(const std::vector<nsb::Json>& cases, const std::vector<nsb::Json>& results,
                                       const nsb::StudyOptions&) {
  nsb::Table t;
  t.id = "reduced";
  t.columns = {{"problem", "", "", ""}, {"integrator", "", "", ""}, {"dt", "s", "", ""},
               {"status", "", "", ""},  {"steps", "", "", ""},      {"final E", "J", "", ""},
               {"series", "", "", "every sample, every column, shortest round-trip text"},
               {"CPU", "s", "", "", true}};
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto& c = cases[k];
    const auto& r = results[k];
    t.add_row({c["problem"].get<std::string>(), c["integrator"].get<std::string>(), c["dt"].get<double>(),
               r["status"].get<std::string>(), r["steps"].get<long>(), nsb::number_cell(r["energy"]),
               r["series"].get<std::string>(), r["cpu"].get<double>()});
  }
  return {t};
}

std::vector<nsb::Table> run_with_jobs(const nsb::StudyEntry& study, const char* jobs) {
  setenv("NSBENCH_JOBS", jobs, 1);
  const auto cases = nsb::study_cases(study, {});
  const auto results = nsb::parallel_map<nsb::Json>(cases.size(), [&](std::size_t k) {
    return nsb::run_study_case(study, cases[k], {});
  }, "reduced");
  unsetenv("NSBENCH_JOBS");
  return nsb::study_tables(study, cases, results, {});
}

}  // namespace

TEST_CASE("studies: the same outputs with 1 and 2 jobs, CPU columns aside (reduced study)", "[studies][concurrency]") {
  nsb::StudyEntry reduced;
  reduced.name = "reduced";
  reduced.cases = reduced_cases;
  reduced.run_case = reduced_run;
  reduced.tables = reduced_tables;
  const auto one = run_with_jobs(reduced, "1");
  const auto two = run_with_jobs(reduced, "2");
  REQUIRE(one.size() == two.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    const nsb::VerifyResult v = nsb::verify_table(two[i], nsb::to_csv(one[i]), {0.0, 0.0});
    CHECK(v.differences.empty());
    for (const auto& d : v.differences) UNSCOPED_INFO(d);
    CHECK(v.cells_compared == one[i].rows.size() * (one[i].columns.size() - 1));
  }
}

TEST_CASE("NSBENCH_JOBS: anything but a whole number from 1 up is refused naming the variable", "[studies][jobs]") {
  for (const char* bad : {"0", "-1", "abc", "2x", "99999999999"}) {
    CAPTURE(bad);
    setenv("NSBENCH_JOBS", bad, 1);
    CHECK_THROWS_WITH(nsb::study_jobs(), Catch::StartsWith(std::string("NSBENCH_JOBS='") + bad + "': expected a whole number"));
  }
  setenv("NSBENCH_JOBS", "3", 1);
  CHECK(nsb::study_jobs() == 3);
  unsetenv("NSBENCH_JOBS");
}
