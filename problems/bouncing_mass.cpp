#include "problems/bouncing_mass.hpp"
#include "core/deterministic_math.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace nsb {

ParamSpecs BouncingMass::parameters_spec() {
  return {
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass [kg]", true),
      ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2]", true),
      ParamSpec::real("e", 0.9, 0.0, 1.0, "Newton restitution coefficient"),
      ParamSpec::real("h0", 1.0, 0.0, 1e308, "initial height [m]"),
      ParamSpec::real("v0", 0.0, -1e308, 1e308, "initial velocity, positive upwards [m/s]"),
  };
}

BouncingMass::BouncingMass(const Params& params)
    : params_(params),
      m_(params.real("m")),
      g_(params.real("g")),
      e_(params.real("e")),
      h0_(params.real("h0")),
      v0_(params.real("v0")) {
  w1_ = std::sqrt(v0_ * v0_ + 2.0 * g_ * h0_);
  t1_ = (v0_ + w1_) / g_;
  contacts_.normal.resize(1, 1);
  contacts_.normal.insert(0, 0) = 1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Zero(1);
  contacts_.restitution = e_;
  mass_ = Vec::Constant(1, m_);
  load_ = Vec::Constant(1, -m_ * g_);
  // The flights' start times t_1, t_2, ... up to the first that does not increase (the sum
  // stalls in floating point before the Zeno time) or the 100000th: state(t) used to walk them
  // from t_1 at every call, two pow each, and a study reads the exact state at every step.
  if (e_ < 1.0) {
    impacts_.push_back(t1_);
    for (int i = 1; i < kMaxFlights; ++i) {
      const double next = impact_time(i + 1);
      if (next <= impacts_.back()) break;
      impacts_.push_back(next);
    }
  }
}

State BouncingMass::initial_state() const {
  State s;
  s.u = Vec::Constant(1, h0_);
  s.v = Vec::Constant(1, v0_);
  return s;
}

double BouncingMass::impact_time(int i) const {
  if (i <= 1) return t1_;
  const double flights = (e_ == 1.0) ? (i - 1) : e_ * (1.0 - nsb::dmath::pow(e_, i - 1)) / (1.0 - e_);
  return t1_ + 2.0 * w1_ / g_ * flights;
}

// Every impact up to t_end: for e < 1 the tabulated flights (all that floating point tells
// apart, unless the table is full); for e = 1 the first kMaxFlights (none at rest, w1 = 0).
// A finite t_end past the last of those, with impacts still to come, is refused: a shorter
// list would pass for all of them.
std::vector<double> BouncingMass::impact_times(double t_end) const {
  if (w1_ == 0.0) return {};
  const bool endless = e_ == 1.0 || impacts_.size() == static_cast<std::size_t>(kMaxFlights);
  const double last = e_ == 1.0 ? impact_time(kMaxFlights) : impacts_.back();
  if (endless && std::isfinite(t_end) && t_end > last && t_end < zeno_time())
    throw InputError(fmt::format("bouncing-mass exact solution: impact_times(t_end = {:.6g}) asks past its {}th impact (e = {:.6g}); "
                                 "valid: t_end <= {:.9g}, or inf for the first {}",
                                 t_end, kMaxFlights, e_, last, kMaxFlights));
  std::vector<double> times;
  if (e_ == 1.0) {
    for (int i = 1; i <= kMaxFlights && impact_time(i) <= t_end; ++i) times.push_back(impact_time(i));
    return times;
  }
  for (const double t : impacts_)
    if (t <= t_end && t < zeno_time()) times.push_back(t);
  return times;
}

std::vector<double> BouncingMass::energies_after_impacts(double t_end) const {
  std::vector<double> energies;
  const std::size_t impacts = impact_times(t_end).size();
  for (std::size_t i = 1; i <= impacts; ++i) energies.push_back(energy_after_impact(static_cast<int>(i)));
  return energies;
}

double BouncingMass::zeno_time() const {
  if (e_ == 1.0) return std::numeric_limits<double>::infinity();
  return t1_ + 2.0 * e_ * w1_ / (g_ * (1.0 - e_));
}

std::vector<std::pair<std::string, double>> BouncingMass::summary_values() const { return {{"t_zeno_exact", zeno_time()}}; }

double BouncingMass::energy_after_impact(int i) const {
  return initial_energy() * nsb::dmath::pow(e_, 2 * i);
}

void BouncingMass::exact_qv(double t, double& q, double& v) const {
  if (t < t1_) {
    q = h0_ + v0_ * t - 0.5 * g_ * t * t;
    v = v0_ - g_ * t;
    return;
  }
  if (t >= zeno_time()) {
    q = 0.0;
    v = 0.0;
    return;
  }
  // Flight index i: t_i <= t < t_{i+1}. For e = 1 the period is constant; for e < 1 the
  // flights shrink geometrically: the last tabulated start at or before t (impacts_ increases).
  int i = 1;
  double ti = t1_;
  if (e_ == 1.0) {
    i = 1 + static_cast<int>(std::floor((t - t1_) / (2.0 * w1_ / g_)));
    ti = impact_time(i);
  } else {
    const auto after = std::upper_bound(impacts_.begin() + 1, impacts_.end(), t);
    i = static_cast<int>(after - impacts_.begin());
    ti = impacts_[static_cast<std::size_t>(i - 1)];
  }
  const double speed = nsb::dmath::pow(e_, i) * w1_;
  const double ds = t - ti;
  q = speed * ds - 0.5 * g_ * ds * ds;
  v = speed - g_ * ds;
}

std::optional<State> BouncingMass::state(double t) const {
  State s;
  s.t = t;
  s.u.resize(1);
  s.v.resize(1);
  exact_qv(t, s.u[0], s.v[0]);
  return s;
}

std::vector<std::string> BouncingMass::observable_names() const {
  return {"q", "v", "q_exact", "v_exact"};
}

void BouncingMass::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  out[0] = s.u[0];
  out[1] = s.v[0];
  exact_qv(s.t, out[2], out[3]);  // no State: observe() runs at every step of a study's run
}

std::optional<FieldMesh> BouncingMass::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 2;
  mesh.add_vertex(0.0, 0.0, {-1, 0}, 0);
  return mesh;
}

NSBENCH_PROBLEM({"bouncing-mass", "point mass bouncing on a rigid floor under gravity (exact solution)", &BouncingMass::parameters_spec, &make_from_params<Problem, BouncingMass>});

}  // namespace nsb
