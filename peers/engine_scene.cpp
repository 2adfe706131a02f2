#include "peers/engine_scene.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace nsb::engines {

ParamSpec size_spec() {
  return ParamSpec::real("size", 0.1, 0.0, 10.0, "radius of the bouncing sphere, half side of the sliding box [m] (the disk keeps the problem's R)", true);
}

Scene scene_of(const Problem& problem, const State& initial, double size, const std::string& who) {
  const Contacts& c = problem.contacts();
  for (Index i = 0; i < c.tangent_velocity.size(); ++i)
    if (c.tangent_velocity[i] != 0.0)
      throw InputError(fmt::format("{}: problem '{}' has an obstacle moving along contact {} (tangent_velocity w = {}); the engine's plane is fixed (valid: w = 0)",
                                   who, problem.name(), i, c.tangent_velocity[i]));
  const std::string& name = problem.name();
  if (name != "bouncing-mass" && name != "sliding-mass" && name != "rolling-disk" && name != "rocking-block" && name != "sphere")
    throw InputError(fmt::format("{}: problem '{}' is not one of the rigid problems the engine peers run (valid: {}); the engines see "
                                 "rigid bodies, not a semi-discrete continuum", who, name, kSceneProblems));
  const Params& p = problem.parameters();
  Scene s;
  s.problem = problem.name();
  s.restitution = c.restitution;
  s.mu = c.max_mu();
  s.mass = p.real("m");
  const double g = p.real("g");
  if (s.problem == "bouncing-mass") {
    s.shape = Shape::Sphere;
    s.radius = size;
    s.kappa = 0.4;
    s.gz = -g;
    s.start.z = initial.u[0] + size;
    s.start.vz = initial.v[0];
  } else if (s.problem == "sliding-mass") {
    s.shape = Shape::Box;
    s.radius = size;
    s.half_height = 0.5 * size;
    s.moves_x = true;
    const double alpha = p.real("alpha") * std::numbers::pi / 180.0;
    s.gx = g * std::sin(alpha);
    s.gz = -g * std::cos(alpha);
    s.start = {initial.u[0], initial.u[1] + s.half_height, 0.0, initial.v[0], initial.v[1], 0.0};
  } else if (s.problem == "rocking-block") {
    s.shape = Shape::Box;
    s.radius = p.real("b");
    s.half_height = p.real("h");
    s.kappa = (s.radius * s.radius + s.half_height * s.half_height) / (3.0 * s.radius * s.radius);
    s.moves_x = s.rotates = true;
    s.contacts = 2;
    s.gz = -g;
    s.start = {initial.u[0], initial.u[1], -initial.u[2], initial.v[0], initial.v[1], -initial.v[2]};
  } else if (s.problem == "sphere") {
    s.shape = Shape::Sphere;
    s.radius = p.real("R");
    s.kappa = 0.4;
    s.moves_x = s.rotates = s.spatial = true;
    const double alpha = p.real("alpha") * std::numbers::pi / 180.0;
    s.gx = g * std::sin(alpha);
    s.gz = -g * std::cos(alpha);
    const Vec& u = initial.u;
    const Vec& v = initial.v;
    s.start = {u[0], u[2] + s.radius, 0.0, v[0], v[2], v[4], u[1], v[1], v[3], v[5]};
  } else {
    s.kappa = p.real("kappa");
    s.radius = p.real("R");
    s.moves_x = s.rotates = true;
    if (s.kappa == 0.4) {
      s.shape = Shape::Sphere;
    } else if (s.kappa == 0.5) {
      s.shape = Shape::Cylinder;
      s.half_height = s.radius;
    } else {
      throw InputError(fmt::format("{}: problem 'rolling-disk' has kappa = {}; the engine's bodies are a sphere (kappa = 2/5) and a cylinder "
                                   "(kappa = 1/2) (valid: kappa = 0.4 or 0.5)", who, s.kappa));
    }
    s.gz = -g;
    s.start = {initial.u[0], initial.u[1] + s.radius, -initial.u[2], initial.v[0], initial.v[1], -initial.v[2]};
  }
  return s;
}

double unwrap(double previous, double wrapped) {
  const double two_pi = 2.0 * std::numbers::pi;
  return wrapped + two_pi * std::round((previous - wrapped) / two_pi);
}

void to_state(const Scene& s, const Pose& pose, double t, State& out) {
  const double dt = t - out.t;
  out.t = t;
  if (s.spatial) {
    const Eigen::Vector3d omega(pose.wx, pose.wy, pose.wz);
    out.u.head<3>() << pose.x, pose.y, pose.z - s.radius;
    out.u.tail<3>() += dt * omega;
    out.v << pose.vx, pose.vy, pose.vz, omega;
  } else if (s.problem == "bouncing-mass") {
    out.u[0] = pose.z - s.radius;
    out.v[0] = pose.vz;
  } else if (s.problem == "sliding-mass") {
    out.u << pose.x, pose.z - s.half_height;
    out.v << pose.vx, pose.vz;
  } else {
    const double lift = s.problem == "rocking-block" ? 0.0 : s.radius;  // the block's u[1] is its centre's height
    out.u << pose.x, pose.z - lift, -pose.angle;
    out.v << pose.vx, pose.vz, -pose.wy;
  }
}

void StepResult::add(const Scene& scene, double point_x, double centre_x, double normal, double friction_x, double friction_y) {
  const std::size_t contact = scene.contacts == 2 && point_x < centre_x ? 1 : 0;
  normal_impulse[contact] += normal;
  friction_impulse_x[contact] += friction_x;
  friction_impulse_y[contact] += friction_y;
}

}  // namespace nsb::engines

namespace nsb {

void EnginePeer::init(const Problem& problem, const State& initial) {
  const std::string who = fmt::format("--integrator {}", name());
  bind(problem, initial);
  scene_ = engines::scene_of(problem, initial, params_.real("size"), who);
  build(scene_);
}

StepInfo EnginePeer::advance(double dt) {
  const engines::StepResult r = engine_step(dt);
  engines::to_state(scene_, r.pose, state_.t + dt, state_);
  for (int k = 0; k < scene_.contacts; ++k) {
    impulses_[k] = r.normal_impulse[static_cast<std::size_t>(k)];
    if (scene_.moves_x) tangential_impulses_[k] = r.friction_impulse_x[static_cast<std::size_t>(k)];
    if (scene_.spatial) tangential_impulses2_[k] = r.friction_impulse_y[static_cast<std::size_t>(k)];
  }
  ++work_.force_evaluations;
  StepInfo info;
  info.dt = dt;
  info.iterations = r.iterations;
  return info;
}

}  // namespace nsb
