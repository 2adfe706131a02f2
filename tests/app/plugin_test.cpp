// Plugins as a user meets them: the example plugin (examples/plugin) is listed, runs, and
// is stamped into summary.json; every bad plugin gives one line naming the file and the
// reason, exit 2.
#include <catch2/catch.hpp>
#include <filesystem>
#include <algorithm>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "core/plugin.hpp"
#include "integrators/registry.hpp"
#include "run_cli.hpp"

namespace {

using nsb::test::nsbench_command;
using nsb::test::run_command;
using nsb::test::test_plugin;
namespace fs = std::filesystem;

const std::string kPlugin = NSBENCH_EXAMPLE_PLUGIN;

long lines(const std::string& s) { return std::count(s.begin(), s.end(), '\n'); }

}  // namespace

TEST_CASE("plugin: the example's integrator is listed, runs, and summary.json names the plugin file and hash",
          "[app][plugin]") {
  const auto listed = run_command(nsbench_command("--plugin " + kPlugin + " list"));
  CHECK(listed.code == 0);
  CHECK_THAT(listed.output, Catch::Contains("symplectic-euler") && Catch::Contains("cd-lagrange"));
  // Without the plugin it is unknown.
  CHECK_THAT(run_command(nsbench_command("list")).output, !Catch::Contains("symplectic-euler"));

  const fs::path out = fs::temp_directory_path() / "nsbench_plugin_test_run";
  fs::remove_all(out);
  const auto ran = run_command(nsbench_command("run --plugin " + kPlugin +
                                       " --problem bouncing-mass --integrator symplectic-euler --dt 1e-3 --t-end 1 --out " +
                                       out.string()));
  REQUIRE(ran.code == 0);
  std::ifstream in(out / "summary.json");
  const auto summary = nlohmann::json::parse(in);
  CHECK(summary["integrator"] == "symplectic-euler");
  REQUIRE(summary["build"]["plugins"].size() == 1);
  CHECK(summary["build"]["plugins"][0]["file"] == "symplectic_euler.so");
  CHECK_THAT(summary["build"]["plugins"][0]["hash"].get<std::string>(), Catch::StartsWith("fnv1a64:"));
  CHECK(summary["build"]["plugins"][0]["hash"].get<std::string>().size() == 8 + 16);

  const auto by_env = run_command("NSBENCH_PLUGINS=" + kPlugin + ": " + nsbench_command("list"));
  CHECK(by_env.code == 0);
  CHECK_THAT(by_env.output, Catch::Contains("symplectic-euler"));
  // Named twice (environment and flag): loaded once, no clash with itself.
  CHECK(run_command("NSBENCH_PLUGINS=" + kPlugin + " " + nsbench_command("--plugin " + kPlugin + " list")).code == 0);
}

