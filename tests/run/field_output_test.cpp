// Field output (run/field_output.hpp): a run with a FieldWriter writes the first,
// every k-th and the last state, the .pvd lists them with the steps' times, the values read
// back are the run's doubles exactly, writing allocates nothing and changes no number of
// the run.
#include "run/field_output.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "problems/rigid_problem.hpp"
#include "tests/support/allocation_counter.hpp"

namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / fmt::format("nsbench_fields_test_{}_{}", name, ::getpid());
  fs::remove_all(dir);
  return dir;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  REQUIRE(in.good());
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The numbers of a .vtu DataArray named `name`, parsed with strtod.
std::vector<double> data_array(const std::string& vtu, const std::string& name) {
  const auto at = vtu.find("Name=\"" + name + "\"");
  REQUIRE(at != std::string::npos);
  const auto begin = vtu.find('>', at) + 1, end = vtu.find("</DataArray>", begin);
  std::vector<double> values;
  const char* p = vtu.c_str() + begin;
  const char* stop = vtu.c_str() + end;
  while (true) {
    char* next = nullptr;
    const double x = std::strtod(p, &next);
    if (next == p || next > stop) break;
    values.push_back(x);
    p = next;
  }
  return values;
}

// The times and files of the .pvd's DataSets of part `part`.
std::vector<double> pvd_times(const std::string& pvd, std::vector<std::string>& files, int part = 0) {
  std::vector<double> times;
  const std::regex entry(fmt::format(R"re(<DataSet timestep="([^"]+)" group="" part="{}" file="([^"]+)"/>)re", part));
  for (auto it = std::sregex_iterator(pvd.begin(), pvd.end(), entry); it != std::sregex_iterator(); ++it) {
    times.push_back(std::strtod((*it)[1].str().c_str(), nullptr));
    files.push_back((*it)[2].str());
  }
  return times;
}

// A plugin-like problem: one free mass, no contact, and the mesh it is given (none by default).
class Meshless final : public nsb::RigidProblem {
 public:
  explicit Meshless(std::optional<nsb::FieldMesh> mesh = std::nullopt) : mesh_(std::move(mesh)) {
    mass_ = nsb::Vec::Ones(1);
    load_ = nsb::Vec::Zero(1);
    contacts_.normal.resize(0, 1);
    contacts_.gap_offset.resize(0);
  }
  std::string name() const override { return "meshless"; }
  const nsb::Params& parameters() const override { return params_; }
  nsb::State initial_state() const override { return {0.0, nsb::Vec::Zero(1), nsb::Vec::Zero(1)}; }
  std::optional<nsb::FieldMesh> field_mesh() const override { return mesh_; }

 private:
  nsb::Params params_;
  std::optional<nsb::FieldMesh> mesh_;
};

}  // namespace

