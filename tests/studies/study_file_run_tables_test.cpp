// Study files: the tables of some runs (FileTable::of_some_runs): rows = "pivot", "periodic",
// "trajectory" (at times or every s-th step) and "flights", their runs picked by `where` and left
// out by `drop_above`, and their bad input.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "reference/modal_exact.hpp"
#include "run/run.hpp"
#include "studies/measures.hpp"
#include "studies/study.hpp"
#include "studies/study_file.hpp"

namespace {

// The bouncing mass to t = 1, elastic and with e = 0.5 on a budget of 45 F_int evaluations
// (over budget near t = 0.45, measured up to the stop), two schemes at two steps; the energy
// error sampled at 0.35, 0.6, 0.85.
const std::string kSomeRuns = R"([study]
title = "t"
t_end = 1.0
cpu_repeats = 0
targets = [1e-2]
measure_over_budget = true

[[problem]]
name = "bouncing-mass"
label = "elastic"
parameters = { e = 1 }

[[problem]]
name = "bouncing-mass"
label = "stopped"
parameters = { e = 0.5 }
max_force_evaluations = 45

[[integrator]]
name = "moreau-jean"
steps = [1e-2, 5e-3]

[[integrator]]
name = "schatzman-paoli"
steps = [1e-2, 5e-3]

[[measure]]
kind = "energy"
every = 0.25
from = 0.1
norm = "final"
label = "E end"

[[table]]
id = "runs"
title = "runs"
columns = ["problem", "integrator", "dt", "E end", "outcome", "t reached"]

[[table]]
id = "pivot"
title = "pivot"
rows = "pivot"
where = { dt = 0.01 }
across = "parameter e"
columns = ["integrator", { of = "E end", header = "E end, e = {}" }]

[[table]]
id = "periodic"
title = "periodic"
rows = "periodic"
measure = "E end"
where = { dt = 0.01 }
columns = ["problem", "integrator", "k", "value", "|value|"]

[[table]]
id = "elastic_trajectory"
title = "trajectory"
rows = "trajectory"
observable = "q"
exact = "q_exact"
last = 0.8
points = 10
where = { problem = "elastic" }
columns = ["problem", "integrator", "run", "t", "value"]

[[table]]
id = "stopped_trajectory"
title = "trajectory"
rows = "trajectory"
observable = "q"
last = 0.8
points = 10
drop_above = { "t reached" = 0.9 }
columns = ["problem", "integrator", "run", "t", "value"]

[[figure]]
id = "periodic_figure"
table = "periodic"
title = "E"
x = "k"
y = "value"
log_x = false
log_y = false
)";

// kSomeRuns with a case table of some runs: dt = 0.01, less the runs that reached past t = 0.9.
const std::string kSomeCaseRuns = kSomeRuns + R"(
[[table]]
id = "some_cases"
title = "some cases"
where = { dt = 0.01 }
drop_above = { "t reached" = 0.9 }
columns = ["problem", "integrator", "dt", "t reached"]
)";

// kSomeRuns with a bouncing mass at e = 0.5 to t = 1.5 (impacts near 0.45, 0.90, 1.13, 1.24),
// the energies of its first 3 flights, in a table at dt = 0.005, and E / E0 of the elastic runs
// at dt = 0.01 every (steps / 7)-th step.
const std::string kFlightRuns = kSomeRuns + R"(
[[problem]]
name = "bouncing-mass"
label = "half"
parameters = { e = 0.5 }
t_end = 1.5

[[measure]]
kind = "flight-energy"
label = "E_i err"
count = 3
at = "mid-flight step"
problems = ["half"]

[[table]]
id = "flights"
title = "flights"
rows = "flights"
measure = "E_i err"
where = { dt = 0.005 }
columns = ["problem", "integrator", "flight", "energy ratio", "exact energy ratio", "|rel. err|"]

[[table]]
id = "energy_steps"
title = "E/E0"
rows = "trajectory"
observable = "total_energy"
relative = true
spacing = "steps"
points = 7
where = { dt = 0.01, problem = "elastic" }
columns = ["integrator", "t", "value"]
)";

// The line of `text` where `needle` first occurs (1: the first).
long line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  REQUIRE(at != std::string::npos);
  return 1 + std::count(text.begin(), text.begin() + static_cast<long>(at), '\n');
}

std::vector<nsb::Table> run_some_runs(const std::string& text) {
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(text, "f.toml", false));
  const auto cases = nsb::study_cases(entry, {});
  std::vector<nsb::Json> results;
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {}));
  return nsb::study_tables(entry, cases, results, {});
}

const nsb::Table& table_of(const std::vector<nsb::Table>& tables, const std::string& id) {
  const auto t = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& u) { return u.id == id; });
  REQUIRE(t != tables.end());
  return *t;
}

