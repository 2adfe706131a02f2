// The sphere problem (problems/sphere.hpp): its 3D contact rows against the contact point's
// velocity, its exact state against its own equations (u' = v, energy), bad input.
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <cmath>
#include <map>
#include <string>

#include "problems/sphere.hpp"
#include "tests/support/input_error.hpp"

using Catch::Detail::Approx;
using nsb::Params;
using nsb::Sphere;

namespace {

Sphere make_sphere(const std::map<std::string, std::string>& set = {}) { return Sphere(Params(Sphere::parameters_spec(), set)); }

}  // namespace

TEST_CASE("sphere: the tangent rows are the contact point's velocity, the Delassus block diag(1, 7/2, 7/2) / m",
          "[sphere]") {
  const Sphere s = make_sphere({{"m", "2"}, {"R", "0.25"}});
  const nsb::Contacts& c = s.contacts();
  REQUIRE(c.has_cone());
  Eigen::VectorXd v(6);
  v << 0.3, -1.1, 0.7, 2.0, -5.0, 1.5;
  const Eigen::Vector3d omega = v.segment<3>(3), r(0.0, 0.0, -0.25);
  const Eigen::Vector3d point = v.head<3>() + omega.cross(r);  // the contact point's velocity
  CHECK((c.tangent * v)(0) == Approx(point.x()));
  CHECK((c.tangent2 * v)(0) == Approx(point.y()));
  CHECK((c.normal * v)(0) == Approx(point.z()));
  Eigen::MatrixXd C(3, 6);
  C.row(0) = Eigen::MatrixXd(c.normal);
  C.row(1) = Eigen::MatrixXd(c.tangent);
  C.row(2) = Eigen::MatrixXd(c.tangent2);
  const Eigen::MatrixXd W = C * Eigen::MatrixXd(s.mass_matrix()).inverse() * C.transpose();
  CHECK(W.isApprox(Eigen::Vector3d(0.5, 1.75, 1.75).asDiagonal().toDenseMatrix(), 1e-14));
  CHECK_FALSE(make_sphere({{"mu", "0"}}).contacts().has_cone());  // mu = 0: frictionless, no rows
}

TEST_CASE("sphere: the exact state solves u' = v and keeps the energy balance", "[sphere]") {
  const Sphere s = make_sphere();
  const double t_roll = s.roll_time();
  REQUIRE(t_roll == Approx(0.238575312993057).epsilon(1e-12));  // docs/three_d.md
  for (const double t : {0.3 * t_roll, 0.9 * t_roll, 1.5 * t_roll}) {
    const double h = 1e-5;
    const nsb::State a = *s.state(t - h), b = *s.state(t + h), x = *s.state(t);
    const Eigen::VectorXd rate = (b.u - a.u) / (2.0 * h);
    CHECK((rate - x.v).lpNorm<Eigen::Infinity>() < 1e-8 * x.v.lpNorm<Eigen::Infinity>());
    // Kinetic + load potential is the exact solution's energy, which falls by the friction work.
    const double energy = 0.5 * x.v.dot(s.mass_matrix() * x.v) + s.load_potential(x.u);
    const nsb::SphereInclineExact::State e = s.closed_form().state(t);
    CHECK(energy == Approx(s.closed_form().energy(e)).epsilon(1e-14));
    const double friction_work = 0.3 * 9.81 * std::cos(20.0 * M_PI / 180.0) * s.closed_form().slip_path_length(t);
    const nsb::State x0 = s.initial_state();
    CHECK(energy == Approx(0.5 * x0.v.dot(s.mass_matrix() * x0.v) - friction_work).epsilon(1e-13));
    double slip[2];
    s.observe(x, nsb::Vec(), 0.0, slip);
    CHECK(slip[0] == Approx(slip[1]).margin(1e-13));
  }
  const auto figures = s.summary_values();
  REQUIRE(figures.size() == 1);
  CHECK(figures[0].first == "t_roll_exact");
  CHECK(figures[0].second == t_roll);
  // Dropped: no exact solution here.
  const Sphere dropped = make_sphere({{"h0", "0.1"}});
  CHECK_FALSE(dropped.state(0.1));
  CHECK(std::isnan(dropped.roll_time()));
  // mu below (2/7) tan(alpha): it slides for ever.
  CHECK(std::isinf(make_sphere({{"mu", "0.1"}}).roll_time()));
}

TEST_CASE("sphere: bad input is one line naming the parameter and its range", "[sphere]") {
  const auto text = [](const std::map<std::string, std::string>& set) {
    return nsb::test::input_error_text_of([&] { make_sphere(set); });
  };
  for (const auto& [name, value] : std::map<std::string, std::string>{{"alpha", "90"}, {"alpha", "-1"}, {"mu", "-0.1"}, {"h0", "-0.01"}}) {
    const std::string t = text({{name, value}});
    CHECK_THAT(t, Catch::Contains(name) && Catch::Contains("["));
    CHECK(t.find('\n') == std::string::npos);
  }
  CHECK_THAT(text({{"alpha", "90"}}), Catch::Contains("90)"));  // the open bound
  CHECK(text({{"alpha", "89.9"}}).empty());
}

TEST_CASE("sphere: the field mesh is one 3D vertex with the body arrays", "[sphere]") {
  const Sphere s = make_sphere();
  const nsb::FieldMesh mesh = *s.field_mesh();
  CHECK(mesh.dimension == 3);
  CHECK(mesh.nbodies() == 1);
  CHECK(mesh.body_columns() == 7);
  Eigen::MatrixXd out(1, 7);
  const nsb::State x = *s.state(0.1);
  s.body_data(x, out);
  CHECK(out(0, 0) == 0.1);
  CHECK(out.block<1, 3>(0, 1).transpose().isApprox(x.v.tail<3>()));
  CHECK(out.block<1, 3>(0, 4).transpose().isApprox(x.u.tail<3>()));
}
