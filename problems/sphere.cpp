#include "problems/sphere.hpp"
#include "core/deterministic_math.hpp"
#include "problems/registry.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace nsb {

namespace {

SphereInclineSpec spec_of(const Params& p) {
  SphereInclineSpec s;
  s.R = p.real("R");
  s.alpha = p.real("alpha");
  s.mu = p.real("mu");
  s.m = p.real("m");
  s.g = p.real("g");
  s.vx0 = p.real("vx0");
  s.vy0 = p.real("vy0");
  s.wx0 = p.real("wx0");
  s.wy0 = p.real("wy0");
  s.wz0 = p.real("wz0");
  return s;
}

}  // namespace

ParamSpecs Sphere::parameters_spec() {
  return {
      ParamSpec::real("R", 0.1, 0.0, 1e308, "radius [m]", true),
      ParamSpec::real("alpha", 20.0, 0.0, 90.0, "slope of the plane [degrees]", false, true),
      ParamSpec::real("mu", 0.3, 0.0, 1e308, "Coulomb friction coefficient (0: frictionless)"),
      ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient"),
      ParamSpec::real("h0", 0.0, 0.0, 1e308, "initial gap of the lowest point (0: on the plane; < 0 would start in penetration) [m]"),
      ParamSpec::real("vx0", 1.0, -1e308, 1e308, "initial velocity of the centre down the slope [m/s]"),
      ParamSpec::real("vy0", 0.5, -1e308, 1e308, "initial velocity of the centre across the slope [m/s]"),
      ParamSpec::real("wx0", 4.0, -1e308, 1e308, "initial angular velocity about x [rad/s]"),
      ParamSpec::real("wy0", -3.0, -1e308, 1e308, "initial angular velocity about y [rad/s]"),
      ParamSpec::real("wz0", 2.0, -1e308, 1e308, "initial angular velocity about z, the normal [rad/s]"),
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass [kg]", true),
      ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2]", true),
  };
}

Sphere::Sphere(const Params& params) : params_(params), spec_(spec_of(params)), h0_(params.real("h0")), exact_(spec_) {
  const double m = spec_.m, R = spec_.R, I = 0.4 * m * R * R;
  const double alpha = spec_.alpha * std::numbers::pi / 180.0;
  mass_ = Vec(6);
  mass_ << m, m, m, I, I, I;
  load_ = Vec::Zero(6);
  load_[0] = m * spec_.g * nsb::dmath::sin(alpha);
  load_[2] = -m * spec_.g * nsb::dmath::cos(alpha);

  contacts_.normal.resize(1, 6);
  contacts_.normal.insert(0, 2) = 1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Zero(1);
  contacts_.restitution = params.real("e");
  if (spec_.mu > 0.0) {
    SpMat T(1, 6), T2(1, 6);
    T.insert(0, 0) = 1.0;
    T.insert(0, 4) = -R;
    T2.insert(0, 1) = 1.0;
    T2.insert(0, 3) = R;
    contacts_.set_cone(std::move(T), std::move(T2), spec_.mu);
  }
}

State Sphere::initial_state() const {
  State s;
  s.u = Vec::Zero(6);
  s.u[2] = h0_;
  s.v = Vec::Zero(6);
  s.v << spec_.vx0, spec_.vy0, 0.0, spec_.wx0, spec_.wy0, spec_.wz0;
  return s;
}

double Sphere::roll_time() const { return h0_ > 0.0 ? std::numeric_limits<double>::quiet_NaN() : exact_.roll_time(); }

std::optional<double> Sphere::event_time(ExactEvent event) const {
  if (event == ExactEvent::roll_onset && h0_ <= 0.0) return exact_.roll_time();
  return std::nullopt;
}

std::optional<State> Sphere::state(double t) const {
  if (h0_ > 0.0) return std::nullopt;
  const SphereInclineExact::State e = exact_.state(t);
  State s;
  s.t = t;
  s.u = Vec::Zero(6);
  s.v = Vec::Zero(6);
  s.u << e.position.x(), e.position.y(), 0.0, e.rotation;
  s.v << e.velocity.x(), e.velocity.y(), 0.0, e.omega;
  return s;
}

std::vector<std::string> Sphere::observable_names() const { return {"slip_speed", "slip_speed_exact"}; }

void Sphere::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const double R = spec_.R;
  out[0] = nsb::dmath::hypot(s.v[0] - R * s.v[4], s.v[1] + R * s.v[3]);
  out[1] = h0_ > 0.0 ? std::numeric_limits<double>::quiet_NaN() : exact_.slip_speed(s.t);
}

std::vector<std::pair<std::string, double>> Sphere::summary_values() const { return {{"t_roll_exact", roll_time()}}; }

std::optional<FieldMesh> Sphere::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 3;
  mesh.points = Eigen::RowVector3d(0.0, 0.0, spec_.R);
  mesh.point_dofs = Eigen::RowVector3i(0, 1, 2);
  mesh.cells = Eigen::MatrixXi::Zero(1, 1);
  mesh.cell_body = {0};
  mesh.body_arrays = {{"radius", 1}, {"angular_velocity", 3}, {"rotation_integral", 3}};
  mesh.body_rotation_dofs = {3};
  return mesh;
}

void Sphere::body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const {
  out.row(0) << spec_.R, s.v[3], s.v[4], s.v[5], s.u[3], s.u[4], s.u[5];
}

NSBENCH_PROBLEM({"sphere", "rigid sphere sliding then rolling on an incline, spin across the slope, Coulomb cone (exact solution)", &Sphere::parameters_spec, &make_from_params<Problem, Sphere>});

}  // namespace nsb