TEST_CASE("plugin: each plugin's own build is stamped in summary.json and the tables; an unoptimised one is warned about",
          "[app][plugin]") {
  const fs::path out = fs::temp_directory_path() / "nsbench_plugin_test_build";
  const std::string run = " run --problem bouncing-mass --integrator symplectic-euler --dt 1e-3 --t-end 0.1 --out " + out.string();
  const auto plugin_build = [&] {
    std::ifstream in(out / "summary.json");
    const auto summary = nlohmann::json::parse(in);
    REQUIRE(summary["build"]["plugins"].size() == 1);
    return summary["build"]["plugins"][0];
  };
  // Built as nsbench_add_plugin builds it in this tree, with the tree's build type (Release, or
  // the sanitizer build's RelWithDebInfo at -O1): optimised, no warning.
  const std::string build_type = NSBENCH_TEST_BUILD_TYPE;
  fs::remove_all(out);
  const auto optimised = run_command(nsbench_command("--plugin " + kPlugin + run));
  REQUIRE(optimised.code == 0);
  CHECK_THAT(optimised.output, !Catch::Contains("warning"));
  const auto release = plugin_build();
  CHECK(release["build_known"] == true);
  CHECK(release["optimized"] == true);
  CHECK(release["build_type"] == build_type);
  if (build_type == "Release") CHECK_THAT(release["compile_flags"].get<std::string>(), Catch::Contains("-O3"));

  // The same source at -O0 (tests/CMakeLists.txt): stamped so, one warning line naming it.
  const std::string slow = test_plugin("symplectic_euler_O0");
  fs::remove_all(out);
  const auto unoptimised = run_command(nsbench_command("--plugin " + slow + run));
  REQUIRE(unoptimised.code == 0);
  CHECK_THAT(unoptimised.output, Catch::Contains("warning: plugin symplectic_euler_O0.so (" + build_type + ", UNOPTIMISED (-O0), flags "));
  CHECK(lines(unoptimised.output) - lines(optimised.output) == 1);
  const auto debug = plugin_build();
  CHECK(debug["optimized"] == false);
  CHECK_THAT(debug["compile_flags"].get<std::string>(), Catch::Contains(" -O0"));

  // A study's tables carry the stamp, and the study warns too.
  const fs::path reports = fs::temp_directory_path() / "nsbench_plugin_test_build_reports";
  fs::remove_all(reports);
  const std::string study_file = (fs::temp_directory_path() / "nsbench_plugin_test_build.toml").string();
  std::ofstream(study_file) << "[study]\ntitle = \"t\"\nt_end = 0.1\ncpu_repeats = 0\n[[problem]]\nname = \"bouncing-mass\"\n"
                               "[[integrator]]\nname = \"symplectic-euler\"\nsteps = [1e-2]\n[[measure]]\nkind = \"penetration\"\n";
  const auto studied = run_command(std::string(NSBENCH_STUDY_CLI) + " --plugin " + slow + " run " + study_file + " --out " + reports.string());
  REQUIRE(studied.code == 0);
  CHECK_THAT(studied.output, Catch::Contains("nsbench-study: warning: plugin symplectic_euler_O0.so"));
  std::ifstream csv(reports / "nsbench_plugin_test_build_work_precision.csv");
  const std::string table((std::istreambuf_iterator<char>(csv)), std::istreambuf_iterator<char>());
  CHECK_THAT(table, Catch::Contains("# plugins: symplectic_euler_O0.so (fnv1a64:") &&
                        Catch::Contains("; " + build_type + ", UNOPTIMISED (-O0), flags "));
}

TEST_CASE("plugin: a bad plugin gives one line naming the file and the reason, exit 2", "[app][plugin][bad-input]") {
  const std::string not_elf = (fs::temp_directory_path() / "nsbench_plugin_test_not_elf.so").string();
  std::ofstream(not_elf) << "not a shared library\n";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"/nonexistent/plugin.so", "plugin /nonexistent/plugin.so: no such file"},
      {fs::temp_directory_path().string(), "not a regular file"},
      {not_elf, "plugin " + not_elf + ": not a loadable shared library"},
      {test_plugin("not_a_plugin"), "not_a_plugin.so: not an nsbench plugin"},
      {test_plugin("wrong_abi"), "wrong_abi.so: built for plugin ABI 999, this nsbench has ABI " + std::to_string(NSBENCH_PLUGIN_ABI) +
                                     ": rebuild it against this nsbench (CHANGELOG.md, 'Plugin API: what to change',"},
      {test_plugin("clash_builtin"), "clash_builtin.so: integrator 'cd-lagrange' is already registered by nsbench (built-in)"},
      {kPlugin + " --plugin " + test_plugin("clash_example"),
       "clash_example.so: integrator 'symplectic-euler' is already registered by plugin "},
  };
  for (const auto& [plugin, message] : cases) {
    for (const std::string& tool : {nsbench_command("list"), std::string(NSBENCH_STUDY_CLI) + " bouncing",
                                    std::string(NSBENCH_STUDY_CLI) + " list"}) {
      const auto r = run_command(tool + " --plugin " + plugin);
      INFO(tool << " --plugin " << plugin << "\n" << r.output);
      CHECK(r.code == 2);
      CHECK(lines(r.output) == 1);
      CHECK_THAT(r.output, Catch::Contains(message));
    }
  }
  const auto r = run_command("NSBENCH_PLUGINS=" + test_plugin("wrong_abi") + " " + nsbench_command("list"));
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Contains("wrong_abi.so: built for plugin ABI 999"));
}

