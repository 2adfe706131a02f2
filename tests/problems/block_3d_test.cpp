// block-3d (problems/block_3d.hpp): the hex8 block's force against its energy and its tangent
// against its force (central differences, both laws, a random deformed configuration); zero
// force under rigid motions; the mass; the contact rows L, T1, T2 against differences of the
// gaps and node positions; momentum changed by gravity alone in free flight; the field mesh;
// bad input in one line.
#include <catch2/catch.hpp>
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>
#include <string>

#include "check/conformance.hpp"
#include "core/threads.hpp"
#include "integrators/registry.hpp"
#include "problems/block_3d.hpp"
#include "tests/problems/forwarding_problem.hpp"
#include "run/run.hpp"
#include "tests/support/input_error.hpp"

namespace {

nsb::Block3d make_block3d(std::map<std::string, std::string> values) {
  values.emplace("nx", "3");
  values.emplace("ny", "2");
  values.emplace("nz", "2");
  values.emplace("tilt", "20");
  return nsb::Block3d(nsb::Params(nsb::Block3d::parameters_spec(), values));
}

nsb::Vec random_vector(nsb::Index n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  return nsb::Vec::NullaryExpr(n, [&] { return uniform(rng); });
}

// A rigid motion: u_a = (Q - I) X_a + c.
nsb::Vec rigid_displacement(const nsb::Block3d& b, const Eigen::Matrix3d& Q, const Eigen::Vector3d& c) {
  nsb::Vec u(b.ndof());
  for (nsb::Index a = 0; a < b.nodes(); ++a) u.segment<3>(3 * a) = (Q - Eigen::Matrix3d::Identity()) * b.reference_position(a) + c;
  return u;
}

}  // namespace

TEST_CASE("block-3d: F_int = dV/du and K = dF_int/du on a random deformed configuration, both laws", "[problems][block-3d]") {
  std::mt19937_64 rng(33);
  for (const char* material : {"svk", "neo-hookean"}) {
    INFO(material);
    const auto b = make_block3d({{"material", material}});
    const nsb::Index n = b.ndof();
    // Strains of a few percent on elements of 0.25 m.
    const nsb::Vec u = 0.01 * random_vector(n, rng), d = random_vector(n, rng);
    nsb::Vec f(n), fp(n), fm(n);
    b.internal_force(u, f);
    const double eps = 1e-6;
    const double dV = (b.strain_energy(u + eps * d) - b.strain_energy(u - eps * d)) / (2.0 * eps);
    CHECK(std::abs(dV - f.dot(d)) <= 1e-6 * std::abs(f.dot(d)));
    nsb::SpMat K;
    b.tangent_stiffness(u, K);
    b.internal_force(u + eps * d, fp);
    b.internal_force(u - eps * d, fm);
    const nsb::Vec Kd = K * d, fd = (fp - fm) / (2.0 * eps);
    CHECK((Kd - fd).norm() <= 1e-6 * Kd.norm());
    CHECK((nsb::SpMat(K.transpose()) - K).norm() <= 1e-12 * K.norm());  // hyperelastic: symmetric
    // Refilled in place: the same pattern, the same values.
    const double* values = K.valuePtr();
    b.tangent_stiffness(u, K);
    CHECK(K.valuePtr() == values);
    CHECK((K * d - Kd).norm() == 0.0);
  }
}

TEST_CASE("block-3d: force, tangent and energy are bitwise the same on 1 and 2 threads", "[problems][block-3d][threads]") {
  // 16 x 8 x 8 = 1024 elements: enough for two threads (kMinElementsPerThread = 512).
  const auto b = make_block3d({{"nx", "16"}, {"ny", "8"}, {"nz", "8"}});
  std::mt19937_64 rng(5);
  const nsb::Vec u = 0.001 * random_vector(b.ndof(), rng);
  std::vector<nsb::Vec> forces;
  std::vector<nsb::SpMat> tangents;
  std::vector<double> energies;
  for (int threads : {1, 2}) {
    nsb::ThreadScope scope(threads);
    nsb::Vec f(b.ndof());
    b.internal_force(u, f);
    forces.push_back(f);
    tangents.emplace_back();
    b.tangent_stiffness(u, tangents.back());
    energies.push_back(b.strain_energy(u));
  }
  CHECK(forces[0] == forces[1]);
  CHECK(tangents[0].nonZeros() == tangents[1].nonZeros());
  CHECK(nsb::Vec(Eigen::Map<const nsb::Vec>(tangents[0].valuePtr(), tangents[0].nonZeros())) ==
        nsb::Vec(Eigen::Map<const nsb::Vec>(tangents[1].valuePtr(), tangents[1].nonZeros())));
  CHECK(energies[0] == energies[1]);
}

