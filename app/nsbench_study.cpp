// nsbench-study: runs the registered studies and writes their reports.
//
//   nsbench-study list                                             the studies, each with the file that defines it
//   nsbench-study show NAME                                        the text of a built-in study file (studies/builtin/)
// Every form takes --plugin FILE (repeatable) and reads NSBENCH_PLUGINS (core/plugin.hpp).
//   nsbench-study all|NAME... [--out DIR] [--full]                 run, write the reports
//   nsbench-study all|NAME... [--out DIR] [--full] --shard I/N     run shard I of N only
//   nsbench-study all|NAME... [--out DIR] [--full] --merge         merge the N shards, write
//   nsbench-study all|NAME... [--full] --verify DIR [--rtol R] [--atol A]
//                                  recompute, compare with the report in DIR (studies/verify.hpp),
//                                  print the differences; exit 1 when there are any
//   nsbench-study run FILE.toml [--out DIR] [--shard I/N | --merge]  a study from a file
//                                                                  (studies/study_file.hpp)
//   nsbench-study performance BENCH.json... [--out DIR]  the performance table from the
//                                  benchmarks' JSON output (studies/performance.hpp)
//
// Reports: DIR/<table>.csv, .md, .tex for every table, DIR/figures.json (the figures for
// scripts/figures.py) and DIR/index.md linking them, opening with the lead tables (the claims)
// and the headline tables (the rankings) in full, listing every study of DIR: each study's
// entries are kept in DIR/.index/<study>.json, so a run of one study keeps the others listed.
// Shards: DIR/shards/<study>-I-of-N.json. DIR is the suite's own (core/output.hpp,
// kOutputMarker): a directory it did not write is refused.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>

#include "app/cli_options.hpp"
#include "core/build_info.hpp"
#include "core/environment.hpp"
#include "core/json.hpp"
#include "core/output.hpp"
#include "core/parameters.hpp"
#include "core/plugin.hpp"
#include "studies/driver.hpp"
#include "studies/parallel.hpp"
#include "studies/performance.hpp"
#include "studies/report_index.hpp"
#include "studies/shard.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include "studies/verify.hpp"
#include "studies/study_file.hpp"

namespace {

using nsb::InputError;
using nsb::Json;
namespace fs = std::filesystem;

// Writes the performance table into `out` and lists it in out/index.md when that exists
// (written by the studies before the benchmarks run), keeping its section as an index part
// (.index/performance.json, studies/report_index.hpp) so that a later study run into `out`
// lists it too.
void write_performance(const std::vector<std::string>& files, const fs::path& out) {
  const nsb::Table table = nsb::performance_table(std::vector<fs::path>(files.begin(), files.end()));
  nsb::StudyEntry performance;
  performance.name = "performance";
  performance.description = "The benchmarks (nsbench-bench-*), each step against its limit.";
  nsb::ensure_directory(out);
  const std::string section = nsb::ReportIndex(false, out).add_study(performance, {table});
  const fs::path index = out / "index.md";
  if (!fs::exists(index)) return;
  std::ifstream in(index);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.find(section) != std::string::npos) return;
  const auto footer = text.rfind("---\n");  // the environment footer stays last
  text.insert(footer == std::string::npos ? text.size() : footer, section);
  nsb::write_file_atomic(index, text);
}

// `nsbench-study show NAME`: the text of a built-in study file, to copy and edit.
void show_study_file(const std::vector<nsb::StudyEntry>& registry, const std::vector<std::string>& names) {
  std::vector<std::string> files, studies;
  for (const auto& s : registry) {
    studies.push_back(s.name);
    if (nsb::builtin_study_file(s.source)) files.push_back(s.name);
  }
  const std::string valid = files.empty() ? "none (every built-in study is C++)" : fmt::format("{}", fmt::join(files, ", "));
  if (names.size() != 2) throw InputError(fmt::format("show: give one study (nsbench-study show NAME); valid: {}", valid));
  const auto it = std::find_if(registry.begin(), registry.end(), [&](const nsb::StudyEntry& s) { return s.name == names[1]; });
  if (it == registry.end())
    throw InputError(fmt::format("show: unknown study '{}' (nearest: {}); valid: {}", names[1], nsb::nearest_name(names[1], studies), valid));
  const nsb::EmbeddedStudyFile* file = nsb::builtin_study_file(it->source);
  if (!file) throw InputError(fmt::format("show {}: written in C++ ({}), not a study file; valid: {}", names[1], it->source, valid));
  fmt::print("{}", file->text);
}