TEST_CASE("fields: the first, every k-th and the last state, read back exactly; the run's numbers unchanged",
          "[integrators][fields]") {
  const auto problem = nsb::make_problem("signorini-bar", {{"N", "10"}, {"g0", "0.05"}});
  nsb::RunOptions options;
  options.dt = 0.01;
  options.t_end = 0.5;  // 50 steps
  options.state_every = 7;
  auto plain = nsb::make_integrator("cd-lagrange");
  plain->init(*problem, problem->initial_state());
  const nsb::RunResult reference = nsb::run(*problem, *plain, options);

  const fs::path dir = scratch("bar");
  auto integrator = nsb::make_integrator("cd-lagrange");
  integrator->init(*problem, problem->initial_state());
  nsb::FieldWriter writer(*problem, dir, "--fields", 9);
  options.state_sink = &writer;
  const nsb::RunResult result = nsb::run(*problem, *integrator, options);
  writer.commit();
  // The same run, sample for sample and state for state.
  CHECK(result.series.values == reference.series.values);
  CHECK(integrator->state().u == plain->state().u);
  CHECK(integrator->state().v == plain->state().v);
  CHECK(result.steps == 50);

  std::vector<std::string> files;
  const std::vector<double> times = pvd_times(slurp(dir / "fields.pvd"), files);
  const std::vector<long> steps = {0, 7, 14, 21, 28, 35, 42, 49, 50};
  REQUIRE(times.size() == steps.size());
  CHECK(writer.files() == 9);
  const std::size_t t_col = reference.series.column("t");
  for (std::size_t i = 0; i < steps.size(); ++i) {
    CHECK(times[i] == reference.series.at(static_cast<std::size_t>(steps[i]), t_col));
    CHECK(files[i] == fmt::format("fields_{:06d}.vtu", i));
    CHECK(fs::exists(dir / files[i]));
  }
  CHECK(times.back() == result.t_final);
  // The last file is the final state, exactly.
  const std::string vtu = slurp(dir / files.back());
  const auto u = data_array(vtu, "displacement"), v = data_array(vtu, "velocity");
  const auto mesh = problem->field_mesh();
  Eigen::MatrixXd sigma(mesh->ncells(), 1);
  problem->cell_stress(integrator->state().u, sigma);
  REQUIRE(u.size() == 33);
  for (nsb::Index a = 0; a < 11; ++a) {
    CHECK(u[3 * a] == integrator->state().u[a]);
    CHECK(v[3 * a] == integrator->state().v[a]);
    CHECK(u[3 * a + 1] == 0.0);
  }
  const auto stress = data_array(vtu, "sigma");
  REQUIRE(stress.size() == 10);
  for (nsb::Index e = 0; e < 10; ++e) CHECK(stress[e] == sigma(e, 0));
  CHECK(data_array(vtu, "reference_position")[3] == 0.1);
  CHECK(data_array(vtu, "connectivity") == std::vector<double>{0, 1, 1, 2, 2, 3, 3, 4, 4, 5, 5, 6, 6, 7, 7, 8, 8, 9, 9, 10});
  CHECK(data_array(vtu, "types") == std::vector<double>(10, 3.0));  // VTK_LINE
  // The contact impulse sits on node 0 (the contact row's dof), the first file has none.
  bool impulse = false;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto lambda = data_array(slurp(dir / files[i]), "contact_impulse");
    for (std::size_t k = 1; k < lambda.size(); ++k) CHECK(lambda[k] == 0.0);
    impulse = impulse || lambda[0] > 0.0;
    if (i == 0) CHECK(lambda[0] == 0.0);
  }
  CHECK(impulse);
  fs::remove_all(dir);
}

TEST_CASE("fields: a run stopped early writes its last state, and an earlier run's files are not kept",
          "[integrators][fields]") {
  const auto problem = nsb::make_problem("block-2d", {{"nx", "4"}, {"ny", "2"}});
  const fs::path dir = scratch("budget");
  auto integrator = nsb::make_integrator("cd-lagrange");
  nsb::RunOptions options;
  options.dt = 1e-5;
  {  // An earlier run into the directory: 11 states (t = 0 .. 10 dt).
    integrator->init(*problem, problem->initial_state());
    nsb::FieldWriter earlier(*problem, dir, "--fields", 11);
    options.t_end = 1e-4;
    options.state_every = 1;
    options.state_sink = &earlier;
    REQUIRE(nsb::run(*problem, *integrator, options).status == nsb::RunStatus::Ok);
    earlier.commit();
    REQUIRE(fs::exists(dir / "fields_000010.vtu"));
  }
  integrator->init(*problem, problem->initial_state());
  nsb::FieldWriter writer(*problem, dir, "--fields", 4);
  options.t_end = 1.0;
  options.state_every = 1000;
  options.max_force_evaluations = 25;  // stops after about 25 steps
  options.state_sink = &writer;
  const nsb::RunResult result = nsb::run(*problem, *integrator, options);
  writer.commit();
  REQUIRE(result.status == nsb::RunStatus::OverBudget);
  std::vector<std::string> files;
  const auto times = pvd_times(slurp(dir / "fields.pvd"), files);
  REQUIRE(times.size() == 2);
  CHECK(times[0] == 0.0);
  CHECK(times[1] == result.t_final);
  // The directory is replaced whole (core/output.hpp): none of the earlier run's files is left.
  for (const char* earlier : {"fields_000002.vtu", "fields_000010.vtu"}) CHECK_FALSE(fs::exists(dir / earlier));
  const auto u = data_array(slurp(dir / files[1]), "displacement");
  REQUIRE(u.size() == 3 * 15);
  for (nsb::Index a = 0; a < 15; ++a) {
    CHECK(u[3 * a] == integrator->state().u[2 * a]);
    CHECK(u[3 * a + 1] == integrator->state().u[2 * a + 1]);
  }
  CHECK(data_array(slurp(dir / files[1]), "types") == std::vector<double>(8, 9.0));  // VTK_QUAD
  fs::remove_all(dir);
}

