#pragma once
// Sliding mass: a point mass on a rigid plane inclined at angle alpha, Coulomb friction mu,
// launched along the slope at speed v0 (docs/method.md section 6).
//
//     m x'' = m g sin(alpha) + lambda_T,        x along the slope, positive down it
//     m y'' = -m g cos(alpha) + lambda_N,       y normal to the plane, height above it
//     0 <= y  _|_  lambda_N >= 0,   |lambda_T| <= mu lambda_N,   lambda_T x' <= 0, and
//     |lambda_T| < mu lambda_N  =>  x' = 0
//
// Parameters: alpha in [0, 90) degrees, mu >= 0, v0 (positive down the slope), m > 0, g > 0.
//
// The mass starts on the plane (y = 0, y' = 0) and stays on it: lambda_N = m g cos(alpha).
// While it slides, friction is mu m g cos(alpha) against the motion, so with
//     a_down = g (sin alpha - mu cos alpha)    (moving down, x' > 0)
//     a_up   = g (sin alpha + mu cos alpha)    (moving up,   x' < 0)
// the motion from v0 is x = v0 t + a1 t^2 / 2, a1 = a_down (v0 > 0) or a_up (v0 < 0), up to
// the stop time t_s = -v0 / a1 when the speed decreases (a1 v0 < 0), reached after the
// distance d = v0^2 / (2 |a1|); it never stops otherwise. At rest (t_s, or t = 0 for v0 = 0)
// it sticks when tan(alpha) <= mu (static friction can hold m g sin alpha), else it slides
// down from rest: x = x(t_s) + a_down (t - t_s)^2 / 2.
// At mu = tan(alpha) (a_down = 0) a mass moving down keeps v0 for ever and one at rest stays;
// mu is taken equal to tan(alpha) when they differ by a few rounding errors of tan.
// Energy: d/dt (m x'^2 / 2 - m g sin(alpha) x) = lambda_T x' = -mu m g cos(alpha) |x'|, so the
// mechanical energy falls by mu m g cos(alpha) times the path length; sticking does no work.
//
// Unknowns U = (x, y), M = diag(m, m); one contact: normal row [0, 1], g0 = 0, e = 0,
// tangent row [1, 0] (slip u_T = x'), w = 0, friction only when mu > 0.
//
// Field output (`--fields`): the mass is a vertex in the frame of the plane (x down the
// slope, y its normal, the plane y = 0; not rotated by alpha): reference point (0, 0),
// displacement (x, y).
//
// Reference for the contact law: J. J. Moreau, "Unilateral contact and dry friction in finite
// freedom analysis", Nonsmooth Mechanics and Applications, CISM 302, Springer, 1988.
#include "problems/rigid_problem.hpp"

namespace nsb {

class SlidingMass final : public RigidProblem, public ExactSolution {
 public:
  // The exact solution's impact times, not 0.1.0's Problem::impact_times (kept for plugins).
  using ExactSolution::impact_times;
  explicit SlidingMass(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "sliding-mass"; }
  const Params& parameters() const override { return params_; }
  State initial_state() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  // slip_stop (stop_time()); stop_distance and stays_stopped (sticks()).
  std::optional<double> event_time(ExactEvent event) const override;
  std::optional<double> value(ExactValue what) const override;
  std::optional<FieldMesh> field_mesh() const override;

  // Acceleration along the slope while sliding down (a_down above); 0 at mu = tan(alpha).
  double sliding_acceleration() const { return a_down_; }
  // Time at which the speed first vanishes (0 for v0 = 0); +inf when it never does.
  double stop_time() const { return t_stop_; }
  // Path length travelled up to stop_time() (+inf when it never stops).
  double stop_distance() const { return d_stop_; }
  // Whether the mass stays at rest once stopped (tan(alpha) <= mu).
  bool sticks() const { return sticks_; }

 private:
  Params params_;
  double alpha_, mu_, v0_, m_, g_;
  double a_down_, a_first_;  // a_first_: acceleration until the stop (a_down or a_up)
  double t_stop_, d_stop_, x_stop_;
  bool sticks_;
};

}  // namespace nsb