// The directory that holds the Python package nsbench for this executable: build/python beside
// build/studies/nsbench-study, or the installed one (NSBENCH_PYTHON_DIR).
[[maybe_unused]] fs::path python_module_dir(const nsb::StudyEntry& s) {
  std::error_code ec;
  const fs::path bin = fs::read_symlink("/proc/self/exe", ec).parent_path();
#ifdef NSBENCH_PYTHON_FROM_BIN
  for (const fs::path& dir : {bin / ".." / "python", bin / NSBENCH_PYTHON_FROM_BIN})
    if (fs::exists(dir / "nsbench" / "__init__.py", ec)) return fs::weakly_canonical(dir, ec);
#endif
  throw InputError(fmt::format("study {} is written in Python ({}): no Python module nsbench beside {} (build it: "
                               "cmake --build BUILD --target nsbench_python, with NSBENCH_PYTHON=ON)", s.name, s.source,
                               bin.string()));
}

// A Python study (StudyEntry::script) run as `python3 -c SCRIPT OPTIONS...`: the options of this
// run, the module beside this executable first on PYTHONPATH, signals unblocked (the report
// directory of the C++ studies blocks them in this process: core/output.hpp). Its exit status.
int run_python_study(const nsb::StudyEntry& s, const std::vector<std::string>& options) {
#ifndef NSBENCH_PYTHON_EXECUTABLE
  (void)options;
  throw InputError(fmt::format("study {} is written in Python ({}): this build has no Python module (NSBENCH_PYTHON=OFF)",
                               s.name, s.source));
#else
  const fs::path module = python_module_dir(s);
  const char* old = std::getenv("PYTHONPATH");
  ::setenv("PYTHONPATH", (module.string() + (old && *old ? std::string(":") + old : "")).c_str(), 1);
  ::setenv("NSBENCH_STUDY_COMMAND", nsb::command_line().c_str(), 1);  // the report's footer names this command
  std::vector<std::string> args = {NSBENCH_PYTHON_EXECUTABLE, "-c", std::string(s.script)};
  args.insert(args.end(), options.begin(), options.end());
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  pid_t pid = 0;
  const int failed = posix_spawn(&pid, argv[0], nullptr, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  if (failed) throw InputError(fmt::format("study {}: cannot run {}: {}", s.name, argv[0], std::strerror(failed)));
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
#endif
}

// The options a Python study is given: this run's.
std::vector<std::string> forwarded_options(const nsb::DriverOptions& o, const std::string& shard, const std::vector<std::string>& plugins) {
  std::vector<std::string> args;
  if (o.verify_dir.empty()) args.insert(args.end(), {"--out", o.out});
  else args.insert(args.end(), {"--verify", o.verify_dir, "--rtol", fmt::format("{}", o.tolerance.rtol), "--atol",
                                fmt::format("{}", o.tolerance.atol)});
  if (o.full) args.push_back("--full");
  if (!shard.empty()) args.insert(args.end(), {"--shard", shard});
  if (o.merge) args.push_back("--merge");
  for (const auto& p : plugins) args.insert(args.end(), {"--plugin", p});
  return args;
}

}  // namespace