std::string some_runs_error(const std::string& text) {
  try {
    nsb::parse_study_text(text, "f.toml", false);
  } catch (const nsb::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string with_replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("study file: a pivot, a periodic and a trajectory table of the runs where/drop_above pick", "[studies][study_file]") {
  const auto tables = run_some_runs(kSomeRuns);
  const nsb::Table& runs = table_of(tables, "runs");
  REQUIRE(runs.rows.size() == 8);
  // runs row of (problem, integrator, dt)
  const auto run = [&](const std::string& problem, const std::string& integrator, double dt) {
    const auto r = std::find_if(runs.rows.begin(), runs.rows.end(), [&](const std::vector<nsb::Cell>& row) {
      return row[0] == nsb::Cell{problem} && row[1] == nsb::Cell{integrator} && row[2] == nsb::Cell{dt};
    });
    REQUIRE(r != runs.rows.end());
    return *r;
  };
  CHECK(run("stopped", "moreau-jean", 1e-2)[4] == nsb::Cell{std::string("over budget")});
  CHECK(run("elastic", "moreau-jean", 1e-2)[4] == nsb::Cell{std::string("ok")});

  // Pivot: one row per integrator, one column per e (in the order of the runs); the stopped
  // run shows its outcome, the elastic one its value.
  const nsb::Table& pivot = table_of(tables, "pivot");
  REQUIRE(pivot.columns.size() == 3);
  CHECK(pivot.columns[1].name == "E end, e = 1");
  CHECK(pivot.columns[2].name == "E end, e = 0.5");
  REQUIRE(pivot.rows.size() == 2);
  for (const auto& row : pivot.rows) {
    const std::string integrator = std::get<std::string>(row[0]);
    CHECK(row[1] == run("elastic", integrator, 1e-2)[3]);
    CHECK(std::holds_alternative<double>(row[1]));
    CHECK(row[2] == nsb::Cell{std::string("over budget")});
  }

  // Periodic: the runs at dt = 0.01, k = 1, 2, 3 (elastic) and 1 (stopped at 0.45); the last
  // sample is the measure's final value.
  const nsb::Table& periodic = table_of(tables, "periodic");
  CHECK(periodic.csv_only);
  REQUIRE(periodic.rows.size() == 2 * 3 + 2 * 1);
  CHECK(periodic.rows[0][2] == nsb::Cell{1L});
  CHECK(periodic.rows[2][2] == nsb::Cell{3L});
  CHECK(periodic.rows[2][3] == run(std::get<std::string>(periodic.rows[2][0]), std::get<std::string>(periodic.rows[2][1]), 1e-2)[3]);
  for (const auto& row : periodic.rows) CHECK(std::get<double>(row[4]) == std::abs(std::get<double>(row[3])));
  REQUIRE(periodic.figures.size() == 1);
  CHECK(periodic.figures[0].id == "f_periodic_figure");

  // Trajectory of the elastic runs: q at the first step at or after 0.2 + 0.08 n (n = 0..10),
  // then after the first run (moreau-jean, dt = 0.01) the exact q at the same times.
  const nsb::Table& elastic = table_of(tables, "elastic_trajectory");
  std::vector<std::string> order;
  for (const auto& row : elastic.rows) {
    const std::string who = std::get<std::string>(row[1]) + " " + std::get<std::string>(row[2]);
    if (order.empty() || order.back() != who) order.push_back(who);
    CHECK(std::get<std::string>(row[0]) == "elastic");
    CHECK(std::get<double>(row[3]) >= 0.2);
  }
  REQUIRE(order.size() == 5);
  CHECK(order[0] == "moreau-jean dt = 1.00e-02");
  CHECK(order[1] == "exact ");
  const auto elastic_mass = nsb::make_problem("bouncing-mass", {{"e", "1"}});  // owns the exact solution
  const auto exact = elastic_mass->exact();
  std::size_t first = 0, exact_rows = 0;
  for (const auto& row : elastic.rows) {
    if (row[1] == nsb::Cell{std::string("exact")}) {
      const double t = std::get<double>(row[3]);
      CHECK(row[3] == elastic.rows[exact_rows][3]);  // the first run's times
      CHECK(std::get<double>(row[4]) == Approx(exact->state(t)->u[0]).margin(1e-12));
      ++exact_rows;
    } else if (row[1] == elastic.rows[0][1] && row[2] == elastic.rows[0][2]) {
      ++first;
    }
  }
  CHECK(first >= 10);
  CHECK(first <= 11);
  CHECK(exact_rows == first);

  // drop_above: the runs that reached t > 0.9 (the elastic ones) left out; the stopped runs'
  // samples end where they stopped, and no exact rows without `exact`.
  const nsb::Table& stopped = table_of(tables, "stopped_trajectory");
  REQUIRE(!stopped.rows.empty());
  for (const auto& row : stopped.rows) {
    CHECK(row[0] == nsb::Cell{std::string("stopped")});
    CHECK(std::get<double>(row[3]) < 0.5);
  }
}

TEST_CASE("study file: a case table of the runs where/drop_above pick", "[studies][study_file]") {
  const auto tables = run_some_runs(kSomeCaseRuns);
  const nsb::Table& runs = table_of(tables, "runs");
  const nsb::Table& some = table_of(tables, "some_cases");
  REQUIRE(runs.rows.size() == 8);
  // The runs at dt = 0.01 (4) less the elastic problem's (they reach t_end = 1): the stopped
  // problem's (over budget at 45 F_int evaluations, before t = 0.9), in the runs' order.
  std::vector<std::vector<nsb::Cell>> expected;
  for (const auto& row : runs.rows)
    if (row[2] == nsb::Cell{0.01} && std::get<double>(row[5]) <= 0.9) expected.push_back({row[0], row[1], row[2], row[5]});
  REQUIRE(expected.size() == 2);
  CHECK(some.rows == expected);
  CHECK(expected[0][0] == nsb::Cell{std::string("stopped")});
}

TEST_CASE("study file: tables of some runs: bad input named", "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  CHECK(some_runs_error(kSomeRuns) == "(no error)");
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "across = \"parameter e\"\n", "")),
             StartsWith("f.toml:39: table[1]: missing key 'across'"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "columns = [\"problem\", \"integrator\", \"dt\", \"E end\", \"outcome\", \"t reached\"]",
                                           "across = \"dt\"\ncolumns = [\"problem\"]")),
             StartsWith("f.toml:37: table[0].across: a table of rows = \"case\" has no across; valid: rows = \"pivot\""));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "where = { dt = 0.01 }\nacross", "where = { dtt = 0.01 }\nacross")),
             StartsWith("f.toml:43: table[1].where.dtt: 'dtt' is not valid (nearest: dt)"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "where = { dt = 0.01 }\nacross", "where = { dt = true }\nacross")),
             StartsWith("f.toml:43: table[1].where.dt: expected a number or a text, got a boolean"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "drop_above = { \"t reached\" = 0.9 }", "drop_above = { \"t reached\" = -1 }")),
             StartsWith("f.toml:73: table[4].drop_above.t reached: -1 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "columns = [\"integrator\", { of = \"E end\", header = \"E end, e = {}\" }]",
                                           "columns = [\"integrator\"]")),
             StartsWith("f.toml:45: table[1].columns: a pivot needs the columns naming a row and the value column last; valid: two or more columns"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "measure = \"E end\"", "measure = \"E\"")),
             StartsWith("f.toml:51: table[2].measure: 'E' is not valid (nearest: E end); valid: E end"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "observable = \"q\"\nexact", "observable = \"u_contact\"\nexact")),
             StartsWith("f.toml:59: table[3].observable: 'u_contact' is not an observable of problem 'elastic'; valid: q, v, q_exact, v_exact"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "last = 0.8\npoints = 10\nwhere", "last = 0.8\npoints = 0\nwhere")),
             StartsWith("f.toml:62: table[3].points: 0 is out of range; valid: [1, 100000]"));
  CHECK(some_runs_error(kSomeCaseRuns) == "(no error)");
  CHECK_THAT(some_runs_error(with_replaced(kSomeCaseRuns, "title = \"some cases\"", "title = \"some cases\"\nrows = \"group\"")),
             StartsWith("f.toml:89: table[5].where: a table of rows = \"group\" has no where; valid: rows = \"case\", \"pivot\", \"periodic\", \"trajectory\" or \"flights\""));
  CHECK_THAT(some_runs_error(with_replaced(kSomeCaseRuns, "where = { dt = 0.01 }\ndrop", "where = { dtt = 0.01 }\ndrop")),
             StartsWith("f.toml:88: table[5].where.dtt: 'dtt' is not valid (nearest: dt)"));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns, "table = \"periodic\"", "table = \"runs\"")),
             StartsWith("f.toml:78: figure[0].table: 'runs' is no declared table a figure names (rows = history, samples, periodic, "
                        "trajectory, flights, impulses, field or pivot); valid: pivot, periodic, elastic_trajectory, stopped_trajectory"));
}

