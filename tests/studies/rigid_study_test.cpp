// The rigid study (studies/builtin/rigid.toml) and the study-file measures it is written in:
// impact-ratio, amplitude, impact-count, rest-time, peak-time, value (studies/study_file/run_recorders.hpp, EventFigures),
// ContactImpacts and the closed forms of studies/measures.hpp, and case tables that pick
// their problems.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "studies/measures.hpp"
#include "studies/registry.hpp"
#include "studies/study_file.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;

namespace {

const nsb::StudyEntry& rigid_entry() {
  const auto& studies = nsb::study_registry();
  const auto it = std::find_if(studies.begin(), studies.end(), [](const nsb::StudyEntry& e) { return e.name == "rigid"; });
  REQUIRE(it != studies.end());
  return *it;
}

// A one-problem study of cd-lagrange at one step with the measures given.
std::string one_run(const std::string& problem, const std::string& t_end, const std::string& dt, const std::string& measures) {
  return "[study]\ntitle = \"r\"\nt_end = " + t_end + "\ncpu_repeats = 0\n[[problem]]\n" + problem +
         "\n[[integrator]]\nname = \"cd-lagrange\"\nsteps = [" + dt + "]\n" + measures;
}

std::string parse_error(const std::string& text) {
  return nsb::test::input_error_text_of([&] { nsb::parse_study_text(text, "r.toml", false); });
}

// The values of the one case of a one-run study, in the order of its measures.
nsb::Json run_values(const std::string& text) {
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(text, "r.toml", false));
  const auto cases = nsb::study_cases(entry, {});
  REQUIRE(cases.size() == 1);
  const nsb::Json result = nsb::run_study_case(entry, cases[0], {});
  REQUIRE(result["status"] == "ok");
  return result["values"];
}

}  // namespace

TEST_CASE("built-in study rigid: registered from its file, every integrator on each problem at the problem's steps",
          "[studies][rigid]") {
  const nsb::StudyEntry& rigid = rigid_entry();
  CHECK(rigid.source == "studies/builtin/rigid.toml");
  const nsb::EmbeddedStudyFile* file = nsb::builtin_study_file("studies/builtin/rigid.toml");
  REQUIRE(file != nullptr);
  const nsb::StudySpec spec = nsb::parse_study_text(std::string(file->text), "rigid.toml", false);
  const auto& registry = nsb::integrator_registry();
  REQUIRE(spec.problems.size() == 5);
  CHECK(spec.problems[0].name == "rocking-block");
  CHECK(spec.problems[0].parameters.at("mu") == "1");
  CHECK(spec.problems[1].name == "rocking-block");
  CHECK(spec.problems[1].parameters.at("mu") == "0.1");
  CHECK(spec.problems[2].name == "painleve-rod");
  CHECK(spec.problems[2].parameters.empty());  // the cardillo example's data are the defaults
  // The two blocks, large sliding and small, launched alike (only `sliding` differs), one step.
  for (std::size_t p : {3, 4}) {
    CHECK(spec.problems[p].name == "two-blocks");
    CHECK(spec.problems[p].steps == std::vector<double>{1e-4});
  }
  CHECK(spec.problems[3].parameters.at("sliding") == "large");
  CHECK(spec.problems[4].parameters.at("sliding") == "small");
  nsb::Overrides small = spec.problems[4].parameters;
  small["sliding"] = "large";
  CHECK(small == spec.problems[3].parameters);
  CHECK(nsb::make_problem("two-blocks", spec.problems[3].parameters)->contacts_move());
  CHECK_FALSE(nsb::make_problem("two-blocks", spec.problems[4].parameters)->contacts_move());
  std::vector<std::string> ids;
  for (const auto& t : spec.tables) ids.push_back(t.id);
  CHECK(ids == std::vector<std::string>{"rigid_rocking", "rigid_painleve", "rigid_sliding", "rigid_ranking"});
  const auto cases = nsb::study_cases(rigid, {false});
  REQUIRE(cases.size() == 3 * registry.size() * 3 + 2 * registry.size());
  std::size_t k = 0;
  for (std::size_t p = 0; p < 5; ++p)
    for (std::size_t i = 0; i < registry.size(); ++i)
      for (const double dt : spec.problems[p].steps) {
        CHECK(cases[k]["problem"] == p);
        CHECK(spec.integrators[cases[k]["integrator"].get<std::size_t>()].name == registry[i].name);
        CHECK(cases[k++]["dt"].get<double>() == dt);
      }
  // The schemes that run it are those with the capability; every other one declines (n/a).
  std::vector<std::string> moving;
  for (const auto& e : registry)
    if (e.capabilities.moving_contacts) moving.push_back(e.name);
  CHECK(std::find(moving.begin(), moving.end(), "cd-lagrange") != moving.end());
  CHECK(std::find(moving.begin(), moving.end(), "moreau-jean") != moving.end());
  const auto declined = nsb::run_study_case(rigid, cases[3 * std::size_t(std::find_if(registry.begin(), registry.end(), [](const auto& e) {
                                                                                    return !e.capabilities.moving_contacts;
                                                                                  }) - registry.begin())],
                                            {});
  CHECK(declined["status"] == "n/a");
  CHECK(declined["message"].get<std::string>().find("moving contacts") != std::string::npos);
}

