#pragma once
// Bouncing mass: a point mass on a rigid floor under gravity, Newton restitution e.
//
//     m q'' = -m g + lambda,     g(q) = q >= 0,     0 <= q  _|_  lambda >= 0
//     impact:  q'(+) = -e q'(-)
//
// Parameters: m > 0 (mass), g > 0 (gravity), e in [0, 1] (restitution), h0 >= 0 (initial
// height), v0 (initial velocity, positive upwards).
//
// Exact solution (docs/method.md section 3). First impact t1 solves h0 + v0 t - g t^2/2 = 0:
//     t1 = (v0 + w1) / g,   w1 = sqrt(v0^2 + 2 g h0) = |q'(t1-)|
// Flight i (after impact i >= 1) starts at t_i with speed e^i w1 and lasts 2 e^i w1 / g:
//     t_{i+1} = t_i + 2 e^i w1 / g,    q(t) = e^i w1 s - g s^2/2,  s = t - t_i
// Impacts accumulate (Zeno) at t_inf = t1 + 2 e w1 / (g (1 - e)) for e < 1; the mass then
// rests on the floor. Energy (from the floor) after impact i: E0 e^{2i}, E0 = m w1^2 / 2.
//
// Unknown: U = q (height), so L = [1], g0 = 0.
//
// Field output (`--fields`): the mass is a vertex in the vertical plane, the floor y = 0:
// reference point (0, 0), displacement (0, q), the height as y.
#include "problems/rigid_problem.hpp"

namespace nsb {

class BouncingMass final : public RigidProblem, public ExactSolution {
 public:
  explicit BouncingMass(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "bouncing-mass"; }
  const Params& parameters() const override { return params_; }
  State initial_state() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  // Before the Zeno time; at most kMaxFlights (a finite t_end past the last is refused).
  std::vector<double> impact_times(double t_end) const override;
  std::vector<double> energies_after_impacts(double t_end) const override;  // E0 e^{2i}, of those impacts
  std::optional<FieldMesh> field_mesh() const override;
  // t_zeno_exact: the accumulation time of the impacts (zeno_time(), +inf for e = 1).
  std::vector<std::pair<std::string, double>> summary_values() const override;

  // Exact impact sequence.
  double initial_energy() const { return 0.5 * m_ * w1_ * w1_; }
  double first_impact_speed() const { return w1_; }
  double restitution() const { return e_; }
  // Time of impact i >= 1 (t_1 is the first); equals zeno_time() in the limit.
  double impact_time(int i) const;
  // Accumulation time of the impacts; +inf for e = 1.
  double zeno_time() const;
  double energy_after_impact(int i) const;

 private:
  // The exact height and velocity at t (state(t) without its State).
  void exact_qv(double t, double& q, double& v) const;

  static constexpr int kMaxFlights = 100000;
  Params params_;
  double m_, g_, e_, h0_, v0_;
  double t1_, w1_;
  std::vector<double> impacts_;  // e < 1: t_1, t_2, ... while they increase (at most kMaxFlights)
};

}  // namespace nsb
