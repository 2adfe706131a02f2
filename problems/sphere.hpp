#pragma once
// Sphere: a rigid sphere (radius R, mass m, inertia I = (2/5) m R^2) on a plane inclined at
// alpha, Coulomb friction mu (the 3D cone), Newton restitution e, launched with a spin not
// aligned with the slope so that the slip turns (issue 33; docs/three_d.md).
//
// Axes: x down the slope, y across it, z the plane's normal; gravity m g (sin alpha, 0,
// -cos alpha). Unknowns U = (x, y, z, theta_x, theta_y, theta_z): the centre's displacement
// along the plane (x, y), the gap of its lowest point z (the centre is at (x, y, z + R)), and
// the integrals of the angular velocity, theta' = omega (world axes). The contact point is
// always straight below the centre, so the kinematics are constant (linear):
//     M = diag(m, m, m, I, I, I)       (no gyroscopic term: a sphere's inertia is isotropic)
//     normal row  L  = e_z                        g = z,  g0 = 0
//     tangent rows T  = (1, 0, 0, 0, -R, 0)       slip w_x = v_x - R omega_y
//                  T2 = (0, 1, 0, R, 0, 0)        slip w_y = v_y + R omega_x
//     F = m g (sin alpha, 0, -cos alpha, 0, 0, 0),   F_int = 0
// (w = v + omega x (0, 0, -R)); the contact's Delassus block is diag(1/m, 7/(2m), 7/(2m)).
// Friction (T, T2, mu) only when mu > 0, so mu = 0 is described exactly like a frictionless
// problem. The orientation is not a function of U (it depends on the path of omega): the
// rotation dofs integrate omega component-wise, and the orientation appears in no equation.
//
// Exact solution (SphereInclineExact, problems/sphere_incline_exact.hpp, derived and tested
// there) for a sphere released on the plane (h0 = 0): the sliding phase in closed form, rolling
// from t_roll on iff mu > (2/7) tan(alpha) (or launched straight up the slope with mu >= (2/7)
// tan alpha), else sliding for ever. Dropped (h0 > 0: the rotating bouncing ball in 3D) there
// is no exact solution here: the exact state() is empty and the *_exact observables NaN.
//
// Observables: slip_speed |w| = |(T U', T2 U')|, slip_speed_exact; summary figure t_roll_exact
// (the exact roll-onset time; +inf when it slides for ever, written as null; NaN for h0 > 0).
//
// Field output: a vertex at the centre (3D), displacement (x, y, z); body arrays radius,
// angular_velocity (omega, 3) and rotation_integral (theta = int omega, 3). The orientation is
// not a function of the state (see above): the rotation dofs are declared
// (FieldMesh::body_rotation_dofs) and the field writer follows it step by step
// (orientation_x, orientation_z: the body's axes, run/field_output.hpp).
//
// Bad input (one line naming the parameter and its range, exit 2): alpha outside [0, 90)
// degrees, mu < 0, h0 < 0 (the sphere would start in penetration), R, m, g not > 0, e outside
// [0, 1].
#include "problems/rigid_problem.hpp"
#include "problems/sphere_incline_exact.hpp"

namespace nsb {

class Sphere final : public RigidProblem, public ExactSolution {
 public:
  // The exact solution's impact times, not 0.1.0's Problem::impact_times (kept for plugins).
  using ExactSolution::impact_times;
  explicit Sphere(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "sphere"; }
  const Params& parameters() const override { return params_; }
  State initial_state() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  // roll_onset: roll_time(), where it is known (released on the incline).
  std::optional<double> event_time(ExactEvent event) const override;
  std::vector<std::pair<std::string, double>> summary_values() const override;
  std::optional<FieldMesh> field_mesh() const override;
  void body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const override;

  // The exact roll-onset time: +inf if it slides for ever, NaN when dropped (h0 > 0).
  double roll_time() const;
  const SphereInclineExact& closed_form() const { return exact_; }

 private:
  Params params_;
  SphereInclineSpec spec_;
  double h0_;
  SphereInclineExact exact_;
};

}  // namespace nsb