TEST_CASE("study file: a flights table and a trajectory every s-th step, relative to its start", "[studies][study_file]") {
  const auto tables = run_some_runs(kFlightRuns);
  // Flights: the half problem's runs at dt = 0.005 alone (the elastic runs end before their
  // second impact, the stopped ones at the first), flights 1, 2, 3 each, against (e^2)^i.
  const nsb::Table& flights = table_of(tables, "flights");
  CHECK_FALSE(flights.csv_only);
  REQUIRE(flights.rows.size() == 2 * 3);
  for (std::size_t r = 0; r < flights.rows.size(); ++r) {
    const auto& row = flights.rows[r];
    const long i = static_cast<long>(r % 3) + 1;
    CHECK(row[0] == nsb::Cell{std::string("half")});
    CHECK(row[2] == nsb::Cell{i});
    const double ratio = std::get<double>(row[3]), exact = std::get<double>(row[4]);
    CHECK(exact == Approx(std::pow(0.25, static_cast<double>(i))));
    CHECK(std::abs(ratio / exact - 1.0) < 0.5);  // the 3rd flight lasts 22 steps: coarse
    CHECK(std::get<double>(row[5]) == Approx(std::abs(ratio / exact - 1.0)).epsilon(1e-12));
  }
  // Every step of the 100 of the elastic runs at dt = 0.01: s = 100 / 7 = 14, steps 1, 15, .., 99.
  const nsb::Table& steps = table_of(tables, "energy_steps");
  REQUIRE(steps.rows.size() == 2 * 8);
  for (std::size_t r = 0; r < steps.rows.size(); ++r) {
    CHECK(std::get<double>(steps.rows[r][1]) == Approx(0.01 + 0.14 * static_cast<double>(r % 8)));
    CHECK(std::get<double>(steps.rows[r][2]) == Approx(1.0).epsilon(0.05));  // E / E0
  }
}

