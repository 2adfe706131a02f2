#pragma once
// Rocking block: a rigid rectangle of half-width b and half-height h, mass m, on a rigid floor
// under gravity g, touching it by its two bottom corners, whose gaps depend on its angle
// (moving contacts, docs/contacts.md; derivations in docs/rigid_bodies.md section 1).
//
// Unknowns U = (x, y, theta): the centre and the counter-clockwise angle;
// M = diag(m, m, m R^2 / 3), R = sqrt(b^2 + h^2), load (0, -m g, 0). Contacts, the corners
// (+b, -h) (right, contact 0) and (-b, -h) (left, contact 1), p = (p_x, p_y):
//     g(U) = y + p_x sin theta + p_y cos theta,
//     L(U) = dg/dU = (0, 1, p_x cos theta - p_y sin theta),
//     T(U)        = (1, 0, -p_x sin theta - p_y cos theta)   (the corner's horizontal velocity)
// Newton restitution e on both, Coulomb friction mu on both (tangent rows only when mu > 0).
// contacts_move() is true: schemes that treat moving contacts evaluate these at each step;
// contacts() holds the rows at U0 and g0 = g(U0) - L(U0) U0.
//
// Parameters: b > 0, h > 0 (slenderness alpha = atan(b / h) in (0, 90) degrees), theta0 in
// (-pi/2, pi/2) rad (beyond, an upper corner starts in the floor), omega0 (rad/s), mu >= 0,
// e in [0, 1], m > 0, g > 0. Initial state: rocking about the corner on the floor, sigma =
// sign(theta0) (sign(omega0) at theta0 = 0; +1 the left corner), x(0) = 0,
//     y = h cos theta0 + sigma b sin theta0,
//     (x', y') = (-h cos theta0 - sigma b sin theta0, -h sin theta0 + sigma b cos theta0) omega0,
// so the pivot's gap is 0 and the other corner's 2 b |sin theta0| >= 0.
//
// Exact solution (problems/rocking_block_exact.hpp, RockingBlockExact with Moreau's law, the
// suite's contact law: Newton on both corners, Coulomb on their common tangent row): rocking
// about a corner between impacts (Housner's inverted pendulum, integrated to round-off), at
// theta = 0 Moreau's impact outcome, which equals Housner's law
//     omega+ / omega- = 1 - (3/2) sin^2(alpha)
// for e = 0, mu >= mu_H = 3 sin(alpha) cos(alpha) / (1 + 3 cos^2(alpha)), alpha below 54.7
// degrees (the defaults); e > 0 gives flight, mu < mu_H slip, and the exact solution ends
// there (the exact state() has nothing after it). It assumes no slip and no lift-off of the pivot
// between impacts (|F| <= mu N, N >= 0: RockingBlockExact::pivot_force), which the defaults
// satisfy. impact_times: the marched impacts.
//
// Observables: theta, omega (theta'), omega_exact (NaN where the exact solution has ended).
// Field output: the block is a vertex at its centre (reference point (0, h)), its angle,
// angular velocity, half sizes and orientation (cos theta, sin theta, 0) in body arrays.
//
// Bad input (InputError, one line naming the parameter and its range, exit 2 from the
// commands): b or h not > 0, mu < 0, e outside [0, 1], m or g not > 0, |theta0| >= pi/2.
//
// References: G. W. Housner, Bulletin of the Seismological Society of America 53 (1963);
// J. J. Moreau, CISM 302, Springer 1988.
#include <vector>

#include "problems/rigid_problem.hpp"
#include "problems/rocking_block_exact.hpp"

namespace nsb {

class RockingBlock : public RigidProblem, public ExactSolution {
 public:
  explicit RockingBlock(const Params& params);
  static ParamSpecs parameters_spec();

  std::string name() const override { return "rocking-block"; }
  const Params& parameters() const override { return params_; }
  bool contacts_move() const override { return true; }
  void evaluate_contacts(ConstVecRef u, ContactGeometry& out) const override;
  // The corners' abscissae X (T = dX/dU).
  void contact_slide(ConstVecRef u, VecRef s) const override;
  State initial_state() const override;
  std::vector<std::string> observable_names() const override;
  void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const override;
  const ExactSolution* exact() const override { return this; }
  std::optional<State> state(double t) const override;
  std::vector<double> impact_times(double t_end) const override;
  // The marched impacts' amplitude_after.
  std::vector<double> amplitudes_after_impacts() const override;
  // rest (RockingBlockExact::rest_time(), +inf unless it comes to rest).
  std::optional<double> event_time(ExactEvent event) const override;
  // impact_ratio (Moreau's, RockingBlockExact::impact_ratio()) and housner_ratio.
  std::optional<double> value(ExactValue what) const override;
  std::optional<FieldMesh> field_mesh() const override;
  void body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const override;

  const RockingBlockExact& closed_form() const { return exact_; }
  // The corners' gaps and rows at u (contact 0 right, 1 left).
  BlockCorners corners(ConstVecRef u) const;

 private:
  Params params_;
  double b_, h_;
  RockingBlockExact exact_;
};

}  // namespace nsb
