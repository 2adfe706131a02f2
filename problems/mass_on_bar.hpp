#pragma once
// Mass on a bar: a rigid mass strikes the free end of an elastic bar clamped at its far end
// (Saint-Venant's problem; Timoshenko and Goodier, Theory of Elasticity, sec. 153
// "Longitudinal impact of bars"). One contact row with entries on two bodies.
//
//     rho A u_tt - E A u_xx = 0   on (0, L),   u(L, t) = 0 (clamped),   E A u_x(0, t) = -F
//     M X'' = -F,    g = u(0, t) - X >= 0,   F >= 0,   g F = 0
//     u = 0, u_t = 0 (bar at rest);  X(0) = 0, X'(0) = v0 (the mass touches the free end x = 0
//     at t = 0, moving towards the clamp, +x)
//
// Parameters: M (default 1 = the bar's mass; within [0.01, 100] rho A L), v0 > 0, L, E, rho, A (defaults 1: c = 1), N
// (linear elements, >= 2), mass = lumped | consistent | singular.
//
// Exact solution (derived here; it is the classical one). Z = A rho c, theta = M / Z,
// T = 2L/c (the round trip of a wave), alpha = rho A L / M (bar mass over M), T/theta = 2 alpha.
// At x = 0 the wave leaving into the bar has velocity amplitude a(t), the wave arriving from
// the clamp b(t) = -a(t - T) (the clamp reflects with -1; b = 0 for t < T). In contact the
// mass moves with the end, V = a + b, and F = Z (a - b) = Z (V - 2 b), so
//     M V' + Z V = 2 Z b(t).
// In the n-th interval n T <= t < (n+1) T, with tau = (t - n T)/theta:
//     V = v0 e^{-tau} P_n(tau),   a = v0 e^{-tau} Q_n(tau),   F = Z v0 e^{-tau} (P_n + 2 Q_{n-1}),
//     P_0 = 1, Q_{-1} = 0,   P_n(tau) = e^{-2 alpha} P_{n-1}(2 alpha) - 2 int_0^tau Q_{n-1},
//     Q_n = P_n + Q_{n-1}
// (polynomials of degree n). First interval: F = Z v0 exp(-Z t / M) (Saint-Venant). At each
// t = n T in the first contact, a jumps by v0 (the front of the first wave, reflected), so
// F jumps by +2 Z v0 and V is continuous. The contact ends at the first zero of F (never at
// a jump, which is upward there); the mass then moves at a constant V(t_s). In the second
// interval F = 0 at tau = 1 + e^{-2 alpha}/2, within the interval when 2 alpha exceeds it:
// alpha > 0.5786, i.e. M < 1.728 rho A L (the classical threshold: first contact over before
// 4L/c).
// Later contacts (derived here): the front keeps running in the lossless bar, so after the
// separation the free end (a = b, end velocity 2 b) is thrown back towards the mass when
// the front returns, and the end strikes the mass again (a fine-mesh run shows it for every
// M tried). The exact solution therefore sweeps time in pieces: on each piece the incoming
// b is a shifted copy of an earlier a, b = v0 e^{-sigma} B(sigma), sigma = (t - t_piece)/theta;
// in contact V = v0 e^{-sigma} P with P = V(t_piece)/v0 + 2 int_0^sigma B, a = V - b,
// F = Z v0 e^{-sigma} (P - 2 B), up to F = 0; free, a = b, V constant and the gap
// u(0, t) - X(t) = int (2 b - V) dt (closed form: int e^{-s} p = -e^{-s} (p + p' + p'' ...)),
// up to its next zero, where contact resumes (F = Z (V - 2 b) >= 0 there: no impulse, the end
// is massless). The sweep stops when the mass, moving away (V < 0), is past
// -sqrt(2 L E0 / (E A)), the largest |u(0, t)| a strain energy <= E0 = M v0^2 / 2 allows: no
// contact after that. contact_end() is that last separation; impact_times() are the starts
// of the contacts. Default M = the bar's mass (alpha = 1: the first contact ends during the
// second interval); the tests also take M = 4 rho A L (alpha = 1/4, several reflections) and
// M = rho A L / 4 (alpha = 4).
// Momentum: M v0 = M V(t) + int_0^t F; energy M v0^2 / 2 = kinetic + strain at all times.
// No exact field in the bar is provided (the exact state(): none); the observables carry F and V.
//
// Discretisation (problems/bar_elements.hpp): nodes x_i = i h, h = L/N; dofs 0..N-1 are the
// bar's nodes 0..N-1 (node N is clamped and removed), dof N is X. Contact row: +1 on dof 0,
// -1 on dof N, gap offset 0, e = 0. Singular mass: node 0 massless, its mass moved to node 1.
// Stable step h/c (lumped, singular), h/(sqrt(3) c) (consistent): the bar's bounds of
// signorini_bar.hpp (the clamp only lowers omega_max; the mass dof has no stiffness).
#include <memory>
#include <vector>

#include "problems/bar_elements.hpp"
#include "problems/linear_problem.hpp"

namespace nsb {

class MassOnBar final : public LinearProblem, public ExactSolution {
 public:
  explicit MassOnBar(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "mass-on-bar"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return n_ + 1; }
  void external_force(double, VecRef f) const override { f.setZero(); }
  double strain_energy(ConstVecRef u) const override;
  double load_potential(ConstVecRef) const override { return 0.0; }
  State initial_state() const override;
  double stable_step() const override;
  // contact_force (impulse / dt), v_mass and their exact values.
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double) const override { return std::nullopt; }  // no exact field
  std::vector<double> impact_times(double t_end) const override;
  // Field output: the bar (body 0), nodes x_i = i h on dof i, the clamped node N on none (its
  // displacement is 0); sigma = E (u_{i+1} - u_i) / h on each element, constant over it. The
  // rigid striker (body 1, dof N, a point with no extent) is a vertex at x = 0, where it
  // touches the free end in the reference; it has no stress. The contact impulse shows on
  // node 0 (+) and on the striker (-).
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  // Exact contact force and mass velocity (header; after the last separation F = 0 and V
  // is constant).
  double exact_contact_force(double t) const;
  double exact_mass_velocity(double t) const;
  double first_separation() const { return first_separation_; }
  double contact_end() const { return segments_.back().t0; }  // the last separation
  double round_trip() const { return 2.0 * len_ / c_; }  // T
  double impedance() const { return area_ * rho_ * c_; }  // Z
  double striker_mass() const { return mass_; }
  double bar_mass() const { return rho_ * area_ * len_; }
  double exact_energy() const { return 0.5 * mass_ * v0_ * v0_; }
  Index mass_dof() const { return n_; }

 private:
  // A piece of the exact solution from t0: in contact V = v0 e^{-sigma} velocity(sigma) and
  // F = Z v0 e^{-sigma} force(sigma), sigma = (t - t0)/theta; free, F = 0 and V = v_free.
  struct Segment {
    double t0;
    bool contact;
    std::vector<double> velocity, force;
    double v_free;
  };
  void sweep_exact();
  const Segment& segment_at(double t) const;

  Params params_;
  double mass_, v0_, len_, young_, rho_, area_;
  Index n_;
  BarMassModel model_;
  double c_, theta_;
  std::vector<double> ke_;
  std::vector<Segment> segments_;  // from t = 0 on; the last one free, for ever
  double first_separation_ = 0.0;
};

}  // namespace nsb