TEST_CASE("study file: flights and step-spaced trajectory tables: bad input named", "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  CHECK(some_runs_error(kFlightRuns) == "(no error)");
  // Each error names the line of its key (`after`: a key inserted after the needle's line).
  const auto at = [&](const std::string& needle, long after = 0) { return fmt::format("f.toml:{}: ", line_of(kFlightRuns, needle) + after); };
  CHECK_THAT(some_runs_error(with_replaced(kFlightRuns, "measure = \"E_i err\"", "measure = \"E end\"")),
             StartsWith(at("measure = \"E_i err\"") + "table[5].measure: 'E end' is not valid (nearest: E_i err); valid: E_i err"));
  CHECK_THAT(some_runs_error(with_replaced(kFlightRuns, "spacing = \"steps\"", "spacing = \"step\"")),
             StartsWith(at("spacing = \"steps\"") + "table[6].spacing: 'step' is not valid (nearest: steps); valid: times, steps"));
  CHECK_THAT(some_runs_error(with_replaced(kFlightRuns, "points = 7", "points = 7\nlast = 0.5")),
             StartsWith(at("points = 7", 1) + "table[6].last: a trajectory of spacing = \"steps\" spans the whole run; valid: no last"));
  CHECK_THAT(some_runs_error(with_replaced(kFlightRuns, "rows = \"flights\"", "rows = \"flights\"\nrelative = true")),
             StartsWith(at("rows = \"flights\"", 1) + "table[5].relative: a table of rows = \"flights\" has no relative; valid: rows = \"trajectory\""));
  CHECK_THAT(some_runs_error(with_replaced(kFlightRuns, "relative = true", "relative = 1")),
             StartsWith(at("relative = true") + "table[6].relative: expected a boolean"));
  CHECK_THAT(some_runs_error(with_replaced(kFlightRuns, "observable = \"total_energy\"", "observable = \"energy\"")),
             StartsWith(at("observable = \"total_energy\"") + "table[6].observable: 'energy' is not an observable of problem 'elastic'"));
  // Without a flight-energy measure, a flights table has nothing to show.
  CHECK_THAT(some_runs_error(with_replaced(kFlightRuns, "kind = \"flight-energy\"\nlabel = \"E_i err\"\ncount = 3\nat = \"mid-flight step\"",
                                           "kind = \"penetration\"\nlabel = \"E_i err\"")),
             StartsWith(at("rows = \"flights\"", -2) + "table[5].rows: the study has no flight-energy measure; valid: a [[measure]] with kind = \"flight-energy\""));
}

