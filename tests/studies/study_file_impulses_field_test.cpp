// Study files: impulses tables (the contact impulses summed over each nominal step bin, the exact
// force beside them), field tables (the element stresses after every step, the exact field
// first) with their space-time figures, metadata lines, and their bad input.
#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "studies/study.hpp"
#include "studies/study_file.hpp"

namespace {

// The Signorini bar of 10 elements (L = c = v0 = 1: contact on (0, 2), force 1), lumped and
// singular mass at 0.9 of the stable step, run to t = 3 by CD-Lagrange, its adaptive variant
// and CD-penalty (both decline the singular mass); a trajectory of the contact force at every
// step beside the impulses, the momentum at the end.
const std::string kImpulsesBar = R"TOML([study]
title = "t"
t_end = 3.0
cpu_repeats = 0
metadata = [{ line = "N", of = "parameter N" }, { line = "schemes", text = "three of them" }]

[[problem]]
name = "signorini-bar"
label = "lumped"
parameters = { mass = "lumped", N = 10 }
stable_steps = [0.9]

[[problem]]
name = "signorini-bar"
label = "singular"
parameters = { mass = "singular", N = 10 }
stable_steps = [0.9]

[[integrator]]
name = "cd-lagrange"

[[integrator]]
name = "cd-lagrange-adaptive"

[[integrator]]
name = "cd-penalty"

[[measure]]
kind = "value"
observable = "momentum"
label = "P end"

[[table]]
id = "runs"
title = "runs"
columns = ["problem", "integrator", "dt", "P end", "steps", "outcome"]

[[table]]
id = "force"
title = "force"
rows = "impulses"
exact = "contact_force_exact"
exact_per = "integrator"
exact_in = "problem"
columns = ["integrator", "problem", "t", "value"]

[[table]]
id = "steps"
title = "steps"
rows = "trajectory"
observable = "contact_force"
spacing = "steps"
points = 100000
columns = ["integrator", "problem", "t", "value"]

[[table]]
id = "stress"
title = "stress"
rows = "field"
problems = ["lumped", "singular"]
integrators = ["cd-lagrange", "cd-penalty"]
exact_times = 4
metadata = [{ line = "cells", text = "10" }]
columns = ["integrator", "problem", "t", { of = "field", header = "s(x = {})" }]

[[figure]]
id = "force"
title = "force"
table = "force"
x = "t"
y = "value"
series = ["problem"]
panels = ["integrator"]
log_x = false
log_y = false

[[figure]]
id = "stress"
title = "stress"
table = "stress"
y = "t"
series = []
panels = ["integrator", "problem"]
log_x = false
log_y = false
value_label = "sigma"
caption = "A panel per run"
)TOML";

std::vector<nsb::Table> run_impulses_study(const std::string& text) {
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(text, "f.toml", false));
  const auto cases = nsb::study_cases(entry, {});
  std::vector<nsb::Json> results;
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {}));
  return nsb::study_tables(entry, cases, results, {});
}

const nsb::Table& impulses_table_named(const std::vector<nsb::Table>& tables, const std::string& id) {
  const auto t = std::find_if(tables.begin(), tables.end(), [&](const nsb::Table& u) { return u.id == id; });
  REQUIRE(t != tables.end());
  return *t;
}

std::string cell_text(const nsb::Cell& c) { return std::get<std::string>(c); }
double cell_number(const nsb::Cell& c) { return std::get<double>(c); }

// The rows of `t` by (integrator, problem), in order.
std::map<std::pair<std::string, std::string>, std::vector<std::vector<nsb::Cell>>> rows_by_run(const nsb::Table& t) {
  std::map<std::pair<std::string, std::string>, std::vector<std::vector<nsb::Cell>>> out;
  for (const auto& row : t.rows) out[{cell_text(row[0]), cell_text(row[1])}].push_back(row);
  return out;
}

