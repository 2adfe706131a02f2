// `nsbench check`: every built-in integrator holds the generic properties (in process: the
// library's check_integrator, the same code the command runs); the example plugin passes
// through the command; the broken test plugin (tests/plugins/broken.cpp) fails it, the
// properties it breaks named.
#include <catch2/catch.hpp>
#include <filesystem>
#include <string>

#include "check/conformance.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "run_cli.hpp"
#include "tests/integrators/every_integrator.hpp"

namespace {

using nsb::test::nsbench_command;
using nsb::test::run_command;
using nsb::test::test_plugin;


// The line of `property` in check's output.
std::string line_of(const std::string& output, const std::string& property) {
  const auto at = output.find("  " + property + " ");
  if (at == std::string::npos) return "";
  return output.substr(at, output.find('\n', at) - at);
}

}  // namespace

TEST_CASE("check: every built-in integrator holds every measured property", "[app][check]") {
  for (const auto& entry : nsb::integrator_registry()) {
    DYNAMIC_SECTION(entry.name) {
      // The physics engines keep their own contact laws (tests/peers/engines_test.cpp bounds
      // them); `nsbench check` shows where they differ from the exact ones.
      if (nsb::testing::is_engine_peer(entry.name)) continue;
      for (const auto& v : nsb::check_integrator(entry)) {
        INFO(entry.name << ": " << v.property << " " << nsb::outcome_name(v.outcome) << " " << v.figure);
        // newmark-lm gains energy on the Signorini bar: the check says so (tests/check/conformance_test.cpp).
        if (entry.name == "newmark-lm" && v.property == "deformable") continue;
        CHECK(v.outcome != nsb::CheckVerdict::Outcome::Fail);
      }
    }
  }
}

TEST_CASE("check: every built-in problem holds its contract; the command checks one", "[app][check]") {
  for (const auto& entry : nsb::problem_registry()) {
    DYNAMIC_SECTION(entry.name) {
      for (const auto& v : nsb::check_problem(entry)) {
        INFO(entry.name << ": " << v.property << " " << nsb::outcome_name(v.outcome) << " " << v.figure);
        CHECK(v.outcome == nsb::CheckVerdict::Outcome::Pass);
      }
    }
  }
  const auto r = run_command(nsbench_command("check --problem block-2d"));
  INFO(r.output);
  CHECK(r.code == 0);
  CHECK_THAT(line_of(r.output, "force = dV/du"), Catch::Contains(" pass "));
}

TEST_CASE("check: the example plugin passes, one line per property with its figure", "[app][check][plugin]") {
  const auto r = run_command(nsbench_command("check --plugin " + std::string(NSBENCH_EXAMPLE_PLUGIN) + " --integrator symplectic-euler"));
  INFO(r.output);
  CHECK(r.code == 0);
  for (const char* p : {"impulse sign", "open contacts", "impact times", "flight energies", "step counters", "momentum",
                        "order", "bad parameters", "determinism", "friction", "allocation"})
    CHECK_THAT(line_of(r.output, p), Catch::Contains(" pass ") || Catch::Contains("not measured"));
  CHECK_THAT(line_of(r.output, "impulse sign"), Catch::Contains(" pass "));
  CHECK_THAT(line_of(r.output, "order"), Catch::Contains(" pass "));
}

TEST_CASE("check: the broken plugin fails, naming the impulse sign and the step counters", "[app][check][plugin]") {
  const auto r = run_command(nsbench_command("--plugin " + test_plugin("broken") + " check --integrator broken"));
  INFO(r.output);
  CHECK(r.code == 1);
  CHECK_THAT(line_of(r.output, "impulse sign"), Catch::Contains("FAIL"));
  CHECK_THAT(line_of(r.output, "step counters"), Catch::Contains("FAIL"));
  CHECK_THAT(line_of(r.output, "momentum"), Catch::Contains(" pass "));  // its motion is CD-Lagrange's
}