TEST_CASE("plugin: --plugin (and --plugin=FILE) works before and after the subcommand or the study names",
          "[app][plugin]") {
  const std::string study = NSBENCH_STUDY_CLI;
  for (const std::string& args : {"--plugin " + kPlugin + " list", "list --plugin " + kPlugin, "--plugin=" + kPlugin + " list",
                                  "list --plugin=" + kPlugin}) {
    const auto r = run_command(nsbench_command(args));
    INFO(args << "\n" << r.output);
    CHECK(r.code == 0);
    CHECK_THAT(r.output, Catch::Contains("symplectic-euler"));
  }
  const fs::path out = fs::temp_directory_path() / "nsbench_plugin_test_order";
  const std::string run = "run --problem bouncing-mass --integrator symplectic-euler --dt 1e-3 --t-end 0.1 --out " + out.string();
  for (const std::string& args : {"--plugin " + kPlugin + " " + run, run + " --plugin " + kPlugin, "--plugin=" + kPlugin + " " + run}) {
    const auto r = run_command(nsbench_command(args));
    INFO(args << "\n" << r.output);
    CHECK(r.code == 0);
  }
  // nsbench-study: the words after --plugin FILE are the studies, not more plugins. A study
  // that does not exist shows what was parsed without running one.
  for (const std::string& args : {"--plugin " + kPlugin + " no-such-study", "--plugin=" + kPlugin + " no-such-study",
                                  "no-such-study --plugin " + kPlugin}) {
    const auto r = run_command(study + " " + args);
    INFO(args << "\n" << r.output);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Contains("unknown study 'no-such-study'"));
  }
  const auto file = run_command(study + " --plugin " + kPlugin + " run /nonexistent/f.toml --out " + out.string());
  CHECK(file.code == 2);
  CHECK_THAT(file.output, Catch::Contains("/nonexistent/f.toml"));
  const auto listed = run_command(study + " --plugin " + kPlugin + " list");
  CHECK(listed.code == 0);
  CHECK_THAT(listed.output, Catch::Contains("bouncing"));
}

// Issue 30, finding 5: `head -c 21356 symplectic_euler.so > cut.so; nsbench --plugin cut.so
// list` died of SIGBUS inside dlopen (a segment mapped past the end of the file). A file cut
// anywhere is one line naming it, exit 2.
TEST_CASE("plugin: a truncated plugin file is refused before dlopen, exit 2", "[app][plugin][bad-input][reliability]") {
  std::ifstream in(kPlugin, std::ios::binary);
  const std::string whole((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(whole.size() > 4096);
  const std::string cut = (fs::temp_directory_path() / "nsbench_plugin_test_cut.so").string();
  for (const std::size_t size : {std::size_t{3}, std::size_t{63}, std::size_t{200}, std::size_t{4096}, whole.size() / 2,
                                 whole.size() - 1}) {
    std::ofstream(cut, std::ios::binary | std::ios::trunc) << whole.substr(0, size);
    const auto r = run_command(nsbench_command("--plugin " + cut + " list"));
    INFO(size << " bytes: " << r.output);
    CHECK(r.code == 2);
    CHECK(lines(r.output) == 1);
    CHECK_THAT(r.output, Catch::StartsWith("nsbench: error: plugin " + cut + ": not a loadable shared library ("));
  }
  fs::remove(cut);
}

TEST_CASE("plugin: a plugin refused on its second entry leaves none registered, and is refused again", "[app][plugin][bad-input]") {
  // In this process (the tests load the example plugin first): before, the companion stayed
  // usable, studies with it carried no "# plugins:" stamp, and a second call returned quietly.
  const std::string clash = test_plugin("clash_builtin");
  const std::string why = "integrator 'cd-lagrange' is already registered by nsbench (built-in)";
  CHECK_THROWS_WITH(nsb::load_plugin(clash), Catch::Contains(why));
  CHECK_THROWS_AS(nsb::find_integrator("cd-lagrange-companion"), nsb::InputError);
  CHECK_THROWS_WITH(nsb::load_plugin(clash), Catch::Contains(why));
  for (const auto& p : nsb::loaded_plugins()) CHECK(p.file != "clash_builtin.so");
}
