#pragma once
// Signorini bar: a 1D linear elastic bar hitting a rigid wall (docs/method.md section 3).
//
//     rho A u_tt - E A u_xx = -rho A g   on (0, L),      E A u_x(L, t) = 0     (free end)
//     g(t) = g0 + u(0, t) >= 0,   lambda >= 0,   g lambda = 0,   E A u_x(0, t) = -lambda
//     u(x, 0) = 0,   u_t(x, 0) = -v0                 (rigid motion towards the wall)
//
// The wall is at x = -g0. Parameters: L, E, rho, A, v0 >= 0, g0 >= 0, g >= 0 (gravity towards
// the wall, default 0), N (linear elements), mass = lumped | consistent | singular,
// stiff_ratio r > 0, e (Newton restitution of the contact node, default 0; see below).
// c = sqrt(E / rho), T = 2 L / c, t0 = g0 / v0 (v0 = 0: never, or
// at once when g0 = 0 too).
// Stiff/soft bar (hard cases): the elements of the half at the wall (centre x < L/2) have
// Young's modulus r E. The stable step is then set by the stiffer half and the slow
// dynamics by the softer one, a contrast of max(r, 1/r) in M^{-1} K. For r != 1 waves
// reflect at x = L/2 and the d'Alembert solution below no longer holds: the exact state()
// gives nothing and the exact observables are NaN (exact_* describe the bar with r = 1).
//
// Exact solution: with g > 0 it is BouncingBarExact (problems/bouncing_bar.hpp), which
// the exact state() and the *_exact observables use (the exact_* functions below describe g = 0
// only). For g = 0 (d'Alembert), s = t - t0 (contact starts at t0 and lasts exactly T):
//     s <= x/c                 u = -v0 t                          v = -v0   sigma = 0
//     x/c < s < (2L - x)/c     u = -g0 - v0 x / c                 v = 0     sigma = -rho c v0
//     (2L - x)/c <= s <= T     u = -g0 - v0 x / c + v0 (s - (2L - x)/c)  v = +v0  sigma = 0
//     s >= T                   u = -g0 + v0 (s - T)               v = +v0   sigma = 0
// u is continuous across both fronts x = c s and x = 2L - c s; v and sigma jump there.
// Contact force A rho c v0 for 0 < s < T, else 0. Energy rho A L v0^2 / 2 at all times;
// momentum -rho A L v0 + A rho c v0 clamp(s, 0, T); the bar leaves the wall with +v0.
//
// Discretisation: nodes x_i = i h, h = L / N, i = 0..N; dof i is u(x_i); contact on node 0:
// L = [1 0 ... 0], gap offset g0, restitution e = 0 by default (a continuum contact has no
// impact law; the lumped model's node impacts are then inelastic and the study shows what that
// costs; e = 1 makes them elastic, the claims study's energy-at-impact test).
//     K: element (E A / h) [1 -1; -1 1];  strain energy U^T K U / 2.
//     lumped      M = rho A h diag(1/2, 1, ..., 1, 1/2)
//     consistent  element (rho A h / 6) [2 1; 1 2]
//     singular    M = rho A h diag(0, 3/2, 1, ..., 1, 1/2)
// Stable step 2/omega_max: the free-free lumped chain has omega_max = 2c/h exactly, so h/c;
// singular: Gershgorin on M^{-1} K over the massive dofs (node 0 condensed, free or on the
// wall) gives at most 4 c^2 / h^2 too, so h/c; consistent: omega_max = 2 sqrt(3) c / h, so
// h / (sqrt(3) c). With r != 1, c is the stiffer half's c sqrt(max(r, 1)): Gershgorin
// (lumped, singular) and the element bound (consistent) hold with it, as a bound.
//
// Singular mass (Khenous, Laborde, Renard, Eur. J. Mech. A/Solids 27, 2008; Di Stasio et
// al. 2021). The contact node gets no mass; its lumped mass rho A h / 2 goes to node 1.
// Kept: the total mass, hence the momentum and kinetic energy of rigid motions and the
// rebound velocity. Not kept: the centre of mass moves inward by h^2 / (2L) (O(h^2)), and
// so does the second moment. With linear elements and non-negative masses nothing better
// exists locally: keeping the centre of mass too needs node 1 += rho A h, node 2 -= rho A h/2
// (node 2 at half mass halves its stable-step margin: h / (sqrt(2) c)); keeping the second
// moment as well needs a negative mass. We keep the stable step h / c.
// Massless contact node: with m_0 = 0 the node's equation is static,
//     0 = F_ext,0 - F_int,0(U) + lambda,   F_int,0 = (E A / h)(u_0 - u_1),
//     0 <= g0 + u_0  _|_  lambda >= 0,
// whose solution given u_1 is u_0 = max(-g0, u_1) and lambda = (E A / h)(u_0 - u_1) >= 0:
// the node sits on the wall while its element pushes and follows the element otherwise,
// and the contact force is the node's internal force. Condensing u_0 out leaves the massive
// dofs with a unilateral spring E A / h from node 1 to the wall: a Lipschitz force, so the
// semi-discrete problem is an ODE (well posed, energy conserving, no impacts, hence neither
// the impact energy loss nor the contact-force chatter of the lumped model). Integrators
// see only a zero diagonal mass entry and treat the dof quasi-statically (cd_lagrange.hpp).
//
// Repeated bouncing: gravity g towards the wall (the energy study's long runs need many
// contact/flight cycles; with g = 0 the bar leaves for ever after one contact). Gravity acts
// on the model's masses m_i = (M 1)_i:
//     F_ext = -g M 1,        V_load(U) = g (M 1)^T U,        F_ext = -grad V_load.
// For the lumped and consistent models M 1 is the consistent load of the body force -rho A g
// (V_load = integral of rho A g u dx, exact for linear elements); for the singular model the
// contact node's share moves to node 1 with its mass, so the total weight rho A L g is kept
// and the massless node carries no load: its static equation above is unchanged. Why not a
// bar between two walls: that needs a second contact row and, for the singular model, a
// second massless node (both ends), so a new mass model, stable-step argument and
// observables; gravity changes only F_ext and V_load. What it costs: no exact solution for
// g > 0, and linear momentum is no longer balanced by the impulses alone (the weight adds
// -rho A L g t, which staggered schemes sample at their own half steps).
// Cycle: the bar leaves the wall at about +v0 and flies about 2 v0 / g; the continuum
// problem conserves kinetic + strain + V_load (Lebeau and Schatzman, J. Differential
// Equations 53, 1984: the 1D wave equation with a unilateral boundary constraint conserves
// energy). g L / (c v0) compares the static stress rho g L with the impact stress rho c v0:
// keep it below 1 for contacts close to the d'Alembert one (the energy study uses 1/4).
#include <memory>
#include <mutex>
#include <vector>

