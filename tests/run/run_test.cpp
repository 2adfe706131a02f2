// The run driver's series streamed to a file (issue 20: memory bounded whatever the length),
// its energy-error scale when E0 = 0, and its checks of what the problem and the integrator
// report at every step (issue 56).
#include "run/run.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "tests/problems/forwarding_problem.hpp"

namespace fs = std::filesystem;

namespace {

nsb::RunResult run_case(const std::string& problem, nsb::RunOptions options, const std::string& integrator = "cd-lagrange") {
  const auto p = nsb::make_problem(problem);
  auto it = nsb::make_integrator(integrator);
  it->init(*p, p->initial_state());
  return nsb::run(*p, *it, options);
}

}  // namespace

TEST_CASE("run: a streamed series is the in-memory one, byte for byte, and nothing is kept", "[integrators][run]") {
  const fs::path dir = fs::temp_directory_path() / ("nsbench_run_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  nsb::RunOptions options;
  options.dt = 1e-3;
  options.t_end = 1.0;
  options.sample_every = 7;  // the last step is sampled off the stride
  const nsb::RunResult kept = run_case("bouncing-mass", options);
  {
    nsb::CsvSeriesFile file(dir / "series.csv");
    options.series_sink = &file;
    const nsb::RunResult streamed = run_case("bouncing-mass", options);
    CHECK(streamed.series.values.empty());
    CHECK(streamed.steps == kept.steps);
    CHECK_FALSE(fs::exists(dir / "series.csv"));  // not before commit
    file.commit();
  }
  std::ifstream in(dir / "series.csv");
  std::stringstream text;
  text << in.rdbuf();
  CHECK(text.str() == nsb::series_to_csv(kept.series));
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++entries;
  CHECK(entries == 1);  // no temporary left
  {
    nsb::CsvSeriesFile abandoned(dir / "other.csv");
    abandoned.columns({"t"});
  }
  CHECK_FALSE(fs::exists(dir / "other.csv"));
  fs::remove_all(dir);
}

TEST_CASE("run: energy errors relative to the problem's energy scale when E0 = 0, said in the summary", "[integrators][run]") {
  nsb::RunOptions options;
  options.dt = 1e-3;
  options.t_end = 2.0;
  options.record_series = false;
  const auto bar = nsb::make_problem("bouncing-bar");
  auto it = nsb::make_integrator("moreau-jean");  // its energy is v^T M v / 2 + V(u): 0 at the start
  it->init(*bar, bar->initial_state());
  const nsb::RunResult r = nsb::run(*bar, *it, options);
  REQUIRE(r.initial_energy == 0.0);
  CHECK(r.energy_scale == 500.0);  // rho A L g g0 = 10 * 10 * 5: the kinetic energy at the impact (t = 1)
  CHECK(std::isfinite(r.max_energy_error));
  CHECK(r.final_energy_error() == std::abs(r.final_energy) / 500.0);
  const auto summary = nlohmann::json::parse(nsb::summary_to_json(*bar, *it, options, r));
  CHECK(summary["energy_error_scale"] == 500.0);
  CHECK(summary["energy_error_scale_is"] == "E0 = 0: kinetic energy at the first impact, rho A L (v0^2 + 2 g g0) / 2");
  // E0 != 0: |E0| as before.
  const nsb::RunResult m = run_case("bouncing-mass", options);
  CHECK(m.energy_scale == std::abs(m.initial_energy));
}

TEST_CASE("run: min_gap and max_penetration of moving contacts are those of g(u), not of its linearisation at U0",
          "[integrators][run][rocking_block]") {
  nsb::RunOptions options;
  options.dt = 1e-4;
  options.t_end = 1.5;  // the first impacts: the linearised gap of the tilted corner is off by ~1e-2
  const nsb::RunResult r = run_case("rocking-block", options);
  REQUIRE(r.status == nsb::RunStatus::Ok);
  const auto p = nsb::make_problem("rocking-block");
  nsb::ContactGeometry at = p->contact_geometry();
  p->evaluate_contacts(p->initial_state().u, at);
  CHECK(r.max_penetration < 1e-4);  // g(u): 1.6e-5 over 3 s; g0 + L u reported 1.7e-2 there
  const std::size_t gap = r.series.column("min_gap");
  CHECK(r.series.at(0, gap) == at.gap.minCoeff());
}

namespace {

// The bouncing mass whose contact geometry turns NaN below y = 0.3 (issue 56: a plugin problem's
// NaN gaps passed as ok, 623 rows of min_gap NaN, the mass at y = -3.9).
class NanGeometry final : public ForwardingProblem {
 public:
  NanGeometry() : ForwardingProblem(nsb::make_problem("bouncing-mass")) {}
  bool contacts_move() const override { return true; }
  void evaluate_contacts(nsb::ConstVecRef u, nsb::ContactGeometry& out) const override {
    held().evaluate_contacts(u, out);
    if (u[0] < 0.3) out.gap.setConstant(std::numeric_limits<double>::quiet_NaN());
  }
};

// Free flight whose reported impulse or work counter is the one given: what the run driver must
// not take for a result.
class Reporting final : public nsb::Integrator {
 public:
  Reporting(double impulse, long force_evaluations) : Integrator(nsb::Params{}), impulse_(impulse), evaluations_(force_evaluations) {}
  void init(const nsb::Problem& p, const nsb::State& s) override { bind(p, s); }

 private:
  nsb::StepInfo advance(double dt) override {
    state_.u += dt * state_.v;
    impulses_.setConstant(impulse_);
    work_.force_evaluations = evaluations_;
    return {dt};
  }
  double impulse_;
  long evaluations_;
};

}  // namespace

TEST_CASE("run: non-finite contact geometry ends the run as diverged with the reason", "[integrators][run][bad-input]") {
  const NanGeometry problem;
  nsb::RunOptions options;
  options.dt = 1e-3;
  options.t_end = 3.0;
  for (const char* name : {"cd-lagrange", "moreau-jean", "nsga"}) {
    auto it = nsb::make_integrator(name);
    it->init(problem, problem.initial_state());
    const nsb::RunResult r = nsb::run(problem, *it, options);
    INFO(name);
    CHECK(r.status == nsb::RunStatus::Diverged);
    CHECK_THAT(r.message, Catch::StartsWith("non-finite contact gap (the problem's contact geometry) at t = "));
    CHECK(r.t_final < 1.0);
    const std::size_t gap = r.series.column("min_gap");
    for (std::size_t k = 0; k < r.series.rows(); ++k) CHECK(std::isfinite(r.series.at(k, gap)));
  }
}

TEST_CASE("run: an integrator's NaN or negative impulse, or a negative work counter, ends the run as diverged",
          "[integrators][run][bad-input]") {
  const auto problem = nsb::make_problem("bouncing-mass");
  nsb::RunOptions options;
  options.dt = 1e-2;
  options.t_end = 0.5;
  const auto run_reporting = [&](double impulse, long evaluations) {
    Reporting it(impulse, evaluations);
    it.init(*problem, problem->initial_state());
    return nsb::run(*problem, it, options);
  };
  CHECK(run_reporting(0.0, 1).status == nsb::RunStatus::Ok);
  const nsb::RunResult nan = run_reporting(std::numeric_limits<double>::quiet_NaN(), 1);
  CHECK(nan.status == nsb::RunStatus::Diverged);
  CHECK(nan.steps == 1);
  CHECK_THAT(nan.message, Catch::StartsWith("non-finite normal impulse (the integrator's; valid: finite, >= 0) at t = 0.01"));
  CHECK_THAT(run_reporting(-1.0, 1).message, Catch::StartsWith("negative normal impulse"));
  CHECK_THAT(run_reporting(0.0, -1).message, Catch::StartsWith("negative work counter (the integrator's; valid: >= 0)"));
}

namespace {

// Free flight at a fixed wall time per step: a long run's step (a 1e8-element bar's).
class Slow final : public nsb::Integrator {
 public:
  explicit Slow(double seconds) : Integrator(nsb::Params{}), seconds_(seconds) {}
  void init(const nsb::Problem& p, const nsb::State& s) override { bind(p, s); }

 private:
  nsb::StepInfo advance(double dt) override {
    ::usleep(static_cast<useconds_t>(seconds_ * 1e6));
    state_.u += dt * state_.v;
    ++work_.force_evaluations;
    return {dt};
  }
  double seconds_;
};

// What the run writes on stderr (fd 2, redirected to a file while it runs).
std::string stderr_of(const std::function<void()>& body) {
  const fs::path file = fs::temp_directory_path() / ("nsbench_run_test_stderr_" + std::to_string(::getpid()));
  std::fflush(stderr);
  const int saved = ::dup(2), fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  ::dup2(fd, 2);
  body();
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(fd);
  ::close(saved);
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  fs::remove(file);
  return text.str();
}

}  // namespace

// Issue 56, finding 14: the clock was read every 16 steps, so a run of slow steps (a 1e8-element
// bar) printed nothing for 16 of them.
TEST_CASE("run: a run of slow steps shows its progress once a period, from the first period on", "[integrators][run]") {
  const auto problem = nsb::make_problem("bouncing-mass", {{"h0", "100"}});
  Slow it(0.15);
  it.init(*problem, problem->initial_state());
  nsb::RunOptions options;
  options.dt = 1e-2;
  options.t_end = 0.1;  // 10 steps, 1.5 s
  options.progress_every = 0.5;
  const std::string lines = stderr_of([&] { CHECK(nsb::run(*problem, it, options).status == nsb::RunStatus::Ok); });
  INFO(lines);
  std::size_t count = 0;
  for (std::size_t at = lines.find("of t_end, elapsed"); at != std::string::npos; at = lines.find("of t_end, elapsed", at + 1)) ++count;
  CHECK(count >= 2);  // at about 0.6, 1.05 and 1.5 s
  CHECK(count <= 3);  // no more than one a period
  CHECK_THAT(lines, Catch::Contains("% of t_end, elapsed 0."));  // the first within a step of the first period
}
