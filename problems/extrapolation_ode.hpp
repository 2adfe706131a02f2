#pragma once
// Gragg–Bulirsch–Stoer extrapolation for smooth ODEs y' = f(t, y), to round-off: the exact
// solutions of the rigid bodies (docs/rigid_bodies.md) integrate their smooth phases with it.
//
// One step of size H: Gragg's modified midpoint rule with n = 2, 4, ..., 2 k_max substeps,
//     z_0 = y,  z_1 = z_0 + h f(t, z_0),  z_{i+1} = z_{i-1} + 2 h f(t + i h, z_i),  h = H / n,
// whose error z_n - y(t + H) is an even power series in h (n even), extrapolated to h = 0 by
// the Aitken–Neville table
//     T_{j,k+1} = T_{j,k} + (T_{j,k} - T_{j-1,k}) / ((n_j / n_{j-k})^2 - 1)
// (order 2 k in row k). The step is accepted at the first row whose last two entries agree
// within tol (a max-norm scaled by 1 + |y_i|); the next step size follows from that row's
// error, H (0.65 / err)^(1 / (2k - 1)) within [H / 5, 4 H].
//
// integrate_to reaches an end point exactly; find_event marches until a scalar event function
// changes sign between two accepted steps and locates the root by the Illinois method, each
// trial point integrated afresh from the step's start (one or a few extrapolated steps), so
// the event time is as accurate as the solution.
//
// Reference: E. Hairer, S. P. Nørsett, G. Wanner, "Solving Ordinary Differential Equations I",
// 2nd ed., Springer 1993, section II.9 (extrapolation methods).
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/deterministic_math.hpp"

namespace nsb::extrapolation {

template <int N>
using Vec = Eigen::Matrix<double, N, 1>;

inline constexpr double default_tol = 1e-15;
inline constexpr int max_rows = 9;  // up to 18 midpoint substeps, order 18

// One extrapolated step; returns false (y untouched) when no row met tol. `next_h` receives
// the step size to try next (accepted or not).
template <int N, class F>
bool try_step(const F& f, double t, Vec<N>& y, double H, double tol, double& next_h) {
  Vec<N> table[max_rows];
  for (int j = 0; j < max_rows; ++j) {
    const int n = 2 * (j + 1);
    const double h = H / n;
    Vec<N> z_prev = y;
    Vec<N> z = y + h * f(t, y);
    for (int i = 1; i < n; ++i) {
      Vec<N> z_next = z_prev + 2.0 * h * f(t + i * h, z);
      z_prev = z;
      z = z_next;
    }
    // table[k] holds T_{j,k}; update in place from the previous row's entries.
    Vec<N> row_prev = j > 0 ? table[0] : z;
    table[0] = z;
    for (int k = 1; k <= j; ++k) {
      const double ratio = static_cast<double>(n) / (n - 2 * k);
      Vec<N> improved = table[k - 1] + (table[k - 1] - row_prev) / (ratio * ratio - 1.0);
      if (k < j) row_prev = table[k];
      table[k] = improved;
    }
    if (j < 2) continue;
    const Vec<N> scale = Vec<N>::Ones() + y.cwiseAbs().cwiseMax(table[j].cwiseAbs());
    const double err = ((table[j] - table[j - 1]).cwiseQuotient(scale)).cwiseAbs().maxCoeff() / tol;
    const double factor = err == 0.0 ? 4.0 : 0.94 * nsb::dmath::pow(0.65 / err, 1.0 / (2 * j + 1));
    next_h = H * std::clamp(factor, 0.2, 4.0);
    if (err <= 1.0) {
      y = table[j];
      return true;
    }
  }
  return false;
}

// Advances (t, y) by one accepted step no longer than max_h, adapting h; returns the step taken.
template <int N, class F>
double accepted_step(const F& f, double t, Vec<N>& y, double& h, double max_h, double tol) {
  for (int attempt = 0; attempt < 200; ++attempt) {
    const double H = std::min(h, max_h);
    double next_h = H;
    if (try_step<N>(f, t, y, H, tol, next_h)) {
      h = next_h;
      return H;
    }
    h = std::min(next_h, 0.5 * H);
  }
  throw std::runtime_error("extrapolation: no step size met the tolerance (a singular right-hand side?)");
}

// y(t1) from y(t0) = y (t1 >= t0). `h` is the first trial step, updated to the last one.
template <int N, class F>
Vec<N> integrate_to(const F& f, double t0, Vec<N> y, double t1, double& h, double tol = default_tol) {
  double t = t0;
  while (t < t1) {
    const double remaining = t1 - t;
    const double taken = accepted_step<N>(f, t, y, h, remaining, tol);
    t = taken == remaining ? t1 : t + taken;
  }
  return y;
}

template <int N>
struct Event {
  bool found = false;
  double t = 0.0;  // the root, or t_end when none
  Vec<N> y;        // the state there
};

// Marches from (t0, y0) to t_end; stops at the first sign change of event(t, y) from its
// value at t0 (which must be non-zero) and returns the root, located to round-off.
template <int N, class F, class G>
Event<N> find_event(const F& f, const G& event, double t0, const Vec<N>& y0, double t_end,
                    double h_first, double tol = default_tol) {
  double t = t0, h = h_first;
  Vec<N> y = y0;
  double e0 = event(t, y);
  while (t < t_end) {
    Vec<N> y_new = y;
    const double remaining = t_end - t;
    const double taken = accepted_step<N>(f, t, y_new, h, remaining, tol);
    const double t_new = taken == remaining ? t_end : t + taken;
    const double e_new = event(t_new, y_new);
    if ((e_new > 0.0) != (e0 > 0.0) || e_new == 0.0) {
      // Illinois (modified regula falsi) on [t, t_new], every trial from (t, y).
      double a = t, b = t_new, ea = e0, eb = e_new;
      Vec<N> yb = y_new;
      int kept_side = 0;
      for (int it = 0; it < 200 && eb != 0.0 && b - a > 4e-16 * std::max(1.0, std::abs(b)); ++it) {
        const double c = std::clamp(b - eb * (b - a) / (eb - ea), a, b);
        double hc = c - t;
        const Vec<N> yc = c == t ? y : integrate_to<N>(f, t, y, c, hc, tol);
        const double ec = event(c, yc);
        if ((ec > 0.0) == (eb > 0.0)) {
          b = c, eb = ec, yb = yc;
          if (kept_side == -1) ea *= 0.5;
          kept_side = -1;
        } else {
          a = c, ea = ec;
          if (kept_side == 1) eb *= 0.5;
          kept_side = 1;
        }
      }
      return {true, b, yb};
    }
    t = t_new, y = y_new, e0 = e_new;
  }
  return {false, t, y};
}

}  // namespace nsb::extrapolation
