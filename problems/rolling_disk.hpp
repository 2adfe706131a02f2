#pragma once
// Rolling disk: a rigid disk (mass m, radius R, inertia kappa m R^2) on a rigid floor under
// gravity, Coulomb friction mu and Newton restitution e, launched or dropped with spin
// (docs/method.md section 6).
//
//     m x'' = lambda_T,    m y'' = -m g + lambda_N,    kappa m R^2 theta'' = R lambda_T
//     0 <= y  _|_  lambda_N >= 0,   slip s = x' + R theta'   (the contact point's velocity:
//     theta' e_z x (0, -R) = (R theta', 0)),   |lambda_T| <= mu lambda_N,  lambda_T s <= 0,
//     |lambda_T| < mu lambda_N  =>  s = 0;   impacts: Newton on y', Coulomb on the impulses.
//
// Parameters: R > 0, kappa > 0 (1/2 disk, 2/5 ball, 1 ring), mu >= 0, v0 (x'(0)), omega0
// (theta'(0), counter-clockwise), h0 >= 0 (drop height of the lowest point), e in [0, 1],
// m > 0, g > 0.
//
// Exact solution. Every tangential force or impulse acts along T = [1, 0, R], so
//     J = x' - kappa R theta'     is constant for all t
// (J m R = -(angular momentum about the contact point), which is kappa m R^2 theta' - m R x'
// counter-clockwise) and the state is a function of the slip: x' = (J + kappa s) / (1 + kappa),
// theta' = (s - J) / (R (1 + kappa)). On the floor (lambda_N = m g) the slip falls at
//     |s|' = -mu g (1 + 1/kappa)      until  t* = |s0| / (mu g (1 + 1/kappa)),
// then the disk rolls: v_f = J / (1 + kappa) = (v0 - kappa R omega0) / (1 + kappa),
// omega_f = -v_f / R. The kinetic energy lost, m kappa s0^2 / (2 (1 + kappa)), is the
// friction work mu m g int |s| dt.
// Dropped (h0 > 0): free fall to t1 = sqrt(2 h0 / g), speed V = sqrt(2 g h0); impact k meets
// the floor at V_k = e^(k-1) V (times as the bouncing mass) and gives Lambda_N = m (1 + e) V_k.
// The tangential impulse that stops the slip is -s / W_TT = -m kappa s / (1 + kappa)
// (W_TT = T M^-1 T^T = (1 + 1/kappa) / m); it is taken when within mu Lambda_N (stick),
// else Lambda_T = -sign(s) mu Lambda_N (slip, |s| falls by mu (1 + 1/kappa) Lambda_N / m).
// x' and theta' are constant in flight, so once an impact sticks every later one does, with
// Lambda_T = 0. For e < 1 the impacts accumulate at t_z = t1 + 2 e V / (g (1 - e)) (t1 for
// e = 0); the disk then lies on the floor and slides from the slip left, as above. For e = 1
// it bounces for ever. The march covers the first 1000 impacts (e^1000 V is below round-off
// for e < 0.96); beyond them the horizontal motion keeps the last marched state.
//
// Unknowns U = (x, y, theta), y the height of the lowest point, M = diag(m, m, kappa m R^2);
// one contact: normal row [0, 1, 0], g0 = 0, e; tangent row [1, 0, R], w = 0, friction only
// when mu > 0. Normal and tangent are decoupled (W_NT = 0).
//
// Field output (`--fields`): the disk is a vertex at its centre, in the vertical plane with
// the floor y = 0: reference point (0, R), displacement (x, y). Its rotation, which no point
// component carries, is in body arrays: radius R, angle theta and angular_velocity theta'
// (counter-clockwise, rad and rad/s) and orientation (cos theta, sin theta, 0), the unit
// vector of the body-fixed radius along +x at theta = 0 (exact, whatever the angle: a
// ParaView Glyph arrow along it, scaled by radius, turns with the disk). No rim points: a
// rim point moves nonlinearly with theta, which point_dofs cannot express.
//
// References: G. Capobianco, J. Harsch, S. R. Eugster, R. I. Leine, "A nonsmooth generalized-
// alpha method for mechanical systems with frictional contact", International Journal for
// Numerical Methods in Engineering 122 (2021), the rotating bouncing ball (m = 1, R = 0.1,
// kappa = 2/5, e = 0.5, mu = 0.2, v0 = 1, omega0 = 50, h0 = 0.9).
#include <vector>

#include "problems/rigid_problem.hpp"

namespace nsb {

class RollingDisk final : public RigidProblem, public ExactSolution {
 public:
  // What one impact did; (x, theta, v, omega) is the state just after it.
  struct Impact {
    double t = 0.0;
    double V = 0.0;  // normal approach speed
    double Lambda_N = 0.0;
    double Lambda_T = 0.0;
    double slip_before = 0.0;
    double slip_after = 0.0;
    bool stuck = false;  // the sticking impulse lay within mu Lambda_N: the slip stopped
    double x = 0.0, theta = 0.0, v = 0.0, omega = 0.0;
  };

  explicit RollingDisk(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "rolling-disk"; }
  const Params& parameters() const override { return params_; }
  State initial_state() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  // The marched impacts (a finite t_end past the last of a truncated march is refused).
  std::vector<double> impact_times(double t_end) const override;
  // rest and roll_onset (rest_time(), rolling_onset_time()).
  std::optional<double> event_time(ExactEvent event) const override;
  // first_rebound_speed: impacts()[0].v.
  std::optional<double> value(ExactValue what) const override;
  std::optional<FieldMesh> field_mesh() const override;
  void body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const override;

  // The marched impacts in order (empty for h0 = 0).
  const std::vector<Impact>& impacts() const { return impacts_; }
  // From this time on the disk lies on the floor: 0 (h0 = 0), the Zeno time (e < 1), +inf (e = 1).
  double rest_time() const { return t_rest_; }
  // From this time on the disk rolls on the floor without slipping; +inf if it never does.
  double rolling_onset_time() const { return t_roll_; }
  // x' and theta' for t -> inf (rolling: final_velocity() = -R final_spin()); for e = 1, after
  // the last marched impact.
  double final_velocity() const { return v_final_; }
  double final_spin() const { return omega_final_; }
  // Rate at which |s| falls while sliding on the floor, mu g (1 + 1/kappa).
  double slip_decay_rate() const { return mu_ * g_ * (1.0 + 1.0 / kappa_); }

 private:
  // Horizontal state (x, theta, v, omega) at t on the floor from `start`: sliding, then rolling.
  void floor_motion(const Impact& start, double t, State& s) const;
  double impact_time(int i) const;  // as the bouncing mass: i >= 1, closed form

  Params params_;
  double R_, kappa_, mu_, v0_, omega0_, h0_, e_, m_, g_;
  double t1_, V_;
  std::vector<Impact> impacts_;
  Impact start_;  // the initial horizontal state, as if an impact at t = 0
  Impact rest_;   // the horizontal state when the disk comes to lie on the floor (t = t_rest_)
  double t_rest_, t_roll_, v_final_, omega_final_;
};

}  // namespace nsb
