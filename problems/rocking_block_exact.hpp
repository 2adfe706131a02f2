#pragma once
// Rocking block, exact solution (Housner 1963; derivations in docs/rigid_bodies.md).
//
// A rigid rectangle of half-width b and half-height h, mass m, on a rigid floor under gravity
// g. R = sqrt(b^2 + h^2), slenderness alpha = atan(b / h) in (0, 90) degrees, inertia
// I_c = m R^2 / 3 about the centre and I_O = (4/3) m R^2 about a corner, p^2 = m g R / I_O
// = 3 g / (4 R). Unknowns U = (x, y, theta): the centre and the counter-clockwise angle.
//
// Corners (contacts). The body point (p_x, p_y) is at world (x + p_x cos theta - p_y sin theta,
// y + p_x sin theta + p_y cos theta); the bottom corners are (+b, -h) (right) and (-b, -h):
//     g = y + p_x sin theta + p_y cos theta,      L = dg/dU = (0, 1, p_x cos theta - p_y sin theta)
//     T = (1, 0, -p_x sin theta - p_y cos theta)  (the corner's horizontal velocity is T U')
//
// Rocking phase. With theta > 0 the block turns about its left corner (sigma = +1), with
// theta < 0 about its right one (sigma = -1); the pivot is fixed (no slip, no lift-off). In
// psi = alpha - sigma theta (the angle of the pivot-to-centre line from the vertical)
//     I_O theta'' = -sigma m g R sin(alpha - |theta|)   <=>   psi'' = p^2 sin(psi),
// energy (1/2) I_O theta'^2 + m g R cos(psi) constant. From theta = 0 at speed w the block
// rises to |theta_max| = alpha - psi_m, cos(psi_m) = cos(alpha) + w^2 / (2 p^2), in
//     t_rise(w) = F(gamma, k) / p,   k = cos(psi_m / 2),
//     tan(gamma) = w / (2 p sin(psi_m / 2) cos(alpha / 2)),
//     sin^2(psi_m / 2) = sin^2(alpha / 2) - w^2 / (4 p^2)
// (F the incomplete elliptic integral of the first kind), and returns to theta = 0 at speed w
// after 2 t_rise(w). With w^2 >= 4 p^2 sin^2(alpha / 2) it passes psi = 0 and topples; the
// phase then ends at |theta| = 90 degrees (the block on its side). Within a phase the state
// is integrated by Gragg–Bulirsch–Stoer extrapolation (problems/extrapolation_ode.hpp) to
// round-off, and so is the first phase from (theta0, omega0), its impact or toppling time
// located on the integrated solution.
// The centre (the pivots stay where they are): with x_mid the centre's abscissa at theta = 0,
//     x = x_mid - h sin theta + sigma b (cos theta - 1),   y = h cos theta + sigma b sin theta.
// x(0) = 0, so x_mid = h sin theta0 - sigma0 b (cos theta0 - 1).
//
// Impact at theta = 0 (the other corner strikes, both corners on the floor, omega- the angular
// velocity before):
// - Housner: no slip, no bounce, angular momentum about the new corner kept:
//     omega+ / omega- = r = 1 - (3/2) sin^2(alpha);
//   defined for r > 0 (alpha < asin(sqrt(2/3)), 54.7 degrees); for r <= 0 the block stops
//   (omega+ = 0), which is Moreau's outcome with e = 0 for those blocks.
// - Moreau: Newton's law on both corners' normal velocities (restitution e) and Coulomb's law
//   (mu) on their common tangent row T = (1, 0, h) (at theta = 0 both corners have it, so only
//   the sum of the tangential impulses Lambda_T counts, bounded by mu (Lambda_new + Lambda_old)):
//   the 3x3 complementarity problem with the Delassus matrix G M^-1 G^T, G = (L_new; L_old; T),
//   solved in closed form by enumerating its ten cases (each contact closed or open; stick,
//   slip forward or back). Homogeneous in omega-: every impact has the same ratio. Outcomes:
//   * e = 0, mu >= mu_H = 3 sin(alpha) cos(alpha) / (1 + 3 cos^2(alpha)), alpha below 54.7
//     degrees: Housner's outcome, the old corner's impulse zero and it lifts;
//   * e > 0 (same blocks): the striking corner bounces, both corners leave the floor (flight);
//   * mu < mu_H: the new corner slips, omega+ / omega- = 1 - 6 (1 + e) sin(alpha)
//     (sin(alpha) - mu cos(alpha)) / (1 + 3 sin^2(alpha) - 3 mu sin(alpha) cos(alpha)), the
//     old corner lifting while 1 - 3 sin^2(alpha) + 3 mu sin(alpha) cos(alpha) >= 0 (else both
//     corners stay down and slide, omega+ = 0, for e = 0);
//   * alpha above 54.7 degrees: the block rebounds about its old corner, omega+ = -e omega-
//     (at rest for e = 0), given mu >= cot(alpha).
//   A sequence of impacts continues while the outcome is a rocking phase (about the new or the
//   old corner) or rest; flight and slip end the exact solution (state() returns nullopt after).
//
// Time to rest: with |ratio| < 1 the speeds after the impacts fall geometrically, and since
// t_rise(w) = w / (p^2 sin(alpha)) (1 + O(w)) the phases' durations do too: the impacts
// accumulate at t_rest = t_1 + sum_k 2 t_rise(w_k). The sum runs until the phases no longer
// advance t in floating point (then the tail, 2 w / (p^2 sin(alpha) (1 - |ratio|)), is added).
//
// Bad input (InputError, one line): b or h not > 0 (alpha outside (0, 90) degrees), m or g not
// > 0, mu < 0, e outside [0, 1], |theta0| >= 90 degrees (radians, pi/2: a corner in the floor).
//
// References: G. W. Housner, "The behavior of inverted pendulum structures during
// earthquakes", Bulletin of the Seismological Society of America 53 (1963); J. J. Moreau,
// "Unilateral contact and dry friction in finite freedom analysis", CISM 302, Springer 1988;
// Ch. Glocker, "Set-valued force laws", Springer 2001.
#include <Eigen/Dense>
#include <optional>
#include <vector>