TEST_CASE("block-3d: a rigid motion has zero energy and zero internal force", "[problems][block-3d]") {
  for (const char* material : {"svk", "neo-hookean"}) {
    INFO(material);
    const auto b = make_block3d({{"material", material}});
    const Eigen::Matrix3d Q = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
    const nsb::Vec u = rigid_displacement(b, Q, Eigen::Vector3d(0.3, -0.2, 1.5));
    nsb::Vec f(b.ndof());
    b.internal_force(u, f);
    // Force scale of a unit strain: E h^2 = 1e6 x 0.0625.
    CHECK(f.lpNorm<Eigen::Infinity>() <= 1e-9 * 1e6 * 0.0625);
    CHECK(std::abs(b.strain_energy(u)) <= 1e-12 * 1e6 * 0.125);
  }
}

TEST_CASE("block-3d: the lumped mass is rho W D H on each direction; gravity acts on z", "[problems][block-3d]") {
  const auto b = make_block3d({{"W", "1.2"}, {"D", "0.4"}, {"H", "0.3"}, {"rho", "800"}});
  CHECK(b.total_mass() == Approx(800.0 * 1.2 * 0.4 * 0.3).epsilon(1e-13));
  CHECK(b.mass_matrix().diagonal().minCoeff() > 0.0);
  nsb::Vec f(b.ndof());
  b.external_force(0.0, f);
  for (nsb::Index a = 0; a < b.nodes(); ++a) {
    CHECK(f[3 * a] == 0.0);
    CHECK(f[3 * a + 1] == 0.0);
  }
  CHECK(f.sum() == Approx(-9.81 * b.total_mass()).epsilon(1e-13));
}

TEST_CASE("block-3d: the contact rows L, T1, T2 are the node's z, x, y against differences", "[problems][block-3d][contact]") {
  const auto b = make_block3d({{"mu", "0.4"}, {"height", "0.05"}});
  const nsb::Contacts& c = b.contacts();
  REQUIRE(c.has_cone());
  CHECK(c.size() == static_cast<nsb::Index>(b.contact_nodes().size()));
  CHECK(c.size() == b.nodes() - 2);  // the 3 x 2 x 2 mesh has 2 interior nodes
  // L, T1 and T2 by the conformance check (gaps and slides at random admissible configurations).
  const nsb::CheckVerdict rows = nsb::check_contact_rows(b, nsb::Vec::Zero(b.ndof()));
  INFO(rows.figure);
  CHECK(rows.outcome == nsb::CheckVerdict::Outcome::Pass);
  CHECK(rows.figure.find("T2 against d s2") != std::string::npos);
  // All three against the node positions x_a = X_a + u_a along a random direction.
  std::mt19937_64 rng(7);
  const nsb::Vec u = 0.01 * random_vector(b.ndof(), rng), d = random_vector(b.ndof(), rng);
  nsb::ContactGeometry plus = b.contact_geometry(), minus = b.contact_geometry();
  const double eps = 1e-6;
  b.evaluate_contacts(u + eps * d, plus);
  b.evaluate_contacts(u - eps * d, minus);
  const nsb::Vec L_d = c.normal * d, T1_d = c.tangent * d, T2_d = c.tangent2 * d;
  for (nsb::Index r = 0; r < c.size(); ++r) {
    const nsb::Index a = b.contact_nodes()[static_cast<std::size_t>(r)];
    const auto position = [&](const nsb::Vec& w, int k) { return b.reference_position(a)[k] + w[3 * a + k]; };
    CHECK(plus.gap[r] == Approx(position(u + eps * d, 2)).margin(1e-15));
    CHECK((plus.gap[r] - minus.gap[r]) / (2.0 * eps) == Approx(L_d[r]).epsilon(1e-8));
    CHECK((position(u + eps * d, 0) - position(u - eps * d, 0)) / (2.0 * eps) == Approx(T1_d[r]).epsilon(1e-8));
    CHECK((position(u + eps * d, 1) - position(u - eps * d, 1)) / (2.0 * eps) == Approx(T2_d[r]).epsilon(1e-8));
  }
  // mu = 0: frictionless, no tangent rows at all.
  const auto frictionless = make_block3d({});
  CHECK(frictionless.contacts().tangent.rows() == 0);
  CHECK(frictionless.contacts().tangent2.rows() == 0);
  CHECK(!frictionless.contacts().has_friction());
}

// block-3d whose second tangential coordinate is twice what T2 says: the check must see it.
class WrongSecondTangent final : public ForwardingProblem {
 public:
  using ForwardingProblem::ForwardingProblem;
  void contact_slide2(nsb::ConstVecRef u, nsb::VecRef s2) const override { s2.noalias() = 2.0 * (contacts().tangent2 * u); }
};

TEST_CASE("block-3d: the conformance check fails a T2 row that is not d s2 / du", "[problems][block-3d][contact]") {
  const std::map<std::string, std::string> values = {{"nx", "3"}, {"ny", "2"}, {"nz", "2"}, {"tilt", "20"}, {"mu", "0.4"}};
  const WrongSecondTangent wrong(std::make_unique<nsb::Block3d>(nsb::Params(nsb::Block3d::parameters_spec(), values)));
  const nsb::CheckVerdict rows = nsb::check_contact_rows(wrong, nsb::Vec::Zero(wrong.ndof()));
  INFO(rows.figure);
  CHECK(rows.outcome == nsb::CheckVerdict::Outcome::Fail);
  CHECK(rows.figure.find("T2 against d s2, worst") != std::string::npos);
}

