#include "problems/bouncing_bar.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace nsb {

namespace {
constexpr std::size_t kMaxPieces = 10'000'000;
}

BouncingBarExact::BouncingBarExact(const Params& p, double t_end)
    : len_(p.real("L")),
      young_(p.real("E")),
      rho_(p.real("rho")),
      area_(p.real("A")),
      v0_(p.real("v0")),
      gap0_(p.real("g0")),
      grav_(p.real("g")),
      t_end_(t_end) {
  if (!(grav_ > 0.0)) throw InputError("bouncing bar exact solution: parameter g must be > 0");
  if (p.real("stiff_ratio") != 1.0) throw InputError("bouncing bar exact solution: parameter stiff_ratio must be 1");
  if (!(t_end >= 0.0) || !std::isfinite(t_end)) throw InputError("bouncing bar exact solution: t_end must be finite and >= 0");
  c_ = std::sqrt(young_ / rho_);
  tau_ = len_ / c_;
  // g0 = v0 t1 + g t1^2 / 2, the root written without cancellation.
  t1_ = 2.0 * gap0_ / (v0_ + std::sqrt(v0_ * v0_ + 2.0 * grav_ * gap0_));
  V_ = v0_ + grav_ * t1_;
  march(t_end - t1_ + 2.0 * tau_);
}

std::size_t BouncingBarExact::find(double a) const {
  const auto it = std::upper_bound(pieces_.begin(), pieces_.end(), a, [](double x, const Piece& q) { return x < q.a0; });
  return static_cast<std::size_t>(it - pieces_.begin()) - 1;
}

double BouncingBarExact::f(double a) const {
  if (a < 0.0) return -0.5 * V_;
  const Piece& q = pieces_[find(a)];
  return q.f0 + q.slope * (a - q.a0);
}

double BouncingBarExact::F(double a) const {
  if (a < 0.0) return -0.5 * V_ * a;
  const Piece& q = pieces_[find(a)];
  const double d = a - q.a0;
  return q.F0 + d * (q.f0 + 0.5 * q.slope * d);
}

// One piece per stretch of s on which the incoming wave h(s) = f(s - 2 tau) is linear and the
// mode holds (header). Tolerances: round-off of the velocities (V + g tau) and gaps.
void BouncingBarExact::march(double s_end) {
  const double g = grav_, two_tau = 2.0 * tau_;
  const double tol_v = 1e-12 * (V_ + g * tau_), tol_p = 1e-12 * (V_ + g * tau_) * tau_, tol_s = 1e-12 * tau_;
  double s = 0.0, p = 0.0, F_s = 0.0;
  bool contact = true;
  while (s < s_end) {
    if (pieces_.size() >= kMaxPieces)
      throw InputError(fmt::format("bouncing bar exact solution: more than {} pieces before t = {} (t_end too long)",
                                   kMaxPieces, s + t1_));
    // Incoming wave on [s, next): h0 + beta (sigma - s).
    // A piece boundary that round-off puts a hair before s is passed (no sliver pieces).
    const double a = s - two_tau;
    double h0, beta, next;
    if (s + tol_s < two_tau) {
      h0 = -0.5 * V_, beta = 0.0, next = two_tau;
    } else {
      std::size_t k = find(std::max(a, 0.0));
      while (k + 1 < pieces_.size() && pieces_[k + 1].a0 + two_tau <= s + tol_s) ++k;
      const Piece& q = pieces_[k];
      h0 = q.f0 + q.slope * (a - q.a0), beta = q.slope;
      next = (k + 1 < pieces_.size() ? pieces_[k + 1].a0 : s) + two_tau;
    }
    const double r0 = 2.0 * h0 - g * s, r1 = 2.0 * beta - g;  // r(s) and r'(s)
    if (contact && (r0 > tol_v || (r0 >= -tol_v && r1 > 0.0))) contact = false;  // release
    if (!contact && p <= tol_p && (r0 < -tol_v || (r0 <= tol_v && r1 < 0.0))) contact = true, p = 0.0;  // arrival
    double end = next;
    if (contact) {
      if (r1 > 0.0 && s - r0 / r1 < end - tol_s) end = std::max(s - r0 / r1, s + tol_s);
      pieces_.push_back({s, g * s - h0, g - beta, F_s});
    } else {
      // First root of p + r0 d + r1 d^2 / 2 beyond round-off, if before next.
      double d = std::numeric_limits<double>::infinity();
      if (r1 == 0.0) {
        if (r0 < 0.0) d = -p / r0;
      } else {
        const double disc = r0 * r0 - 2.0 * r1 * p;
        if (disc >= 0.0) {
          const double sq = std::sqrt(disc), qq = -(r0 + std::copysign(sq, r0));
          for (double root : {qq / r1, qq != 0.0 ? 2.0 * p / qq : -1.0})
            if (root > tol_s && root < d) d = root;
        }
      }
      const bool lands = s + d <= end + tol_s;
      if (s + d < end - tol_s) end = s + d;
      pieces_.push_back({s, h0, beta, F_s});
      const double e = end - s;
      p = lands ? 0.0 : std::max(0.0, p + e * (r0 + 0.5 * r1 * e));
    }
    const Piece& q = pieces_.back();
    F_s = q.F0 + (end - s) * (q.f0 + 0.5 * q.slope * (end - s));
    s = end;
  }
}

double BouncingBarExact::displacement(double x, double t) const {
  const double s = t - t1_;
  return F(s - x / c_) + F(s + x / c_ - 2.0 * tau_) - V_ * tau_ - 0.5 * grav_ * s * s - gap0_;
}

double BouncingBarExact::velocity(double x, double t) const {
  const double s = t - t1_;
  return f(s - x / c_) + f(s + x / c_ - 2.0 * tau_) - grav_ * s;
}

double BouncingBarExact::stress(double x, double t) const {
  const double s = t - t1_;
  return rho_ * c_ * (f(s + x / c_ - 2.0 * tau_) - f(s - x / c_));
}

double BouncingBarExact::contact_force(double t) const { return -area_ * stress(0.0, t); }

double BouncingBarExact::momentum(double t) const {
  const double s = t - t1_;
  return rho_ * area_ * c_ * (F(s) - F(s - 2.0 * tau_)) - rho_ * area_ * len_ * grav_ * s;
}

double BouncingBarExact::field_energy(double t) const {
  // Between the points where s -+ x/c crosses a piece boundary the fields are polynomial in
  // x (velocity and stress linear, u quadratic): 2-point Gauss is exact there.
  const double s = t - t1_;
  std::vector<double> cuts = {0.0, len_};
  for (const Piece& q : pieces_) {
    cuts.push_back(c_ * (s - q.a0));
    cuts.push_back(c_ * (q.a0 + 2.0 * tau_ - s));
  }
  std::erase_if(cuts, [&](double x) { return !(x >= 0.0 && x <= len_); });
  std::sort(cuts.begin(), cuts.end());
  const double gp = 0.5 / std::sqrt(3.0);
  double e = 0.0;
  for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
    const double a = cuts[i], b = cuts[i + 1], m = 0.5 * (a + b), w = b - a;
    if (w <= 0.0) continue;
    for (const double x : {m - gp * w, m + gp * w}) {
      const double v = velocity(x, t), sig = stress(x, t), u = displacement(x, t);
      e += 0.5 * w * area_ * (0.5 * rho_ * v * v + 0.5 * sig * sig / young_ + rho_ * grav_ * u);
    }
  }
  return e;
}

}  // namespace nsb
