#pragma once
// The rigid scenes the physics-engine peers (MuJoCo, Bullet, ODE: peers/mujoco, peers/bullet,
// peers/ode) build from nsbench's rigid problems, and the map from the engine's body back to
// the problem's dofs. The world is z up; every body but the sphere moves in the x-z plane:
//
//   bouncing-mass  a sphere (radius `size`) above the plane z = 0, gravity (0, 0, -g);
//                  u = z - size (the gap), v = z'. Frictionless (the problem has mu = 0).
//   sliding-mass   a box (half sides `size`, `size`, `size` / 2) on the plane z = 0; the slope
//                  is made by tilting gravity, not the plane: g (sin alpha, 0, -cos alpha), so x
//                  runs down the slope. u = (x, z - size / 2), v = (x', z'). The problem is a
//                  point mass: an engine that can lock the box's rotation does (Scene::rotates).
//   rolling-disk   a sphere (kappa = 2/5) or a cylinder along y (kappa = 1/2) of the problem's
//                  radius R; u = (x, z - R, theta), theta = -(angle about +y): the problem's
//                  counter-clockwise theta seen with x right and z up, so the contact point's
//                  slip x' + R theta' is the engine's x' - R omega_y.
//   rocking-block  a box (half sides b, b, h: the problem's b and h; its depth along y, 2 b, is
//                  immaterial by symmetry) on the plane z = 0, gravity (0, 0, -g), free to
//                  slide in x and z and to turn about y; its inertia about y is the problem's
//                  m (b^2 + h^2) / 3 (the box's own). The problem's y is the engine's z:
//                  u = (x, z, theta), theta = -(angle about +y) as for the disk. Its contacts
//                  are the box's bottom edges (the engine finds two points on each, at +-b in
//                  y): a point right of the centre (world x above the centre's) belongs to the
//                  problem's contact 0 (the corner (+b, -h)), one left of it to contact 1.
//   sphere         (3D, Scene::spatial) a free sphere of the problem's radius R on the plane
//                  z = 0, the slope made by tilting gravity as for the sliding mass:
//                  g (sin alpha, 0, -cos alpha), x down the slope, y across it, z the normal,
//                  the problem's own axes. u = (x, y, z - R, theta_x, theta_y, theta_z),
//                  v = (x', y', z', omega): omega is the engine's world angular velocity, and
//                  theta, the problem's integral of omega (no function of the orientation), is
//                  summed here as the engines step their positions: theta += dt omega(t + dt).
//                  The engine keeps the orientation (its quaternion) itself; no equation of
//                  the problem reads it. Slip: (x' - R omega_y, y' + R omega_x).
//
// The entries declare node-to-rigid contacts only (one body on a fixed plane; ball-chain's
// contacts between bodies are refused when the problem binds). Every other problem is
// declined (InputError naming the problem): the engines see rigid bodies, not a
// semi-discrete continuum. A rocking block's moving contacts are the engine's own (it
// re-detects the box's corners every step). A rolling-disk whose kappa is not a shape's (2/5,
// 1/2) is declined naming kappa; an obstacle moving along the contact (w != 0) naming w.
//
// Impulses: the engine reports each contact point's normal impulse (>= 0) and the world-x
// component P_x of its friction impulse on the body; the points are summed per problem contact
// (one contact, or the rocking block's two corners, StepResult::add). The tangent row T is
// [1, 0] (sliding), [1, 0, R] (disk) or the corner's horizontal velocity (block): P_x at the
// contact point gives the x dof P_x and the theta dof the moment of P_x, so Lambda_T = P_x.
// The sphere's second tangent row T2 (slip across the slope) takes the world-y component P_y
// likewise: Lambda_T2 = P_y.
#include <array>
#include <string>

#include "integrators/integrator.hpp"

namespace nsb::engines {

// The problems the engines run, each as its scene above; every other problem is declined.
inline constexpr const char* kSceneProblems = "bouncing-mass, sliding-mass, rolling-disk, rocking-block, sphere";
// What `nsbench list` adds to an engine peer's description: its capability marks hold on
// these scenes only.
inline std::string scenes_only() { return std::string(" (runs only its scenes ") + kSceneProblems + "; declines every other problem)"; }

enum class Shape { Sphere, Box, Cylinder };

// The body's pose and velocity in the x-z plane; angle and spin about +y; then, for a
// spatial scene, the position and velocity across (y) and the other spin components (world).
struct Pose {
  double x = 0.0, z = 0.0, angle = 0.0;
  double vx = 0.0, vz = 0.0, wy = 0.0;
  double y = 0.0, vy = 0.0, wx = 0.0, wz = 0.0;
};

struct Scene {
  std::string problem;
  Shape shape = Shape::Sphere;
  double radius = 0.0;       // sphere, cylinder; the box's half side in x and y
  double half_height = 0.0;  // box: half height; cylinder: half length (along y)
  double mass = 0.0;
  double kappa = 0.0;        // inertia about y over m radius^2 (sphere 2/5, cylinder 1/2)
  double gx = 0.0, gz = 0.0; // gravity
  double restitution = 0.0, mu = 0.0;
  bool moves_x = false;      // the problem has an x dof (not the bouncing mass)
  bool rotates = false;      // the problem has a rotation dof (the disk, the block)
  int contacts = 1;          // the problem's contacts (the block: 2, its corners)
  bool spatial = false;      // a free body in 3D (the sphere): every translation and rotation
  Pose start;
};

// The scene of `problem` from `initial`; throws InputError (starting with `who`) when the
// problem is not one of the three, or outside what the shapes can be.
Scene scene_of(const Problem& problem, const State& initial, double size, const std::string& who);
// The problem's state at time t from the engine's body (`out`: the state before the step).
void to_state(const Scene& scene, const Pose& pose, double t, State& out);

// The angle nearest `previous` equal to `wrapped` modulo 2 pi: the disk's unbounded angle from
// an engine that keeps orientations as quaternions (it turns less than pi per step).
double unwrap(double previous, double wrapped);

// The parameter every engine peer shares: the sphere's radius and the box's half side.
ParamSpec size_spec();

// What one engine step reports: the body after it and the step's contact impulses on the
// body per problem contact (normal, summed over the engine's points of that contact;
// world-x and world-y friction components).
struct StepResult {
  static constexpr int kMaxContacts = 2;
  Pose pose;
  std::array<double, kMaxContacts> normal_impulse{}, friction_impulse_x{}, friction_impulse_y{};
  long iterations = 0;

  // Adds an engine contact point at world x `point_x` (the body's centre at `centre_x`) to the
  // problem contact it belongs to (engine_scene.hpp's list).
  void add(const Scene& scene, double point_x, double centre_x, double normal, double friction_x, double friction_y);
};

}  // namespace nsb::engines

namespace nsb {

// The part the three engine peers share: init() builds the scene (declining the rest) and
// hands it to the engine; advance() steps the engine by dt with its own stepper, maps its
// body back to the problem's dofs and fills the impulses. Work: one force evaluation (the
// engine's one evaluation of gravity and contacts) per engine step.
class EnginePeer : public Integrator {
 public:
  void init(const Problem& problem, const State& initial) override;

 protected:
  explicit EnginePeer(const Params& params) : Integrator(params) {}
  // Builds the engine's world for the scene (called by init(); replaces an earlier one).
  virtual void build(const engines::Scene& scene) = 0;
  virtual engines::StepResult engine_step(double dt) = 0;
  const engines::Scene& scene() const { return scene_; }

 private:
  StepInfo advance(double dt) override;
  engines::Scene scene_;
};

}  // namespace nsb