TEST_CASE("rigid study's two blocks: the momentum identity of the 2D two-body mesh per component, round-off for cd-lagrange "
          "in large sliding and small",
          "[studies][rigid][measures]") {
  // As rigid.toml runs them: the node-to-segment weights sum to zero per direction in every
  // configuration, so P changes by the floor impulses only (MeshMomentum takes the rows at the
  // step's end). The upper block lands (y impulses) and slides under friction (x impulses).
  std::string measures;
  for (const char* c : {"px", "py"}) measures += fmt::format("[[measure]]\nkind = \"momentum\"\ncomponent = \"{}\"\n", c);
  measures += "[[measure]]\nkind = \"energy\"\nnorm = \"final\"\n";
  for (const char* sliding : {"large", "small"}) {
    INFO(sliding);
    const nsb::Json v = run_values(one_run(fmt::format("name = \"two-blocks\"\nparameters = {{ sliding = \"{}\", g = 0, e = 0, mu = 0.3, "
                                                       "upper_vx = 1.5, upper_vy = -1 }}",
                                                       sliding),
                                           "0.15", "1e-4", measures));
    CHECK(v[0].get<double>() < 1e-13);
    CHECK(v[1].get<double>() < 1e-13);
    CHECK(v[2].get<double>() < -0.01);  // the landing (e = 0) and the sliding took energy: there was contact
  }
  CHECK_THAT(parse_error(one_run("name = \"two-blocks\"", "0.1", "1e-4", "[[measure]]\nkind = \"momentum\"\ncomponent = \"pz\"\n")),
             Catch::Contains("measure[0].component: problem 'two-blocks' has no mesh component pz"));
}

