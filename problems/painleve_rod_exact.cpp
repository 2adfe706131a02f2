#include "problems/painleve_rod_exact.hpp"
#include "core/deterministic_math.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "problems/extrapolation_ode.hpp"
#include "problems/input_check.hpp"

namespace nsb {

namespace {

using Vec7 = extrapolation::Vec<7>;  // (t, x, y, phi, x', y', phi') as functions of tau
constexpr double jam_denominator = 1e-10;
constexpr double horizon = 1e4;  // in sqrt(s / g)

}  // namespace

// The sliding phase in tau (dt / dtau = D): smooth through the jam, since D lambda is the
// numerator m (g - s phi'^2 sin phi).
struct PainleveRodExact::Equations {
  const PainleveRodExact* rod;
  Vec7 initial() const {
    Vec7 z;
    z << 0.0, 0.0, rod->s_ * nsb::dmath::sin(rod->phi0_), rod->phi0_, rod->v0_, 0.0, 0.0;
    return z;
  }
  // Positive while sliding, each of order one: D above the jam threshold, lambda (as its
  // numerator), the slip in the initial direction, phi above 0 and below 90 degrees.
  std::array<double, 5> margins(const Vec7& z) const {
    const double phi = z(3), v_scale = std::abs(rod->v0_) + std::sqrt(rod->g_ * rod->s_);
    return {rod->denominator(phi) - jam_denominator, 1.0 - rod->s_ * z(6) * z(6) * nsb::dmath::sin(phi) / rod->g_,
            rod->sigma_ * (z(4) - rod->s_ * nsb::dmath::sin(phi) * z(6)) / v_scale, phi, std::numbers::pi / 2 - phi};
  }
  Vec7 operator()(double, const Vec7& z) const {
    const double phi = z(3), D = rod->denominator(phi);
    const double N = rod->m_ * (rod->g_ - rod->s_ * z(6) * z(6) * nsb::dmath::sin(phi));
    const double friction = rod->mu_ * rod->sigma_;
    Vec7 dz;
    dz << D, D * z(4), D * z(5), D * z(6), -friction * N / rod->m_, N / rod->m_ - rod->g_ * D,
        -rod->s_ * N * (nsb::dmath::cos(phi) - friction * nsb::dmath::sin(phi)) / rod->J_;
    return dz;
  }
};

PainleveRodExact::PainleveRodExact(const PainleveRodSpec& spec)
    : s_(spec.s), m_(spec.m), phi0_(spec.phi0_degrees * std::numbers::pi / 180.0), v0_(spec.v0),
      mu_(spec.mu), g_(spec.g), J_(spec.m * spec.s * spec.s / 3.0), sigma_(spec.v0 > 0.0 ? 1.0 : -1.0) {
  require_input(s_ > 0.0 && std::isfinite(s_), "painleve-rod", "s", s_, "(0, inf)");
  require_input(m_ > 0.0 && std::isfinite(m_), "painleve-rod", "m", m_, "(0, inf)");
  require_input(g_ > 0.0 && std::isfinite(g_), "painleve-rod", "g", g_, "(0, inf)");
  require_input(mu_ >= 0.0 && std::isfinite(mu_), "painleve-rod", "mu", mu_, "[0, inf)");
  require_input(spec.phi0_degrees > 0.0 && spec.phi0_degrees < 90.0, "painleve-rod", "phi0", spec.phi0_degrees,
                "(0, 90) degrees (end A on the floor, the other end above it)");
  require_input(v0_ != 0.0 && std::isfinite(v0_), "painleve-rod", "v0", v0_,
                "(-inf, 0) or (0, inf): the closed form is the sliding phase");
  require_input(denominator(phi0_) > 0.0, "painleve-rod", "phi0", spec.phi0_degrees,
                "the degrees where 1 + (m s^2 / J) cos phi (cos phi - mu sigma sin phi) > 0 (no "
                "non-negative normal force holds end A on the floor there)");

  const Equations rate{this};
  const auto event = [&](double, const Vec7& z) {
    const auto margin = rate.margins(z);
    return *std::min_element(margin.begin(), margin.end());
  };
  const double time_scale = std::sqrt(s_ / g_);
  const auto hit = extrapolation::find_event<7>(rate, event, 0.0, rate.initial(), horizon * time_scale, 0.01 * time_scale);
  const Vec7& z = hit.y;
  end_ = {z(0), z(1), z(2), z(3), z(4), z(5), z(6)};
  t_end_ = z(0);
  if (!hit.found) return;
  // The margin that reached 0 is the one nearest to it.
  const auto margin = rate.margins(z);
  const auto nearest = std::min_element(margin.begin(), margin.end(),
                                        [](double a, double b) { return std::abs(a) < std::abs(b); }) - margin.begin();
  constexpr Ending endings[] = {Ending::jam, Ending::lifts_off, Ending::slip_stops, Ending::leaves_range,
                                Ending::leaves_range};
  ending_ = endings[nearest];
  if (ending_ == Ending::jam) {  // the time left to reach D = 0, u / phi'* = D / (-D'(phi) phi')
    const double phi = z(3);
    const double D_prime = -(m_ * s_ * s_ / J_) * (nsb::dmath::sin(2.0 * phi) + mu_ * sigma_ * nsb::dmath::cos(2.0 * phi));
    t_end_ += denominator(phi) / (-D_prime * z(6));
  }
}

PointContact PainleveRodExact::end_contact(const Eigen::Vector3d& U) const {
  const double c = nsb::dmath::cos(U(2)), sn = nsb::dmath::sin(U(2));
  PointContact k;
  k.gap = U(1) - s_ * sn;
  k.normal_row << 0.0, 1.0, -s_ * c;
  k.tangent_row << 1.0, 0.0, -s_ * sn;
  return k;
}

double PainleveRodExact::denominator(double phi) const {
  return 1.0 + (m_ * s_ * s_ / J_) * nsb::dmath::cos(phi) * (nsb::dmath::cos(phi) - mu_ * sigma_ * nsb::dmath::sin(phi));
}

double PainleveRodExact::normal_force(double phi, double phi_dot) const {
  return m_ * (g_ - s_ * phi_dot * phi_dot * nsb::dmath::sin(phi)) / denominator(phi);
}

std::optional<PainleveRodExact::State> PainleveRodExact::state(double t) const {
  if (!(t >= 0.0 && t <= t_end_)) return std::nullopt;
  const Equations rate{this};
  const Vec7 z0 = rate.initial();
  if (t == 0.0) return State{0.0, z0(1), z0(2), z0(3), z0(4), z0(5), z0(6)};
  const double time_scale = std::sqrt(s_ / g_);
  const auto before_t = [t](double, const Vec7& z) { return t - z(0); };
  const auto hit = extrapolation::find_event<7>(rate, before_t, 0.0, z0, horizon * time_scale, 0.01 * time_scale);
  if (!hit.found) return std::nullopt;  // t lies in the jam's closing tail
  const Vec7& z = hit.y;
  return State{t, z(1), z(2), z(3), z(4), z(5), z(6)};
}

double PainleveRodExact::x_end(const State& s) const { return s.x + s_ * nsb::dmath::cos(s.phi); }
double PainleveRodExact::end_height(const State& s) const { return s.y - s_ * nsb::dmath::sin(s.phi); }

}  // namespace nsb