namespace {

// The Signorini bar (N = 20, lumped) to t = 3 at 0.5 and 0.9 of its stable step: the time error
// |u_0 - u_0,semi| against modal-exact at most once per nominal step, cd-lagrange (fixed step),
// cd-lagrange-adaptive (smaller steps in the contact), modal-exact (the reference itself) and
// event-driven (a reference: at 0.9 only); a pivot of the time error over the steps, its order
// against dt, modal-exact left out.
const std::string kSemiDiscrete = R"([study]
title = "t"
t_end = 3.0
cpu_repeats = 0
targets = [1e-2]

[[problem]]
name = "signorini-bar"
label = "bar"
parameters = { mass = "lumped", N = 20 }
stable_steps = [0.5, 0.9]

[[integrator]]
name = "cd-lagrange"
[[integrator]]
name = "cd-lagrange-adaptive"
[[integrator]]
name = "modal-exact"
[[integrator]]
name = "event-driven"

[[exclude]]
integrators = "references"
stable_steps_except = [0.9]

[[measure]]
kind = "error"
semi_discrete = true
dof = 0
per_nominal_step = true
scale = 1.0
label = "u time err"

[[table]]
id = "runs"
title = "runs"
columns = ["integrator", "stable steps", "dt", "u time err", "note"]

[[table]]
id = "time"
title = "time"
rows = "pivot"
across = "stable steps"
except = { integrator = "modal-exact" }
order = { of = "dt", header = "time order" }
columns = ["integrator", { of = "u time err", header = "u time err, alpha = {}", missing = "n/a" }]
)";

// What the C++ study bar computed (studies/bar.cpp, which studies/builtin/bar.toml replaced):
// max over the steps sampled (the first step ending at or after the last sample + (1 - 1e-9) dt)
// of |u_0 - u_0,semi|, modal-exact advanced to each sample's time; and how many steps were
// sampled out of how many.
struct TimeError {
  double largest = 0.0;
  long samples = 0, steps = 0;
};
TimeError bar_time_error(const std::string& scheme, double alpha) {
  const auto problem = nsb::make_problem("signorini-bar", {{"mass", "lumped"}, {"N", "20"}});
  auto integrator = nsb::make_integrator(scheme);
  REQUIRE_FALSE(nsb::init_or_decline(*integrator, *problem));
  nsb::ModalExact semi(nsb::Params(nsb::ModalExact::parameters_spec()));
  semi.init(*problem, problem->initial_state());
  nsb::RunOptions options;
  options.dt = alpha * problem->stable_step();
  options.t_end = 3.0;
  options.record_series = false;
  TimeError out;
  double next = 0.0;
  nsb::run(*problem, *integrator, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
    ++out.steps;
    const double t = it.state().t;
    if (t < next) return;
    semi.advance_to(t);
    out.largest = std::max(out.largest, std::abs(it.state().u[0] - semi.displacement(0)));
    next = t + (1.0 - 1e-9) * options.dt;
    ++out.samples;
  });
  return out;
}

// A bar study of three meshes refined jointly (N = 20, 40, 80) at 0.9 of the stable step, one
// converging error and one energy error (no fit of the engine's own), and a case table of a
// diverging run (N = 100 at 2 stable steps: its state overflows at step 139 of 150) and a
// declined one (cd-lagrange, consistent mass).
const std::string kRefined = R"([study]
title = "t"
t_end = 3.0
cpu_repeats = 0
targets = [1e-2]

[[problem]]
name = "signorini-bar"
label = "bar"
parameters = { mass = "lumped" }
grid = { N = [20, 40, 80] }
refine = "N"
stable_steps = [0.9]

[[problem]]
name = "signorini-bar"
label = "unstable"
parameters = { mass = "lumped", N = 100 }
stable_steps = [2.0]

[[problem]]
name = "signorini-bar"
label = "consistent"
parameters = { mass = "consistent", N = 20 }
stable_steps = [0.9]

[[integrator]]
name = "cd-lagrange"

[[measure]]
kind = "error"
observable = "u_contact"
against = "u_contact_exact"
scale = 1.0
label = "u err"

[[measure]]
kind = "energy"
label = "E err"

[[table]]
id = "runs"
title = "runs"
not_ok = "outcome"
columns = ["problem", "dt", "u err", "E err", "CPU", "outcome"]

[[table]]
id = "orders"
title = "orders"
rows = "group"
fit_against = "1/N"
problems = ["bar"]
columns = ["integrator", "stable steps", "order of u err", "order of E err", "points of E err"]

[[table]]
id = "dt_orders"
title = "orders against dt"
rows = "group"
problems = ["bar"]
columns = ["integrator", "order of u err"]
)";

double number_of(const nsb::Cell& cell) {
  return std::holds_alternative<double>(cell) ? std::get<double>(cell) : std::holds_alternative<long>(cell) ? static_cast<double>(std::get<long>(cell)) : NAN;
}

}  // namespace

