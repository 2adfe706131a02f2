// The command line as a user meets it: bad input exits 2 with one line naming the
// parameter and its valid range; a good run writes series.csv and summary.json.
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "run_cli.hpp"

namespace {

using nsb::test::Outcome;

Outcome nsbench(const std::string& args) { return nsb::test::run_command(std::string(NSBENCH_CLI) + " " + args); }

std::string tmpdir(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("nsbench_cli_test_" + name)).string();
}

const std::string kRun = "run --problem bouncing-mass --integrator cd-lagrange --t-end 0.5 ";

}  // namespace

TEST_CASE("cli: list shows every problem and integrator with parameters", "[app]") {
  const auto r = nsbench("list");
  CHECK(r.code == 0);
  CHECK_THAT(r.output, Catch::Contains("bouncing-mass") && Catch::Contains("cd-lagrange") &&
                           Catch::Contains("moreau-jean") && Catch::Contains("theta"));
}

TEST_CASE("cli: bad input exits 2 with a message naming the parameter and its range", "[app][bad-input]") {
  const std::string out = " --out " + tmpdir("bad");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {kRun + "--dt -1" + out, "--dt -1: must be > 0"},
      {kRun + "--dt 0" + out, "--dt 0: must be > 0"},
      {kRun + "--dt 1e-3x" + out, "--dt: '1e-3x' is not a finite number"},
      {kRun + "--dt 1e-3 --set e=1.5" + out, "parameter 'e' = 1.5 is outside its valid range [0, 1]"},
      {kRun + "--dt 1e-3 --set e=-0.1" + out, "parameter 'e' = -0.1 is outside its valid range [0, 1]"},
      {kRun + "--dt 1e-3 --set m=abc" + out, "parameter 'm': 'abc' is not a finite number"},
      {kRun + "--dt 1e-3 --set bogus=1" + out, "unknown parameter 'bogus'"},
      {"run --problem bouncing-mass --integrator moreau-jean --t-end 1 --dt 1e-3 --set theta=0.3" + out,
       "parameter 'theta' = 0.3 is outside its valid range [0.5, 1]"},
      {"run --problem nope --integrator cd-lagrange --t-end 1 --dt 1e-3" + out, "unknown problem (valid: "},
      {"run --problem bouncing-mass --integrator nope --t-end 1 --dt 1e-3" + out, "unknown integrator (valid: "},
      {"run --problem bouncing-mass --integrator cd-lagrange --dt 1e-3 --t-end -2" + out, "--t-end -2: must be > 0"},
  };
  for (const auto& [args, message] : cases) {
    CAPTURE(args);
    const auto r = nsbench(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Contains(message));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  CHECK(nsbench("run --problem bouncing-mass").code == 2);  // missing required options
}

TEST_CASE("cli: a run writes series.csv and summary.json", "[app]") {
  const std::string dir = tmpdir("good");
  std::filesystem::remove_all(dir);
  const auto r = nsbench(kRun + "--dt 1e-3 --set e=0.8 --out " + dir);
  REQUIRE(r.code == 0);
  std::ifstream csv(dir + "/series.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header == "t,dt,kinetic,potential,total_energy,min_gap,impulse,active_contacts,q,v,q_exact,v_exact");
  std::ifstream json(dir + "/summary.json");
  const std::string summary((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  CHECK_THAT(summary, Catch::Contains("\"e\": 0.8") && Catch::Contains("\"steps\": 500") &&
                          Catch::Contains("\"cpu_seconds\"") && Catch::Contains("\"max_penetration\"") &&
                          Catch::Contains("\"git_revision\""));
}
