// The three-d study (studies/builtin/three_d.toml) and the study-file features it is written in:
// a joint refinement (refine = KEY), an error of v and against a problem's own exact column,
// rest time against a summary value and kind summary, the momentum identities of a 3D mesh
// (MeshMomentum, studies/measures.hpp), each on a case with a known answer.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
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

const nsb::StudyEntry& three_d_entry() {
  const auto& studies = nsb::study_registry();
  const auto it = std::find_if(studies.begin(), studies.end(), [](const nsb::StudyEntry& e) { return e.name == "three-d"; });
  REQUIRE(it != studies.end());
  return *it;
}

// A study of one problem table and the integrators and measures given (cpu_repeats = 0).
std::string three_d_study_text(const std::string& t_end, const std::string& problem, const std::string& rest) {
  return "[study]\ntitle = \"t\"\nt_end = " + t_end + "\ncpu_repeats = 0\n[[problem]]\n" + problem + "\n" + rest;
}

std::string three_d_parse_error(const std::string& text) {
  return nsb::test::input_error_text_of([&] { nsb::parse_study_text(text, "t.toml", false); });
}

// Runs every case in this thread: the results and the tables.
std::vector<nsb::Table> three_d_run(const std::string& text, std::vector<nsb::Json>& results) {
  const nsb::StudyEntry entry = nsb::file_study(nsb::parse_study_text(text, "t.toml", false));
  const auto cases = nsb::study_cases(entry, {});
  for (const auto& c : cases) results.push_back(nsb::run_study_case(entry, c, {}));
  return nsb::study_tables(entry, cases, results, {});
}

double three_d_value(const nsb::Json& result, std::size_t measure) {
  REQUIRE(result["status"] == "ok");
  return nsb::real(result["values"][measure]);
}

}  // namespace

TEST_CASE("built-in study three-d: registered from its file; every integrator on each problem; references at nx = 4 only",
          "[studies][three_d]") {
  const nsb::StudyEntry& study = three_d_entry();
  CHECK(study.source == "studies/builtin/three_d.toml");
  const nsb::EmbeddedStudyFile* file = nsb::builtin_study_file("studies/builtin/three_d.toml");
  REQUIRE(file != nullptr);
  const nsb::StudySpec spec = nsb::parse_study_text(std::string(file->text), "three_d.toml", false);
  const auto& registry = nsb::integrator_registry();
  REQUIRE(spec.problems.size() == 12 + 2 + 4);
  for (std::size_t p = 0; p < 12; ++p) {  // N outer, mass inner: one family per mass model
    CHECK(spec.problems[p].name == "bar-3d");
    CHECK(spec.problems[p].family == "bar-3d, mass = " + spec.problems[p].parameters.at("mass"));
  }
  CHECK(spec.problems[0].label == "bar-3d, N = 10, mass = lumped");
  CHECK(spec.problems[11].label == "bar-3d, N = 80, mass = singular");
  CHECK(spec.problems[12].name == "sphere");
  CHECK(spec.problems[13].parameters.at("mu") == "0.05");  // below (2/7) tan 20 deg: slides for ever
  CHECK(spec.problems[17].label == "block-3d, mu = 0.3, nx = 8");
  // block-3d's own reference: penalty-bdf on the same mesh, cached, past the runs' last steps.
  for (std::size_t p = 14; p < 18; ++p) {
    const nsb::FileReference* ref = spec.reference_of(spec.problems[p]);
    REQUIRE(ref != nullptr);
    CHECK_FALSE(ref->exact);
    CHECK(ref->integrator == "penalty-bdf");
    CHECK_FALSE(ref->lockstep);
    CHECK(ref->dt == 2.5e-4);
    const double dt = 0.9 * nsb::make_problem("block-3d", spec.problems[p].parameters)->stable_step();
    CHECK(ref->t_end >= std::ceil(spec.t_end_of(spec.problems[p]) / dt) * dt);  // the run's last step's end
  }
  std::vector<std::string> labels;
  for (const auto& m : spec.measures) labels.push_back(m.label);
  for (const char* error : {"err zc max", "err xc max"}) CHECK(std::find(labels.begin(), labels.end(), error) != labels.end());
  // Every registered integrator, MuJoCo (where built) as its two cones in its place.
  std::size_t references = 0;
  for (const auto& it : spec.integrators) references += nsb::find_integrator(it.name).reference;
  const bool mujoco = std::any_of(registry.begin(), registry.end(), [](const auto& e) { return e.name == "mujoco"; });
  CHECK(spec.integrators.size() == registry.size() + (mujoco ? 1 : 0));
  const auto cases = nsb::study_cases(study, {false});
  CHECK(cases.size() == spec.integrators.size() * (12 + 2 * 3 + 4) - 2 * references);
  for (const auto& c : cases) {
    const auto& problem = spec.problems[c["problem"].get<std::size_t>()];
    const bool reference = nsb::find_integrator(spec.integrators[c["integrator"].get<std::size_t>()].name).reference;
    CHECK_FALSE((reference && problem.name == "block-3d" && problem.parameters.at("nx") == "8"));
  }
  std::vector<std::string> ids;
  for (const auto& t : spec.tables) ids.push_back(t.id);
  CHECK(ids == std::vector<std::string>{"three_d_bar", "three_d_bar_orders", "three_d_sphere", "three_d_block", "three_d_ranking"});
  CHECK(spec.measures[spec.ranked].label == "err u max");
}

