#pragma once
// Bouncing bar (Doyen, Ern, Piperno, SISC 33, 2011; docs/method.md "Bouncing bar"): the Signorini
// bar (problems/signorini_bar.hpp) dropped under gravity onto the wall, and its exact
// continuum solution. The problem itself is a SignoriniBar (registry line bouncing-bar,
// SignoriniBar::bouncing_parameters_spec): DEP's data L = 10, E = 900, rho = 1, A = 1, g = 10,
// v0 = 0, g0 = 5 (c = 30, tau = L/c = 1/3; it hits at t1 = 1 with speed V = 10).
//
//     rho u_tt = E u_xx - rho g  on (0, L),  E u_x(L) = 0,  w = u + g0 >= 0 at x = 0,
//     lambda = -A E u_x(0) >= 0,  w(0) lambda = 0;   u(x, 0) = 0,  u_t(x, 0) = -v0.
//
// Derivation (d'Alembert in the free-falling frame). Before the impact the bar falls rigidly
// and unstressed (a uniform body force on a free bar): w = g0 - v0 t - g t^2/2, hitting at t1
// (g0 = v0 t1 + g t1^2/2) with speed V = v0 + g t1. With s = t - t1 and z = w + g s^2/2 the
// body force vanishes, z_tt = c^2 z_xx, so z = F(s - x/c) + G(s + x/c). Write f = F'.
//   free end:  z_x(L) = 0  =>  G'(b) = f(b - 2 tau), and matching the rigid fall
//              (f = -V/2 before the impact, F(a) = -V a / 2 for a < 0):
//                  z(x, s) = F(s - x/c) + F(s + x/c - 2 tau) - V tau;
//   the end:   gap p(s) = w(0, s) = z(0, s) - g s^2/2, contact force
//                  lambda(s) = rho A c (f(s) - f(s - 2 tau));
//              with the incoming wave h(s) = f(s - 2 tau) and r(s) = 2 h(s) - g s (the end's
//              velocity if it were free):
//                  contact (p = 0, r <= 0):  f(s) = g s - h(s),  lambda = -rho A c r >= 0
//                  free    (p > 0 or r > 0): f(s) = h(s),        p' = r,  lambda = 0
//              (the rule of a massless end: Signorini's conditions on the wave that leaves).
// f is piecewise linear with slopes 0 or g (each piece of f begets one 2 tau later), p is
// piecewise quadratic: the solution is built by marching over these pieces, switching mode
// where r changes sign in contact or p reaches 0 in flight (closed-form roots). Then
//     u = z - g s^2/2 - g0,   u_t = f(s - x/c) + f(s + x/c - 2 tau) - g s,
//     sigma = rho c (f(s + x/c - 2 tau) - f(s - x/c)).
// DEP's data (V = 3 g tau), worked by hand: contact on s in [0, 2 tau] (lambda = rho A c (V +
// g s): 300 rising to 500), flight on [2 tau, 8 tau], contact on [8 tau, 10 tau] (lambda =
// rho A c (5 g tau - g (s - 8 tau))), then f = 13 g tau / 2 on [8 tau, 16 tau): the bar flies
// rigidly from s = 10 tau, leaving at speed V, stops at s = 13 tau at its initial height and
// lands at s = 16 tau unstressed at speed V: periodic with period 16 tau = 16/3 for t >= 0.
// Other data need not be periodic; the march holds for any (no closed form assumed).
// Momentum: P = rho A int_0^L u_t dx; the two waves integrate to c (F(s) - F(s - tau)) and
// c (F(s - tau) - F(s - 2 tau)), so P(t) = rho A c (F(s) - F(s - 2 tau)) - rho A L g s
// (before the impact F(a) = -V a / 2: P = -rho A L (v0 + g t), the rigid fall).
// Energy: kinetic + strain + rho A g int u dx is conserved (Lebeau and Schatzman 1984): it
// stays rho A L v0^2 / 2 (0 for DEP: the drop's potential rho A L g g0 = 500 turns into
// kinetic and strain energy). field_energy(t) integrates it from the exact fields.
#include <memory>
#include <vector>

#include "core/parameters.hpp"

namespace nsb {

class BouncingBarExact {
 public:
  // Reads L, E, rho, A, v0, g0, g of a bar's parameters (g > 0, E uniform: stiff_ratio 1);
  // the solution is built up to t_end.
  BouncingBarExact(const Params& bar_params, double t_end);

  double impact_time() const { return t1_; }    // first contact t1
  double impact_speed() const { return V_; }    // V = v0 + g t1
  double wave_time() const { return tau_; }     // L / c
  double t_end() const { return t_end_; }
  double energy() const { return 0.5 * rho_ * area_ * len_ * v0_ * v0_; }  // conserved total
  double impact_energy() const { return 0.5 * rho_ * area_ * len_ * V_ * V_; }  // kinetic at t1

  // Exact fields at x in [0, L], 0 <= t <= t_end (fronts: the value just after).
  double displacement(double x, double t) const;
  double velocity(double x, double t) const;
  double stress(double x, double t) const;
  double contact_force(double t) const;
  double momentum(double t) const;  // rho A int_0^L u_t dx
  // Kinetic + strain + rho A g int u dx, integrated piece by piece (exact to round-off).
  double field_energy(double t) const;
  std::size_t pieces() const { return pieces_.size(); }

 private:
  struct Piece {
    double a0, f0, slope, F0;  // f(a) = f0 + slope (a - a0), F(a) = F0 + int_a0^a f
  };
  double len_, young_, rho_, area_, v0_, gap0_, grav_, t_end_;
  double c_, tau_, t1_, V_;
  std::vector<Piece> pieces_;  // a0 increasing, the first at a0 = 0

  std::size_t find(double a) const;  // last piece with a0 <= a (a >= 0)
  double f(double a) const;
  double F(double a) const;
  void march(double s_end);
};

}  // namespace nsb
