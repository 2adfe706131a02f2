#include "problems/rolling_disk.hpp"
#include "core/deterministic_math.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace nsb {

namespace {
constexpr double inf = std::numeric_limits<double>::infinity();
constexpr int max_impacts = 1000;
}  // namespace

ParamSpecs RollingDisk::parameters_spec() {
  return {
      ParamSpec::real("R", 0.1, 0.0, 1e308, "radius [m]", true),
      ParamSpec::real("kappa", 0.5, 0.0, 1e308, "inertia / (m R^2): 1/2 disk, 2/5 ball, 1 ring", true),
      ParamSpec::real("mu", 0.3, 0.0, 1e308, "Coulomb friction coefficient (0: frictionless)"),
      ParamSpec::real("v0", 1.0, -1e308, 1e308, "initial horizontal velocity of the centre [m/s]"),
      ParamSpec::real("omega0", 0.0, -1e308, 1e308, "initial spin, counter-clockwise [rad/s]"),
      ParamSpec::real("h0", 0.0, 0.0, 1e308, "drop height of the lowest point (0: on the floor) [m]"),
      ParamSpec::real("e", 0.5, 0.0, 1.0, "Newton restitution coefficient"),
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass [kg]", true),
      ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2]", true),
  };
}

RollingDisk::RollingDisk(const Params& params)
    : params_(params),
      R_(params.real("R")),
      kappa_(params.real("kappa")),
      mu_(params.real("mu")),
      v0_(params.real("v0")),
      omega0_(params.real("omega0")),
      h0_(params.real("h0")),
      e_(params.real("e")),
      m_(params.real("m")),
      g_(params.real("g")) {
  V_ = std::sqrt(2.0 * g_ * h0_);
  t1_ = V_ / g_;
  start_.v = v0_;
  start_.omega = omega0_;
  start_.slip_after = v0_ + R_ * omega0_;

  if (h0_ == 0.0) {
    t_rest_ = 0.0;
    rest_ = start_;
  } else {
    t_rest_ = e_ == 1.0 ? inf : t1_ + 2.0 * e_ * V_ / (g_ * (1.0 - e_));
    const Impact* prev = &start_;
    for (int k = 1; k <= max_impacts; ++k) {
      Impact im;
      im.t = impact_time(k);
      // Once the times no longer increase the impacts have accumulated to round-off.
      if (!impacts_.empty() && !(im.t > impacts_.back().t)) break;
      im.V = nsb::dmath::pow(e_, k - 1) * V_;
      im.Lambda_N = m_ * (1.0 + e_) * im.V;
      im.x = prev->x + prev->v * (im.t - prev->t);
      im.theta = prev->theta + prev->omega * (im.t - prev->t);
      im.slip_before = prev->v + R_ * prev->omega;
      const double stick = -m_ * kappa_ * im.slip_before / (1.0 + kappa_);
      const double bound = mu_ * im.Lambda_N;
      im.stuck = std::abs(stick) <= bound;
      im.Lambda_T = im.stuck ? stick : -std::copysign(bound, im.slip_before);
      im.v = prev->v + im.Lambda_T / m_;
      im.omega = prev->omega + im.Lambda_T / (kappa_ * m_ * R_);
      im.slip_after = im.v + R_ * im.omega;
      impacts_.push_back(im);
      prev = &impacts_.back();
    }
    if (e_ < 1.0) {
      rest_ = impacts_.back();
      rest_.t = t_rest_;
      rest_.x += rest_.v * (t_rest_ - impacts_.back().t);
      rest_.theta += rest_.omega * (t_rest_ - impacts_.back().t);
    }
  }

  const Impact& last = std::isfinite(t_rest_) ? rest_ : impacts_.back();
  const double s = last.v + R_ * last.omega;
  const double sliding = s == 0.0 ? 0.0 : (mu_ > 0.0 ? std::abs(s) / slip_decay_rate() : inf);
  t_roll_ = t_rest_ + sliding;
  if (std::isfinite(t_roll_)) {
    State end;
    end.u = Vec::Zero(3);
    end.v = Vec::Zero(3);
    floor_motion(rest_, t_roll_, end);
    v_final_ = end.v[0];
    omega_final_ = end.v[2];
  } else {
    v_final_ = last.v;
    omega_final_ = last.omega;
  }

  mass_ = Vec(3);
  mass_ << m_, m_, kappa_ * m_ * R_ * R_;
  load_ = Vec::Zero(3);
  load_[1] = -m_ * g_;

  contacts_.normal.resize(1, 3);
  contacts_.normal.insert(0, 1) = 1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Zero(1);
  contacts_.restitution = e_;
  // Friction only when mu > 0, so that mu = 0 is described exactly like a frictionless problem.
  if (mu_ > 0.0) {
    SpMat T(1, 3);
    T.insert(0, 0) = 1.0;
    T.insert(0, 2) = R_;
    contacts_.set_friction(std::move(T), mu_, 0.0);
  }
}

State RollingDisk::initial_state() const {
  State s;
  s.u = Vec::Zero(3);
  s.u[1] = h0_;
  s.v = Vec::Zero(3);
  s.v[0] = v0_;
  s.v[2] = omega0_;
  return s;
}

double RollingDisk::impact_time(int i) const {
  if (i <= 1) return t1_;
  const double flights = (e_ == 1.0) ? (i - 1) : e_ * (1.0 - nsb::dmath::pow(e_, i - 1)) / (1.0 - e_);
  return t1_ + 2.0 * V_ / g_ * flights;
}