// The known answer: the C++ study bar's time error, bit for bit (the same samples, the same
// modal-exact calls): every step of the fixed-step scheme sampled, fewer than the adaptive
// scheme's steps; n/a on modal-exact's own run (no note) and, with a note, above its max_dofs.
TEST_CASE("study file: an error against the semi-discrete solution, sampled once per nominal step, as the bar study's",
          "[studies][study_file]") {
  std::vector<nsb::Json> results;
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(kSemiDiscrete, "f.toml", false));
  const auto cases = nsb::study_cases(entry, {});
  REQUIRE(cases.size() == 6);  // cd-lagrange and cd-lagrange-adaptive at 0.5, 0.9; the references at 0.9
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {}));
  const auto tables = nsb::study_tables(entry, cases, results, {});
  const nsb::Table& runs = table_of(tables, "runs");
  REQUIRE(runs.rows.size() == 6);
  for (std::size_t k = 0; k < 4; ++k) {
    const std::string scheme = std::get<std::string>(runs.rows[k][0]);
    const double alpha = std::get<double>(runs.rows[k][1]);
    INFO(scheme << " at " << alpha);
    const TimeError want = bar_time_error(scheme, alpha);
    CHECK(want.largest > 1e-4);
    CHECK(std::get<double>(runs.rows[k][3]) == want.largest);
    CHECK(std::get<std::string>(runs.rows[k][4]).empty());
    if (scheme == "cd-lagrange") CHECK(want.samples == want.steps);
    else CHECK(want.samples < want.steps / 2);  // the adaptive scheme's small steps are not all sampled
  }
  CHECK(runs.rows[4][0] == nsb::Cell{std::string("modal-exact")});
  CHECK(number_of(runs.rows[4][3]) != number_of(runs.rows[4][3]));  // n/a: its error is 0 by construction
  CHECK(std::get<std::string>(runs.rows[4][4]).empty());
  CHECK(runs.rows[5][0] == nsb::Cell{std::string("event-driven")});
  CHECK(std::get<double>(runs.rows[5][3]) > 0.0);
  // The pivot: one row per integrator but modal-exact, its order the slope of log(error)
  // against log(dt) over its steps; event-driven's missing step n/a, no order.
  const nsb::Table& time = table_of(tables, "time");
  REQUIRE(time.columns.size() == 4);
  CHECK(time.columns[1].name == "u time err, alpha = 0.5");
  CHECK(time.columns[2].name == "u time err, alpha = 0.9");
  CHECK(time.columns[3].name == "time order");
  CHECK(time.columns[3].format == nsb::kOrderFormat);
  REQUIRE(time.rows.size() == 3);
  for (std::size_t r = 0; r < 2; ++r) {
    const std::vector<double> dt = {std::get<double>(runs.rows[2 * r][2]), std::get<double>(runs.rows[2 * r + 1][2])};
    const std::vector<double> e = {std::get<double>(runs.rows[2 * r][3]), std::get<double>(runs.rows[2 * r + 1][3])};
    CHECK(time.rows[r][1] == nsb::Cell{e[0]});
    CHECK(std::get<double>(time.rows[r][3]) == nsb::fitted_order(dt, e));
  }
  CHECK(time.rows[2][0] == nsb::Cell{std::string("event-driven")});
  CHECK(time.rows[2][1] == nsb::Cell{std::string("n/a")});
  CHECK(number_of(time.rows[2][3]) != number_of(time.rows[2][3]));

  // Above modal-exact's max_dofs (2000): the run is measured, its time error n/a with the reason.
  std::string big = with_replaced(kSemiDiscrete, "N = 20 }\nstable_steps = [0.5, 0.9]", "N = 2000 }\nstable_steps = [0.9]\nt_end = 0.01");
  big = with_replaced(big, "[[integrator]]\nname = \"cd-lagrange-adaptive\"\n", "");
  big = with_replaced(big, "[[integrator]]\nname = \"event-driven\"\n", "");
  const auto big_tables = run_some_runs(big);
  const nsb::Table& big_runs = table_of(big_tables, "runs");
  REQUIRE(big_runs.rows.size() == 2);
  CHECK(number_of(big_runs.rows[0][3]) != number_of(big_runs.rows[0][3]));
  CHECK_THAT(std::get<std::string>(big_runs.rows[0][4]),
             Catch::StartsWith("u time err n/a: integrator modal-exact") && Catch::Contains("2001 dofs"));
}

