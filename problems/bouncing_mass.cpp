#include "problems/bouncing_mass.hpp"
#include "problems/registry.hpp"

#include <cmath>
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
}

State BouncingMass::initial_state() const {
  State s;
  s.u = Vec::Constant(1, h0_);
  s.v = Vec::Constant(1, v0_);
  return s;
}

double BouncingMass::impact_time(int i) const {
  if (i <= 1) return t1_;
  const double flights = (e_ == 1.0) ? (i - 1) : e_ * (1.0 - std::pow(e_, i - 1)) / (1.0 - e_);
  return t1_ + 2.0 * w1_ / g_ * flights;
}

std::vector<double> BouncingMass::impact_times(double t_end) const {
  std::vector<double> times;
  for (int i = 1; i <= 1000 && impact_time(i) <= t_end && impact_time(i) < zeno_time(); ++i) times.push_back(impact_time(i));
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
  return initial_energy() * std::pow(e_, 2 * i);
}

std::optional<State> BouncingMass::state(double t) const {
  State s;
  s.t = t;
  s.u.resize(1);
  s.v.resize(1);
  if (t < t1_) {
    s.u[0] = h0_ + v0_ * t - 0.5 * g_ * t * t;
    s.v[0] = v0_ - g_ * t;
    return s;
  }
  if (t >= zeno_time()) {
    s.u[0] = 0.0;
    s.v[0] = 0.0;
    return s;
  }
  // Flight index i: t_i <= t < t_{i+1}. For e = 1 the period is constant; for e < 1 the
  // flights shrink geometrically, so a short walk finds i (bounded by underflow of e^i).
  int i = 1;
  if (e_ == 1.0) {
    i = 1 + static_cast<int>(std::floor((t - t1_) / (2.0 * w1_ / g_)));
  } else {
    while (i < 100000 && impact_time(i + 1) <= t && impact_time(i + 1) > impact_time(i)) ++i;
  }
  const double speed = std::pow(e_, i) * w1_;
  const double ds = t - impact_time(i);
  s.u[0] = speed * ds - 0.5 * g_ * ds * ds;
  s.v[0] = speed - g_ * ds;
  return s;
}

std::vector<std::string> BouncingMass::observable_names() const {
  return {"q", "v", "q_exact", "v_exact"};
}

void BouncingMass::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const State ex = *state(s.t);
  out[0] = s.u[0];
  out[1] = s.v[0];
  out[2] = ex.u[0];
  out[3] = ex.v[0];
}

std::optional<FieldMesh> BouncingMass::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 2;
  mesh.add_vertex(0.0, 0.0, {-1, 0}, 0);
  return mesh;
}

NSBENCH_PROBLEM({"bouncing-mass", "point mass bouncing on a rigid floor under gravity (exact solution)", &BouncingMass::parameters_spec, &make_from_params<Problem, BouncingMass>});

}  // namespace nsb