#include "problems/point_contact.hpp"

namespace nsb {

// The bottom corners' gaps and rows at U = (x, y, theta).
struct BlockCorners {
  PointContact right, left;  // (+b, -h) and (-b, -h)
};
BlockCorners block_corners(double b, double h, const Eigen::Vector3d& U);

// Housner's ratio omega+ / omega- = 1 - (3/2) sin^2(alpha) (negative above 54.7 degrees).
double housner_ratio(double alpha);

// Moreau's outcome of the impact at theta = 0 while pivoting on corner `pivot` (+1 left,
// -1 right) with angular velocity omega_minus (pivot * omega_minus < 0: the other corner
// approaches; std::invalid_argument otherwise).
struct CornerImpact {
  enum class Kind { rocks_on_new_corner, rocks_on_old_corner, rest, flight, slip };
  Kind kind = Kind::rest;
  double ratio = 0.0;        // omega+ / omega-
  double Lambda_new = 0.0;   // normal impulse of the striking corner
  double Lambda_old = 0.0;   // normal impulse of the old pivot
  double Lambda_T = 0.0;     // tangential impulse (sum over both corners) along +T
  Eigen::Vector3d velocity_before, velocity_after;  // (x', y', theta')
  Eigen::Vector3d normal_velocity_after;  // (new corner, old corner, tangential slip) after
  int solutions = 0;         // distinct solutions of the impact problem (1: unique)
};
CornerImpact moreau_impact(double b, double h, double m, double e, double mu, int pivot, double omega_minus);

enum class RockingImpactLaw { housner, moreau };

struct RockingBlockSpec {
  double b = 0.2, h = 1.0, m = 1.0, g = 9.81;
  double theta0 = 0.1, omega0 = 0.0;  // rad, rad/s (counter-clockwise)
  double mu = 1e308, e = 0.0;         // used by Moreau's law only
  RockingImpactLaw law = RockingImpactLaw::housner;
};

class RockingBlockExact {
 public:
  struct State {
    double theta = 0.0, omega = 0.0, x = 0.0, y = 0.0, vx = 0.0, vy = 0.0;
  };
  struct Impact {
    double t = 0.0;
    double omega_before = 0.0, omega_after = 0.0;
    double amplitude_after = 0.0;  // |theta| at the next turning point; +inf if it topples
  };
  enum class Ending {
    rest,            // at rest from rest_time() on (the impacts accumulate, or an impact stops it)
    topples,         // ends on its side (|theta| = 90 degrees) at end_time()
    leaves_rocking,  // an impact gives flight or slip (Moreau's law) at end_time()
    rocks_forever,   // |ratio| = 1: impacts never accumulate; marched up to end_time()
    balances         // no event within the horizon (near the upright equilibrium theta = alpha)
  };

