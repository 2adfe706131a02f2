// nsbench: list the problems and integrators, run one case.
//
//   nsbench [--plugin FILE]... list
//   nsbench [--plugin FILE]... run --problem P --integrator I --dt DT --t-end T [--set key=value]... --out DIR
//                                  [--fields DIR [--fields-every K]]   ParaView field output
//                                  (run/field_output.hpp) of the problem's bodies
//   nsbench [--plugin FILE]... check --integrator I | --problem P [--set key=value]...   the generic properties
//                                  every integrator (problem) is held to
//                                  (check/conformance.hpp), one line each; exit 1 when
//                                  one fails
// Every option may stand before or after the subcommand (app/cli_options.hpp).
// Plugins (core/plugin.hpp) also come from NSBENCH_PLUGINS (colon-separated).
//
// Exit codes: 0 ok, 1 a property of check failed, 2 bad input (one line on stderr naming the parameter and its valid
// range), 3 the run diverged (its files are still written, with status "diverged"),
// 128 + signal number after SIGINT or SIGTERM: the run stops at the next step and its files
// are written whole, with status "interrupted" (a second signal kills at once; the files
// are renamed into place, never half-written).
// Guardrails: a conditionally stable scheme with dt above the problem's stable step gets one
// warning line on stderr (and runs); a run longer than a few seconds shows its progress.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <algorithm>
#include <condition_variable>
#include <csignal>
#include <iostream>
#include <mutex>
#include <optional>
#include <thread>

#include "app/cli_options.hpp"
#include "core/build_info.hpp"
#include "core/output.hpp"
#include "core/plugin.hpp"
#include "core/wait_policy.hpp"
#include "check/conformance.hpp"
#include "run/energy_balance.hpp"
#include "run/field_output.hpp"
#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "run/run_case.hpp"
#include "problems/registry.hpp"