// The marched impacts up to t_end. When the march stopped at max_impacts with impacts still
// to come (e = 1, or e near 1), a finite t_end past the last marched one is refused: the
// list would silently lack the impacts after it.
std::vector<double> RollingDisk::impact_times(double t_end) const {
  const bool truncated = impacts_.size() == static_cast<std::size_t>(max_impacts);
  if (truncated && std::isfinite(t_end) && t_end > impacts_.back().t && t_end < t_rest_)
    throw InputError(fmt::format("rolling-disk exact solution: impact_times(t_end = {:.6g}) asks past its {}th (last marched) impact "
                                 "(e = {:.6g}); valid: t_end <= {:.9g}, or inf for the first {}",
                                 t_end, max_impacts, e_, impacts_.back().t, max_impacts));
  std::vector<double> times;
  for (const auto& im : impacts_)
    if (im.t <= t_end) times.push_back(im.t);
  return times;
}

void RollingDisk::floor_motion(const Impact& start, double t, State& s) const {
  const double slip = start.v + R_ * start.omega;
  const double tau = t - start.t;
  // Sliding lasts |s| / (mu g (1 + 1/kappa)): not at all without slip, for ever without friction.
  const double sliding = slip == 0.0 ? 0.0 : (mu_ == 0.0 ? tau : std::min(tau, std::abs(slip) / slip_decay_rate()));
  const double a = -std::copysign(mu_ * g_, slip), alpha = a / (kappa_ * R_);
  const double v = start.v + a * sliding, omega = start.omega + alpha * sliding;
  s.u[0] = start.x + start.v * sliding + 0.5 * a * sliding * sliding + v * (tau - sliding);
  s.u[2] = start.theta + start.omega * sliding + 0.5 * alpha * sliding * sliding + omega * (tau - sliding);
  s.v[0] = v;
  s.v[2] = omega;
}

std::optional<double> RollingDisk::event_time(ExactEvent event) const {
  if (event == ExactEvent::rest) return t_rest_;
  if (event == ExactEvent::roll_onset) return t_roll_;
  return std::nullopt;
}

std::optional<double> RollingDisk::value(ExactValue what) const {
  if (what == ExactValue::first_rebound_speed && !impacts_.empty()) return impacts_.front().v;
  return std::nullopt;
}

std::optional<State> RollingDisk::state(double t) const {
  State s;
  s.t = t;
  s.u = Vec::Zero(3);
  s.v = Vec::Zero(3);
  if (t >= t_rest_) {
    floor_motion(rest_, t, s);
    return s;
  }
  // In the air: horizontal motion from the last marched impact before t (or the start).
  const auto after = std::upper_bound(impacts_.begin(), impacts_.end(), t,
                                      [](double time, const Impact& im) { return time < im.t; });
  const Impact& from = after == impacts_.begin() ? start_ : *(after - 1);
  s.u[0] = from.x + from.v * (t - from.t);
  s.u[2] = from.theta + from.omega * (t - from.t);
  s.v[0] = from.v;
  s.v[2] = from.omega;
  if (t < t1_) {
    s.u[1] = h0_ - 0.5 * g_ * t * t;
    s.v[1] = -g_ * t;
    return s;
  }
  // Vertical: flight i >= 1 (t_i <= t < t_{i+1}); past the march, by the closed-form times.
  int i = static_cast<int>(after - impacts_.begin());
  if (e_ == 1.0) {
    i = std::max(i, 1 + static_cast<int>(std::floor((t - t1_) / (2.0 * V_ / g_))));
  } else {
    while (i < 100000 && impact_time(i + 1) <= t && impact_time(i + 1) > impact_time(i)) ++i;
  }
  const double speed = nsb::dmath::pow(e_, i) * V_;
  const double ds = t - impact_time(i);
  s.u[1] = speed * ds - 0.5 * g_ * ds * ds;
  s.v[1] = speed - g_ * ds;
  return s;
}

std::vector<std::string> RollingDisk::observable_names() const {
  return {"x", "v", "omega", "x_exact", "v_exact", "omega_exact", "slip", "slip_exact"};
}

void RollingDisk::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const State ex = *state(s.t);
  out[0] = s.u[0];
  out[1] = s.v[0];
  out[2] = s.v[2];
  out[3] = ex.u[0];
  out[4] = ex.v[0];
  out[5] = ex.v[2];
  out[6] = s.v[0] + R_ * s.v[2];
  out[7] = ex.v[0] + R_ * ex.v[2];
}

std::optional<FieldMesh> RollingDisk::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 2;
  mesh.add_vertex(0.0, R_, {0, 1}, 0);
  mesh.body_arrays = {{"radius", 1}, {"angle", 1}, {"angular_velocity", 1}, {"orientation", 3}};
  return mesh;
}

void RollingDisk::body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const {
  const double theta = s.u[2];
  out.row(0) << R_, theta, s.v[2], nsb::dmath::cos(theta), nsb::dmath::sin(theta), 0.0;
}

NSBENCH_PROBLEM({"rolling-disk", "rigid disk sliding, rolling and bouncing on a floor with Coulomb friction (exact solution)", &RollingDisk::parameters_spec, &make_from_params<Problem, RollingDisk>});

}  // namespace nsb