TEST_CASE("study file: refine = KEY makes the grid's problems one sweep: orders over the meshes, one ranked problem",
          "[studies][three_d][study_file]") {
  const std::string text = three_d_study_text(
      "2.5", "name = \"bar-3d\"\nlabel = \"bar\"\ngrid = { N = [10, 20, 40] }\nrefine = \"N\"\nstable_steps = [0.9]\n"
             "reference = { solution = \"exact\" }",
      "[[integrator]]\nname = \"cd-lagrange\"\n[[measure]]\nkind = \"error\"\n");
  std::vector<nsb::Json> results;
  const auto tables = three_d_run(text, results);
  REQUIRE(results.size() == 3);
  const auto& orders = *std::find_if(tables.begin(), tables.end(), [](const nsb::Table& t) { return t.id == "t_orders"; });
  REQUIRE(orders.rows.size() == 1);
  CHECK(std::get<std::string>(orders.rows[0][0]) == "bar");
  CHECK(std::get<long>(orders.rows[0][7]) == 3);
  // The fit over the three meshes: dt halves with h.
  std::vector<double> dt, e;
  const nsb::StudySpec spec = nsb::parse_study_text(text, "t.toml", false);
  for (std::size_t k = 0; k < 3; ++k) {
    dt.push_back(0.9 * nsb::make_problem("bar-3d", spec.problems[k].parameters)->stable_step());
    e.push_back(three_d_value(results[k], 0));
  }
  CHECK(std::get<double>(orders.rows[0][4]) == Approx(nsb::fitted_order(dt, e)).epsilon(1e-12));
  CHECK(std::get<double>(orders.rows[0][4]) > 0.5);
  const auto& ranking = *std::find_if(tables.begin(), tables.end(), [](const nsb::Table& t) { return t.id == "t_ranking"; });
  for (const auto& row : ranking.rows) CHECK(std::get<std::string>(row[0]) == "bar");

  CHECK_THAT(three_d_parse_error(three_d_study_text("1", "name = \"bar-3d\"\ngrid = { N = [10, 20] }\nrefine = \"mass\"\nsteps = [1e-2]",
                                                    "[[integrator]]\nname = \"cd-lagrange\"\n")),
             Catch::Contains("problem[0].refine: not a key of the problem's grid"));
}