TEST_CASE("fields: writing a state allocates nothing; a problem that describes no bodies is refused",
          "[integrators][fields]") {
  const auto problem = nsb::make_problem("two-blocks", {{"mu", "0.3"}});  // tangent rows too
  const fs::path dir = scratch("alloc");
  {
    nsb::FieldWriter writer(*problem, dir, "--fields", 3);
    nsb::State s = problem->initial_state();
    s.u = nsb::Vec::LinSpaced(problem->ndof(), -1e-3, 1e-3);
    const nsb::Vec normal = nsb::Vec::Ones(problem->ncontacts()), tangential = 0.5 * normal;
    writer.state(s, normal, tangential, tangential);
    long allocations = 0;
    {
      nsb::test::CountAllocations count;
      writer.state(s, normal, tangential, tangential);
      s.t = 1.0;
      writer.state(s, normal, tangential, tangential);
      allocations = count.count();
    }
    CHECK(allocations == 0);
    writer.commit();
    // L^T Lambda_N + T^T Lambda_T over the points: the node-to-segment rows' weights sum to
    // zero, so the total is the floor rows' (1 per row along y, 0.5 along x).
    std::vector<std::string> files;
    REQUIRE(pvd_times(slurp(dir / "fields.pvd"), files).size() == 3);
    const auto lambda = data_array(slurp(dir / files[2]), "contact_impulse");
    double x = 0.0, y = 0.0;
    for (std::size_t k = 0; k < lambda.size(); k += 3) {
      x += lambda[k];
      y += lambda[k + 1];
    }
    const auto floors = static_cast<double>(problem->ncontacts() - 8);  // upper_nx + 1 = 8 node-to-segment rows
    CHECK(y == Approx(floors).epsilon(1e-12));
    CHECK(x == Approx(0.5 * floors).epsilon(1e-12));
  }
  fs::remove_all(dir);
  const Meshless meshless;
  CHECK_THROWS_WITH(nsb::FieldWriter(meshless, dir, "--fields", 1),
                    Catch::Contains("--fields") && Catch::Contains("meshless") && Catch::Contains("describes no bodies"));
  // A malformed mesh: one line naming what is wrong, and no directory.
  nsb::FieldMesh good;
  good.add_vertex(0.0, 0.0, {0}, 0);
  CHECK_NOTHROW(nsb::FieldWriter(Meshless(good), dir, "--fields", 1));
  fs::remove_all(dir);
  nsb::FieldMesh bad = good;
  bad.point_dofs(0, 0) = 1;  // ndof = 1
  CHECK_THROWS_WITH(nsb::FieldWriter(Meshless(bad), dir, "--fields", 1),
                    "--fields: problem meshless: field_mesh(): a point dof outside [-1, ndof = 1)");
  bad = good;
  bad.points = Eigen::MatrixXd::Zero(3, 2);
  bad.point_dofs = Eigen::MatrixXi::Constant(3, 1, -1);
  bad.cells = Eigen::MatrixXi(1, 3);
  bad.cells << 0, 1, 2;
  CHECK_THROWS_WITH(nsb::FieldWriter(Meshless(bad), dir, "--fields", 1),
                    "--fields: problem meshless: field_mesh(): cell 0 has 3 points; valid: 1, 2, 4 or 8");
  bad.cells << 0, 1, -1;
  CHECK_THROWS_WITH(nsb::FieldWriter(Meshless(bad), dir, "--fields", 1),
                    "--fields: problem meshless: field_mesh(): element cells and no stress component");
  CHECK_FALSE(fs::exists(dir));
}