namespace {

volatile std::sig_atomic_t interrupt_signal = 0;

extern "C" void on_interrupt(int signal) {
  interrupt_signal = signal;
  std::signal(signal, SIG_DFL);  // a second one ends the process
}

// A line on stderr every 3 s while a run is prepared, until its steps start (and with them the
// run's own progress lines): a 1e8-element bar takes about a minute to assemble and bind,
// which printed nothing before.
class SetupProgress {
 public:
  SetupProgress() : thread_([this] { beat(); }) {}
  ~SetupProgress() { stop(); }
  SetupProgress(const SetupProgress&) = delete;
  SetupProgress& operator=(const SetupProgress&) = delete;
  void stage(const char* what) {
    const std::lock_guard lock(mutex_);
    stage_ = what;
  }
  void stop() {
    {
      const std::lock_guard lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

 private:
  void beat() {
    const auto start = std::chrono::steady_clock::now();
    std::unique_lock lock(mutex_);
    while (!wake_.wait_for(lock, std::chrono::seconds(3), [&] { return done_; }))
      fmt::print(stderr, "nsbench: preparing the run: {}, elapsed {:.0f} s\n", stage_,
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }

  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  const char* stage_ = "building the problem";
  std::thread thread_;  // last: started once the rest is set
};

void print_params(const nsb::ParamSpecs& specs) {
  for (const auto& s : specs)
    fmt::print("      {:<14} default {:<10} {:<28} {}\n", s.name, s.default_value.empty() ? "unset" : s.default_value,
               s.range_text(), s.description);
}

void list() {
  fmt::print("problems:\n");
  for (const auto& e : nsb::problem_registry()) {
    fmt::print("  {:<22} {}\n", e.name, e.description);
    print_params(e.parameters());
    // What a study file's measures can name (at the default parameters; every problem also
    // has kinetic, potential, total_energy, and min_gap when it has contacts).
    const auto names = e.make(nsb::Params(e.parameters()))->observable_names();
    fmt::print("      observables (at the defaults): {}\n", names.empty() ? std::string("none of its own") : fmt::format("{}", fmt::join(names, ", ")));
  }
  fmt::print("integrators (friction: treats Coulomb friction, mu > 0; moving contacts: treats contacts whose rows\n"
             "follow the configuration; 3D friction cone: treats 3D contacts, two tangent rows; the others decline\n"
             "them. needs: what it can run, declared in its registry entry, refused when it binds a problem;\n"
             "integrators/capabilities.hpp):\n");
  for (const auto& e : nsb::integrator_registry()) {
    const nsb::DeclaredCapabilities declared = e.declared();
    const nsb::Capabilities& can = declared.resolved(nsb::Params(e.parameters()));
    fmt::print("  {:<22} {}{}{}{}\n", e.name, e.description, can.friction ? " [friction]" : "",
               can.moving_contacts ? " [moving contacts]" : "", can.friction_cone ? " [3D friction cone]" : "");
    fmt::print("      needs: {}\n", declared.text());
    print_params(e.parameters());
  }
}

// --fields DIR before any work: DIR is not --out, does not hold it and is not in it (each
// is replaced whole when the run ends, a nested one would be undone by the other's swap). A
// problem that describes no bodies (a plugin's) is refused by FieldWriter.
void check_fields_dir(const std::string& fields, const std::string& out) {
  namespace fs = std::filesystem;
  const fs::path f = fs::weakly_canonical(fields), o = fs::weakly_canonical(out);
  const auto within = [](const fs::path& inner, const fs::path& outer) {
    return std::mismatch(outer.begin(), outer.end(), inner.begin(), inner.end()).first == outer.end();
  };
  if (within(o, f) || within(f, o))
    throw nsb::InputError(fmt::format("--fields '{}': is, contains or is in --out '{}', and both are replaced whole when "
                                      "the run ends; valid: a directory beside it (e.g. {}-fields)",
                                      fields, out, o.string()));
}

// What overflowed, for the divergence line: the first non-finite displacement and velocity
// components and the energy ("u[3] = inf, v[3] = -inf, energy inf"); empty when all are finite.
std::string non_finite(const nsb::Integrator& integrator) {
  const nsb::State& s = integrator.state();
  std::vector<std::string> parts;
  for (const auto& [name, x] : {std::pair<const char*, const nsb::Vec*>{"u", &s.u}, {"v", &s.v}})
    for (Eigen::Index i = 0; i < x->size(); ++i)
      if (!std::isfinite((*x)[i])) {
        parts.push_back(fmt::format("{}[{}] = {}", name, i, (*x)[i]));
        break;
      }
  if (const double e = integrator.energy().total(); !std::isfinite(e)) parts.push_back(fmt::format("energy {}", e));
  return fmt::format("{}", fmt::join(parts, ", "));
}

// An energy figure as printed (signed for a change): n/a when there is no scale (E0 = 0 and the
// problem has none).
std::string energy_text(double e, bool with_sign = false) {
  return std::isnan(e) ? "n/a" : with_sign ? fmt::format("{:+.3e}", e) : fmt::format("{:.3e}", e);
}

// The run's one line. The energy change, not an "error": a dissipative run (e < 1, friction)
// loses energy by its law.
void print_result(const nsb::Problem& problem, const nsb::Integrator& integrator, const nsb::RunResult& result) {
  const std::string scale = std::isnan(result.energy_scale) ? fmt::format("E0 = 0 and {} has no energy scale", problem.name())
                                                            : "both relative to " + result.energy_scale_text;
  fmt::print("{} on {}: {} steps, t = {:.6g}, cpu {:.3g} s (stepping {:.3g} s), energy change E_end - E0 {} (largest |E - E0| "
             "{}; {}), max penetration {:.3e}\n",
             integrator.name(), problem.name(), result.steps, result.t_final, result.cpu_seconds, result.step_cpu_seconds,
             energy_text(result.final_energy_change(), true), energy_text(result.max_energy_error), scale, result.max_penetration);
}

// The balance's line beside it (run/energy_balance.hpp): what of the energy change the loads and
// the contact impulses did, and what neither did (the scheme's own error or dissipation).
void print_energy_balance(const nsb::RunEnergyBalance& b) {
  if (!b.not_derived.empty()) {
    fmt::print("{}\n", b.not_derived);
    return;
  }
  fmt::print("energy balance over {} steps (absolute): energy change {:+.3e} = work of the loads {:+.3e} + work of the "
             "contact impulses {:+.3e} + residual {:+.3e} (round-off bound {:.1e})\n",
             b.steps_closed, b.energy_change, b.load_work, b.contact_work, b.residual, b.round_off);
}

struct RunArgs {
  std::string problem, integrator, dt, t_end, out, sample_every = "1", fields, fields_every;
  std::vector<std::string> sets;
};

int run_case(const RunArgs& a) {
  SetupProgress setup;
  auto [problem, integrator] = nsb::make_run_case(a.problem, a.integrator, a.sets);
  setup.stage("checking the options and the stable step");
  nsb::RunOptions options = nsb::parse_run_options(a.dt, a.t_end, a.sample_every, nsb::OptionStyle::CommandLine);
  if (!a.fields_every.empty() && a.fields.empty())
    throw nsb::InputError(fmt::format("--fields-every {}: given without --fields DIR", a.fields_every));
  if (!a.fields_every.empty()) {
    const double k = nsb::parse_real(a.fields_every, "--fields-every");
    if (k < 1 || k != static_cast<long>(k) || k > 1e15)
      throw nsb::InputError(fmt::format("--fields-every {}: must be an integer >= 1 (every k-th step; the first and last "
                                        "states are always written)", a.fields_every));
    options.state_every = static_cast<long>(k);
  }
  if (!a.fields.empty()) check_fields_dir(a.fields, a.out);
  // series.csv, summary.json and events.csv are written into a staging directory and swapped
  // in together (core/output.hpp): a reader never sees one run's series beside another's summary.
  nsb::ReportDirectory out(a.out, "--out");
  nsb::remove_stale_temporaries(out.path());  // half-written files of a version that wrote in place
  if (integrator->conditionally_stable() && options.dt > problem->stable_step())
    fmt::print(stderr, "nsbench: warning: --dt {} is above the stable step {:.4g} of {} for {} (ratio {:.3g}): expect a blow-up\n",
               options.dt, problem->stable_step(), problem->name(), integrator->name(), options.dt / problem->stable_step());
  if (const std::string slow = nsb::unoptimized_plugins_warning(); !slow.empty()) fmt::print(stderr, "nsbench: {}\n", slow);
  options.progress_every = 3.0;
  options.interrupt = &interrupt_signal;
  std::signal(SIGINT, on_interrupt);
  std::signal(SIGTERM, on_interrupt);

  setup.stage("initialising the integrator");
  integrator->init(*problem, problem->initial_state());
  if (const std::string overflow = non_finite(*integrator); !overflow.empty())  // before any step: the parameters
    throw nsb::InputError(fmt::format("problem {}: its initial state is not finite ({}): a parameter overflows; "
                                      "parameters given: {}", problem->name(), overflow,
                                      a.sets.empty() ? "none (the defaults)" : "--set " + fmt::format("{}", fmt::join(a.sets, " --set "))));
  std::optional<nsb::FieldWriter> fields;
  if (!a.fields.empty()) {
    fields.emplace(*problem, a.fields, "--fields", static_cast<long>(options.t_end / options.dt) / options.state_every + 2);
    options.state_sink = &*fields;
  }
  const std::filesystem::path& dir = out.path();
  nsb::CsvSeriesFile series(dir / "series.csv");  // streamed: memory bounded whatever the length
  options.series_sink = &series;
  // After every step: the orientation of bodies that turn in 3D (it depends on the path), the balance.
  nsb::RunBalance balance(*problem, *integrator);
  const bool follow = fields && fields->follows_rotations();
  nsb::StepObserver observer;
  if (follow || balance.derived())
    observer = [&](const nsb::Integrator& i, const nsb::StepInfo&) {
      if (follow) fields->follow(i.state());
      balance.add(i);
    };
  setup.stop();
  // Once the input is checked, before the first step: a binary built from changed sources
  // says so and which (the same list is in summary.json's build), its numbers not the commit's.
  fmt::print(stderr, "{}", nsb::dirty_build_note("nsbench"));
  const nsb::RunResult result = nsb::run(*problem, *integrator, options, observer);
  series.commit();
  nsb::write_file_atomic(dir / "summary.json",
                         nsb::with_energy_balance(nsb::summary_to_json(*problem, *integrator, options, result), balance.figures()));
  if (!integrator->events().empty())  // the references' located events
    nsb::write_file_atomic(dir / "events.csv", nsb::events_to_csv(integrator->events()));
  else
    std::filesystem::remove(dir / "events.csv");  // an earlier run's, not this one's
  if (fields) fields->commit();
  out.commit();
  if (interrupt_signal != 0) {  // during the run, or while its files were written
    fmt::print(stderr, "nsbench: interrupted by signal {}{} (files written to {})\n", static_cast<int>(interrupt_signal),
               result.status == nsb::RunStatus::Interrupted ? ", " + result.message : std::string(), a.out);
    return 128 + interrupt_signal;
  }
  if (result.status != nsb::RunStatus::Ok) {
    const std::string overflow = non_finite(*integrator);
    fmt::print(stderr, "nsbench: run diverged: {}{} (files written to {})\n", result.message,
               overflow.empty() ? "" : " (" + overflow + ")", a.out);
    return 3;
  }
  print_result(*problem, *integrator, result);
  print_energy_balance(balance.figures());
  return 0;
}

int print_verdicts(const std::string& what, const std::vector<nsb::CheckVerdict>& verdicts) {
  fmt::print("nsbench check: {}\n", what);
  int failed = 0;
  for (const auto& v : verdicts) {
    fmt::print("  {:<16} {:<13} {}\n", v.property, nsb::outcome_name(v.outcome), v.figure);
    failed += v.outcome == nsb::CheckVerdict::Outcome::Fail;
  }
  fmt::print("{}: {}\n", what, failed ? fmt::format("{} properties failed", failed) : "every measured property holds");
  return failed;
}

int check(const std::string& integrator, const std::string& problem, const std::vector<std::string>& sets) {
  if (integrator.empty() && problem.empty()) throw nsb::InputError("check: give --integrator NAME or --problem NAME (or both)");
  // The integrator's properties are measured on the suite's own problems at fixed parameters.
  if (problem.empty() && !sets.empty())
    throw nsb::InputError(fmt::format("check --set {}: sets a parameter of the problem checked; valid: with --problem NAME", sets.front()));
  int failed = 0;
  if (!integrator.empty()) {
    const auto& entry = nsb::find_integrator(integrator);
    failed += print_verdicts("integrator " + entry.name, nsb::check_integrator(entry));
  }
  if (!problem.empty()) {
    const auto& entry = nsb::find_problem(problem);
    const auto routed = nsb::route_overrides(sets, entry.parameters(), {});
    failed += print_verdicts("problem " + entry.name, nsb::check_problem(entry, routed.problem));
  }
  return failed ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"nsbench: benchmark and verification of time integrators for non-smooth dynamics"};
  app.set_version_flag("--version", nsb::version_text("nsbench"));
  app.require_subcommand(1);
  app.fallthrough();  // --plugin before or after the subcommand
  std::vector<std::string> plugins;
  app.add_option("--plugin", plugins, "load integrators/problems from a plugin module (repeatable; also NSBENCH_PLUGINS)");
  auto* list_cmd = app.add_subcommand("list", "list problems and integrators with their parameters");
  auto* run_cmd = app.add_subcommand("run", "run one integrator on one problem");
  RunArgs a;
  run_cmd->add_option("--problem", a.problem, "problem name (see nsbench list)")->required();
  run_cmd->add_option("--integrator", a.integrator, "integrator name (see nsbench list)")->required();
  run_cmd->add_option("--dt", a.dt, "time step, > 0")->required();
  run_cmd->add_option("--t-end", a.t_end, "final time, > 0")->required();
  run_cmd->add_option("--set", a.sets, "parameter as key=value (repeatable)");
  run_cmd->add_option("--sample-every", a.sample_every, "record every k-th step (default 1)");
  run_cmd->add_option("--out", a.out, "output directory")->required();
  run_cmd->add_option("--fields", a.fields, "write ParaView fields (fields.pvd, fields_NNNNNN.vtu) into this directory");
  run_cmd->add_option("--fields-every", a.fields_every, "write the fields every k-th step (default: --sample-every)");
  auto* check_cmd = app.add_subcommand("check", "hold an integrator (a plugin's too) to the generic properties of every scheme");
  std::string checked_integrator, checked_problem;
  check_cmd->add_option("--integrator", checked_integrator, "integrator to check (see nsbench list)");
  check_cmd->add_option("--problem", checked_problem, "problem to check (see nsbench list)");
  std::vector<std::string> checked_sets;
  check_cmd->add_option("--set", checked_sets, "a parameter of the problem checked as key=value (repeatable)");
  nsb::cli::one_value_each(app);
  try {
    nsb::cli::check_option_names(app, argc, argv);
    app.parse(argc, argv);
    nsb::cli::refuse_empty_values(app);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  } catch (const nsb::InputError& e) {
    fmt::print(stderr, "nsbench: error: {}\n", e.what());
    return 2;
  }
  // run and check start threads (core/threads.hpp): they wait as wait_policy.hpp says.
  if (!list_cmd->parsed()) nsb::choose_openmp_wait_policy(argv);
  try {
    nsb::load_plugins(plugins);
    if (list_cmd->parsed()) {
      list();
      return 0;
    }
    if (check_cmd->parsed()) return check(checked_integrator, checked_problem, checked_sets);
    return run_case(a);
  } catch (const nsb::InputError& e) {
    fmt::print(stderr, "nsbench: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {  // one line, and the staging directories removed (no std::terminate)
    fmt::print(stderr, "nsbench: error: {}\n", e.what());
    return 2;
  }
}