TEST_CASE("study file: the sphere's roll onset against its summary value t_roll_exact; v and an observable against its exact "
          "column",
          "[studies][three_d][study_file]") {
  // Moreau-Jean at dt = 1e-3 on the default sphere: the slip ends inside the step ending at
  // 0.239, so the last step with slip > 1e-6 ends at 0.238 (t_roll = 0.238575312993057 s,
  // docs/three_d.md). After the onset v follows from the momentum balances alone, which
  // Moreau-Jean keeps to round-off: its final v is exact; CD-Lagrange's is not.
  const std::string measures = R"(
[[measure]]
kind = "summary"
summary = "t_roll_exact"
[[measure]]
kind = "rest-time"
observable = "slip_speed"
threshold = 1e-6
exact = true
summary = "t_roll_exact"
[[measure]]
kind = "error"
observable = "v"
norm = "final"
[[measure]]
kind = "error"
observable = "slip_speed"
[[measure]]
kind = "error"
observable = "slip_speed"
against = "slip_speed_exact"
)";
  const std::string sphere = "name = \"sphere\"\nsteps = [1e-3]\nreference = { solution = \"exact\" }";
  std::vector<nsb::Json> mj, cd;
  three_d_run(three_d_study_text("0.5", sphere, "[[integrator]]\nname = \"moreau-jean\"\n" + measures), mj);
  three_d_run(three_d_study_text("0.5", sphere, "[[integrator]]\nname = \"cd-lagrange\"\n" + measures), cd);
  CHECK(three_d_value(mj[0], 0) == Approx(0.238575312993057).epsilon(1e-14));
  CHECK(three_d_value(mj[0], 1) == Approx(0.238575312993057 - 0.238).epsilon(1e-9));
  CHECK(three_d_value(mj[0], 2) < 1e-12);
  CHECK(three_d_value(cd[0], 2) > 1e-5);
  // The exact slip speed as a reference and as the problem's own column: the same error.
  CHECK(three_d_value(mj[0], 4) == Approx(three_d_value(mj[0], 3)).epsilon(0).margin(1e-12));  // two round-offs of one closed form
  CHECK(three_d_value(mj[0], 3) > 0.0);

  // Sliding for ever: t_roll_exact is +inf, refused as an exact time, shown as a summary.
  CHECK_THAT(three_d_parse_error(three_d_study_text("0.5", "name = \"sphere\"\nparameters = { mu = 0.05 }\nsteps = [1e-3]",
                                                    "[[integrator]]\nname = \"cd-lagrange\"\n" + measures)),
             Catch::Contains("measure[1].summary: summary value 't_roll_exact' of problem 'sphere' is not a finite time"));
  CHECK_THAT(three_d_parse_error(three_d_study_text("0.5", sphere, "[[integrator]]\nname = \"cd-lagrange\"\n[[measure]]\nkind = \"summary\"\nsummary = \"t_stop\"\n")),
             Catch::Contains("measure[0].summary: 't_stop' is not a summary value of problem 'sphere'; valid: t_roll_exact"));
  CHECK_THAT(three_d_parse_error(three_d_study_text("0.5", sphere, "[[integrator]]\nname = \"cd-lagrange\"\n[[measure]]\nkind = \"error\"\n"
                                                                   "observable = \"slip_speed\"\nagainst = \"slip\"\n")),
             Catch::Contains("measure[0].against: 'slip' is not an observable of problem 'sphere'"));
  // bar-3d's summary: the exact end of its one contact phase, 2 L / c_p (held, g = 0).
  const auto bar = nsb::make_problem("bar-3d", {});
  const double c_p = std::sqrt(0.7 / (1.3 * 0.4));
  CHECK(nsb::summary_value(*bar, "contact_end_exact") == Approx(2.0 / c_p).epsilon(1e-14));
  CHECK(std::isnan(nsb::summary_value(*nsb::make_problem("bar-3d", {{"lateral", "free"}}), "contact_end_exact")));
}