int main(int argc, char** argv) {
  nsb::set_command_line(argc, argv);
  CLI::App app{"nsbench-study: run studies and write citable reports"};
  app.set_version_flag("--version", nsb::version_text("nsbench-study"));
  std::vector<std::string> names;
  std::string out = "reports", shard_text, verify_dir;
  bool full = false, merge = false;
  nsb::VerifyTolerance tolerance;
  app.add_option("studies", names, "'list', 'show NAME' (a built-in study file's text), 'all', study names, 'run FILE.toml' (a study file, README), or "
                                   "'performance BENCH.json...' (the benchmarks' table)")->required();
  std::vector<std::string> plugins;
  app.add_option("--out", out, "output directory (default reports)");
  app.add_flag("--full", full, "run the long sweeps");
  app.add_option("--shard", shard_text, "run only shard I of N of the cases (job arrays), e.g. 3/8");
  app.add_flag("--merge", merge, "merge the shards' results in DIR/shards and write the reports");
  app.add_option("--verify", verify_dir, "recompute and compare with the report in this directory; writes nothing");
  app.add_option("--rtol", tolerance.rtol, "--verify: relative tolerance on reals (default 1e-9)")->check(CLI::NonNegativeNumber);
  app.add_option("--atol", tolerance.atol, "--verify: absolute tolerance on reals (default 0)")->check(CLI::NonNegativeNumber);
  app.add_option("--plugin", plugins, "load integrators/problems from a plugin module (repeatable; also NSBENCH_PLUGINS)");
  nsb::cli::one_value_each(app);
  try {
    nsb::cli::check_option_names(app, argc, argv);
    app.parse(argc, argv);
    nsb::cli::refuse_empty_values(app);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const InputError& e) {
    fmt::print(stderr, "nsbench-study: error: {}\n", e.what());
    return 2;
  }
  try {
    nsb::load_plugins(plugins);
    const auto& registry = nsb::study_registry();  // after the plugins: a study of integrators = "all" runs theirs
    if (names == std::vector<std::string>{"list"}) {
      for (const auto& s : registry)  // what each is written in: a study file, Python, or C++
        fmt::print("{:<12} {} [{}: {}]\n", s.name, s.description,
                   !s.script.empty() ? "Python" : nsb::builtin_study_file(s.source) ? "study file" : "C++", s.source);
      return 0;
    }
    if (names[0] == "show") {
      show_study_file(registry, names);
      return 0;
    }
    if (const std::string slow = nsb::unoptimized_plugins_warning(); !slow.empty()) fmt::print(stderr, "nsbench-study: {}\n", slow);
    if (names[0] == "performance") {
      if (names.size() < 2) throw InputError("performance: give the benchmarks' JSON files (nsbench-study performance BENCH.json...)");
      write_performance({names.begin() + 1, names.end()}, out);
      return 0;
    }
    nsb::DriverOptions options{out, full, shard_text.empty() ? nsb::Shard{} : nsb::parse_shard(shard_text), merge, verify_dir,
                               tolerance};
    nsb::check_driver_options(options);
    std::vector<const nsb::StudyEntry*> selected;
    std::optional<nsb::StudyEntry> file_study;  // nsbench-study run FILE
    std::optional<nsb::StudySpec> spec;
    if (names[0] == "run") {
      if (names.size() != 2) throw InputError("run: give one study file (nsbench-study run FILE.toml)");
      spec = nsb::read_study_file(names[1]);
      file_study = nsb::file_study(*spec);
      selected.push_back(&*file_study);
      options.result_check = [&spec](const nsb::StudyEntry& s, const Json&, const Json& result) {
        return s.name == spec->name ? nsb::file_result_damage(*spec, result) : std::string{};
      };
      options.before_commit = [&spec](const fs::path& report) { nsb::write_study_copy(*spec, report); };
    }
    for (const auto& n : file_study ? std::vector<std::string>{} : names) {
      bool found = false;
      for (const auto& s : registry)
        if (n == "all" || s.name == n) {
          selected.push_back(&s);
          found = true;
        }
      if (!found) {
        std::vector<std::string> valid{"all"};
        for (const auto& s : registry) valid.push_back(s.name);
        throw InputError(fmt::format("unknown study '{}' (nearest: {}; valid: {})", n, nsb::nearest_name(n, valid),
                                     fmt::join(valid, ", ")));
      }
    }
    // Once the input is checked (the output directory too, claimed here as the studies would),
    // before the first case: the tables stamp "-dirty", this says which code files were, as
    // nsbench run does. Not for --merge: it runs no case, its numbers are the shards'.
    if (!merge) {
      if (verify_dir.empty()) nsb::claim_output_directory(out, "--out");
      fmt::print(stderr, "{}", nsb::dirty_build_note("nsbench-study"));
    }
    std::vector<const nsb::StudyEntry*> in_cpp, in_python;
    for (const auto* s : selected) (s->script.empty() ? in_cpp : in_python).push_back(s);
    int status = in_cpp.empty() ? 0 : nsb::drive_studies(in_cpp, options);
    for (const auto* s : in_python) status = std::max(status, run_python_study(*s, forwarded_options(options, shard_text, plugins)));
    return status;
  } catch (const InputError& e) {
    fmt::print(stderr, "nsbench-study: error: {}\n", e.what());
    return 2;
  } catch (const Json::exception& e) {
    fmt::print(stderr, "nsbench-study: error: unreadable shard file: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // one line, and the staging directory removed (no std::terminate)
    fmt::print(stderr, "nsbench-study: error: {}\n", e.what());
    return 2;
  }
  return 0;
}
