#include "problems/sliding_mass.hpp"
#include "core/deterministic_math.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace nsb {

ParamSpecs SlidingMass::parameters_spec() {
  return {
      ParamSpec::real("alpha", 20.0, 0.0, 90.0, "slope angle [deg]", false, true),
      ParamSpec::real("mu", 0.5, 0.0, 1e308, "Coulomb friction coefficient (0: frictionless)"),
      ParamSpec::real("v0", 2.0, -1e308, 1e308, "initial speed along the slope, positive down it [m/s]"),
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass [kg]", true),
      ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2]", true),
  };
}

SlidingMass::SlidingMass(const Params& params)
    : params_(params),
      alpha_(params.real("alpha") * std::numbers::pi / 180.0),
      mu_(params.real("mu")),
      v0_(params.real("v0")),
      m_(params.real("m")),
      g_(params.real("g")) {
  const double sin_a = nsb::dmath::sin(alpha_), cos_a = nsb::dmath::cos(alpha_), tan_a = nsb::dmath::tan(alpha_);
  // tan(alpha) of an angle in degrees carries a few rounding errors (tan(45 deg) is 1 - 2^-53),
  // so a mu typed as tan(alpha) is the limit case a_down = 0, not a slow stop or a slow slide.
  const bool limit = std::abs(tan_a - mu_) <= 8.0 * std::numeric_limits<double>::epsilon() * std::max(tan_a, mu_);
  a_down_ = limit ? 0.0 : g_ * (sin_a - mu_ * cos_a);
  sticks_ = limit || tan_a <= mu_;
  const double a_up = g_ * (sin_a + mu_ * cos_a);
  a_first_ = v0_ > 0.0 ? a_down_ : (v0_ < 0.0 ? a_up : 0.0);
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (v0_ == 0.0) {
    t_stop_ = 0.0;
    d_stop_ = 0.0;
  } else if (a_first_ * v0_ < 0.0) {
    t_stop_ = -v0_ / a_first_;
    d_stop_ = v0_ * v0_ / (2.0 * std::abs(a_first_));
  } else {
    t_stop_ = inf;
    d_stop_ = inf;
  }
  x_stop_ = std::copysign(d_stop_, v0_);
  mass_ = Vec::Constant(2, m_);
  load_ = Vec(2);
  load_ << m_ * g_ * sin_a, -m_ * g_ * cos_a;

  contacts_.normal.resize(1, 2);
  contacts_.normal.insert(0, 1) = 1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Zero(1);
  contacts_.restitution = 0.0;
  // Friction only when mu > 0, so that mu = 0 is described exactly like a frictionless problem.
  if (mu_ > 0.0) {
    SpMat T(1, 2);
    T.insert(0, 0) = 1.0;
    contacts_.set_friction(std::move(T), mu_, 0.0);
  }
}

State SlidingMass::initial_state() const {
  State s;
  s.u = Vec::Zero(2);
  s.v = Vec::Zero(2);
  s.v[0] = v0_;
  return s;
}

std::optional<double> SlidingMass::event_time(ExactEvent event) const {
  return event == ExactEvent::slip_stop ? std::optional<double>(t_stop_) : std::nullopt;
}

std::optional<double> SlidingMass::value(ExactValue what) const {
  if (what == ExactValue::stop_distance) return d_stop_;
  if (what == ExactValue::stays_stopped) return sticks_ ? 1.0 : 0.0;
  return std::nullopt;
}

std::optional<State> SlidingMass::state(double t) const {
  State s;
  s.t = t;
  s.u = Vec::Zero(2);
  s.v = Vec::Zero(2);
  if (t <= t_stop_) {
    s.u[0] = v0_ * t + 0.5 * a_first_ * t * t;
    s.v[0] = v0_ + a_first_ * t;
  } else if (sticks_) {
    s.u[0] = x_stop_;
  } else {
    const double dt = t - t_stop_;
    s.u[0] = x_stop_ + 0.5 * a_down_ * dt * dt;
    s.v[0] = a_down_ * dt;
  }
  return s;
}

std::vector<std::string> SlidingMass::observable_names() const { return {"x", "v", "x_exact", "v_exact"}; }

void SlidingMass::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const State ex = *state(s.t);
  out[0] = s.u[0];
  out[1] = s.v[0];
  out[2] = ex.u[0];
  out[3] = ex.v[0];
}

std::optional<FieldMesh> SlidingMass::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 2;
  mesh.add_vertex(0.0, 0.0, {0, 1}, 0);
  return mesh;
}

NSBENCH_PROBLEM({"sliding-mass", "point mass sliding on an inclined plane with Coulomb friction (exact solution)", &SlidingMass::parameters_spec, &make_from_params<Problem, SlidingMass>});

}  // namespace nsb