TEST_CASE("ContactImpacts: an impact is a contact's impulse after steps without one in which its gap opened and fell; before, after and amplitude",
          "[studies][measures][rigid]") {
  // Contact 0 closed at t = 0 (it carries its load: no impact), contact 1 open.
  nsb::Vec gaps(2);
  gaps << 0.0, 0.3;
  nsb::ContactImpacts impacts(gaps, -1.0);
  const auto pair = [](double a, double b) {
    nsb::Vec v(2);
    v << a, b;
    return v;
  };
  impacts.add(0.1, pair(0, 0), pair(5e-11, 0.25), -1.0);  // the pivot without impulse for a step, its gap drifted open
  impacts.add(0.12, pair(1, 0), pair(0, 0.2), -1.5);      // takes its load again, the gap never fell: no impact
  impacts.add(0.14, pair(0, 0), pair(-1e-6, 0.15), -1.0);  // without impulse, still closed
  impacts.add(0.15, pair(1, 0), pair(0, 0.1), -2.0);       // no impact either
  impacts.add(0.2, pair(0, 1), pair(0.1, 0), 1.5);       // contact 1 struck: -2 -> 1.5
  impacts.add(0.3, pair(0, 1), pair(0.2, 0), 3.0);
  impacts.add(0.4, pair(0, 1), pair(0.1, 0), -4.0);  // amplitude 4 until the next impact
  impacts.add(0.5, pair(1, 0), pair(0, 0.1), 0.5);   // contact 0 struck: open at the step's start
  impacts.add(0.6, pair(1, 0), pair(0, 0.2), 0.25);
  REQUIRE(impacts.impacts().size() == 2);
  const auto& first = impacts.impacts()[0];
  CHECK(first.t == 0.2);
  CHECK(first.before == -2.0);
  CHECK(first.after == 1.5);
  CHECK(first.amplitude == 4.0);
  CHECK(impacts.impacts()[1].t == 0.5);
  CHECK(impacts.impacts()[1].before == -4.0);
  CHECK(impacts.impacts()[1].amplitude == 0.25);
}

TEST_CASE("closed forms: Housner's and Moreau's ratios of the rocking block, its amplitudes and rest, the Painleve jam",
          "[studies][measures][rigid]") {
  const auto block = nsb::make_problem("rocking-block", {{"mu", "1"}});
  const double alpha = std::atan(0.2 / 1.0);
  const double housner = 1.0 - 1.5 * std::sin(alpha) * std::sin(alpha);
  CHECK(nsb::rocking_law_ratio(*block, nsb::ImpactLaw::housner) == Approx(housner).epsilon(1e-15));
  CHECK(nsb::rocking_law_ratio(*block, nsb::ImpactLaw::moreau) == Approx(housner).epsilon(1e-12));  // mu above mu_H
  // mu = 0.1 < mu_H: the corner slips, 1 - 6 s (s - mu c) / (1 + 3 s^2 - 3 mu s c) with e = 0.
  const auto slipping = nsb::make_problem("rocking-block", {{"mu", "0.1"}});
  const double s = std::sin(alpha), c = std::cos(alpha);
  // Rocking about a stuck pivot needs |F / N| = mu_H at theta = 0: below it the pivot slides
  // before the impact, and Moreau's slip outcome has no rocking approach to start from.
  CHECK(3.0 * s * c / (4.0 - 3.0 * s * s) == Approx(3.0 * s * c / (1.0 + 3.0 * c * c)).epsilon(1e-15));
  CHECK(std::isnan(nsb::rocking_law_ratio(*slipping, nsb::ImpactLaw::moreau)));
  CHECK(nsb::rocking_law_ratio(*slipping, nsb::ImpactLaw::housner) == Approx(housner).epsilon(1e-15));
  // Amplitudes fall at every impact; the rest time is finite; nothing of the kind elsewhere.
  CHECK(nsb::rocking_amplitude_after(*block, 2) < nsb::rocking_amplitude_after(*block, 1));
  CHECK(std::isnan(nsb::rocking_amplitude_after(*block, 0)));
  CHECK(std::isfinite(nsb::rocking_rest_time(*block)));
  const auto rod = nsb::make_problem("painleve-rod", {});
  CHECK(nsb::painleve_jam_time(*rod) == Approx(0.8145).margin(5e-4));
  CHECK(std::isnan(nsb::painleve_jam_time(*block)));
  CHECK(std::isnan(nsb::rocking_law_ratio(*rod, nsb::ImpactLaw::housner)));
  CHECK(std::isnan(nsb::rocking_rest_time(*rod)));
}

