#include "problems/two_bars.hpp"

#include "problems/bar_memory.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace nsb {

ParamSpecs TwoBars::parameters_spec() {
  constexpr double inf = 1e308;
  ParamSpecs specs{
      ParamSpec::real("L1", 1.0, 0.0, inf, "length of bar 1, the striker [m]", true),
      ParamSpec::real("L2", 2.0, 0.0, inf, "length of bar 2, at rest [m] (>= L1)", true),
      ParamSpec::integer("N1", 50, 1, 100'000'000, "linear elements of bar 1"),
      ParamSpec::integer("N2", 100, 1, 100'000'000, "linear elements of bar 2"),
      ParamSpec::real("v0", 1.0, 0.0, inf, "initial speed of bar 1 towards bar 2 [m/s]", true),
      ParamSpec::real("g0", 0.0, 0.0, inf, "initial gap between the bars [m]"),
  };
  const ParamSpecs material = bar_material_specs(1.0, 1.0, 1.0);
  specs.insert(specs.end(), material.begin(), material.end());
  specs.push_back(bar_mass_spec());
  return specs;
}

TwoBars::TwoBars(const Params& params)
    : params_(params),
      len1_(params.real("L1")),
      len2_(params.real("L2")),
      young_(params.real("E")),
      rho_(params.real("rho")),
      area_(params.real("A")),
      v0_(params.real("v0")),
      gap0_(params.real("g0")),
      n1_(params.integer("N1")),
      n2_(params.integer("N2")),
      model_(parse_bar_mass_model(params.choice("mass"))) {
  if (len2_ < len1_)
    throw InputError(fmt::format("problem two-bars: L2 = {} must be >= L1 = {} (the exact solution needs bar 2's "
                                 "reflected pulse to come back after the contact ends)", len2_, len1_));
  // Refused before anything of size N1 + N2 is allocated (problems/bar_memory.hpp).
  require_bar_memory(static_cast<double>(n1_) + static_cast<double>(n2_), fmt::format("two-bars: N1 + N2 = {} + {}", n1_, n2_),
                     "N1 + N2");
  c_ = std::sqrt(young_ / rho_);
  tc_ = gap0_ / v0_;
  ke1_.assign(static_cast<std::size_t>(n1_), young_ * area_ / element_size(1));
  ke2_.assign(static_cast<std::size_t>(n2_), young_ * area_ / element_size(2));
  const Index n = ndof();
  std::vector<Eigen::Triplet<double>> kt, mt;
  add_bar_triplets(dof(1, 0), ke1_, rho_ * area_ * element_size(1), model_, kt, mt);
  add_bar_triplets(dof(2, 0), ke2_, rho_ * area_ * element_size(2), model_, kt, mt);
  K_.resize(n, n);
  K_.setFromTriplets(kt.begin(), kt.end());
  M_.resize(n, n);
  M_.setFromTriplets(mt.begin(), mt.end());
  if (model_ == BarMassModel::Singular) {
    make_node_massless(M_, dof(1, n1_), dof(1, n1_ - 1));
    make_node_massless(M_, dof(2, 0), dof(2, 1));
  }
  M_.makeCompressed();
  mass_rows_ = M_ * Vec::Ones(n);

  contacts_.normal.resize(1, n);
  contacts_.normal.insert(0, dof(1, n1_)) = -1.0;
  contacts_.normal.insert(0, dof(2, 0)) = 1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Constant(1, gap0_);
}

double TwoBars::strain_energy(ConstVecRef u) const {
  return bar_strain_energy(u, dof(1, 0), ke1_) + bar_strain_energy(u, dof(2, 0), ke2_);
}

std::optional<FieldMesh> TwoBars::field_mesh() const {
  FieldMesh mesh;
  add_bar_field_mesh(mesh, 0.0, element_size(1), n1_, dof(1, 0), false, 0);
  add_bar_field_mesh(mesh, len1_ + gap0_, element_size(2), n2_, dof(2, 0), false, 1);
  return mesh;
}

void TwoBars::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  bar_stress(u, dof(1, 0), ke1_, area_, false, out.col(0).head(n1_));
  bar_stress(u, dof(2, 0), ke2_, area_, false, out.col(0).tail(n2_));
}

State TwoBars::initial_state() const {
  State s;
  s.u = Vec::Zero(ndof());
  s.v = Vec::Zero(ndof());
  s.v.head(n1_ + 1).setConstant(v0_);
  return s;
}