std::string impulses_study_error(const std::string& text) {
  try {
    nsb::parse_study_text(text, "f.toml", false);
  } catch (const nsb::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string impulses_replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

// "f.toml:LINE: " of the line where `needle` first occurs in kImpulsesBar, `after` lines on.
std::string impulses_at(const std::string& needle, long after = 0) {
  const auto pos = kImpulsesBar.find(needle);
  REQUIRE(pos != std::string::npos);
  return fmt::format("f.toml:{}: ", 1 + std::count(kImpulsesBar.begin(), kImpulsesBar.begin() + static_cast<long>(pos), '\n') + after);
}

}  // namespace

TEST_CASE("study file: an impulses table sums each nominal step's impulses, the exact force in each integrator's panel",
          "[studies][study_file]") {
  const auto tables = run_impulses_study(kImpulsesBar);
  const nsb::Table& runs = impulses_table_named(tables, "runs");
  const nsb::Table& force = impulses_table_named(tables, "force");
  CHECK(force.csv_only);
  const auto bins = rows_by_run(force), steps = rows_by_run(impulses_table_named(tables, "steps"));
  // The runs that step: CD-Lagrange on both masses, its adaptive variant and CD-penalty lumped.
  const std::vector<std::pair<std::string, std::string>> ran = {
      {"cd-lagrange", "lumped"}, {"cd-lagrange", "singular"}, {"cd-lagrange-adaptive", "lumped"}, {"cd-penalty", "lumped"}};
  for (const auto& run : ran) {
    INFO(run.first << ", " << run.second);
    REQUIRE(bins.count(run));
    const auto& b = bins.at(run);
    const auto& s = steps.at(run);
    const auto row = std::find_if(runs.rows.begin(), runs.rows.end(),
                                  [&](const auto& r) { return cell_text(r[0]) == run.second && cell_text(r[1]) == run.first; });
    REQUIRE(row != runs.rows.end());
    const double dt = cell_number((*row)[2]);
    // Bins j = 1, 2, ... up to the one of the last step (t_end = 3 past a whole number of steps).
    REQUIRE(b.size() == static_cast<std::size_t>(std::ceil(3.0 / dt - 1e-9)));
    for (std::size_t j = 0; j < b.size(); ++j) CHECK(cell_number(b[j][2]) == static_cast<double>(j + 1) * dt);
    if (run.first != "cd-lagrange-adaptive") {
      // A fixed step is its bin: its impulse over dt, the trajectory's contact force, bit for bit.
      REQUIRE(s.size() == b.size());
      for (std::size_t j = 0; j < b.size(); ++j) CHECK(b[j][3] == s[j][3]);
    } else {
      // The adaptive scheme's smaller steps summed into their bins: sum_k F_k dt_k / dt over the
      // steps ending in (t_j - dt, t_j].
      REQUIRE(s.size() > b.size());
      std::vector<double> sums(b.size(), 0.0);
      double t_prev = 0.0;
      for (const auto& step : s) {
        const double t = cell_number(step[2]);
        sums[static_cast<std::size_t>(std::ceil(t / dt - 1e-9)) - 1] += cell_number(step[3]) * (t - t_prev) / dt;
        t_prev = t;
      }
      for (std::size_t j = 0; j < b.size(); ++j) CHECK(cell_number(b[j][3]) == Approx(sums[j]).margin(1e-12));
    }
    // The impulses sum to the momentum's change (no load, internal forces summing to zero),
    // P0 = -rho A L v0 = -1.
    if (run.first == "cd-lagrange") {
      double total = 0.0;
      for (const auto& bin : b) total += cell_number(bin[3]) * dt;
      CHECK(total == Approx(cell_number((*row)[3]) + 1.0).margin(1e-9));
    }
  }
  CHECK_FALSE(bins.count({"cd-penalty", "singular"}));  // declined: no bins
  // The exact force after each integrator's first run, at its bins' ends: 1 on (0, 2), else 0.
  for (const std::string integrator : {"cd-lagrange", "cd-lagrange-adaptive", "cd-penalty"}) {
    INFO(integrator);
    const auto& exact = bins.at({integrator, "exact"});
    const auto& own = bins.at({integrator, "lumped"});
    REQUIRE(exact.size() == own.size());
    for (std::size_t j = 0; j < exact.size(); ++j) {
      const double t = cell_number(exact[j][2]);
      CHECK(t == cell_number(own[j][2]));
      CHECK(cell_number(exact[j][3]) == (t > 0.0 && t < 2.0 ? 1.0 : 0.0));
    }
  }
  // Rows in the order of the runs, the exact rows right after the first run of their integrator.
  std::vector<std::string> order;
  for (const auto& row : force.rows)
    if (order.empty() || order.back() != cell_text(row[0]) + "/" + cell_text(row[1])) order.push_back(cell_text(row[0]) + "/" + cell_text(row[1]));
  // (problem by problem: the lumped runs, then the singular).
  CHECK(order == std::vector<std::string>{"cd-lagrange/lumped", "cd-lagrange/exact", "cd-lagrange-adaptive/lumped", "cd-lagrange-adaptive/exact",
                                          "cd-penalty/lumped", "cd-penalty/exact", "cd-lagrange/singular"});
  // Its figure, under the table's headers.
  REQUIRE(force.figures.size() == 1);
  CHECK(force.figures[0].x == "t");
  CHECK(force.figures[0].series == std::vector<std::string>{"problem"});
}

TEST_CASE("study file: a field table of the element stresses after every step, the exact field first, a space-time figure",
          "[studies][study_file]") {
  const auto tables = run_impulses_study(kImpulsesBar);
  const nsb::Table& stress = impulses_table_named(tables, "stress");
  CHECK(stress.csv_only);
  // integrator, problem, t, then a column per element by its centre (h = 0.1).
  REQUIRE(stress.columns.size() == 3 + 10);
  std::vector<double> centres;
  for (int e = 0; e < 10; ++e) {
    centres.push_back(0.5 * (e * 0.1 + (e + 1) * 0.1));
    CHECK(stress.columns[3 + static_cast<std::size_t>(e)].name == fmt::format("s(x = {:g})", centres.back()));
  }
  const auto rows = rows_by_run(stress);
  // Exact: t = 3 k / 4, sigma = -rho c v0 = -1 between the fronts x < t < 2 - x, else 0.
  const auto& exact = rows.at({"exact", "lumped"});
  REQUIRE(exact.size() == 5);
  CHECK(cell_text(stress.rows[0][0]) == "exact");  // first
  for (std::size_t k = 0; k < exact.size(); ++k) {
    const double t = 3.0 * static_cast<double>(k) / 4.0;
    CHECK(cell_number(exact[k][2]) == t);
    for (std::size_t e = 0; e < 10; ++e) CHECK(cell_number(exact[k][3 + e]) == (t > centres[e] && t < 2.0 - centres[e] ? -1.0 : 0.0));
  }
  // The runs of the integrators named: a row at the start (no stress yet), then one per step.
  const nsb::Table& runs = impulses_table_named(tables, "runs");
  for (const auto& run : std::vector<std::pair<std::string, std::string>>{{"cd-lagrange", "lumped"}, {"cd-lagrange", "singular"},
                                                                          {"cd-penalty", "lumped"}}) {
    INFO(run.first << ", " << run.second);
    const auto row = std::find_if(runs.rows.begin(), runs.rows.end(),
                                  [&](const auto& r) { return cell_text(r[0]) == run.second && cell_text(r[1]) == run.first; });
    REQUIRE(row != runs.rows.end());
    const auto& field = rows.at(run);
    REQUIRE(field.size() == static_cast<std::size_t>(std::get<long>((*row)[4])) + 1);
    CHECK(cell_number(field[0][2]) == 0.0);
    for (std::size_t e = 0; e < 10; ++e) CHECK(cell_number(field[0][3 + e]) == 0.0);
    // After the contact and its release (t = 3) the bar flies off: no compression left to speak of.
    double compressed = 0.0;
    for (const auto& r : field)
      if (cell_number(r[2]) > 0.5 && cell_number(r[2]) < 1.5) compressed = std::min(compressed, cell_number(r[3]));
    CHECK(compressed < -0.5);  // the element at the wall compressed during the contact
  }
  CHECK_FALSE(rows.count({"cd-lagrange-adaptive", "lumped"}));  // not named
  CHECK_FALSE(rows.count({"cd-penalty", "singular"}));          // declined
  // The space-time figure: a panel per run, the declined one named in its caption.
  REQUIRE(stress.figures.size() == 1);
  const nsb::Figure& f = stress.figures[0];
  CHECK(f.kind == "space_time");
  CHECK(f.x.empty());
  CHECK(f.y == "t");
  CHECK(f.panels == std::vector<std::string>{"integrator", "problem"});
  CHECK(f.positions == centres);
  CHECK(f.values.size() == 10);
  CHECK(f.values.front() == "s(x = 0.05)");
  CHECK(f.value_label == "sigma");
  CHECK(f.caption == "A panel per run; no panel for cd-penalty (singular): n/a.");
}

TEST_CASE("study file: metadata lines, the study's on every declared table, a table's own after them", "[studies][study_file]") {
  // The singular bar of 20 elements: N takes 10, then 20 (the field table shows the lumped one only).
  std::string text = impulses_replaced(kImpulsesBar, "parameters = { mass = \"singular\", N = 10 }", "parameters = { mass = \"singular\", N = 20 }");
  text = impulses_replaced(text, "problems = [\"lumped\", \"singular\"]", "problems = [\"lumped\"]");
  const auto tables = run_impulses_study(text);
  for (const std::string id : {"runs", "force", "steps", "stress"}) {
    INFO(id);
    const auto& meta = impulses_table_named(tables, id).metadata;
    REQUIRE(meta.size() >= 2);
    const auto own = std::find(meta.begin(), meta.end(), std::pair<std::string, std::string>{"N", "10 20"});
    REQUIRE(own != meta.end());
    CHECK(*(own + 1) == std::pair<std::string, std::string>{"schemes", "three of them"});
    CHECK((own + 2 == meta.end()) == (id != "stress"));
    if (id == "stress") CHECK(*(own + 2) == std::pair<std::string, std::string>{"cells", "10"});
  }
}

TEST_CASE("study file: impulses and field tables, space-time figures, metadata lines: bad input named", "[studies][study_file][bad-input]") {
  using Catch::StartsWith;
  CHECK(impulses_study_error(kImpulsesBar) == "(no error)");
  // Impulses tables.
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact_per = \"integrator\"", "exact_per = \"integrator\"\ncomponent = \"sigma\"")),
             StartsWith(impulses_at("exact_per = \"integrator\"", 1) + "table[1].component: a table of rows = \"impulses\" has no component; valid: rows = \"field\""));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact_per = \"integrator\"", "exact_per = \"integrator\"\nscale = -1")),
             StartsWith(impulses_at("exact_per = \"integrator\"", 1) + "table[1].scale: -1 is not positive and finite; valid: (0, inf)"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact = \"contact_force_exact\"", "exact = \"contact_force_exac\"")),
             StartsWith(impulses_at("exact = \"contact_force_exact\"") + "table[1].exact: 'contact_force_exac' is not an observable of problem 'lumped'; valid: "));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact_per = \"integrator\"", "exact_per = \"value\"")),
             StartsWith(impulses_at("exact_per = \"integrator\"") + "table[1].exact_per: 'value' is not valid"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact = \"contact_force_exact\"\n", "")),
             StartsWith(impulses_at("exact_per = \"integrator\"", -1) + "table[1].exact_per: where the exact rows go, without exact rows; valid: exact = OBSERVABLE beside it"));
  // Impulses of a problem without contacts, the exact force of a problem without an exact solution.
  const std::string chain = "[study]\ntitle = \"t\"\nt_end = 1.0\n[[problem]]\nname = \"spring-chain\"\nparameters = { wall = \"none\" }\n"
                            "[[integrator]]\nname = \"moreau-jean\"\nsteps = [1e-2]\n[[table]]\nid = \"force\"\ntitle = \"force\"\n"
                            "rows = \"impulses\"\ncolumns = [\"integrator\", \"value\"]\n";
  CHECK_THAT(impulses_study_error(chain),
             StartsWith("f.toml:13: table[0].rows: problem 'spring-chain' has no contacts, hence no impulses; valid: problems with contacts"));
  CHECK_THAT(impulses_study_error(impulses_replaced(impulses_replaced(chain, "wall = \"none\"", "wall = \"left\""), "rows = \"impulses\"\n",
                                                    "rows = \"impulses\"\nexact = \"momentum\"\n")),
             StartsWith("f.toml:14: table[0].exact: problem 'spring-chain' has no exact solution; valid: problems with one"));
  // Field tables.
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact_times = 4", "exact_times = 4\ncomponent = \"tau\"")),
             StartsWith(impulses_at("exact_times = 4", 1) + "table[3].component: 'tau' is not a stress component of problem 'lumped'; valid: sigma"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact_times = 4", "exact_times = 0")),
             StartsWith(impulses_at("exact_times = 4") + "table[3].exact_times: 0 is out of range; valid: [1, 100000]"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "exact_times = 4", "exact_times = 4\nexact_per = \"problem\"")),
             StartsWith(impulses_at("exact_times = 4", 1) + "table[3].exact_per: a table of rows = \"field\" has no exact_per; valid: rows = \"impulses\""));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "parameters = { mass = \"singular\", N = 10 }", "parameters = { mass = \"singular\", N = 20 }")),
             StartsWith(impulses_at("rows = \"field\"", 1) + "table[3].problems: problems 'lumped' and 'singular' have different field meshes (10 and 20 cells); valid: problems of one mesh"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "parameters = { mass = \"lumped\", N = 10 }", "parameters = { mass = \"lumped\", N = 10, g = 1, g0 = 1 }")),
             StartsWith(impulses_at("exact_times = 4") + "table[3].exact_times: problem 'lumped' has no exact field; valid: "));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "{ of = \"field\", header = \"s(x = {})\" }", "{ of = \"field\", header = \"s\" }")),
             StartsWith(impulses_at("{ of = \"field\", header") + "table[3].columns[3].header: 's' does not name the cell; valid: a header with {} where each cell's centre x goes"));
  const std::string mass = "[study]\ntitle = \"t\"\nt_end = 1.0\n[[problem]]\nname = \"bouncing-mass\"\n[[integrator]]\nname = \"moreau-jean\"\n"
                           "steps = [1e-2]\n[[table]]\nid = \"stress\"\ntitle = \"stress\"\nrows = \"field\"\ncolumns = [\"integrator\", \"field\"]\n";
  CHECK_THAT(impulses_study_error(mass),
             StartsWith("f.toml:12: table[0].rows: problem 'bouncing-mass' has no 1D field mesh of bar elements with a stress; valid: "));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "integrators = [\"cd-lagrange\", \"cd-penalty\"]", "integrators = [\"cd-lagrang\"]")),
             StartsWith(impulses_at("integrators = [\"cd-lagrange\", \"cd-penalty\"]") + "table[3].integrators[0]: 'cd-lagrang' is not valid (nearest: cd-lagrange)"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "spacing = \"steps\"", "spacing = \"steps\"\nintegrators = [\"cd-lagrange\"]")),
             StartsWith(impulses_at("spacing = \"steps\"", 1) + "table[2].integrators: only a table of one row per run, or of its impulses or field, picks its integrators' runs; valid: rows = \"case\", \"impulses\" or \"field\""));
  // Space-time figures.
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "table = \"stress\"\ny = \"t\"", "table = \"stress\"\nx = \"t\"\ny = \"t\"")),
             StartsWith(impulses_at("table = \"stress\"", 1) + "figure[1].x: a space-time picture's horizontal axis is the cells' position; valid: no x"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "table = \"force\"\nx = \"t\"", "table = \"force\"")),
             StartsWith(impulses_at("[[figure]]\nid = \"force\"") + "figure[0]: missing key 'x'"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "panels = [\"integrator\"]\nlog_x", "panels = [\"integrator\"]\nvalue_label = \"F\"\nlog_x")),
             StartsWith(impulses_at("panels = [\"integrator\"]\nlog_x", 1) + "figure[0].value_label: only a space-time picture has a colour scale; valid: table = a table of rows = \"field\""));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "{ of = \"field\", header = \"s(x = {})\" }]", "\"integrator label\"]")),
             StartsWith(impulses_at("table = \"stress\"") + "figure[1].table: table 'stress' shows no field to draw; valid: a table whose columns hold \"field\""));
  // Metadata lines.
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "of = \"parameter N\"", "of = \"parameter Q\"")),
             StartsWith(impulses_at("of = \"parameter N\"") + "study.metadata[0].of: 'parameter Q' is not valid (nearest: parameter L)"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "of = \"parameter N\"", "of = \"parameter N\", text = \"N\"")),
             StartsWith(impulses_at("of = \"parameter N\"") + "study.metadata[0]: give one of of = COLUMN (its values over the runs) or text = TEXT"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "line = \"schemes\"", "line = \"N\"")),
             StartsWith(impulses_at("line = \"schemes\"") + "study.metadata[1].line: line 'N' given twice; valid: each name once"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "line = \"schemes\"", "line = \"two\\nlines\"")),
             StartsWith(impulses_at("line = \"schemes\"") + "study.metadata[1].line: holds the control character 0x0a; valid: a text of one line"));
  CHECK_THAT(impulses_study_error(impulses_replaced(kImpulsesBar, "line = \"cells\"", "line = \"\"")),
             StartsWith(impulses_at("line = \"cells\"") + "table[3].metadata[0].line: an empty name; valid: the name of the line, e.g. N"));
  const auto table_start = kImpulsesBar.find("[[table]]");
  CHECK_THAT(impulses_study_error(kImpulsesBar.substr(0, table_start)), StartsWith(impulses_at("metadata = [") + "study.metadata: metadata lines are written on declared tables; valid: [[table]]s, or no metadata"));
}
