#include <catch2/catch.hpp>
#include <Eigen/Core>
#include <cmath>
#include <map>
#include <string>

#include "problems/bar3d_exact.hpp"
#include "problems/hex8_elements.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::Params;
using nsb::SignoriniBar;

TEST_CASE("bar-3d: the oedometric wave speed and contact duration", "[bar3d_exact]") {
  // nu = 0: no lateral coupling, the 1D bar's c = sqrt(E / rho).
  CHECK(nsb::p_wave_speed(4.0, 0.0, 1.0) == 2.0);
  // nu = 0.3: M = E 0.7 / (1.3 * 0.4) = 1.3461538... E.
  CHECK(nsb::oedometric_modulus(1.0, 0.3) == Approx(0.7 / 0.52).epsilon(1e-15));
  CHECK(nsb::p_wave_speed(210e9, 0.3, 7800.0) == Approx(std::sqrt(210e9 * 0.7 / (0.52 * 7800.0))).epsilon(1e-15));
  CHECK(nsb::bar3d_contact_duration(2.0, 1.0, 0.25, 1.0) == Approx(4.0 / std::sqrt(0.75 / (1.25 * 0.5))).epsilon(1e-15));
  // The modulus is the hex8 material's lambda + 2 mu: the stiffness a laterally held element has.
  for (const double nu : {0.0, 0.2, 0.3, 0.45, 0.499}) {
    const auto mat = nsb::Hex8Material::from_young(nsb::Hex8Law::svk, 7.0, nu);
    CHECK(nsb::oedometric_modulus(7.0, nu) == Approx(mat.lambda + 2.0 * mat.mu).epsilon(1e-14));
  }
}

TEST_CASE("bar-3d: one hex8 element in axial motion is the 1D bar's element", "[bar3d_exact]") {
  // An element of length h and cross-section b x b, its faces x = 0 and x = h moving as wholes
  // along x (lateral displacements held): face stiffness (M A / h) [1 -1; -1 1], face masses
  // (lumped) rho A h / 2, the 1D linear element's, so the semi-discrete systems coincide.
  const double h = 0.3, b = 0.2, E = 5.0, nu = 0.3, rho = 2.0;
  nsb::Hex8Nodes X;
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int n = 0; n < 8; ++n) X.col(n) << h * corner[n][0], b * corner[n][1], b * corner[n][2];
  const nsb::Hex8Element element(X);
  nsb::Hex8Matrix K;
  element.tangent(X, nsb::Hex8Material::from_young(nsb::Hex8Law::svk, E, nu), K);
  Eigen::Matrix2d face = Eigen::Matrix2d::Zero();  // x-dofs summed per face (rows and columns)
  for (int a = 0; a < 8; ++a)
    for (int c = 0; c < 8; ++c) face(corner[a][0], corner[c][0]) += K(3 * a, 3 * c);
  const double k = nsb::oedometric_modulus(E, nu) * b * b / h;
  CHECK(face(0, 0) == Approx(k).epsilon(1e-14));
  CHECK(face(1, 1) == Approx(k).epsilon(1e-14));
  CHECK(face(0, 1) == Approx(-k).epsilon(1e-14));
  Eigen::Matrix<double, 8, 1> m;
  element.lumped_mass(rho, m);
  double face_mass = 0.0;
  for (int a = 0; a < 8; ++a) face_mass += corner[a][0] == 0 ? m(a) : 0.0;
  CHECK(face_mass == Approx(rho * b * b * h / 2.0).epsilon(1e-14));
}

TEST_CASE("bar-3d: the exact solution is the 1D bar's with the oedometric modulus", "[bar3d_exact]") {
  const Params prm(SignoriniBar::parameters_spec(), {{"E", "2"}, {"rho", "3"}, {"L", "1.5"}, {"A", "0.5"},
                                                     {"v0", "0.7"}, {"g0", "0.1"}});
  const double nu = 0.3;
  const auto bar = nsb::oedometric_bar(prm, nu);
  const double c_p = nsb::p_wave_speed(2.0, nu, 3.0), T = nsb::bar3d_contact_duration(1.5, 2.0, nu, 3.0);
  CHECK(bar->wave_speed() == Approx(c_p).epsilon(1e-15));
  CHECK(bar->contact_duration() == Approx(T).epsilon(1e-15));
  const double t0 = 0.1 / 0.7, force = 0.5 * 3.0 * c_p * 0.7;
  CHECK(bar->exact_contact_force(t0 + 0.5 * T) == Approx(force).epsilon(1e-15));
  CHECK(bar->exact_contact_force(t0 + 1.01 * T) == 0.0);
  CHECK(bar->exact_contact_force(t0 - 0.01 * T) == 0.0);
  // The other parameters are the given ones.
  CHECK(bar->parameters().real("L") == 1.5);
  CHECK(bar->parameters().real("v0") == 0.7);
}

TEST_CASE("bar-3d: bad input is one line naming the parameter and its range", "[bar3d_exact]") {
  for (const double nu : {0.5, -0.1, 0.7}) {
    const std::string t = nsb::test::input_error_text_of([nu] { nsb::p_wave_speed(1.0, nu, 1.0); });
    INFO(t);
    CHECK(t.find("nu = ") != std::string::npos);
    CHECK(t.find("[0, 0.5)") != std::string::npos);
    CHECK(t.find('\n') == std::string::npos);
  }
  CHECK(nsb::test::input_error_text_of([] { nsb::p_wave_speed(1.0, 0.3, 0.0); }).find("rho = ") != std::string::npos);
  CHECK(nsb::test::input_error_text_of([] { nsb::bar3d_contact_duration(-1.0, 1.0, 0.3, 1.0); }).find("L = ") != std::string::npos);
  CHECK(nsb::test::input_error_text_of([] { nsb::oedometric_modulus(0.0, 0.3); }).find("E = ") != std::string::npos);
}
