#pragma once
// A rigid sphere sliding then rolling on an inclined plane, exact solution (derivations in
// docs/three_d.md; the contact point's equation as in C. Aghamohammadi and A. Aghamohammadi,
// "Slipping and rolling on an inclined plane", European Journal of Physics 32, 2011).
//
// Sphere of radius R, mass m, inertia I = (2/5) m R^2, on a plane inclined at alpha with Coulomb
// friction mu; x down the slope, y across it, z the plane's normal; the centre starts at
// (0, 0, R). a = g sin(alpha), b = (7/2) mu g cos(alpha), k = b / a = (7/2) mu cot(alpha).
// Slip velocity of the contact point (r = (0, 0, -R) from the centre, w = v + omega x r):
//     w = (v_x - R omega_y, v_y + R omega_x).
// With friction F (in the plane; N = m g cos(alpha)) the momentum equations are
//     m v' = m a e_x + F,   I omega' = (R F_y, -R F_x, 0),
// so w' = a e_x + (7/2) F / m, and the full state follows from w alone (any phase):
//     v(t)       = v0 + (5/7) a t e_x + (2/7) (w(t) - w0),
//     omega_x(t) = omega_x0 + (5 / (7R)) (w_y(t) - w_y0),
//     omega_y(t) = omega_y0 - (5 / (7R)) (w_x(t) - w_x0 - a t),   omega_z = omega_z0,
//     centre(t)  = (0, 0, R) + v0 t + (5/14) a t^2 e_x + (2/7) (int_0^t w - w0 t),
//     int_0^t omega = (omega_x0 t + (5 / (7R)) (int w_y - w_y0 t),
//                      omega_y0 t - (5 / (7R)) (int w_x - w_x0 t - a t^2 / 2),  omega_z0 t).
// Invariants: the angular momentum about the contact point, L_P = I omega + m (0, 0, R) x v,
// changes only by gravity's moment, L_P(t) = L_P(0) + (0, m g R sin(alpha) t, 0); the energy
// E = m |v|^2 / 2 + I |omega|^2 / 2 - m a x falls by the friction work mu m g cos(alpha) int |w|.
//
// Sliding (|w| > 0, F = -mu N w / |w|): w' = a e_x - b w / |w|. The slip direction turns
// towards e_x; with lambda >= 0 as parameter (lambda = 0 at t = 0),
//     A = (|w0| + w_x0) / 2,  B = (|w0| - w_x0) / 2   (A B = w_y0^2 / 4),
//     w     = (A e^{-(k-1) lambda} - B e^{-(k+1) lambda},  w_y0 e^{-k lambda}),
//     |w|   = A e^{-(k-1) lambda} + B e^{-(k+1) lambda},
//     t     = (A G(k-1) + B G(k+1)) / a,                     G(q) = (1 - e^{-q lambda}) / q,
//     int w = ((A^2 G(2k-2) - B^2 G(2k+2)) / a,  w_y0 (A G(2k-1) + B G(2k+1)) / a),
//     int |w| = (A^2 G(2k-2) + 2 A B G(2k) + B^2 G(2k+2)) / a;
// t(lambda) is inverted by safeguarded Newton (dt/dlambda = |w| / a) to round-off.
// The slip ends (lambda -> inf) at
//     t_1 = (A / (k - 1) + B / (k + 1)) / a    if k > 1, or if A = 0 (launched straight up
//                                               the slope: t_1 = |w0| / (a + b)) for any k;
// otherwise (k <= 1, A > 0) it never ends: it slides for ever, w -> (A, 0) for k = 1, and
// |w| grows like (a - b) t for k < 1. Level floor (a = 0): the direction is fixed,
//     w = w0 (1 - t / t_1),   t_1 = |w0| / b = 2 |w0| / (7 mu g).
// After t_1 (w = 0): rolling, w = 0 and v' = (5/7) a e_x (the centre on a parabola), iff the
// friction it needs, (2/7) m a, is within mu N, i.e. k >= 1 (mu >= (2/7) tan(alpha)); else
// it slides from zero slip straight down the slope, w = (a - b) (t - t_1) e_x. Hence rolling
// starts, at t_roll = t_1, iff mu > (2/7) tan(alpha) (or mu = (2/7) tan(alpha) and A = 0).
//
// Bad input (InputError, one line): R, m or g not > 0, alpha outside [0, 90) degrees, mu < 0,
// a velocity not finite.
#include <Eigen/Core>
#include <limits>

namespace nsb {

struct SphereInclineSpec {
  double R = 0.1;        // radius (m)
  double alpha = 20.0;   // slope (degrees)
  double mu = 0.3;       // Coulomb coefficient
  double m = 1.0, g = 9.81;
  double vx0 = 1.0, vy0 = 0.5;             // centre's velocity: down the slope, across it
  double wx0 = 0.0, wy0 = 0.0, wz0 = 0.0;  // angular velocity (rad/s)
};

class SphereInclineExact {
 public:
  struct State {
    Eigen::Vector3d position;  // the centre, (0, 0, R) at t = 0
    Eigen::Vector3d velocity;
    Eigen::Vector3d omega;
    Eigen::Vector3d rotation;  // int_0^t omega (the sphere problem's rotation dofs)
  };

  explicit SphereInclineExact(const SphereInclineSpec& spec);  // InputError on bad input

  double k() const { return k_; }  // (7/2) mu cot(alpha); +inf on a level floor
  // t_roll: when the slip ends and rolling starts; +inf if it slides for ever.
  double roll_time() const { return rolls_ ? t1_ : inf_; }
  Eigen::Vector2d slip(double t) const;  // w(t), t >= 0
  double slip_speed(double t) const { return slip(t).norm(); }
  State state(double t) const;           // t >= 0
  double slip_path_length(double t) const;  // int_0^t |w|
  Eigen::Vector3d contact_angular_momentum(const State& s) const;  // L_P
  double energy(const State& s) const;  // kinetic - m g sin(alpha) x

 private:
  static constexpr double inf_ = std::numeric_limits<double>::infinity();
  struct SlipIntegrals {
    Eigen::Vector2d w = Eigen::Vector2d::Zero();     // w(t)
    Eigen::Vector2d path = Eigen::Vector2d::Zero();  // int_0^t w
    double length = 0.0;                             // int_0^t |w|
  };
  SlipIntegrals integrals(double t) const;
  SlipIntegrals turning_phase(double lambda) const;  // the sliding phase from w0 on a slope
  double turning_time(double lambda) const;
  double lambda_at(double t) const;

  double R_, m_, g_, alpha_, mu_;
  double a_, b_, k_;
  Eigen::Vector2d v0_, w0_;
  Eigen::Vector3d omega0_;
  double A_ = 0.0, B_ = 0.0;
  double t1_ = 0.0;        // end of the sliding phase from w0 (0 if w0 = 0)
  SlipIntegrals at_t1_;    // the integrals there (when t1_ is finite)
  bool rolls_ = true;      // after t1_: rolling (else sliding from zero slip down the slope)
};

}  // namespace nsb