// The known answer: each measure's least-squares order against log(1/N) over the refined runs
// (fit_order of their values, bit for bit, the energy error's too), the same slope as against
// log(dt) to round-off; a diverged and a declined run show their outcome in the measures' cells.
TEST_CASE("study file: group fits against 1/N and a run's outcome in its measured cells", "[studies][study_file]") {
  std::vector<nsb::Json> results;
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(kRefined, "f.toml", false));
  const auto cases = nsb::study_cases(entry, {});
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {}));
  const auto tables = nsb::study_tables(entry, cases, results, {});
  REQUIRE(cases.size() == 5);
  std::vector<double> h = {1.0 / 20.0, 1.0 / 40.0, 1.0 / 80.0}, u, e;
  for (std::size_t k = 0; k < 3; ++k) {
    u.push_back(results[k]["values"][0].get<double>());
    e.push_back(results[k]["values"][1].get<double>());
  }
  const nsb::Table& orders = table_of(tables, "orders");
  REQUIRE(orders.rows.size() == 1);
  CHECK(orders.columns[1].name == "stable steps");
  CHECK(orders.rows[0][1] == nsb::Cell{0.9});
  CHECK(std::get<double>(orders.rows[0][2]) == nsb::fit_order(h, u).order);
  CHECK(std::get<double>(orders.rows[0][3]) == nsb::fit_order(h, e).order);
  CHECK(std::get<long>(orders.rows[0][4]) == 3);
  CHECK(std::get<double>(orders.rows[0][2]) == Catch::Detail::Approx(std::get<double>(table_of(tables, "dt_orders").rows[0][1])).epsilon(1e-12));
  const nsb::Table& runs = table_of(tables, "runs");
  REQUIRE(runs.rows.size() == 5);
  CHECK(runs.rows[0][5] == nsb::Cell{std::string("ok")});
  CHECK(runs.rows[0][2] == nsb::Cell{u[0]});
  CHECK(runs.rows[3][5] == nsb::Cell{std::string("diverged")});
  CHECK(runs.rows[3][2] == nsb::Cell{std::string("diverged")});
  CHECK(runs.rows[3][3] == nsb::Cell{std::string("diverged")});
  CHECK(std::get<double>(runs.rows[3][4]) > 0.0);  // its CPU: no measure
  CHECK(runs.rows[4][2] == nsb::Cell{std::string("n/a")});
  // Without not_ok the values as the runs report them: none.
  const auto plain = run_some_runs(with_replaced(kRefined, "not_ok = \"outcome\"\n", ""));
  CHECK(std::holds_alternative<std::monostate>(table_of(plain, "runs").rows[3][2]));
}

TEST_CASE("study file: semi-discrete errors, not_ok, fit_against, except and a pivot's order: bad input named",
          "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  const auto error_at = [](const std::string& text, const std::string& needle, const std::string& what) {
    CHECK_THAT(some_runs_error(text), StartsWith(fmt::format("f.toml:{}: {}", line_of(text, needle), what)));
  };
  CHECK(some_runs_error(kSemiDiscrete) == "(no error)");
  CHECK(some_runs_error(kRefined) == "(no error)");
  std::string t = with_replaced(kSemiDiscrete, "semi_discrete = true", "semi_discrete = 1");
  error_at(t, "semi_discrete = 1", "measure[0].semi_discrete: expected a boolean, got an integer");
  t = with_replaced(kSemiDiscrete, "dof = 0", "dof = 21");
  error_at(t, "dof = 21", "measure[0].dof: 21 is out of range; valid: [0, 20]");
  t = with_replaced(kSemiDiscrete, "dof = 0\n", "");
  error_at(t, "[[measure]]", "measure[0]: missing key 'dof'");
  t = with_replaced(kSemiDiscrete, "semi_discrete = true", "against = \"u_contact_exact\"\nsemi_discrete = true");
  error_at(t, "against", "measure[0].against: a semi-discrete error compares one dof's displacement with modal-exact's; valid: no against");
  t = with_replaced(kSemiDiscrete, "semi_discrete = true", "semi_discrete = false\nobservable = \"u_contact\"\nagainst = \"u_contact_exact\"");
  error_at(t, "dof = 0", "measure[0].dof: only a semi-discrete error compares one dof's displacement; valid: semi_discrete = true beside it");
  t = with_replaced(kSemiDiscrete, "per_nominal_step = true", "per_nominal_step = \"yes\"");
  error_at(t, "per_nominal_step", "measure[0].per_nominal_step: expected a boolean, got a string");
  t = with_replaced(kRefined, "not_ok = \"outcome\"", "not_ok = \"status\"");
  error_at(t, "not_ok", "table[0].not_ok: 'status' is not valid (nearest: ");
  CHECK_THAT(some_runs_error(t), Catch::Contains("valid: values, outcome"));
  t = with_replaced(kRefined, "fit_against = \"1/N\"", "fit_against = \"1/N\"\nnot_ok = \"outcome\"");
  error_at(t, "not_ok = \"outcome\"\nproblems", "table[1].not_ok: only a table of one row per run shows a run's outcome; valid: rows = \"case\"");
  t = with_replaced(kRefined, "columns = [\"problem\", \"dt\", \"u err\", \"E err\", \"CPU\", \"outcome\"]", "columns = [\"problem\", \"dt\"]");
  error_at(t, "not_ok", "table[0].not_ok: the table shows no measure's column; valid: a measure's label among its columns");
  t = with_replaced(kRefined, "fit_against = \"1/N\"", "fit_against = \"N\"");
  error_at(t, "fit_against", "table[1].fit_against: 'N' is not 1/KEY, KEY a numeric parameter of problem 'bar, N = 20'; valid: ");
  CHECK_THAT(some_runs_error(t), Catch::Contains("1/N"));
  t = with_replaced(kRefined, "fit_against = \"1/N\"", "fit_against = \"1/mass\"");
  error_at(t, "fit_against", "table[1].fit_against: '1/mass' is not 1/KEY");
  t = with_replaced(kRefined, "not_ok = \"outcome\"", "fit_against = \"1/N\"");
  error_at(t, "fit_against", "table[0].fit_against: only a table of fitted orders fits; valid: rows = \"group\"");
  t = with_replaced(kRefined, "fit_against = \"1/N\"", "fit_against = \"1/N\"\nexcept = { integrator = \"cd-lagrange\" }");
  error_at(t, "except", "table[1].except: a table of rows = \"group\" has no except; valid: rows = \"case\", \"pivot\"");
  t = with_replaced(kSemiDiscrete, "except = { integrator", "except = { integrater");
  error_at(t, "except = {", "table[1].except.integrater: 'integrater' is not valid (nearest: integrator)");
  t = with_replaced(kSemiDiscrete, "except = { integrator = \"modal-exact\" }", "except = { integrator = true }");
  error_at(t, "except = {", "table[1].except.integrator: expected a number or a text, got a boolean");
  t = with_replaced(kRefined, "not_ok = \"outcome\"", "order = { of = \"dt\" }");
  error_at(t, "order = ", "table[0].order: only a pivot fits the values of its rows; valid: rows = \"pivot\"");
  t = with_replaced(kSemiDiscrete, "order = { of = \"dt\", header = \"time order\" }", "order = { header = \"time order\" }");
  error_at(t, "order = ", "table[1].order: missing key 'of'");
  t = with_replaced(kSemiDiscrete, "order = { of = \"dt\", header = \"time order\" }", "order = { of = \"dt\", missing = \"-\" }");
  error_at(t, "order = ", "table[1].order.missing: an order is fitted, never missing; valid: of, header, unit, format, description");
  t = with_replaced(kSemiDiscrete, "columns = [\"integrator\", {", "columns = [{ of = \"integrator\", missing = \"-\" }, {");
  error_at(t, "missing = \"-\"", "table[1].columns[0].missing: only a table of one row per run shows its missing cells otherwise; valid: rows = \"case\", or a pivot's value column (the last)");
}