#include "problems/bar_elements.hpp"
#include "problems/linear_problem.hpp"

namespace nsb {

class BouncingBarExact;

class SignoriniBar final : public LinearProblem, public ExactSolution {
 public:
  // The exact solution's impact times, not 0.1.0's Problem::impact_times (kept for plugins).
  using ExactSolution::impact_times;
  using MassModel = BarMassModel;

  explicit SignoriniBar(const Params& params, std::string name = "signorini-bar");
  // Nondimensional defaults: L = E = rho = A = v0 = 1, g0 = 0, g = 0, N = 100, lumped.
  static ParamSpecs parameters_spec();
  // Steel defaults: L = 1 m, E = 210 GPa, rho = 7800 kg/m^3, A = 3.14e-4 m^2, v0 = 0.1 m/s,
  // g0 = 5e-5 m (registry line signorini-bar-steel).
  static ParamSpecs steel_parameters_spec();
  static std::unique_ptr<Problem> make_steel(const Params& params);
  // Doyen-Ern-Piperno defaults (problems/bouncing_bar.hpp): L = 10, E = 900, rho = A = 1,
  // v0 = 0, g0 = 5, g = 10, N = 100 (registry line bouncing-bar).
  static ParamSpecs bouncing_parameters_spec();
  static std::unique_ptr<Problem> make_bouncing(const Params& params);