TEST_CASE("fields: a bar and a striker are two parts, elements with stress and the vertex without; a body's arrays",
          "[integrators][fields]") {
  const auto problem = nsb::make_problem("mass-on-bar", {{"N", "4"}});
  const fs::path dir = scratch("parts");
  nsb::State s = problem->initial_state();
  s.u = nsb::Vec::LinSpaced(problem->ndof(), 0.1, 0.5);  // striker (dof 4) at 0.5
  {
    nsb::FieldWriter writer(*problem, dir, "--fields", 2);
    const nsb::Vec lambda = nsb::Vec::Constant(1, 2.0);
    writer.state(s, lambda, nsb::Vec(), nsb::Vec());
    s.t = 0.25;
    writer.state(s, lambda, nsb::Vec(), nsb::Vec());
    writer.commit();
  }
  std::vector<std::string> elements, bodies;
  const std::string pvd = slurp(dir / "fields.pvd");
  CHECK(pvd_times(pvd, elements, 0) == std::vector<double>{0.0, 0.25});
  CHECK(pvd_times(pvd, bodies, 1) == std::vector<double>{0.0, 0.25});
  CHECK(elements == std::vector<std::string>{"fields_000000.vtu", "fields_000001.vtu"});
  CHECK(bodies == std::vector<std::string>{"bodies_000000.vtu", "bodies_000001.vtu"});
  // The bar: 5 nodes (node 4 clamped), 4 lines with sigma; no striker point.
  const std::string bar = slurp(dir / elements[1]), striker = slurp(dir / bodies[1]);
  CHECK(data_array(bar, "types") == std::vector<double>(4, 3.0));
  CHECK(data_array(bar, "displacement").size() == 15);
  CHECK(data_array(bar, "sigma").size() == 4);
  CHECK(data_array(bar, "contact_impulse")[0] == 2.0);
  // The striker: one vertex (VTK_VERTEX), at x = 0, its own displacement and the impulse's
  // reaction; no stress array.
  CHECK(data_array(striker, "types") == std::vector<double>{1.0});
  CHECK(data_array(striker, "connectivity") == std::vector<double>{0.0});
  CHECK(data_array(striker, "reference_position") == std::vector<double>{0.0, 0.0, 0.0});
  CHECK(data_array(striker, "displacement") == std::vector<double>{0.5, 0.0, 0.0});
  CHECK(data_array(striker, "contact_impulse") == std::vector<double>{-2.0, 0.0, 0.0});
  CHECK(data_array(striker, "body") == std::vector<double>{1.0});
  CHECK(striker.find("sigma") == std::string::npos);
  fs::remove_all(dir);

  // A rigid disk: one part (bodies_), the rotation in body arrays, exactly.
  const auto disk = nsb::make_problem("rolling-disk", {{"R", "0.25"}});
  nsb::State d = disk->initial_state();
  d.u << 1.5, 0.125, 2.0;
  d.v << -1.0, 0.5, 3.0;
  {
    nsb::FieldWriter writer(*disk, dir, "--fields", 1);
    writer.state(d, nsb::Vec::Zero(1), nsb::Vec::Zero(1), nsb::Vec());
    writer.commit();
  }
  std::vector<std::string> files;
  CHECK(pvd_times(slurp(dir / "fields.pvd"), files, 0).size() == 1);
  REQUIRE(files == std::vector<std::string>{"bodies_000000.vtu"});
  const std::string vtu = slurp(dir / files[0]);
  CHECK(data_array(vtu, "reference_position") == std::vector<double>{0.0, 0.25, 0.0});
  CHECK(data_array(vtu, "displacement") == std::vector<double>{1.5, 0.125, 0.0});
  CHECK(data_array(vtu, "velocity") == std::vector<double>{-1.0, 0.5, 0.0});
  CHECK(data_array(vtu, "radius") == std::vector<double>{0.25});
  CHECK(data_array(vtu, "angle") == std::vector<double>{2.0});
  CHECK(data_array(vtu, "angular_velocity") == std::vector<double>{3.0});
  CHECK(data_array(vtu, "orientation") == std::vector<double>{std::cos(2.0), std::sin(2.0), 0.0});
  fs::remove_all(dir);
}