double TwoBars::stable_step() const {
  const double h = std::min(element_size(1), element_size(2));
  return model_ == BarMassModel::Consistent ? h / (std::sqrt(3.0) * c_) : h / c_;
}

double TwoBars::pulse_amplitude(double len, double s) const {
  if (s <= 0.0) return 0.0;
  const double period = 2.0 * len / c_, duration = 2.0 * len1_ / c_;
  return s - std::floor(s / period) * period < duration || period == duration ? 0.5 * v0_ : 0.0;
}

double TwoBars::pulse_integral(double len, double s) const {
  if (s <= 0.0) return 0.0;
  const double period = 2.0 * len / c_, duration = 2.0 * len1_ / c_;
  const double k = std::floor(s / period);
  return 0.5 * v0_ * (k * duration + std::min(s - k * period, duration));
}

double TwoBars::local_velocity(double len, double xi, double s) const {
  return pulse_amplitude(len, s - xi / c_) + pulse_amplitude(len, s - (2.0 * len - xi) / c_);
}

double TwoBars::local_displacement(double len, double xi, double s) const {
  return pulse_integral(len, s - xi / c_) + pulse_integral(len, s - (2.0 * len - xi) / c_);
}

double TwoBars::exact_displacement(int bar, double x, double t) const {
  const double s = t - tc_;
  return bar == 1 ? v0_ * t - local_displacement(len1_, len1_ - x, s) : local_displacement(len2_, x, s);
}

double TwoBars::exact_velocity(int bar, double x, double t) const {
  const double s = t - tc_;
  return bar == 1 ? v0_ - local_velocity(len1_, len1_ - x, s) : local_velocity(len2_, x, s);
}

double TwoBars::exact_stress(int bar, double x, double t) const {
  const double s = t - tc_, len = bar == 1 ? len1_ : len2_, xi = bar == 1 ? len1_ - x : x;
  return -rho_ * c_ * (pulse_amplitude(len, s - xi / c_) - pulse_amplitude(len, s - (2.0 * len - xi) / c_));
}

double TwoBars::exact_contact_force(double t) const {
  return t > tc_ && t < contact_end() ? contact_force_level() : 0.0;
}

double TwoBars::exact_mean_velocity(int bar, double t) const {
  const double impulse = contact_force_level() * std::clamp(t - tc_, 0.0, 2.0 * len1_ / c_);
  return bar == 1 ? v0_ - impulse / bar_mass(1) : impulse / bar_mass(2);
}

double TwoBars::mean_velocity(int bar, ConstVecRef v) const {
  const Index first = dof(bar, 0), count = (bar == 1 ? n1_ : n2_) + 1;
  return mass_rows_.segment(first, count).dot(v.segment(first, count)) / bar_mass(bar);
}

std::optional<State> TwoBars::state(double t) const {
  State s;
  s.t = t;
  s.u.resize(ndof());
  s.v.resize(ndof());
  for (int bar : {1, 2}) {
    const Index n = bar == 1 ? n1_ : n2_;
    const double h = element_size(bar);
    for (Index i = 0; i <= n; ++i) {
      const double x = static_cast<double>(i) * h;
      s.u[dof(bar, i)] = exact_displacement(bar, x, t);
      s.v[dof(bar, i)] = exact_velocity(bar, x, t);
    }
  }
  return s;
}

std::vector<double> TwoBars::impact_times(double t_end) const {
  if (tc_ <= t_end) return {tc_};
  return {};
}

std::vector<std::string> TwoBars::observable_names() const {
  return {"v1_mean", "v2_mean", "contact_force", "v1_mean_exact", "v2_mean_exact", "contact_force_exact",
          "momentum", "momentum_exact", "gap"};
}

void TwoBars::observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const {
  out[0] = mean_velocity(1, s.v);
  out[1] = mean_velocity(2, s.v);
  out[2] = dt > 0.0 ? impulses[0] / dt : 0.0;  // dt = 0: no step, no impulse
  out[3] = exact_mean_velocity(1, s.t);
  out[4] = exact_mean_velocity(2, s.t);
  out[5] = exact_contact_force(s.t);
  out[6] = momentum(s.v);
  out[7] = exact_momentum();
  out[8] = gap0_ + s.u[dof(2, 0)] - s.u[dof(1, n1_)];
}

NSBENCH_PROBLEM({"two-bars", "1D elastic bar striking an equal-material bar at rest (contact row on two bodies); mass lumped|consistent|singular (exact d'Alembert solution)", &TwoBars::parameters_spec, &make_from_params<Problem, TwoBars>});

}  // namespace nsb
