#include "problems/rocking_block.hpp"
#include "core/deterministic_math.hpp"
#include "problems/floor_contacts.hpp"
#include "problems/registry.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace nsb {

namespace {

RockingBlockSpec rocking_spec(const Params& p) {
  RockingBlockSpec s;
  s.b = p.real("b");
  s.h = p.real("h");
  s.m = p.real("m");
  s.g = p.real("g");
  s.theta0 = p.real("theta0");
  s.omega0 = p.real("omega0");
  s.mu = p.real("mu");
  s.e = p.real("e");
  s.law = RockingImpactLaw::moreau;
  return s;
}

}  // namespace

ParamSpecs RockingBlock::parameters_spec() {
  const double half_pi = std::numbers::pi / 2;
  return {
      ParamSpec::real("b", 0.2, 0.0, 1e308, "half-width [m] (alpha = atan(b / h) in (0, 90) degrees)", true),
      ParamSpec::real("h", 1.0, 0.0, 1e308, "half-height [m] (alpha = atan(b / h) in (0, 90) degrees)", true),
      ParamSpec::real("theta0", 0.1, -half_pi, half_pi,
                      "initial angle, counter-clockwise [rad] (beyond +-pi/2 an upper corner starts in the floor)", true, true),
      ParamSpec::real("omega0", 0.0, -1e308, 1e308, "initial angular velocity [rad/s]"),
      ParamSpec::real("mu", 1.0, 0.0, 1e308, "Coulomb friction coefficient of both corners (0: frictionless)"),
      ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient of both corners"),
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass [kg]", true),
      ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2]", true),
  };
}

RockingBlock::RockingBlock(const Params& params)
    : params_(params), b_(params.real("b")), h_(params.real("h")), exact_(rocking_spec(params)) {
  const double m = params.real("m"), R = exact_.R();
  mass_ = Vec(3);
  mass_ << m, m, m * R * R / 3.0;
  load_ = Vec::Zero(3);
  load_[1] = -m * params.real("g");

  const Vec u0 = initial_state().u;
  const BlockCorners c = corners(u0);
  contacts_ = floor_contacts({c.right, c.left}, u0, params.real("e"), params.real("mu"));
}

BlockCorners RockingBlock::corners(ConstVecRef u) const { return block_corners(b_, h_, Eigen::Vector3d(u[0], u[1], u[2])); }

void RockingBlock::evaluate_contacts(ConstVecRef u, ContactGeometry& out) const {
  const BlockCorners c = corners(u);
  write_floor_contact(0, c.right, out);
  write_floor_contact(1, c.left, out);
}

void RockingBlock::contact_slide(ConstVecRef u, VecRef s) const {
  const double c = nsb::dmath::cos(u[2]), sn = nsb::dmath::sin(u[2]);
  s[0] = u[0] + b_ * c + h_ * sn;  // (+b, -h): x + p_x cos theta - p_y sin theta
  s[1] = u[0] - b_ * c + h_ * sn;  // (-b, -h)
}

State RockingBlock::initial_state() const { return *state(0.0); }

std::optional<State> RockingBlock::state(double t) const {
  const auto s = exact_.state(t);
  if (!s) return std::nullopt;
  State out;
  out.t = t;
  out.u = Vec(3);
  out.v = Vec(3);
  out.u << s->x, s->y, s->theta;
  out.v << s->vx, s->vy, s->omega;
  return out;
}

std::vector<double> RockingBlock::impact_times(double t_end) const {
  std::vector<double> times;
  for (const auto& im : exact_.impacts())
    if (im.t <= t_end) times.push_back(im.t);
  return times;
}

std::vector<double> RockingBlock::amplitudes_after_impacts() const {
  std::vector<double> amplitudes;
  for (const auto& im : exact_.impacts()) amplitudes.push_back(im.amplitude_after);
  return amplitudes;
}

std::optional<double> RockingBlock::event_time(ExactEvent event) const {
  return event == ExactEvent::rest ? std::optional<double>(exact_.rest_time()) : std::nullopt;
}

std::optional<double> RockingBlock::value(ExactValue what) const {
  if (what == ExactValue::impact_ratio) return exact_.impact_ratio();
  if (what == ExactValue::housner_ratio) return housner_ratio(exact_.alpha());
  return std::nullopt;
}

std::vector<std::string> RockingBlock::observable_names() const { return {"theta", "omega", "omega_exact"}; }

void RockingBlock::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const auto ex = exact_.state(s.t);
  out[0] = s.u[2];
  out[1] = s.v[2];
  out[2] = ex ? ex->omega : std::numeric_limits<double>::quiet_NaN();
}

std::optional<FieldMesh> RockingBlock::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 2;
  mesh.add_vertex(0.0, h_, {0, 1}, 0);
  mesh.body_arrays = {{"half_width", 1}, {"half_height", 1}, {"angle", 1}, {"angular_velocity", 1}, {"orientation", 3}};
  return mesh;
}

void RockingBlock::body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const {
  const double theta = s.u[2];
  out.row(0) << b_, h_, theta, s.v[2], nsb::dmath::cos(theta), nsb::dmath::sin(theta), 0.0;
}

NSBENCH_PROBLEM({"rocking-block", "rigid block rocking on two corners whose gaps turn with it (moving contacts; exact: Housner / Moreau)", &RockingBlock::parameters_spec, &make_from_params<Problem, RockingBlock>});

}  // namespace nsb
