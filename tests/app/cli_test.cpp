// The command line as a user meets it: bad input exits 2 with one line naming the
// parameter and its valid range; a good run writes series.csv and summary.json.
#include <fcntl.h>
#include <fmt/format.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "core/build_info.hpp"
#include "core/output.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/registry.hpp"
#include "studies/registry.hpp"
#include "studies/verify.hpp"
#include "run_cli.hpp"
#include "tests/support/files.hpp"

namespace {

using nsb::test::Outcome;

Outcome nsbench(const std::string& args) { return nsb::test::run_command(nsb::test::nsbench_command(args)); }

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
  // An optional parameter (moreau-jean's gamma) is listed as unset.
  CHECK_THAT(r.output, Catch::Contains("gamma          default unset      [0, 1]"));
  // Each problem's observables, what a study file's measures name.
  CHECK_THAT(r.output, Catch::Contains("observables (at the defaults): x, v, omega, x_exact, v_exact, omega_exact, slip, slip_exact"));
  CHECK_THAT(r.output, Catch::Contains("observables (at the defaults): x, v, x_exact, v_exact"));
}

TEST_CASE("cli: an unknown integrator or problem hints that a plugin may be missing", "[app][bad-input]") {
  const std::string out = " --out " + tmpdir("plugin-hint");
  for (const auto& [args, kind] : std::vector<std::pair<std::string, std::string>>{
           {"run --problem bouncing-mass --integrator my-scheme --t-end 1 --dt 1e-3" + out, "integrator"},
           {"run --problem my-problem --integrator cd-lagrange --t-end 1 --dt 1e-3" + out, "problem"}}) {
    CAPTURE(args);
    const auto r = nsbench(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Contains("a plugin's " + kind + "? load its file with --plugin FILE or NSBENCH_PLUGINS "
                                         "(plugins loaded: none)"));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
}

TEST_CASE("cli: bad input exits 2 with a message naming the parameter and its range", "[app][bad-input]") {
  const std::string out = " --out " + tmpdir("bad");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {kRun + "--dt -1" + out, "--dt -1: must be > 0"},
      {kRun + "--dt 0" + out, "--dt 0: must be > 0"},
      {kRun + "--dt 1e-3x" + out, "--dt: '1e-3x' is not a finite number"},
      {kRun + "--dt 1e-3 --set e=1.5" + out, "parameter 'e' = 1.5 is outside its valid range [0, 1]"},
      {kRun + "--dt 1e-3 --set e=-0.1" + out, "parameter 'e' = -0.1 is outside its valid range [0, 1]"},
      {kRun + "--dt 1e-3 --set m=abc" + out, "parameter 'm' = 'abc' is not a finite number; valid: (0, inf)"},
      {kRun + "--dt 1e-3 --set bogus=1" + out, "unknown parameter 'bogus'"},
      {"run --problem bouncing-mass --integrator moreau-jean --t-end 1 --dt 1e-3 --set theta=0.3" + out,
       "parameter 'theta' = 0.3 is outside its valid range [0.5, 1]"},
      {"run --problem bouncing-mass --integrator moreau-jean --t-end 1 --dt 1e-3 --set gamma=1.5" + out,
       "parameter 'gamma' = 1.5 is outside its valid range [0, 1]"},
      {"run --problem nope --integrator cd-lagrange --t-end 1 --dt 1e-3" + out, "unknown problem (nearest: "},
      {"run --problem bouncing-mass --integrator nope --t-end 1 --dt 1e-3" + out, "unknown integrator (nearest: "},
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

TEST_CASE("cli: a typo names the nearest option, integrator, problem or parameter, exit 2", "[app][bad-input]") {
  const std::string out = " --out " + tmpdir("typo");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {kRun + "--dt 1e-3 --t-ned 1" + out, "--t-ned: unknown option (nearest: --t-end;"},
      {"--plugn x.so list", "--plugn: unknown option (nearest: --plugin;"},
      {"run --problem bouncing-mass --integrator cd-lagrang --t-end 1 --dt 1e-3" + out,
       "--integrator 'cd-lagrang': unknown integrator (nearest: cd-lagrange;"},
      {"run --problem bouncing-mas --integrator cd-lagrange --t-end 1 --dt 1e-3" + out,
       "--problem 'bouncing-mas': unknown problem (nearest: bouncing-mass;"},
      {kRun + "--dt 1e-3 --set hh0=1" + out, "unknown parameter 'hh0' (nearest: h0;"},
      {kRun + "--dt 1e-3 --set problem.ee=0.5" + out, "unknown parameter 'ee' (nearest: e;"},
  };
  for (const auto& [args, message] : cases) {
    CAPTURE(args);
    const auto r = nsbench(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::Contains(message));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  const auto study = nsb::test::run_command(std::string(NSBENCH_STUDY_CLI) + " bouncin");
  CHECK(study.code == 2);
  CHECK_THAT(study.output, Catch::Contains("unknown study 'bouncin' (nearest: bouncing;"));
  const auto study_option = nsb::test::run_command(std::string(NSBENCH_STUDY_CLI) + " bouncing --verfy reports");
  CHECK(study_option.code == 2);
  CHECK_THAT(study_option.output, Catch::Contains("--verfy: unknown option (nearest: --verify;"));
}

TEST_CASE("cli: a run writes series.csv and summary.json", "[app]") {
  const std::string dir = tmpdir("good");
  std::filesystem::remove_all(dir);
  const auto r = nsbench(kRun + "--dt 1e-3 --set e=0.8 --out " + dir);
  REQUIRE(r.code == 0);
  std::ifstream csv(dir + "/series.csv");
  std::string header;
  std::getline(csv, header);
  CHECK(header == "t,dt,kinetic,potential,total_energy,min_gap,impulse,active_contacts,tangential_impulse,q,v,q_exact,v_exact");
  std::ifstream json(dir + "/summary.json");
  const std::string summary((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  CHECK_THAT(summary, Catch::Contains("\"e\": 0.8") && Catch::Contains("\"steps\": 500") &&
                          Catch::Contains("\"cpu_seconds\"") && Catch::Contains("\"max_penetration\"") &&
                          Catch::Contains("\"version\": \"" NSBENCH_VERSION "\"") && Catch::Contains("\"git_revision\""));
}

TEST_CASE("cli: a run prints the contact impulses' work and the balance residual beside the energy change, or why not",
          "[app][energy_balance]") {
  const std::string dir = tmpdir("balance");
  std::filesystem::remove_all(dir);
  const auto read_summary = [&] {
    std::ifstream json(dir + "/summary.json");
    return nlohmann::json::parse(json);
  };
  // Dissipative (e = 0 node impacts), moreau-jean theta = 1/2: the residual is round-off.
  const auto r = nsbench("run --problem signorini-bar --set N=20 --integrator moreau-jean --dt 0.025 --t-end 4 --out " + dir);
  REQUIRE(r.code == 0);
  INFO(r.output);
  CHECK_THAT(r.output, Catch::Contains("energy change E_end - E0") &&
                           Catch::Contains("energy balance over 160 steps (absolute): energy change ") &&
                           Catch::Contains(" = work of the loads ") && Catch::Contains(" + work of the contact impulses ") &&
                           Catch::Contains(" + residual "));
  const auto summary = read_summary();
  const auto& b = summary["energy_balance"];
  REQUIRE(b["derived"] == true);
  const double change = b["energy_change"], loads = b["load_work"], contact = b["contact_work"], residual = b["residual"],
               round_off = b["round_off"];
  CHECK(std::abs(change - (summary["final_energy"].get<double>() - summary["initial_energy"].get<double>())) <= round_off);
  CHECK(std::abs(change - (loads + contact + residual)) <= round_off);
  CHECK(change < -1e-3 * summary["initial_energy"].get<double>());
  CHECK(std::abs(residual) <= round_off);
  CHECK(summary.contains("final_energy_change"));  // the existing keys stay
  // No balance derived for nsga: said so, on the line and in summary.json.
  const auto n = nsbench("run --problem signorini-bar --set N=20 --integrator nsga --dt 0.025 --t-end 4 --out " + dir);
  REQUIRE(n.code == 0);
  CHECK_THAT(n.output, Catch::Contains("energy balance: not derived for integrator 'nsga'"));
  CHECK(read_summary()["energy_balance"]["derived"] == false);
  std::filesystem::remove_all(dir);
}

TEST_CASE("cli: an integrator that locates events writes events.csv, at the exact impact times", "[app][events]") {
  const std::string dir = tmpdir("events");
  std::filesystem::remove_all(dir);
  const auto r = nsbench("run --problem bouncing-mass --integrator event-driven --dt 0.0137 --t-end 3 --set e=0.8 --out " + dir);
  REQUIRE(r.code == 0);
  std::ifstream csv(dir + "/events.csv");
  REQUIRE(csv);
  std::string line;
  std::getline(csv, line);
  CHECK(line == "t,contact,kind,rate_before,rate_after,impulse");
  const nsb::BouncingMass exact(nsb::Params(nsb::BouncingMass::parameters_spec(), {{"e", "0.8"}}));
  int impacts = 0;
  while (std::getline(csv, line)) {
    const auto f = nsb::parse_csv(line + "\n").at(0);
    REQUIRE(f.size() == 6);
    CHECK(f[1] == "0");
    CHECK(f[2] == "impact");
    ++impacts;
    CAPTURE(impacts);
    CHECK(std::abs(std::stod(f[0]) - exact.impact_time(impacts)) <= 1e-9);
    CHECK(std::stod(f[4]) == Approx(-0.8 * std::stod(f[3])).epsilon(1e-9));          // Newton's law
    CHECK(std::stod(f[5]) == Approx(std::stod(f[4]) - std::stod(f[3])).epsilon(1e-9));  // m = 1
  }
  CHECK(impacts >= 3);
  CHECK(exact.impact_time(impacts + 1) > 3.0);  // all of them
  // A time-stepping scheme locates no events: no events.csv.
  std::filesystem::remove_all(dir);
  REQUIRE(nsbench(kRun + "--dt 1e-3 --out " + dir).code == 0);
  CHECK_FALSE(std::filesystem::exists(dir + "/events.csv"));
}

TEST_CASE("cli: an explicit scheme above its stable step gets one warning line and runs", "[app][guardrails]") {
  const auto bar = nsb::make_problem("signorini-bar");
  const double dt = 1.5 * bar->stable_step();
  const std::string dir = tmpdir("unstable");
  std::filesystem::remove_all(dir);  // an older version's output there is not the suite's own (no marker)
  const auto r = nsbench(fmt::format("run --problem signorini-bar --integrator cd-lagrange --dt {} --t-end {} --out {}", dt,
                                     20 * dt, dir));
  CHECK((r.code == 0 || r.code == 3));  // it ran (an unstable run may be marked diverged)
  CHECK_THAT(r.output, Catch::Contains(fmt::format("warning: --dt {} is above the stable step", dt)) &&
                           Catch::Contains("ratio 1.5"));
  CHECK(std::filesystem::exists(dir + "/summary.json"));
  const auto stable = nsbench(fmt::format("run --problem signorini-bar --integrator cd-lagrange --dt {} --t-end {} --out {}",
                                          0.5 * dt, 20 * dt, dir));
  CHECK(stable.output.find("warning") == std::string::npos);
  const auto implicit = nsbench(fmt::format("run --problem signorini-bar --integrator moreau-jean --dt {} --t-end {} --out {}",
                                            dt, 20 * dt, dir));
  CHECK(implicit.output.find("warning") == std::string::npos);
}

// Issue 56, finding 14: a 1e8-element bar assembles and binds for about a minute before its
// first step, in silence. A problem that takes 3.5 s to build (tests/plugins/slow_setup.cpp)
// shows one line meanwhile; a quick run shows none.
TEST_CASE("cli: a run whose preparation is long says so every 3 s until its steps start", "[app][guardrails]") {
  const std::string dir = tmpdir("slow_setup");
  const auto slow = nsbench(fmt::format("--plugin {} run --problem slow-setup --integrator cd-lagrange --dt 0.1 --t-end 0.2 --out {}",
                                        nsb::test::test_plugin("slow_setup"), dir));
  INFO(slow.output);
  CHECK(slow.code == 0);
  CHECK_THAT(slow.output, Catch::Contains("nsbench: preparing the run: building the problem, elapsed 3 s\n"));
  const auto quick = nsbench(fmt::format("run --problem bouncing-mass --integrator cd-lagrange --dt 0.1 --t-end 0.2 --out {}", dir));
  CHECK(quick.output.find("preparing the run") == std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST_CASE("cli: SIGTERM stops a run: exit 143, its files whole (status interrupted), no temporaries", "[app][guardrails]") {
  const std::string dir = tmpdir("sigterm");
  std::filesystem::remove_all(dir);
  // An earlier run's leftovers (issue 20): a killed run's temporary (its pid above any
  // pid_max: no such process) and an events.csv this run does not make. Both go.
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/" + nsb::kOutputMarker) << "nsbench output\n";
  const std::string stale = dir + "/.series.csv.tmp.4194305";
  std::ofstream(stale) << "t,dt\n";
  std::ofstream(dir + "/events.csv") << "t\n";
  const pid_t child = fork();
  REQUIRE(child >= 0);
  if (child == 0) {  // a run of 2e8 steps, minutes long
    const int devnull = open("/dev/null", O_WRONLY);
    dup2(devnull, STDERR_FILENO);
    dup2(devnull, STDOUT_FILENO);
    execl(NSBENCH_CLI, NSBENCH_CLI, "run", "--problem", "bouncing-mass", "--integrator", "cd-lagrange", "--dt", "1e-5",
          "--t-end", "2000", "--sample-every", "1000000", "--out", dir.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // The staging directory is made just before the handlers are installed and the run starts.
  const auto staging = std::filesystem::temp_directory_path() / (".nsbench_cli_test_sigterm.staging." + std::to_string(child));
  for (int k = 0; k < 1000 && !std::filesystem::exists(staging); ++k) usleep(10'000);
  usleep(300'000);
  kill(child, SIGTERM);
  int status = 0;
  pid_t done = 0;
  for (int k = 0; k < 1000 && done == 0; ++k) {  // up to 10 s
    done = waitpid(child, &status, WNOHANG);
    if (done == 0) usleep(10'000);
  }
  if (done == 0) kill(child, SIGKILL), waitpid(child, &status, 0);
  REQUIRE(done == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 128 + SIGTERM);
  std::vector<std::string> files;
  for (const auto& f : std::filesystem::directory_iterator(dir)) files.push_back(f.path().filename().string());
  std::sort(files.begin(), files.end());
  CHECK(files == std::vector<std::string>{nsb::kOutputMarker, "series.csv", "summary.json"});
  CHECK_FALSE(std::filesystem::exists(staging));
  std::ifstream json(dir + "/summary.json");
  const std::string summary((std::istreambuf_iterator<char>(json)), std::istreambuf_iterator<char>());
  CHECK_THAT(summary, Catch::Contains("\"status\": \"interrupted\"") && Catch::EndsWith("}\n"));
  // The series ends at the summary's last step, whatever --sample-every (1e6 here).
  std::ifstream csv(dir + "/series.csv");
  std::string line, last;
  while (std::getline(csv, line)) last = line;
  const double t_last = std::stod(last.substr(0, last.find(',')));
  const auto j = nlohmann::json::parse(summary);
  CHECK(t_last == j["t_final"].get<double>());
  CHECK(j["steps"].get<long>() % 1000000 != 0);  // else the test shows nothing
}

TEST_CASE("cli: a step larger than t_end and a read-only --out are refused before the run", "[app][bad-input]") {
  auto r = nsbench("run --problem bouncing-mass --integrator cd-lagrange --dt 16 --t-end 1 --out " + tmpdir("dt16"));
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Contains("--dt 16 is larger than --t-end 1; valid: dt <= t_end"));
  // /proc/self exists and takes no new file, even for root.
  r = nsbench(kRun + "--dt 1e-3 --out /proc/self");
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::StartsWith("nsbench: error: --out '/proc/self': cannot write files there"));
  r = nsb::test::run_command(fmt::format("NSBENCH_JOBS=abc '{}' bouncing --out {}", NSBENCH_STUDY_CLI, tmpdir("jobs")));
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Contains("NSBENCH_JOBS='abc': expected a whole number"));
  r = nsb::test::run_command(fmt::format("'{}' bouncing --out /proc/self", NSBENCH_STUDY_CLI));
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Contains("--out '/proc/self': cannot write files there"));
}

TEST_CASE("cli: --fields writes ParaView files and changes nothing else; bad field options exit 2 before the run",
          "[app][fields]") {
  const std::string run = "run --problem block-2d --integrator cd-lagrange --dt 1e-4 --t-end 0.02 --set nx=4 --set ny=2 ";
  const std::string plain = tmpdir("fields_plain"), out = tmpdir("fields_out"), fields = tmpdir("fields_dir");
  for (const auto& d : {plain, out, fields}) std::filesystem::remove_all(d);
  REQUIRE(nsbench(run + "--sample-every 10 --out " + plain).code == 0);
  REQUIRE(nsbench(run + "--sample-every 10 --out " + out + " --fields " + fields).code == 0);
  const auto read = [](const std::string& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  CHECK(read(plain + "/series.csv") == read(out + "/series.csv"));
  auto a = nlohmann::json::parse(read(plain + "/summary.json")), b = nlohmann::json::parse(read(out + "/summary.json"));
  for (const char* timing : {"cpu_seconds", "step_cpu_seconds", "wall_seconds"}) {
    a.erase(timing);
    b.erase(timing);
  }
  CHECK(a == b);
  // Every 10th of 200 steps by default (--sample-every), the first and the last.
  std::size_t files = 0;
  for (const auto& e : std::filesystem::directory_iterator(fields)) files += e.path().extension() == ".vtu";
  CHECK(files == 21);
  CHECK_THAT(read(fields + "/fields.pvd"), Catch::Contains("timestep=\"0\"") && Catch::Contains("fields_000020.vtu"));

  const std::vector<std::pair<std::string, std::string>> bad = {
      {run + "--out " + out + " --fields " + fields + " --fields-every 0", "--fields-every 0: must be an integer >= 1"},
      {run + "--out " + out + " --fields-every 5", "--fields-every 5: given without --fields DIR"},
      {run + "--out " + out + " --fields " + out, "--fields '" + out + "': is, contains or is in --out"},
      {run + "--out " + out + " --fields " + out + "/fields", "--fields '" + out + "/fields': is, contains or is in --out"},
  };
  for (const auto& [args, message] : bad) {
    const auto r = nsbench(args);
    INFO(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::StartsWith("nsbench: error: " + message.substr(0, 12)) && Catch::Contains(message));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  for (const auto& d : {plain, out, fields}) std::filesystem::remove_all(d);
}

// Issue 30, finding 1: an --out or --fields directory the suite did not write came back
// re-permissioned, its FIFOs and symlinks deleted, exit 0. Refused, untouched.
TEST_CASE("cli: an --out or --fields directory the suite did not write is refused, untouched", "[app][bad-input][reliability]") {
  namespace fs = std::filesystem;
  const std::string d = tmpdir("foreign");
  fs::remove_all(d);
  fs::create_directories(d + "/private");
  fs::permissions(d, fs::perms(01777));
  fs::permissions(d + "/private", fs::perms(0700));
  REQUIRE(::mkfifo((d + "/fifo").c_str(), 0600) == 0);
  fs::create_symlink("nowhere", d + "/dg");
  const auto study = nsb::test::run_command(fmt::format("'{}' run {}/studies/examples/bouncing_quick.toml --out {}",
                                                         NSBENCH_STUDY_CLI, NSBENCH_SOURCE_DIR, d));
  CHECK(study.code == 2);
  CHECK(study.output == "nsbench-study: error: --out '" + d + "': not empty and not an nsbench output directory (no " +
                            nsb::kOutputMarker + " file); the suite replaces its output directory whole and writes only "
                            "into a new or empty directory or one it wrote; valid: a new directory\n");
  const auto fields = nsbench("run --problem block-2d --integrator cd-lagrange --dt 1e-4 --t-end 2e-3 --set nx=2 --set ny=2 "
                              "--out " + tmpdir("foreign_out") + " --fields " + d);
  CHECK(fields.code == 2);
  CHECK_THAT(fields.output, Catch::StartsWith("nsbench: error: --fields '" + d + "': not empty and not an nsbench output"));
  CHECK(fs::status(d).permissions() == fs::perms(01777));
  CHECK(fs::status(d + "/private").permissions() == fs::perms(0700));
  CHECK(fs::is_fifo(fs::symlink_status(d + "/fifo")));
  CHECK(fs::is_symlink(fs::symlink_status(d + "/dg")));
  fs::remove_all(d);
  fs::remove_all(tmpdir("foreign_out"));
}

// Issue 30, finding 4: series.csv was renamed into place before summary.json was written, so
// a kill or a failed write between them left a new series beside the old summary. Here the
// summary cannot be written (a directory stands in its place): nothing of the run is.
TEST_CASE("cli: a run's files are swapped in together or not at all", "[app][reliability]") {
  namespace fs = std::filesystem;
  const std::string dir = tmpdir("whole");
  fs::remove_all(dir);
  REQUIRE(nsbench(kRun + "--dt 1e-3 --set e=0.8 --out " + dir).code == 0);
  const auto read = [](const std::string& path) {
    std::ifstream in(path);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  };
  const std::string series = read(dir + "/series.csv");
  fs::remove(dir + "/summary.json");
  fs::create_directories(dir + "/summary.json");
  std::ofstream(dir + "/summary.json/kept") << "x";
  const auto r = nsbench(kRun + "--dt 1e-3 --set e=0.5 --out " + dir);
  CHECK(r.code == 2);
  CHECK_THAT(r.output, Catch::Contains("cannot write") && Catch::Contains("summary.json"));
  CHECK(read(dir + "/series.csv") == series);
  CHECK(fs::exists(dir + "/summary.json/kept"));
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path()))
    CHECK(e.path().filename().string().rfind(".nsbench_cli_test_whole.staging.", 0) == std::string::npos);
  fs::remove_all(dir);
}

namespace {

// A study file of a second or less: the bouncing mass against a cached event-driven reference.
std::string write_quick_study(const std::string& dir, const std::string& name) {
  std::filesystem::create_directories(dir);
  const std::string path = dir + "/" + name + ".toml";
  std::ofstream(path) << "[study]\ntitle = \"" << name << "\"\nt_end = 0.6\ncpu_repeats = 0\n\n"
                      << "[[problem]]\nname = \"bouncing-mass\"\n\n"
                      << "[[integrator]]\nname = \"cd-lagrange\"\nsteps = [1e-2, 5e-3]\n\n"
                      << "[reference]\nintegrator = \"event-driven\"\ndt = 1e-3\n\n[[measure]]\nkind = \"error\"\n"
                      << "observable = \"q\"\n";
  return path;
}

Outcome study(const std::string& args) { return nsb::test::run_command(fmt::format("'{}' {}", NSBENCH_STUDY_CLI, args)); }

}  // namespace

// Issue 30, finding 3: NSBENCH_REFERENCE_CACHE=/proc/x (or a regular file) threw out of the
// study (SIGABRT) and left .OUT.staging.PID. The cache only saves time: warned, computed.
TEST_CASE("cli: an unusable reference cache is a warning, the study runs and leaves no staging", "[app][reliability]") {
  namespace fs = std::filesystem;
  const std::string dir = tmpdir("cache"), out = dir + "/out";
  fs::remove_all(dir);
  const std::string file = write_quick_study(dir, "quick");
  std::ofstream(dir + "/plain_file") << "x";
  for (const std::string& cache : {std::string("/proc/x"), dir + "/plain_file"}) {
    const auto r = nsb::test::run_command(fmt::format("NSBENCH_REFERENCE_CACHE={} '{}' run {} --out {}", cache,
                                                      NSBENCH_STUDY_CLI, file, out));
    INFO(r.output);
    CHECK(r.code == 0);
    CHECK_THAT(r.output, Catch::Contains("nsbench: warning: reference cache " + cache + ": cannot create the directory"));
    CHECK(fs::exists(out + "/quick_work_precision.csv"));
    for (const auto& e : fs::directory_iterator(dir)) CHECK(e.path().filename().string().find("staging") == std::string::npos);
  }
  fs::remove_all(dir);
}

// Issue 57, item 5: a study built from changed sources says which, once, as nsbench run does
// (tests/core/build_info_test.cpp); a clean build says nothing.
TEST_CASE("cli: a study from a dirty build names the changed files once; a clean build says nothing", "[app][build_info]") {
  namespace fs = std::filesystem;
  const std::string dir = tmpdir("dirty_note"), out = dir + "/out";
  fs::remove_all(dir);
  const auto r = study("run " + write_quick_study(dir, "quick") + " --out " + out);
  INFO(r.output);
  REQUIRE(r.code == 0);
  const nsb::BuildInfo& b = nsb::build_info();
  const std::string note = fmt::format("nsbench-study: note: built from revision {} with changes to {}\n", b.git_revision, b.dirty_files);
  if (!b.dirty_files.empty()) {
    CHECK(r.output.find(note) != std::string::npos);
    CHECK(r.output.find(note) == r.output.rfind(note));
  } else {
    CHECK(r.output.find("note: built from") == std::string::npos);
  }
  fs::remove_all(dir);
}

// Issue 30, finding 10: a second study into the same --out rewrote index.md to list only itself;
// figures.json kept only the last run's figures until the index parts carried them too.
TEST_CASE("cli: index.md and figures.json list every study of the --out, not only the last run's", "[app][reliability]") {
  namespace fs = std::filesystem;
  const std::string dir = tmpdir("index"), out = dir + "/out";
  fs::remove_all(dir);
  REQUIRE(study("run " + write_quick_study(dir, "first") + " --out " + out).code == 0);
  REQUIRE(study("run " + write_quick_study(dir, "second") + " --out " + out).code == 0);
  const std::string index = nsb::test::read_text(out + "/index.md");
  CHECK_THAT(index, Catch::Contains("\n## first\n") && Catch::Contains("\n## second\n") &&
                        Catch::Contains("(first_work_precision.md)") && Catch::Contains("(second_work_precision.md)"));
  REQUIRE(study("run " + write_quick_study(dir, "first") + " --out " + out).code == 0);  // rerun: listed once
  const std::string rerun = nsb::test::read_text(out + "/index.md");
  CHECK(rerun.find("\n## first\n") == rerun.rfind("\n## first\n"));
  CHECK_THAT(rerun, Catch::Contains("\n## second\n"));
  const nlohmann::json figures = nlohmann::json::parse(nsb::test::read_text(out + "/figures.json"));
  std::vector<std::string> ids;
  for (const auto& f : figures) ids.push_back(f["id"]);
  CHECK(std::count(ids.begin(), ids.end(), "first_work_precision") == 1);
  CHECK(std::count(ids.begin(), ids.end(), "second_work_precision") == 1);
  fs::remove_all(dir);
}

// The performance table edited index.md in place and kept no index part: the next study run
// into the same --out rewrote index.md from the parts and its performance section was gone.
TEST_CASE("cli: the performance section of index.md survives a later study run into the --out", "[app][reliability]") {
  namespace fs = std::filesystem;
  const std::string dir = tmpdir("performance_index"), out = dir + "/out";
  fs::remove_all(dir);
  REQUIRE(study("run " + write_quick_study(dir, "first") + " --out " + out).code == 0);
  const nlohmann::json step = {{"name", "BM_Step/a/1000"}, {"run_name", "BM_Step/a/1000"}, {"run_type", "iteration"},
                               {"real_time", 1.0}, {"cpu_time", 1.0}, {"time_unit", "us"}, {"units", 1000.0},
                               {"limit_ns", 250.0}, {"threads", 1}, {"run_threads", 1}, {"label", "limit: a triad"}};
  const nlohmann::json bench = {{"context", {{"executable", "/x/build/studies/nsbench-bench-bar"}, {"num_cpus", 2}}},
                                {"benchmarks", {step}}};
  std::ofstream(dir + "/bench.json") << bench.dump();
  REQUIRE(study("performance " + dir + "/bench.json --out " + out).code == 0);
  REQUIRE(study("run " + write_quick_study(dir, "second") + " --out " + out).code == 0);
  const std::string index = nsb::test::read_text(out + "/index.md");
  CHECK_THAT(index, Catch::Contains("\n## performance\n") && Catch::Contains("(performance.md)") &&
                        Catch::Contains("\n## first\n") && Catch::Contains("\n## second\n"));
  fs::remove_all(dir);
}

// Issue 30, finding 10: a repeated --set key took the last value, an empty --fields or
// --shard was ignored, --rtol nan was accepted, h0 = 0 printed "energy error nan", and an
// overflow exited 3 without naming the parameter.
TEST_CASE("cli: repeated --set keys, empty values, non-finite tolerances and overflows are named", "[app][bad-input][reliability]") {
  const std::string out = tmpdir("smaller");
  const std::vector<std::pair<std::string, std::string>> refused = {
      {kRun + "--dt 1e-3 --set e=0.9 --set e=0.5 --out " + out,
       "nsbench: error: --set e=0.5: parameter 'e' is already set by --set e=0.9; valid: each parameter once"},
      {kRun + "--dt 1e-3 --set e=0.9 --set problem.e=0.5 --out " + out,
       "nsbench: error: --set problem.e=0.5: parameter 'e' is already set by --set e=0.9"},
      {kRun + "--dt 1e-3 --out " + out + " --fields ''", "nsbench: error: --fields '': an empty value"},
      {kRun + "--dt 1e-3 --set v0=1e308 --out " + out,
       "nsbench: error: problem bouncing-mass: its initial state is not finite (energy inf): a parameter overflows; "
       "parameters given: --set v0=1e308"},
  };
  for (const auto& [args, message] : refused) {
    const auto r = nsbench(args);
    INFO(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::StartsWith(message));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  for (const auto& [args, message] : std::vector<std::pair<std::string, std::string>>{
           {"bouncing --shard '' --out " + out, "nsbench-study: error: --shard '': an empty value"},
           {"bouncing --verify reports --rtol nan", "nsbench-study: error: --rtol nan: must be a finite number >= 0"},
           {"bouncing --verify reports --atol nan", "nsbench-study: error: --atol nan: must be a finite number >= 0"}}) {
    const auto r = study(args);
    INFO(args);
    CHECK(r.code == 2);
    CHECK_THAT(r.output, Catch::StartsWith(message));
    CHECK(std::count(r.output.begin(), r.output.end(), '\n') == 1);
  }
  const auto rest = nsbench(kRun + "--dt 1e-3 --set h0=0 --out " + out);
  CHECK(rest.code == 0);
  CHECK_THAT(rest.output, Catch::Contains("energy change E_end - E0 n/a (largest |E - E0| n/a; E0 = 0 and bouncing-mass has no energy "
                                                          "scale)") &&
                              !Catch::Contains("nan"));
  std::filesystem::remove_all(out);
}

TEST_CASE("cli: nsbench-study list names each study's file and what it is written in; show prints a study file, refuses a C++ study and an unknown name", "[app]") {
  const auto list = study("list");
  CHECK(list.code == 0);
  CHECK_THAT(list.output, Catch::Contains("[study file: studies/builtin/bar.toml]") && Catch::Contains("[C++: studies/block.cpp]") &&
                              Catch::Contains("[Python: studies/builtin/peers.py]"));
  for (const auto& s : nsb::study_registry()) CHECK_THAT(list.output, Catch::Contains(s.name) && Catch::Contains(s.source + "]"));
  const auto cpp = study("show block");
  CHECK(cpp.code == 2);
  CHECK_THAT(cpp.output, Catch::Contains("show block: written in C++ (studies/block.cpp), not a study file; valid: "));
  const auto unknown = study("show bouncin");
  CHECK(unknown.code == 2);
  CHECK_THAT(unknown.output, Catch::Contains("show: unknown study 'bouncin' (nearest: bouncing)"));
  CHECK(study("show").code == 2);
  // A study file's text, byte for byte as committed, from any directory.
  const auto shown = nsb::test::run_command(fmt::format("cd / && '{}' show precision", NSBENCH_STUDY_CLI));
  CHECK(shown.code == 0);
  std::ifstream in(std::string(NSBENCH_SOURCE_DIR) + "/studies/builtin/precision.toml", std::ios::binary);
  CHECK(shown.output == std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()));
}