TEST_CASE("fields: bar-3d's hexahedra, VTK_HEXAHEDRON in VTK's node order, 3D points, six stresses, read back",
          "[integrators][fields][bar-3d]") {
  const auto problem = nsb::make_problem("bar-3d", {{"N", "3"}, {"N_side", "2"}, {"lateral", "free"}, {"L", "1.5"}});
  const fs::path dir = scratch("hex");
  nsb::RunOptions options;
  options.dt = 0.5 * problem->stable_step();
  options.t_end = 10 * options.dt;
  options.state_every = 5;
  auto integrator = nsb::make_integrator("cd-lagrange");
  integrator->init(*problem, problem->initial_state());
  nsb::FieldWriter writer(*problem, dir, "--fields", 3);
  options.state_sink = &writer;
  nsb::run(*problem, *integrator, options);
  writer.commit();
  std::vector<std::string> files;
  REQUIRE(pvd_times(slurp(dir / "fields.pvd"), files).size() == 3);
  const std::string vtu = slurp(dir / files.back());
  const auto mesh = problem->field_mesh();
  CHECK(data_array(vtu, "types") == std::vector<double>(12, 12.0));  // VTK_HEXAHEDRON
  std::vector<double> offsets;
  for (int c = 1; c <= 12; ++c) offsets.push_back(8.0 * c);
  CHECK(data_array(vtu, "offsets") == offsets);
  // The points in 3D and, per cell, VTK's order: the bottom face counter-clockwise seen from
  // the top, then the top face above it (edges 0-1, 0-3, 0-4 right-handed, 4 = 0 + e_z).
  const auto X = data_array(vtu, "reference_position"), cells = data_array(vtu, "connectivity");
  REQUIRE(X.size() == 3 * 4 * 3 * 3);
  REQUIRE(cells.size() == 96);
  const auto point = [&](double a) { return Eigen::Vector3d(X[3 * a], X[3 * a + 1], X[3 * a + 2]); };
  for (std::size_t c = 0; c < 12; ++c) {
    const double* n = &cells[8 * c];
    for (int k = 0; k < 8; ++k) CHECK(n[k] == mesh->cells(static_cast<nsb::Index>(c), k));
    const Eigen::Vector3d e1 = point(n[1]) - point(n[0]), e3 = point(n[3]) - point(n[0]), e4 = point(n[4]) - point(n[0]);
    CHECK(e1.cross(e3).dot(e4) > 0.0);
    for (int k = 0; k < 4; ++k) CHECK((point(n[k + 4]) - point(n[k]) - e4).norm() <= 1e-15);
  }
  CHECK(X[3 * 35 + 2] == 1.0);  // the last point, z = a = sqrt(A)
  // Displacements and velocities are the run's, three components each; six stresses.
  const auto u = data_array(vtu, "displacement"), v = data_array(vtu, "velocity");
  for (nsb::Index a = 0; a < mesh->npoints(); ++a)
    for (int k = 0; k < 3; ++k) {
      CHECK(u[3 * a + k] == integrator->state().u[mesh->point_dofs(a, k)]);
      CHECK(v[3 * a + k] == integrator->state().v[mesh->point_dofs(a, k)]);
    }
  Eigen::MatrixXd sigma(12, 6);
  problem->cell_stress(integrator->state().u, sigma);
  for (int k = 0; k < 6; ++k) {
    const auto got = data_array(vtu, mesh->stress_components[static_cast<std::size_t>(k)]);
    REQUIRE(got.size() == 12);
    for (nsb::Index e = 0; e < 12; ++e) CHECK(got[e] == sigma(e, k));
  }
  CHECK(sigma.col(0).minCoeff() < 0.0);  // the wall compresses the bar
  fs::remove_all(dir);
}

