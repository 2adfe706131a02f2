#pragma once
// Painlevé rod: a rod of length 2 s, mass m, inertia J = m s^2 / 3 about its centre, sliding
// with its end A on a rough floor (Coulomb mu) under gravity g (Génot and Brogliato 1999; the
// cardillo example's data are the defaults: m 1, s 1, g 10, mu 5/3, phi0 31 degrees, v0 30).
// One contact whose gap and rows turn with the rod (moving contacts, docs/contacts.md;
// derivations in docs/rigid_bodies.md section 2).
//
// Unknowns U = (x, y, phi): the centre and the rod's angle to the floor; M = diag(m, m, J),
// load (0, -m g, 0). End A = (x + s cos phi, y - s sin phi), ahead of the centre:
//     g(U) = y - s sin phi,   L(U) = (0, 1, -s cos phi),   T(U) = (1, 0, -s sin phi)
// (T = dX_A/dU: A's horizontal velocity is T U'), Newton restitution 0, Coulomb mu (tangent
// row only when mu > 0). contacts() holds the rows at U0 and g0 = g(U0) - L(U0) U0.
//
// Parameters: s > 0, m > 0, phi0 in (0, 90) degrees, v0 = x'(0) != 0, mu >= 0, g > 0; the rod
// starts on the floor (y0 = s sin phi0, A's gap 0) with y'0 = phi'0 = 0.
//
// Exact solution (problems/painleve_rod_exact.hpp): the sliding phase with A held on the floor,
//     lambda = m (g - s phi'^2 sin phi) / D(phi),
//     D(phi) = 1 + (m s^2 / J) cos phi (cos phi - mu sigma sin phi),   sigma = sign(x'_A),
// integrated to round-off up to its end: for the defaults the dynamic jam (D -> 0 with the
// normal force growing without bound, an impact without collision) at t* = 0.8145 s; lift-off,
// the slip stopping or phi leaving (0, 90) degrees for other data. Nothing after the end:
// the exact state() has no value there, and what each scheme does from the jam on is its own (the
// suite reports it, it does not pick a winner).
//
// Observables: phi (rad), x_end (x of end A), normal_force (the step's normal impulse / dt, 0
// at the initial sample), normal_force_exact (lambda of the sliding phase; NaN after its end).
// Field output: the rod is a vertex at its centre (reference point (0, s sin phi0)), its angle,
// angular velocity, half length and orientation (cos phi, -sin phi, 0), the unit vector from
// the centre towards A, in body arrays.
//
// Bad input (InputError, one line naming the parameter and its range, exit 2): s, m or g not
// > 0, mu < 0, phi0 outside (0, 90) degrees, v0 = 0, D(phi0) <= 0 (the Painlevé paradox at
// the start: no non-negative normal force holds A on the floor).
//
// References: F. Génot, B. Brogliato, "New results on Painlevé paradoxes", European Journal of
// Mechanics A/Solids 18 (1999); the cardillo project, examples/Painleve.py (the data).
#include <vector>

#include "problems/painleve_rod_exact.hpp"
#include "problems/rigid_problem.hpp"

namespace nsb {

class PainleveRod final : public RigidProblem, public ExactSolution {
 public:
  // The exact solution's impact times, not 0.1.0's Problem::impact_times (kept for plugins).
  using ExactSolution::impact_times;
  explicit PainleveRod(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "painleve-rod"; }
  const Params& parameters() const override { return params_; }
  bool contacts_move() const override { return true; }
  void evaluate_contacts(ConstVecRef u, ContactGeometry& out) const override;
  // End A's abscissa (T = dX_A/dU).
  void contact_slide(ConstVecRef u, VecRef s) const override;
  State initial_state() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  // jam: PainleveRodExact::end_time() when the sliding phase ends in the jam.
  std::optional<double> event_time(ExactEvent event) const override;
  std::optional<FieldMesh> field_mesh() const override;
  void body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const override;

  const PainleveRodExact& closed_form() const { return exact_; }

 private:
  PointContact end_contact(ConstVecRef u) const { return exact_.end_contact(Eigen::Vector3d(u[0], u[1], u[2])); }

  Params params_;
  double s_;
  PainleveRodExact exact_;
};

}  // namespace nsb