  explicit RockingBlockExact(const RockingBlockSpec& spec);  // InputError on bad input

  double alpha() const { return alpha_; }
  double R() const { return R_; }
  double p() const { return p_; }  // sqrt(3 g / (4 R))
  double pivot_inertia() const { return 4.0 * m_ * R_ * R_ / 3.0; }
  // omega+ / omega- of every impact under the selected law.
  double impact_ratio() const { return ratio_; }
  // Moreau's outcome of the first impact (as computed; Housner's law leaves it unset).
  const std::optional<CornerImpact>& first_impact_outcome() const { return first_outcome_; }

  // The state at t >= 0; nullopt after end_time() and before rest_time() (the solution ended,
  // or the march stopped at its cap short of rest).
  std::optional<State> state(double t) const;
  const std::vector<Impact>& impacts() const { return impacts_; }
  Ending ending() const { return ending_; }
  double rest_time() const { return t_rest_; }  // +inf unless ending() is rest
  // Where the marched solution stops: +inf when it reaches rest_time(); else the topple, the
  // impact that leaves rocking, or the end of the last marched phase.
  double end_time() const { return t_end_; }
  double energy(const State& s) const;          // kinetic + m g y
  // The floor's force on the pivot while rocking, (F, N) = m (x'', y'' + g): with the pivot
  // sigma = sign(theta) (sign(omega) at theta = 0), psi = alpha - sigma theta, psi' = -sigma omega,
  //     F = sigma m R sin(psi) (p^2 cos(psi) - psi'^2),   N = m g - m R (p^2 sin^2(psi) + psi'^2 cos(psi)).
  // The rocking phase is the motion only while N >= 0 and |F| <= mu N; the march does not check it.
  Eigen::Vector2d pivot_force(double theta, double omega) const;

  // Closed forms of a phase started at theta = 0 with speed w (w^2 < 4 p^2 sin^2(alpha / 2)).
  double rise_time(double w) const;
  double amplitude(double w) const;  // |theta_max| = alpha - psi_m
  bool topples_from_upright(double w) const;

 private:
  struct Phase {
    double t = 0.0;
    int sigma = 1;         // pivot: +1 left (theta >= 0), -1 right
    double psi = 0.0, psi_dot = 0.0;  // at t
  };
  State state_in_phase(const Phase& phase, double t) const;
  void first_phase();
  void march_impacts(double t, int sigma, double omega_minus);
  double impact_law_ratio(int sigma, double omega_minus);

  double b_, h_, m_, g_, theta0_, omega0_, mu_, e_;
  RockingImpactLaw law_;
  double R_, alpha_, p_, x_mid_ = 0.0, ratio_ = 0.0;
  std::optional<CornerImpact> first_outcome_;
  std::vector<Phase> phases_;  // phase k starts at impact k (phase 0 at t = 0)
  std::vector<Impact> impacts_;
  Ending ending_ = Ending::rest;
  double t_rest_, t_end_;
};

}  // namespace nsb