TEST_CASE("check: the broken plugin's problem fails on its field mesh, naming the dof", "[app][check][plugin]") {
  const auto r = run_command(nsbench_command("--plugin " + test_plugin("broken") + " check --problem broken-mesh"));
  INFO(r.output);
  CHECK(r.code == 1);
  CHECK_THAT(line_of(r.output, "field mesh"), Catch::Contains("FAIL") && Catch::Contains("a point dof outside [-1, ndof = 1)"));
  CHECK_THAT(line_of(r.output, "mass"), Catch::Contains(" pass "));  // the rest of it is sound
  const auto fields = run_command(nsbench_command("--plugin " + test_plugin("broken") +
                                          " run --problem broken-mesh --integrator cd-lagrange --dt 0.1 --t-end 0.2"
                                          " --out /tmp/nsbench_check_test_broken_mesh --fields /tmp/nsbench_check_test_broken_mesh_fields"));
  CHECK(fields.code == 2);  // and --fields refuses it with the same line
  CHECK_THAT(fields.output, Catch::Contains("a point dof outside [-1, ndof = 1)"));
  std::filesystem::remove_all("/tmp/nsbench_check_test_broken_mesh");
  std::filesystem::remove_all("/tmp/nsbench_check_test_broken_mesh_fields");
}

TEST_CASE("check: an unknown integrator names the nearest, exit 2", "[app][check][bad-input]") {
  const auto r = run_command(nsbench_command("check --integrator cd-lagrang"));
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Contains("--integrator 'cd-lagrang': unknown integrator (nearest: cd-lagrange;"));
  CHECK(run_command(nsbench_command("check")).code == 2);
}

// Issue 57, item 1: a point mass in a curved 3D bowl (examples/plugin/bowl.cpp, built with its
// skewed variant as tests/plugins/bowl.cpp). Its correct
// rows, orthonormal tangents that are no gradients, failed "T against d s"; they pass against
// the contact point's motion, at its defaults and at parameters given with --set, and a second
// tangent neither unit nor orthogonal (the only rows the old check passed) fails, saying what
// to change.
TEST_CASE("check --problem: curved 3D obstacles pass with orthonormal tangents, fail with skewed ones; --set", "[app][check][plugin]") {
  const std::string bowl = "--plugin " + test_plugin("bowl") + " check --problem ";
  for (const std::string sets : {"", " --set x0=-0.6 --set y0=0.45 --set R=0.5 --set h0=0.02"}) {
    const auto r = run_command(nsbench_command(bowl + "bowl" + sets));
    INFO(r.output);
    CHECK(r.code == 0);
    CHECK_THAT(line_of(r.output, "contact rows"), Catch::Contains(" pass ") && Catch::Contains("1 contacts moving, 6 configurations") &&
                                                       Catch::Contains("T, T2 against the contact points' velocity, worst"));
  }
  const auto skewed = run_command(nsbench_command(bowl + "bowl-skewed"));
  INFO(skewed.output);
  CHECK(skewed.code == 1);
  const std::string rows = line_of(skewed.output, "contact rows");
  CHECK_THAT(rows, Catch::Contains("FAIL") && Catch::Contains("fix: T, T2 along two orthonormal tangents orthogonal to the normal"));
  CHECK_THAT(rows, !Catch::Contains("L(U) = dg/dU"));  // its L is right
  CHECK_THAT(line_of(skewed.output, "mass"), Catch::Contains(" pass "));
}

TEST_CASE("check --set: a bad value or key is one line naming it, exit 2; without --problem refused", "[app][check][bad-input]") {
  const std::string bowl = "--plugin " + test_plugin("bowl") + " check --problem bowl --set ";
  const auto negative = run_command(nsbench_command(bowl + "R=-1"));
  CHECK(negative.code == 2);
  CHECK_THAT(negative.output, Catch::Contains("R") && Catch::Contains("-1"));
  const auto unknown = run_command(nsbench_command(bowl + "radius=1"));
  CHECK(unknown.code == 2);
  CHECK_THAT(unknown.output, Catch::Contains("radius"));
  const auto alone = run_command(nsbench_command("check --integrator cd-lagrange --set e=0.5"));
  CHECK(alone.code == 2);
  CHECK_THAT(alone.output, Catch::Contains("check --set e=0.5: sets a parameter of the problem checked; valid: with --problem NAME"));
}
