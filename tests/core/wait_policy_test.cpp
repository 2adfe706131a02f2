// The OpenMP waiting policy `nsbench run` runs with (core/wait_policy.hpp): libgomp shows
// what it read at load time under OMP_DISPLAY_ENV=verbose; the last such display is the one
// of the process that runs.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "core/wait_policy.hpp"
#include "tests/app/run_cli.hpp"

namespace {

// The GOMP_SPINCOUNT the libgomp of `nsbench run` read last, with the user's environment
// `env` (OMP_WAIT_POLICY and GOMP_SPINCOUNT unset otherwise).
std::string spin_count(const std::string& env) {
  const auto out = std::filesystem::temp_directory_path() / "nsbench_wait_policy_test";
  const auto r = nsb::test::run_command("env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT " + env + " OMP_DISPLAY_ENV=verbose " +
                                        NSBENCH_CLI + " run --problem bouncing-mass --integrator cd-lagrange --dt 1e-3 "
                                        "--t-end 1e-2 --out " + out.string());
  std::filesystem::remove_all(out);
  REQUIRE(r.code == 0);
  const std::string key = "GOMP_SPINCOUNT = '";
  const auto at = r.output.rfind(key);
  REQUIRE(at != std::string::npos);
  const auto begin = at + key.size();
  return r.output.substr(begin, r.output.find('\'', begin) - begin);
}

}  // namespace

TEST_CASE("wait policy: nsbench run spins kWaitSpinCount turns before it sleeps, unless the user chose", "[core][threads]") {
  CHECK(spin_count("") == nsb::kWaitSpinCount);
  CHECK(spin_count("GOMP_SPINCOUNT=300000") == "300000");  // libgomp's default, asked for
  CHECK(spin_count("OMP_WAIT_POLICY=active") != nsb::kWaitSpinCount);
}