// A figure of a pivot table: x, series and panels name its key columns (drawn under their
// headers), y one of its spread columns by header; the reader refuses a y that is no spread
// column's header, and a key the pivot does not have, and the tables refuse a spread value
// no run gave.
TEST_CASE("study file: a figure of a pivot table draws a spread column", "[studies][study_file]") {
  using Catch::StartsWith;
  const std::string figure = R"(
[[figure]]
id = "pivot_figure"
table = "pivot"
title = "E end at e = 0.5"
x = "integrator"
y = "E end, e = 0.5"
panels = []
)";
  const auto tables = run_some_runs(kSomeRuns + figure);
  const nsb::Table& pivot = table_of(tables, "pivot");
  REQUIRE(pivot.figures.size() == 1);
  CHECK(pivot.figures[0].x == "integrator");
  CHECK(pivot.figures[0].y == "E end, e = 0.5");
  CHECK(std::any_of(pivot.columns.begin(), pivot.columns.end(), [](const nsb::Column& c) { return c.name == "E end, e = 0.5"; }));
  const long y = line_of(kSomeRuns + figure, "y = \"E end, e = 0.5\"");
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns + figure, "y = \"E end, e = 0.5\"", "y = \"E end\"")),
             StartsWith(fmt::format("f.toml:{}: figure[1].y: 'E end' is not a spread column of pivot table 'pivot'; valid: 'E end, e = {{}}' "
                                    "with {{}} a value of 'parameter e'",
                                    y)));
  CHECK_THAT(some_runs_error(with_replaced(kSomeRuns + figure, "x = \"integrator\"\ny", "x = \"problem\"\ny")),
             StartsWith(fmt::format("f.toml:{}: figure[1].x: 'problem' is not a column of table 'pivot'; valid: integrator", y - 1)));
  CHECK_THROWS_WITH(run_some_runs(with_replaced(kSomeRuns + figure, "y = \"E end, e = 0.5\"", "y = \"E end, e = 2\"")),
                    StartsWith("figure pivot_figure: y 'E end, e = 2' is not a column of table pivot; its runs gave: integrator, E end, e = 1"));
}