  std::string name() const override { return name_; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return n_ + 1; }
  // K u element by element, the nodes split over threads.
  void internal_force(ConstVecRef u, VecRef f) const override;
  void external_force(double, VecRef f) const override { f = -gravity_ * mass_rows_; }
  double strain_energy(ConstVecRef u) const override;
  double load_potential(ConstVecRef u) const override { return gravity_ * mass_rows_.dot(u); }
  // The kinetic energy at the first impact, rho A L (v0^2 + 2 g g0) / 2 (E0 = 0 when v0 = 0:
  // the dropped bar's energy errors are relative to what the drop gives it).
  double energy_scale() const override { return 0.5 * total_mass() * (v0_ * v0_ + 2.0 * gravity_ * gap0_); }
  std::string energy_scale_text() const override { return "kinetic energy at the first impact, rho A L (v0^2 + 2 g g0) / 2"; }
  State initial_state() const override;
  double stable_step() const override;
  // u_contact, v_contact, contact_force (impulse / dt of the step), their exact values,
  // momentum (sum of M's row sums times v) and its exact value.
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  // contact_start (contact_start(); with g > 0 the first impact t1 of BouncingBarExact), contact_duration
  // (contact_duration()) and wave_time (L / c; the period of DEP's bar is 16 of them); t1 and
  // wave_time only for the uniform bar (stiff_ratio 1), whose exact solution they belong to.
  std::optional<double> event_time(ExactEvent event) const override;
  std::optional<double> value(ExactValue what) const override;
  // exact_stress at each element's centre (x_i + x_{i+1}) / 2, component sigma; g = 0 and r = 1 only.
  bool exact_cell_stress(double t, Eigen::Ref<Eigen::MatrixXd> out) const override;
  // The contact end's u and v (and their *_exact twins) and the exact contact force.
  std::optional<double> observable(std::string_view name, double t) const override;
  // Field output: the bar's nodes x_i = i h (dof i) and elements; one stress component,
  // sigma = E_e (u_{i+1} - u_i) / h on element i (nodes i, i + 1), constant over it (so the
  // exact piecewise-constant sigma of a wave front is met element by element). The same for
  // all three mass models (the mass model changes no node or element).
  std::optional<FieldMesh> field_mesh() const override;
  void cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const override;

  // Exact field at any (x, t), x in [0, L].
  double exact_displacement(double x, double t) const;
  double exact_velocity(double x, double t) const;
  double exact_stress(double x, double t) const;
  double exact_contact_force(double t) const;
  double exact_momentum(double t) const;
  // The columns of observe() at t from the contact end's u_contact, v_contact and the momentum
  // (contact_force 0: no step); the exact ones NaN where there is no exact solution
  // (stiff_ratio != 1, t < 0, or !with_exact), from BouncingBarExact with g > 0, else from the
  // exact_* functions above. bar-3d writes its observables through it.
  void write_observables(double t, double u_contact, double v_contact, double momentum, bool with_exact,
                         std::span<double> out) const;

  MassModel mass_model() const { return model_; }
  double wave_speed() const { return c_; }
  double contact_start() const { return t0_; }      // g0 / v0
  double contact_duration() const { return 2.0 * len_ / c_; }
  double contact_force_level() const { return area_ * rho_ * c_ * v0_; }
  double total_mass() const { return rho_ * area_ * len_; }
  double exact_energy() const { return 0.5 * total_mass() * v0_ * v0_; }
  double rebound_velocity() const { return v0_; }
  double gravity() const { return gravity_; }
  double element_size() const { return len_ / static_cast<double>(n_); }
  // Linear momentum sum_i (row sum of M)_i v_i (exact for every mass model: 1^T M v).
  double momentum(ConstVecRef v) const { return mass_rows_.dot(v); }

 private:
  std::string name_;
  Params params_;
  double len_, young_, rho_, area_, v0_, gap0_, gravity_;
  Index n_;
  MassModel model_;
  double stiff_ratio_;
  double c_, t0_;  // wave speed (of E), contact start
  std::vector<double> ke_;  // element stiffnesses E_e A / h
  Vec mass_rows_;
  // g > 0: the exact solution, marched on demand up to the latest time asked (observe and
  // state() are const and may be called from several threads).
  const BouncingBarExact& bouncing_exact(double t) const;
  void check_representable() const;  // InputError when derived quantities overflow
  mutable std::mutex bouncing_mutex_;
  mutable std::shared_ptr<const BouncingBarExact> bouncing_;
};

}  // namespace nsb