TEST_CASE("fields: a turning body's orientation is the product of its steps' rotations, in their order",
          "[integrators][fields][sphere]") {
  const auto problem = nsb::make_problem("sphere", {});
  const double a = 0.7, b = -1.1;  // a turn about x, then one about y
  const auto orientation_after = [&](bool x_first) {
    const fs::path dir = scratch(x_first ? "turn_xy" : "turn_yx");
    nsb::FieldWriter writer(*problem, dir, "--fields", 2);
    REQUIRE(writer.follows_rotations());
    nsb::State s = problem->initial_state();
    const nsb::Vec none = nsb::Vec::Zero(problem->ncontacts());
    writer.state(s, none, none, none);
    s.u[x_first ? 3 : 4] += x_first ? a : b;
    writer.follow(s);
    s.u[x_first ? 4 : 3] += x_first ? b : a;
    s.t = 1.0;
    writer.state(s, none, none, none);
    writer.commit();
    std::vector<std::string> files;
    REQUIRE(pvd_times(slurp(dir / "fields.pvd"), files).size() == 2);
    const std::string first = slurp(dir / files[0]), last = slurp(dir / files[1]);
    CHECK(data_array(first, "orientation_x") == std::vector<double>{1, 0, 0});
    CHECK(data_array(first, "orientation_z") == std::vector<double>{0, 0, 1});
    std::vector<double> axes = data_array(last, "orientation_x");
    for (const double z : data_array(last, "orientation_z")) axes.push_back(z);
    fs::remove_all(dir);
    return axes;
  };
  // R_y(b) R_x(a) and R_x(a) R_y(b) applied to e_x and e_z, written out by hand.
  const std::vector<double> xy = {std::cos(b), 0.0, -std::sin(b), std::sin(b) * std::cos(a), -std::sin(a), std::cos(b) * std::cos(a)};
  const std::vector<double> yx = {std::cos(b), std::sin(a) * std::sin(b), -std::cos(a) * std::sin(b), std::sin(b),
                                  -std::sin(a) * std::cos(b), std::cos(a) * std::cos(b)};
  const std::vector<double> got_xy = orientation_after(true), got_yx = orientation_after(false);
  REQUIRE(got_xy.size() == 6);
  REQUIRE(got_yx.size() == 6);
  for (std::size_t k = 0; k < 6; ++k) {
    CHECK(got_xy[k] == Approx(xy[k]).margin(1e-15));
    CHECK(got_yx[k] == Approx(yx[k]).margin(1e-15));
  }
}

TEST_CASE("fields: a sphere rolling on a level floor turns at its constant spin; followed every step",
          "[integrators][fields][sphere]") {
  // Rolling from the start (v_x = R omega_y, slip 0) on a level floor: nothing changes the
  // motion, and after T the body has turned by omega_y T about y.
  const double R = 0.1, omega = 7.0, T = 0.5;
  const auto problem = nsb::make_problem("sphere", {{"alpha", "0"}, {"R", "0.1"}, {"vx0", fmt::format("{}", R * omega)},
                                                    {"vy0", "0"}, {"wx0", "0"}, {"wy0", fmt::format("{}", omega)}, {"wz0", "0"}});
  auto integrator = nsb::make_integrator("cd-lagrange");
  integrator->init(*problem, problem->initial_state());
  const fs::path dir = scratch("rolling");
  nsb::FieldWriter writer(*problem, dir, "--fields", 3);
  nsb::RunOptions options;
  options.dt = 1e-3;
  options.t_end = T;
  options.state_every = 200;
  options.state_sink = &writer;
  const nsb::RunResult result =
      nsb::run(*problem, *integrator, options, [&](const nsb::Integrator& i, const nsb::StepInfo&) { writer.follow(i.state()); });
  writer.commit();
  REQUIRE(result.status == nsb::RunStatus::Ok);
  std::vector<std::string> files;
  pvd_times(slurp(dir / "fields.pvd"), files);
  const std::string last = slurp(dir / files.back());
  const double turned = omega * result.t_final;
  const std::vector<double> x = data_array(last, "orientation_x"), z = data_array(last, "orientation_z");
  REQUIRE(x.size() == 3);
  REQUIRE(z.size() == 3);
  CHECK(x[0] == Approx(std::cos(turned)).margin(1e-12));
  CHECK(x[1] == Approx(0.0).margin(1e-12));
  CHECK(x[2] == Approx(-std::sin(turned)).margin(1e-12));
  CHECK(z[0] == Approx(std::sin(turned)).margin(1e-12));
  CHECK(z[2] == Approx(std::cos(turned)).margin(1e-12));
  fs::remove_all(dir);
}