TEST_CASE("study file: block-3d's momentum identities per component, round-off for CD-Lagrange, not for Moreau-Jean's angular",
          "[studies][three_d][study_file][measures]") {
  // CD-Lagrange's step is its exact discrete balance: P by the impulses and dt F_ext, J by their
  // moments at the end-of-step positions. Moreau-Jean's forces act at theta-weighted positions.
  std::string measures;
  for (const char* c : {"px", "py", "pz", "jx", "jy", "jz"}) measures += fmt::format("[[measure]]\nkind = \"momentum\"\ncomponent = \"{}\"\n", c);
  const std::string block = "name = \"block-3d\"\nparameters = { nx = 2, ny = 2, nz = 2, vx = 0.5, spin = 2.0, mu = 0.3 }\nstable_steps = [0.9]";
  std::vector<nsb::Json> cd, mj;
  three_d_run(three_d_study_text("0.15", block, "[[integrator]]\nname = \"cd-lagrange\"\n" + measures), cd);
  three_d_run(three_d_study_text("0.15", block, "[[integrator]]\nname = \"moreau-jean\"\n" + measures), mj);
  for (std::size_t m = 0; m < 6; ++m) CHECK(three_d_value(cd[0], m) < 1e-13);
  for (std::size_t m = 0; m < 3; ++m) CHECK(three_d_value(mj[0], m) < 1e-13);
  CHECK(three_d_value(mj[0], 3) > 1e-7);  // J_x: the block lands tilted about y and spinning
  CHECK(three_d_value(mj[0], 4) > 1e-7);
  CHECK_THAT(three_d_parse_error(three_d_study_text("1", "name = \"bouncing-mass\"\nsteps = [1e-2]",
                                                    "[[integrator]]\nname = \"cd-lagrange\"\n[[measure]]\nkind = \"momentum\"\ncomponent = \"jz\"\n")),
             Catch::Contains("measure[0].component: problem 'bouncing-mass' has no mesh component jz"));
}

TEST_CASE("study file: a reference run's own t_end covers a run's last step past the problem's end; bad input named",
          "[studies][three_d][study_file]") {
  // Free fall (h0 = 10 m: the floor at 1.43 s), t_end = 1 and dt = 0.3: CD-Lagrange's four
  // steps end at 1.2 s, its positions exact for a constant force. Against event-driven's samples
  // up to 1.2 s its error is round-off; against samples that stop at 1 s the run's last q is
  // compared with the reference's last sample, q(1): the clamp the key exists to avoid.
  const auto text = [](const std::string& reference) {
    return three_d_study_text("1.0", "name = \"bouncing-mass\"\nparameters = { h0 = 10 }\nsteps = [0.3]\nreference = { " + reference + " }",
                              "[[integrator]]\nname = \"cd-lagrange\"\n[[measure]]\nkind = \"error\"\nobservable = \"q\"\n");
  };
  const std::string ed = "integrator = \"event-driven\", dt = 0.1";
  const nsb::StudySpec spec = nsb::parse_study_text(text(ed + ", t_end = 1.2"), "t.toml", false);
  CHECK(spec.reference_of(spec.problems[0])->t_end == 1.2);
  std::vector<nsb::Json> covered, clamped;
  three_d_run(text(ed + ", t_end = 1.2"), covered);
  three_d_run(text(ed), clamped);
  REQUIRE(covered[0]["steps"] == 4);
  CHECK(three_d_value(covered[0], 0) < 1e-9);
  // |q(1.2) - q(1)| over the largest reference value at the run's steps, q(0.3).
  CHECK(three_d_value(clamped[0], 0) == Approx(0.5 * 9.81 * (1.2 * 1.2 - 1.0) / (10.0 - 0.5 * 9.81 * 0.09)).epsilon(1e-6));

  CHECK_THAT(three_d_parse_error(text(ed + ", t_end = 0.9")),
             Catch::Contains("problem[0].reference.t_end: 0.9 is before the end of problem 'bouncing-mass' (1 s)"));
  CHECK_THAT(three_d_parse_error(text("solution = \"exact\", t_end = 1.2")),
             Catch::Contains("problem[0].reference.t_end: the exact solution has no end time"));
  CHECK_THAT(three_d_parse_error(text("integrator = \"event-driven\", lockstep = true, t_end = 1.2")),
             Catch::Contains("problem[0].reference.t_end: a lockstep reference steps with each run"));
}