TEST_CASE("block-3d: in free flight (mu = 0) the momentum changes by gravity only, the angular momentum not at all",
          "[problems][block-3d]") {
  const auto b = make_block3d({{"height", "5"}, {"vx", "1"}, {"vy", "-0.5"}, {"spin", "3"}});
  // CD-Lagrange reports (U_k+1, P_k+3/2): from its first step on, P gains dt M g per step, and
  // J_c of that pair is its exact discrete invariant in free flight (the drift keeps
  // x_k x P_k+1/2, the kick adds x_k+1 x dt F_ext, whose moment about x_c(U_k+1) is zero, and
  // F_int has no torque): tests/integrators/block_momentum_test.cpp's argument in 3D.
  auto integ = nsb::make_integrator("cd-lagrange");
  integ->init(b, b.initial_state());
  const double dt = 1e-3;
  integ->step(dt);
  const Eigen::Vector3d P1 = b.linear_momentum(integ->state().v);
  const Eigen::Vector3d J1 = b.angular_momentum(integ->state().u, integ->state().v);
  const int steps = 200;
  for (int k = 0; k < steps; ++k) integ->step(dt);
  REQUIRE(integ->impulses().lpNorm<Eigen::Infinity>() == 0.0);  // never touched the floor
  const Eigen::Vector3d dP = b.linear_momentum(integ->state().v) - P1;
  const Eigen::Vector3d gravity(0.0, 0.0, -9.81 * b.total_mass() * steps * dt);
  const double scale = b.total_mass() * 9.81 * steps * dt;
  CHECK((dP - gravity).norm() <= 1e-12 * scale);
  const Eigen::Vector3d dJ = b.angular_momentum(integ->state().u, integ->state().v) - J1;
  CHECK(J1.norm() > 1.0);  // spin 3 rad/s on the 250 kg block
  CHECK(dJ.norm() <= 1e-12 * J1.norm());
}

TEST_CASE("block-3d: the field mesh is the hexahedra; Cauchy stress zero at rest, finite deformed", "[problems][block-3d][fields]") {
  const auto b = make_block3d({});
  const auto mesh = b.field_mesh();
  REQUIRE(mesh);
  CHECK(mesh->dimension == 3);
  CHECK(mesh->nelements() == b.elements());
  CHECK(mesh->npoints() == b.nodes());
  for (nsb::Index c = 0; c < mesh->ncells(); ++c) CHECK(mesh->cell_size(c) == 8);
  Eigen::MatrixXd stress(b.elements(), 6);
  b.cell_stress(nsb::Vec::Zero(b.ndof()), stress);
  CHECK(stress.lpNorm<Eigen::Infinity>() <= 1e-14 * 1e6);  // F from x = X + u: round-off of E
  // A uniform stretch by 1 % along z of the tilted block: sigma_zz' (its own axis) > 0.
  nsb::Vec u(b.ndof());
  for (nsb::Index a = 0; a < b.nodes(); ++a) u.segment<3>(3 * a) = Eigen::Vector3d(0.0, 0.0, 0.01 * b.reference_position(a).z());
  b.cell_stress(u, stress);
  CHECK(stress.allFinite());
  CHECK(stress.col(2).minCoeff() > 0.0);
  CHECK(stress.col(2).maxCoeff() - stress.col(2).minCoeff() <= 1e-9 * stress.col(2).maxCoeff());  // uniform
}

TEST_CASE("block-3d: bad input is one line naming the parameter and its range", "[problems][block-3d][bad-input]") {
  const auto text = [](std::map<std::string, std::string> values) {
    return nsb::test::input_error_text_of([&] { make_block3d(std::move(values)); });
  };
  CHECK(text({{"nx", "0"}}) == "parameter 'nx' = 0 is outside its valid range integer in [1, 1024]");
  CHECK(text({{"nz", "0"}}) == "parameter 'nz' = 0 is outside its valid range integer in [1, 1024]");
  CHECK(text({{"nu", "0.5"}}) == "parameter 'nu' = 0.5 is outside its valid range [0, 0.5)");
  CHECK(text({{"nu", "-0.1"}}) == "parameter 'nu' = -0.1 is outside its valid range [0, 0.5)");
  CHECK(text({{"mu", "-0.1"}}) == "parameter 'mu' = -0.1 is outside its valid range [0, inf)");
  // Starting in penetration: the lowest corner below the floor.
  CHECK(text({{"height", "-0.01"}}) == "parameter 'height' = -0.01 is outside its valid range [0, inf)");
  CHECK(text({{"material", "rubber"}}).find("material") != std::string::npos);
  // 1024^3 elements: far beyond any machine's memory, refused before allocating.
  const std::string memory = text({{"nx", "1024"}, {"ny", "1024"}, {"nz", "1024"}});
  CHECK_THAT(memory, Catch::Contains("block-3d: nx = 1024, ny = 1024, nz = 1024") && Catch::Contains("GiB") &&
                         Catch::Contains("valid: nx * ny * nz <= "));
}
