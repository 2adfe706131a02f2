#include <catch2/catch.hpp>
#include <cmath>

#include "problems/spring_chain.hpp"

using Catch::Detail::Approx;

namespace {
nsb::SpringChain chain(const std::map<std::string, std::string>& p) {
  return nsb::SpringChain(nsb::Params(nsb::SpringChain::parameters_spec(), p));
}
}  // namespace

TEST_CASE("spring chain: F_int is the gradient of the strain energy and has zero resultant", "[problems][spring-chain]") {
  const auto p = chain({{"n", "5"}, {"k", "30"}});
  nsb::Vec u(5), f(5);
  u << 0.1, -0.3, 0.25, 0.0, 0.7;
  p.internal_force(u, f);
  CHECK(f.sum() == Approx(0.0).margin(1e-12));
  const double h = 1e-6;  // central differences of a quadratic: exact up to round-off
  for (nsb::Index i = 0; i < 5; ++i) {
    nsb::Vec up = u, um = u;
    up[i] += h;
    um[i] -= h;
    CHECK((p.strain_energy(up) - p.strain_energy(um)) / (2 * h) == Approx(f[i]).margin(1e-7));
  }
}

TEST_CASE("spring chain: stable step 2/omega_max, two masses in closed form; wall contact rows", "[problems][spring-chain]") {
  // Two masses m, r m on a spring k: omega^2 = k (1/m + 1/(r m)).
  const auto p = chain({{"n", "2"}, {"m", "2"}, {"mass_ratio", "3"}, {"k", "50"}, {"wall", "left"}, {"gap", "0.2"}});
  CHECK(p.stable_step() == Approx(2.0 / std::sqrt(50.0 * (1.0 / 2.0 + 1.0 / 6.0))).epsilon(1e-12));
  REQUIRE(p.ncontacts() == 1);
  CHECK(p.gap_offset()[0] == 0.2);
  CHECK(p.gap_operator().coeff(0, 0) == 1.0);
  CHECK(chain({{"wall", "none"}}).ncontacts() == 0);
  const auto both = chain({{"n", "4"}, {"wall", "both"}});
  REQUIRE(both.ncontacts() == 2);
  CHECK(both.gap_operator().coeff(1, 3) == -1.0);  // g = gap - U_3: closes when the last mass moves right
}

TEST_CASE("spring chain: field mesh, springs as lines with their force, masses as vertices", "[problems][field-mesh]") {
  const auto p = chain({{"n", "4"}, {"k", "30"}});
  const auto mesh = p.field_mesh();
  REQUIRE(mesh.has_value());
  CHECK(mesh->dimension == 1);
  REQUIRE(mesh->npoints() == 4);
  REQUIRE(mesh->nelements() == 3);
  REQUIRE(mesh->nbodies() == 4);
  for (nsb::Index i = 0; i < 4; ++i) {
    CHECK(mesh->points(i, 0) == static_cast<double>(i));
    CHECK(mesh->point_dofs(i, 0) == i);
    CHECK(mesh->cell_size(3 + i) == 1);
    CHECK(mesh->cells(3 + i, 0) == i);  // a vertex on each mass
  }
  for (nsb::Index i = 0; i < 3; ++i) {
    CHECK(mesh->cell_size(i) == 2);
    CHECK(mesh->cells.row(i) == Eigen::RowVector2i(static_cast<int>(i), static_cast<int>(i + 1)));
  }
  // The spring forces are the internal forces' pieces: F_int,0 = -N_0, F_int,3 = N_2, and
  // N_i - N_{i-1} = -F_int,i in between (positive N: tension).
  nsb::Vec u(4), f(4);
  u << 0.1, -0.3, 0.25, 0.7;
  Eigen::MatrixXd force(3, 1);
  p.cell_stress(u, force);
  p.internal_force(u, f);
  CHECK(force(0, 0) == Approx(30.0 * (-0.4)));
  CHECK(f[0] == Approx(-force(0, 0)));
  CHECK(f[1] == Approx(force(0, 0) - force(1, 0)));
  CHECK(f[2] == Approx(force(1, 0) - force(2, 0)));
  CHECK(f[3] == Approx(force(2, 0)));
}

TEST_CASE("spring chain: observables momentum (sum m_i v_i) and v_first (the first mass's velocity, -v0 + a at the start)",
          "[problems][spring-chain]") {
  const auto p = chain({{"n", "3"}, {"m", "2"}, {"mass_ratio", "3"}, {"v0", "1"}, {"a", "0.25"}, {"wall", "left"}});
  REQUIRE(p.observable_names() == std::vector<std::string>{"momentum", "v_first"});
  std::vector<double> out(2);
  nsb::State s = p.initial_state();
  p.observe(s, nsb::Vec::Zero(1), 0.0, out);
  CHECK(out[1] == -0.75);                                    // -v0 + a on mass 0
  CHECK(out[0] == 2.0 * -0.75 + 6.0 * -1.25 + 2.0 * -0.75);  // masses m, r m, m
  s.v << 0.5, -2.0, 3.0;
  p.observe(s, nsb::Vec::Zero(1), 1e-3, out);
  CHECK(out[1] == 0.5);
  CHECK(out[0] == 1.0 - 12.0 + 6.0);
}
