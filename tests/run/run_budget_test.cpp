#include <catch2/catch.hpp>

#include <time.h>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/registry.hpp"

namespace {
nsb::RunResult run_with_budget(const std::string& integrator, long budget) {
  const auto problem = nsb::make_problem("bouncing-mass", {{"e", "0.5"}});
  auto integ = nsb::make_integrator(integrator);
  integ->init(*problem, problem->initial_state());
  nsb::RunOptions options;
  options.dt = 1e-3;
  options.t_end = 2.0;
  options.record_series = false;
  options.max_force_evaluations = budget;
  return nsb::run(*problem, *integ, options);
}
}  // namespace

TEST_CASE("run: a force-evaluation budget stops the run at the same step every time and says so", "[integrators][run]") {
  const auto full = run_with_budget("cd-lagrange", 0);
  REQUIRE(full.status == nsb::RunStatus::Ok);
  REQUIRE(full.work.force_evaluations > 500);

  const auto a = run_with_budget("cd-lagrange", 500);
  const auto b = run_with_budget("cd-lagrange", 500);
  CHECK(a.status == nsb::RunStatus::OverBudget);
  CHECK(std::string(nsb::status_name(a.status)) == "over budget");
  CHECK_THAT(a.message, Catch::Contains("budget of 500 F_int evaluations exceeded"));
  // Stopped at the first step past the budget: one fixed step costs one evaluation.
  CHECK(a.work.force_evaluations == 501);
  CHECK(a.steps < full.steps);
  CHECK(b.steps == a.steps);
  CHECK(b.t_final == a.t_final);

  // An event-driven reference spends many evaluations per output step: it too stops, once.
  const auto ed = run_with_budget("event-driven", 200);
  CHECK(ed.status == nsb::RunStatus::OverBudget);
  CHECK(ed.work.force_evaluations > 200);
  CHECK(ed.t_final < 2.0);
  CHECK(run_with_budget("event-driven", 200).steps == ed.steps);
}

TEST_CASE("run: a negative force-evaluation budget is an input error", "[integrators][run][bad-input]") {
  CHECK_THROWS_WITH(run_with_budget("cd-lagrange", -1), Catch::Contains("max_force_evaluations -1: must be >= 0"));
}

TEST_CASE("run: the stepping time excludes the observer's and the sampling's time", "[integrators][run]") {
  const auto problem = nsb::make_problem("bouncing-mass", {{"e", "0.5"}});
  auto integ = nsb::make_integrator("cd-lagrange");
  integ->init(*problem, problem->initial_state());
  nsb::RunOptions options;
  options.dt = 1e-3;
  options.t_end = 0.2;
  // An observer that spends at least 50 microseconds of this thread's CPU time per step:
  // 200 steps, 10 ms in all, far more than the steps themselves.
  const auto thread_cpu = [] {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
  };
  double burnt = 0.0;
  const auto r = nsb::run(*problem, *integ, options, [&](const nsb::Integrator&, const nsb::StepInfo&) {
    const double start = thread_cpu();
    while (thread_cpu() - start < 50e-6) {
    }
    burnt += thread_cpu() - start;
  });
  REQUIRE(r.steps == 200);
  CHECK(burnt >= 0.01);
  CHECK(r.step_cpu_seconds >= 0.0);
  CHECK(r.step_cpu_seconds <= r.cpu_seconds);
  // The observer's time is excluded: its share is measured on the wall clock (98 % of this
  // run's time), so up to the preemption's noise.
  CHECK(r.cpu_seconds - r.step_cpu_seconds >= 0.9 * burnt);
}
