#pragma once
// Two bars: an elastic bar strikes another of the same material at rest (one contact row
// with entries on both bodies).
//
//     rho A u_tt - E A u_xx = 0   on bar 1 (0, L1) and bar 2 (L1 + g0, L1 + g0 + L2)
//     free ends, except the contact force F >= 0 pressing bar 1's right end and bar 2's left
//     g(t) = g0 + u_2(L1 + g0, t) - u_1(L1, t) >= 0,   F >= 0,   g F = 0
//     u = 0;  u_t = +v0 on bar 1, 0 on bar 2 at t = 0
//
// Parameters: L1, L2 >= L1, E, rho, A (defaults 1: c = sqrt(E / rho) = 1), v0 > 0, g0 >= 0,
// N1, N2 (linear elements), mass = lumped | consistent | singular.
//
// Exact solution (d'Alembert; Graff, Wave Motion in Elastic Solids, longitudinal waves in thin
// rods: the collinear impact of two rods). Equal impedances Z = A rho c: the contact closes at t_c = g0/v0,
// the interface moves at v0/2 and the force is F0 = Z v0 / 2 while a compressive pulse runs
// into both bars. Bar 1's pulse reflects at its free end as an unloading wave that reaches
// the interface at t_c + 2 L1/c: bar 1 is then at rest, unstressed, and F drops to 0. Bar 2
// carries all the momentum as a pulse of length 2 L1 (velocity v0/2, stress -rho c v0/2).
// Each bar is thus a free bar loaded at one end by F0 for 0 < s < 2 L1/c, s = t - t_c. In
// the coordinate xi from the loaded end (bar 1: xi = L1 - x; bar 2: xi = x - L1 - g0), with
// velocity w along +xi, the wave emitted at the loaded end has the amplitude
//     a(s) = F(s)/Z + a(s - P),   P = 2 L / c   (the free far end reflects b = a; a = 0 for s <= 0)
// so a(s) = v0/2 when s > 0 and (s mod P) < 2 L1/c (bar 1: P = 2 L1/c, always; bar 2: the
// pulse), and
//     w(xi, s) = a(s - xi/c) + a(s - (2L - xi)/c),   W(xi, s) = I(s - xi/c) + I(s - (2L - xi)/c),
//     I(s) = (v0/2) (k 2L1/c + min(s - k P, 2L1/c)),  k = floor(s / P)  (I = 0 for s <= 0),
//     sigma = -rho c (a(s - xi/c) - a(s - (2L - xi)/c)).
//     bar 1:  u = v0 t - W,  v = v0 - w;        bar 2:  u = W,  v = w.
// This holds for all t: after the contact bar 1 rests at u = g0 + v0 L1/c, bar 2's left end
// moves at w = 2 a >= 0 so g never decreases (it stays 0, with F = 0, until bar 2's pulse
// comes back to its left end at t_c + 2 L2/c, then opens); complementarity holds throughout.
// L2 >= L1 is needed: a shorter bar 2 would send its reflected (tensile) pulse back into the
// contact before 2 L1/c and the force would no longer be a single step.
// Mean velocities: bar 1 v0 (1 - clamp(s, 0, 2L1/c) c / (2 L1)), bar 2 F0 clamp(s, 0, 2L1/c)
// / (rho A L2); momentum rho A L1 v0 and energy rho A L1 v0^2 / 2 at all times.
//
// Discretisation (problems/bar_elements.hpp, signorini_bar.hpp): bar 1's nodes x = i h1
// (h1 = L1/N1) are dofs 0..N1; bar 2's nodes x = L1 + g0 + j h2 (h2 = L2/N2) are dofs
// N1+1..N1+1+N2. One contact row: +1 on dof N1+1, -1 on dof N1, gap offset g0, e = 0.
// Singular mass: both contact nodes massless (bar 1's right end, bar 2's left end), their
// masses moved to their neighbours. Stable step: min(h1, h2)/c (lumped, singular: the
// argument of signorini_bar.hpp, with the condensed contact a spring E A / (2h) between the
// massive neighbours, below the Gershgorin bound), min(h1, h2)/(sqrt(3) c) (consistent).
// A lumped model's contact nodes (mass rho A h / 2 each) meet plastically (e = 0): the
// impact loses their relative kinetic energy, (rho A h / 8) v0^2 for h1 = h2 = h.
#include <memory>
#include <vector>

#include "problems/bar_elements.hpp"
#include "problems/linear_problem.hpp"

namespace nsb {

class TwoBars final : public LinearProblem, public ExactSolution {
 public:
  // Defaults: L1 = 1, L2 = 2, N1 = 50, N2 = 100 (h1 = h2), E = rho = A = v0 = 1, g0 = 0, lumped.
  explicit TwoBars(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "two-bars"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return n1_ + n2_ + 2; }
  void external_force(double, VecRef f) const override { f.setZero(); }
  double strain_energy(ConstVecRef u) const override;
  double load_potential(ConstVecRef) const override { return 0.0; }
  State initial_state() const override;
  double stable_step() const override;
  // v1_mean, v2_mean, contact_force (impulse / dt), their exact values, momentum (1^T M v)
  // and its exact value, gap.
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  std::vector<double> impact_times(double t_end) const override;
  // Field output: bar 1 (body 0) then bar 2 (body 1) at their reference positions, node i
  // of a bar on dof(bar, i); sigma = E (u_{i+1} - u_i) / h on each element, constant over it.
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  // Exact fields; bar = 1 or 2, x in the bar's reference position.
  double exact_displacement(int bar, double x, double t) const;
  double exact_velocity(int bar, double x, double t) const;
  double exact_stress(int bar, double x, double t) const;
  double exact_contact_force(double t) const;
  double exact_mean_velocity(int bar, double t) const;

  double wave_speed() const { return c_; }
  double contact_start() const { return tc_; }  // g0 / v0
  double contact_end() const { return tc_ + 2.0 * len1_ / c_; }
  double contact_force_level() const { return 0.5 * area_ * rho_ * c_ * v0_; }
  double bar_mass(int bar) const { return rho_ * area_ * (bar == 1 ? len1_ : len2_); }
  double exact_momentum() const { return bar_mass(1) * v0_; }
  double exact_energy() const { return 0.5 * bar_mass(1) * v0_ * v0_; }
  double element_size(int bar) const { return bar == 1 ? len1_ / static_cast<double>(n1_) : len2_ / static_cast<double>(n2_); }
  // Dof of node i of the bar (i = 0 .. N_bar).
  Index dof(int bar, Index i) const { return bar == 1 ? i : n1_ + 1 + i; }
  // A bar's momentum (its rows of M times v) over its mass.
  double mean_velocity(int bar, ConstVecRef v) const;
  double momentum(ConstVecRef v) const { return mass_rows_.dot(v); }

 private:
  // The loaded-end wave's displacement integral I(s) and amplitude a(s) of a bar of length len
  // (header).
  double pulse_integral(double len, double s) const;
  double pulse_amplitude(double len, double s) const;
  // xi from the loaded end; velocity and displacement along +xi.
  double local_velocity(double len, double xi, double s) const;
  double local_displacement(double len, double xi, double s) const;

  Params params_;
  double len1_, len2_, young_, rho_, area_, v0_, gap0_;
  Index n1_, n2_;
  BarMassModel model_;
  double c_, tc_;
  std::vector<double> ke1_, ke2_;
  Vec mass_rows_;
};

}  // namespace nsb
