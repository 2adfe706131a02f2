#pragma once
// Painlevé rod, exact sliding phase (F. Génot, B. Brogliato, "New results on Painlevé
// paradoxes", European Journal of Mechanics A/Solids 18, 1999; Ch. Glocker, "Set-valued force
// laws", Springer 2001; derivations in docs/rigid_bodies.md).
//
// A rod of length 2 s, mass m, J = m s^2 / 3, centre (x, y), angle phi to the floor; its end
// A = (x + s cos phi, y - s sin phi) slides on the rough floor y = 0 (Coulomb, mu) ahead of
// the centre when x' > 0 (the cardillo example's configuration). Unknowns U = (x, y, phi):
//     g_A = y - s sin phi,   L = (0, 1, -s cos phi),   T = (1, 0, -s sin phi)
// (x'_A = T U'). With the normal force lambda and the slip sign sigma = sign(x'_A):
//     m x'' = -mu sigma lambda,   m y'' = lambda - m g,   J phi'' = -s lambda (cos phi - mu sigma sin phi).
// Holding A on the floor (g_A'' = y'' - s cos phi phi'' + s sin phi phi'^2 = 0) gives
//     lambda = m (g - s phi'^2 sin phi) / D(phi),
//     D(phi) = 1 + (m s^2 / J) cos phi (cos phi - mu sigma sin phi)
//            = (1 + k / 2) + (k / 2) (cos 2 phi - mu sigma sin 2 phi),   k = m s^2 / J = 3.
// The sliding phase is this ODE in (x, y, phi) from y0 = s sin phi0, x'0 = v0, y'0 = phi'0 = 0.
// It ends when lambda reaches 0 (lift-off), x'_A reaches 0 (slip stops), phi leaves (0, 90)
// degrees, or D reaches 0: where D -> 0 the numerator vanishes too (else phi'' ~ 1 / D would
// drive phi'^2 sin phi above g first), the trajectory runs into the point (phi*, phi'*) with
// D(phi*) = 0 and s phi'*^2 sin phi* = g, and lambda grows without bound (dynamic jam, followed
// by an impact without collision); near it lambda ~ (phi* - phi)^(kappa - 1) with
//     kappa = 2 m s sin(phi*) c(phi*) / (-D'(phi*)),  c(phi) = -s (cos phi - mu sigma sin phi) / J
// (2/3 for the cardillo data, phi* = 45 degrees).
// Integration: in the time tau with dt / dtau = D(phi) the system is smooth through the jam
// (D lambda is the numerator), and the singular point is a stable node it approaches as
// tau -> inf. Gragg–Bulirsch–Stoer extrapolation (problems/extrapolation_ode.hpp) integrates
// (t, x, y, phi, x', y', phi') in tau to round-off until D falls below 1e-10; the remaining
// time, D / (-D'(phi) phi') to relative O(D^kappa), closes the jam time. Events (lift-off,
// slip stop, range) are located on the integrated solution.
//
// Bad input (InputError, one line): s, m, g not > 0, mu < 0, phi0 outside (0, 90) degrees (the
// other end in the floor, or A behind the centre), v0 = 0 (no slip: the closed form is the
// sliding phase), D(phi0) <= 0 (no non-negative normal force holds A on the floor at the start).
#include <optional>

#include "problems/point_contact.hpp"

namespace nsb {

struct PainleveRodSpec {
  double s = 1.0, m = 1.0, phi0_degrees = 31.0, v0 = 30.0, mu = 5.0 / 3.0, g = 10.0;
};

class PainleveRodExact {
 public:
  struct State {
    double t = 0.0;
    double x = 0.0, y = 0.0, phi = 0.0, vx = 0.0, vy = 0.0, vphi = 0.0;
  };
  enum class Ending { jam, lifts_off, slip_stops, leaves_range, none };

  explicit PainleveRodExact(const PainleveRodSpec& spec);  // InputError on bad input

  // End A's gap and rows at U = (x, y, phi).
  PointContact end_contact(const Eigen::Vector3d& U) const;
  double denominator(double phi) const;                    // D(phi), with the initial sigma
  double normal_force(double phi, double phi_dot) const;   // lambda while sliding
  double sigma() const { return sigma_; }

  // How and when the sliding phase ends (none: not within the march's horizon).
  Ending ending() const { return ending_; }
  double end_time() const { return t_end_; }
  const State& end_state() const { return end_; }  // at the jam: the last integrated state

  // The state at 0 <= t <= end_time(); nullopt outside, and possibly in the last ~1e-11 s
  // before a jam (past the threshold on D, where the time is closed by the tail formula).
  std::optional<State> state(double t) const;
  double x_end(const State& s) const;       // x of end A
  double end_height(const State& s) const;  // y of end A (0 while sliding)

 private:
  struct Equations;
  double s_, m_, phi0_, v0_, mu_, g_, J_, sigma_;
  Ending ending_ = Ending::none;
  double t_end_ = 0.0;
  State end_;
};

}  // namespace nsb