TEST_CASE("rigid measures on known answers: cd-lagrange's first impact ratio within O(dt) of the law, rest, jam",
          "[studies][rigid]") {
  // Rocking block, mu = 1: the law's ratio 0.942308; the ratio of a step of 1e-4 carries the
  // smooth motion of one step (|omega'| dt ~ 1.4e-4 on |omega| ~ 0.46): error of order 1e-3 at most.
  const std::string measures = R"(
[[measure]]
kind = "impact-ratio"
observable = "omega"
[[measure]]
kind = "impact-ratio"
observable = "omega"
law = "moreau"
[[measure]]
kind = "impact-ratio"
observable = "omega"
law = "housner"
count = 3
[[measure]]
kind = "impact-count"
[[measure]]
kind = "amplitude"
observable = "theta"
impact = 1
exact = true
[[measure]]
kind = "value"
observable = "theta"
norm = "max"
)";
  const nsb::Json v = run_values(one_run("name = \"rocking-block\"\nparameters = { mu = 1 }", "1.5", "1e-4", measures));
  const double law = 1.0 - 1.5 * std::sin(std::atan(0.2)) * std::sin(std::atan(0.2));
  CHECK(v[0].get<double>() == Approx(law).margin(2e-3));
  CHECK(v[1].get<double>() == Approx(std::abs(v[0].get<double>() - law)).epsilon(1e-9));
  CHECK(v[1].get<double>() < 2e-3);
  CHECK(v[2].get<double>() < 2e-3);
  CHECK(v[3].get<double>() == 2.0);  // impacts near 0.50 and 1.36 s (exact solution)
  CHECK(v[4].get<double>() < 2e-2);  // after impact 1, up to impact 2 (its turning point near 0.93 s)
  CHECK(v[5].get<double>() == Approx(0.1));  // theta0, the largest angle
  // Time to rest: long after it (t_end 15), the block is at rest; against the exact time.
  const nsb::Json rest = run_values(one_run("name = \"rocking-block\"", "15", "1e-3", R"(
[[measure]]
kind = "rest-time"
observable = "omega"
threshold = 1e-6
[[measure]]
kind = "rest-time"
observable = "omega"
threshold = 1e-6
exact = true
)"));
  const auto block = nsb::make_problem("rocking-block", {});
  CHECK(rest[0].get<double>() < 15.0);
  CHECK(rest[1].get<double>() == Approx(std::abs(rest[0].get<double>() - nsb::rocking_rest_time(*block))).epsilon(1e-12));
  // Painleve rod: the normal force peaks at the jam, within a few steps of the exact time.
  const nsb::Json jam = run_values(one_run("name = \"painleve-rod\"", "1.0", "1e-4", R"(
[[measure]]
kind = "peak-time"
observable = "normal_force"
[[measure]]
kind = "peak-time"
observable = "normal_force"
exact = true
)"));
  const double exact = nsb::painleve_jam_time(*nsb::make_problem("painleve-rod", {}));
  CHECK(jam[0].get<double>() == Approx(exact).margin(1e-2));
  CHECK(jam[1].get<double>() == Approx(std::abs(jam[0].get<double>() - exact)).epsilon(1e-12));
}

TEST_CASE("rigid measures: bad input named FILE:LINE with the key and the valid choices", "[studies][rigid]") {
  const std::string mass = "name = \"bouncing-mass\"";
  const std::string block = "name = \"rocking-block\"";
  CHECK(parse_error(one_run(mass, "1", "1e-3", "[[measure]]\nkind = \"impact-ratio\"\nobservable = \"v\"\nlaw = \"housner\"\n")) ==
        "r.toml:13: measure[0].law: problem 'bouncing-mass' has no closed-form impacts; valid: rocking-block problems, or problems = [...]");
  // mu = 0.1, below mu_H: one impact in the exact solution, no Moreau ratio of a rocking approach.
  const auto slipping = [&](const std::string& law, const std::string& more) {
    return parse_error(one_run(block + "\nparameters = { mu = 0.1 }", "1", "1e-3",
                               "[[measure]]\nkind = \"impact-ratio\"\nobservable = \"omega\"\nlaw = \"" + law + "\"\n" + more));
  };
  CHECK(slipping("housner", "count = 2\n") ==
        "r.toml:15: measure[0].count: the exact solution of problem 'rocking-block' has 1 impact(s) (it leaves rocking or rests); "
        "valid: 1..1, or problems = [...]");
  CHECK(slipping("housner", "").empty());
  CHECK(slipping("moreau", "") ==
        "r.toml:14: measure[0].law: problem 'rocking-block' has no Moreau ratio of a rocking approach (mu below mu_H: its pivot "
        "slides before theta = 0); valid: law = \"housner\", a block with mu >= mu_H, or problems = [...]");
  // A rocking block with one measure (its keys after [[measure]]) and the error it gets.
  const std::vector<std::pair<std::string, std::string>> block_errors{
      {"kind = \"impact-ratio\"\nobservable = \"omega\"\nlaw = \"newton\"\n",
       "r.toml:13: measure[0].law: 'newton' is not valid (nearest: moreau); valid: housner, moreau"},
      {"kind = \"impact-ratio\"\nobservable = \"omega\"\ncount = 3\n",
       "r.toml:13: measure[0].count: the largest difference over the first count impacts needs a law; valid: law = \"housner\" | "
         "\"moreau\""},
      {"kind = \"impact-ratio\"\nobservable = \"phi\"\n",
       "r.toml:12: measure[0].observable: 'phi' is not an observable of problem 'rocking-block'; valid: theta, omega, omega_exact, "
         "kinetic, potential, total_energy, min_gap (or name the problems it is measured on: problems = [...])"},
      {"kind = \"rest-time\"\nobservable = \"omega\"\n",
       "r.toml:10: measure[0]: missing key 'threshold'"},
      {"kind = \"rest-time\"\nobservable = \"omega\"\nthreshold = 0\n",
       "r.toml:13: measure[0].threshold: 0 is not positive and finite; valid: (0, inf)"},
      {"kind = \"peak-time\"\nobservable = \"omega\"\nexact = true\n",
       "r.toml:13: measure[0].exact: problem 'rocking-block' has no exact dynamic jam; valid: painleve-rod problems whose sliding "
         "phase ends in a jam, or problems = [...]"},
      {"kind = \"value\"\nobservable = \"omega\"\nnorm = \"l2\"\n",
       "r.toml:13: measure[0].norm: 'l2' is not valid (nearest: max); valid: final, max, min"},
      {"kind = \"amplitude\"\nobservable = \"theta\"\nthreshold = 1\n",
       "r.toml:13: measure[0].threshold: unknown key (nearest valid key: label); valid: observable, impact, exact, kind, label, "
         "problems"},
  };
  for (const auto& [measure, error] : block_errors) CHECK(parse_error(one_run(block, "1", "1e-3", "[[measure]]\n" + measure)) == error);
}

TEST_CASE("study file: a case table shows the runs of the problems it names", "[studies][study_file][rigid]") {
  const std::string text = R"([study]
title = "r"
t_end = 0.2
cpu_repeats = 0
[[problem]]
name = "rocking-block"
[[problem]]
name = "painleve-rod"
[[integrator]]
name = "cd-lagrange"
steps = [1e-2]
[[measure]]
kind = "value"
observable = "min_gap"
[[table]]
id = "rod"
title = "rod"
problems = ["painleve-rod"]
columns = ["problem", "integrator", "min_gap final"]
)";
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(text, "r.toml", false));
  const auto cases = nsb::study_cases(entry, {});
  std::vector<nsb::Json> results;
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {}));
  const auto tables = nsb::study_tables(entry, cases, results, {});
  const auto rod = std::find_if(tables.begin(), tables.end(), [](const nsb::Table& t) { return t.id == "rod"; });
  REQUIRE(rod != tables.end());
  REQUIRE(rod->rows.size() == 1);
  CHECK(std::get<std::string>(rod->rows[0][0]) == "painleve-rod");
  std::string grouped = text;
  grouped.insert(grouped.find("problems = [\"painleve-rod\"]"), "rows = \"ranking\"\n");
  CHECK(parse_error(grouped) ==
        "r.toml:19: table[0].problems: a ranking ranks every problem of its measure; valid: rows = \"case\", \"group\", \"history\" or \"samples\"");
}
