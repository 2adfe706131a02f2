#include "problems/signorini_bar.hpp"
#include "problems/bouncing_bar.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "core/threads.hpp"
#include "problems/bar_memory.hpp"

namespace nsb {

namespace {

struct Defaults {
  double L, E, rho, A, v0, g0, g = 0.0;
  Index N = 100;
};

ParamSpecs bar_spec(const Defaults& d) {
  constexpr double inf = 1e308;
  ParamSpecs specs{ParamSpec::real("L", d.L, 0.0, inf, "bar length [m]", true)};
  const ParamSpecs material = bar_material_specs(d.E, d.rho, d.A);
  specs.insert(specs.end(), material.begin(), material.end());
  specs.insert(specs.end(), {
      ParamSpec::real("v0", d.v0, 0.0, inf, "initial speed towards the wall [m/s] (0: a drop from rest, under gravity g)"),
      ParamSpec::real("g0", d.g0, 0.0, inf, "initial gap to the wall [m]"),
      ParamSpec::real("g", d.g, 0.0, inf, "gravity towards the wall [m/s^2] (repeated bouncing; exact solution: problems/bouncing_bar.hpp)"),
      ParamSpec::integer("N", d.N, 1, 100'000'000, "number of linear elements"),
      bar_mass_spec(),
      ParamSpec::real("stiff_ratio", 1.0, 0.0, 1e12,
                      "Young's modulus of the half at the wall over E (stiff/soft bar; no exact solution unless 1)", true),
      ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient of the contact node (no effect on a massless node)"),
  });
  return specs;
}

}  // namespace

ParamSpecs SignoriniBar::parameters_spec() { return bar_spec({1.0, 1.0, 1.0, 1.0, 1.0, 0.0}); }

ParamSpecs SignoriniBar::steel_parameters_spec() { return bar_spec({1.0, 210e9, 7800.0, 3.14e-4, 0.1, 5e-5}); }

std::unique_ptr<Problem> SignoriniBar::make_steel(const Params& params) {
  return std::make_unique<SignoriniBar>(params, "signorini-bar-steel");
}

ParamSpecs SignoriniBar::bouncing_parameters_spec() { return bar_spec({10.0, 900.0, 1.0, 1.0, 0.0, 5.0, 10.0, 100}); }

std::unique_ptr<Problem> SignoriniBar::make_bouncing(const Params& params) {
  return std::make_unique<SignoriniBar>(params, "bouncing-bar");
}

SignoriniBar::SignoriniBar(const Params& params, std::string name)
    : name_(std::move(name)),
      params_(params),
      len_(params.real("L")),
      young_(params.real("E")),
      rho_(params.real("rho")),
      area_(params.real("A")),
      v0_(params.real("v0")),
      gap0_(params.real("g0")),
      gravity_(params.real("g")),
      n_(params.integer("N")),
      model_(parse_bar_mass_model(params.choice("mass"))),
      stiff_ratio_(params.real("stiff_ratio")) {
  // Refused before anything of size N is allocated (problems/bar_memory.hpp).
  require_bar_memory(static_cast<double>(n_), fmt::format("{}: N = {}", name_, n_), "N");
  c_ = std::sqrt(young_ / rho_);
  check_representable();
  t0_ = v0_ > 0.0 ? gap0_ / v0_ : (gap0_ > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);  // at rest: never / now
  const double h = element_size();
  ke_.resize(static_cast<std::size_t>(n_));
  for (Index e = 0; e < n_; ++e)
    ke_[e] = young_ * area_ / h * ((static_cast<double>(e) + 0.5) * h < 0.5 * len_ ? stiff_ratio_ : 1.0);
  const double me = rho_ * area_ * h;  // element mass
  const Index n = ndof();

  std::vector<Eigen::Triplet<double>> kt, mt;
  kt.reserve(4 * n_);
  mt.reserve(4 * n_);
  add_bar_triplets(0, ke_, me, model_, kt, mt);
  K_.resize(n, n);
  K_.setFromTriplets(kt.begin(), kt.end());
  M_.resize(n, n);
  M_.setFromTriplets(mt.begin(), mt.end());
  // The contact node's mass goes to node 1 (header: what is kept and what is not).
  if (model_ == MassModel::Singular) make_node_massless(M_, 0, 1);
  M_.makeCompressed();
  mass_rows_ = M_ * Vec::Ones(n);

  contacts_.normal.resize(1, n);
  contacts_.normal.insert(0, 0) = 1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Constant(1, gap0_);
  contacts_.restitution = params.real("e");
}

// Each parameter may be in range and their products not (L = 1e308 made the momentum -inf in
// every row): the quantities the run and the exact solution compute must be finite doubles,
// and the masses and stiffnesses positive (an underflow to 0 would make M singular).
void SignoriniBar::check_representable() const {
  const double h = element_size(), m = total_mass(), v = std::max(v0_, std::sqrt(2.0 * gravity_ * gap0_));
  const std::pair<const char*, double> positive[] = {
      {"c = sqrt(E / rho)", c_}, {"the mass rho A L", m}, {"an element's mass rho A L / N", rho_ * area_ * h},
      {"an element's stiffness E A N / L", young_ * area_ / h * std::max(stiff_ratio_, 1.0)}};
  const std::pair<const char*, double> finite[] = {
      {"the momentum rho A L (v0 + g t)", m * (v + gravity_ * len_ / c_)}, {"the energy rho A L v^2 / 2", 0.5 * m * v * v},
      {"the contact force rho A c v", rho_ * area_ * c_ * v}, {"the weight's work rho A L g (g0 + L)", m * gravity_ * (gap0_ + len_)}};
  for (const auto& [what, x] : positive)
    if (!(x > 0.0) || !std::isfinite(x))
      throw InputError(fmt::format("{}: these parameters make {} = {:g}, outside the positive finite doubles; valid: "
                                   "parameters whose products stay within about 1e-300 to 1e300", name_, what, x));
  for (const auto& [what, x] : finite)
    if (!std::isfinite(x))
      throw InputError(fmt::format("{}: these parameters make {} = {:g}, beyond the largest double; valid: parameters "
                                   "whose products stay below about 1e300", name_, what, x));
}

std::optional<FieldMesh> SignoriniBar::field_mesh() const {
  FieldMesh mesh;
  add_bar_field_mesh(mesh, 0.0, element_size(), n_, 0, false, 0);
  return mesh;
}

void SignoriniBar::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  bar_stress(u, 0, ke_, area_, false, out.col(0));
}

// Element loop written as a tridiagonal stencil: one pass, no matrix, no allocation.
void SignoriniBar::internal_force(ConstVecRef u, VecRef f) const {
  const Index n = n_;
  const double* x = u.data();
  const double* k = ke_.data();
  double* y = f.data();
  y[0] = k[0] * (x[0] - x[1]);
  y[n] = k[n - 1] * (x[n] - x[n - 1]);
  // Each node's force from its two elements: every entry written once, whatever the split.
  parallel_ranges(n - 1, [&](Index begin, Index end) {
    for (Index i = begin + 1; i < end + 1; ++i) y[i] = k[i - 1] * (x[i] - x[i - 1]) + k[i] * (x[i] - x[i + 1]);
  });
}

double SignoriniBar::strain_energy(ConstVecRef u) const { return bar_strain_energy(u, 0, ke_); }

State SignoriniBar::initial_state() const {
  State s;
  s.u = Vec::Zero(ndof());
  s.v = Vec::Constant(ndof(), -v0_);
  return s;
}

double SignoriniBar::stable_step() const {
  const double h = element_size(), c = c_ * std::sqrt(std::max(stiff_ratio_, 1.0));
  return model_ == MassModel::Consistent ? h / (std::sqrt(3.0) * c) : h / c;
}

double SignoriniBar::exact_displacement(double x, double t) const {
  const double s = t - t0_, T = contact_duration();
  if (s <= x / c_) return -v0_ * t;
  if (s < (2.0 * len_ - x) / c_) return -gap0_ - v0_ * x / c_;
  if (s <= T) return -gap0_ - v0_ * x / c_ + v0_ * (s - (2.0 * len_ - x) / c_);
  return -gap0_ + v0_ * (s - T);
}

double SignoriniBar::exact_velocity(double x, double t) const {
  const double s = t - t0_;
  if (s <= x / c_) return -v0_;
  if (s < (2.0 * len_ - x) / c_) return 0.0;
  return v0_;
}

double SignoriniBar::exact_stress(double x, double t) const {
  const double s = t - t0_;
  return (s > x / c_ && s < (2.0 * len_ - x) / c_) ? -rho_ * c_ * v0_ : 0.0;
}

double SignoriniBar::exact_contact_force(double t) const {
  const double s = t - t0_;
  return (s > 0.0 && s < contact_duration()) ? contact_force_level() : 0.0;
}

double SignoriniBar::exact_momentum(double t) const {
  const double s = std::clamp(t - t0_, 0.0, contact_duration());
  return -total_mass() * v0_ + contact_force_level() * s;
}

const BouncingBarExact& SignoriniBar::bouncing_exact(double t) const {
  const std::lock_guard lock(bouncing_mutex_);
  if (!bouncing_ || t > bouncing_->t_end()) {
    // Built ahead, doubling: a run asks for increasing times, so the march is redone
    // O(log t_end) times (the first horizon covers a few periods of DEP's bar).
    const double horizon = std::max({t, 2.0 * (bouncing_ ? bouncing_->t_end() : 0.0), 64.0 * len_ / c_});
    bouncing_ = std::make_shared<const BouncingBarExact>(params_, horizon);
  }
  return *bouncing_;
}

std::optional<double> SignoriniBar::event_time(ExactEvent event) const {
  if (event != ExactEvent::contact_start) return std::nullopt;
  if (gravity_ == 0.0) return contact_start();
  // The fall's end t1 (BouncingBarExact), which holds only for the uniform bar it solves.
  return stiff_ratio_ == 1.0 ? std::optional<double>(bouncing_exact(0.0).impact_time()) : std::nullopt;
}

std::optional<double> SignoriniBar::value(ExactValue what) const {
  if (what == ExactValue::wave_time) return stiff_ratio_ == 1.0 ? std::optional<double>(len_ / c_) : std::nullopt;
  return what == ExactValue::contact_duration ? std::optional<double>(contact_duration()) : std::nullopt;
}

bool SignoriniBar::exact_cell_stress(double t, Eigen::Ref<Eigen::MatrixXd> out) const {
  if (stiff_ratio_ != 1.0 || gravity_ > 0.0 || !(t >= 0.0)) return false;  // no d'Alembert solution
  const FieldMesh mesh = *field_mesh();
  for (Index e = 0; e < mesh.ncells(); ++e)
    out(e, 0) = exact_stress(0.5 * (mesh.points(mesh.cells(e, 0), 0) + mesh.points(mesh.cells(e, 1), 0)), t);
  return true;
}

std::optional<State> SignoriniBar::state(double t) const {
  if (stiff_ratio_ != 1.0 || !(t >= 0.0)) return std::nullopt;
  const BouncingBarExact* bouncing = gravity_ > 0.0 ? &bouncing_exact(t) : nullptr;
  State s;
  s.t = t;
  s.u.resize(ndof());
  s.v.resize(ndof());
  const double h = element_size();
  for (Index i = 0; i <= n_; ++i) {
    const double x = static_cast<double>(i) * h;
    s.u[i] = bouncing ? bouncing->displacement(x, t) : exact_displacement(x, t);
    s.v[i] = bouncing ? bouncing->velocity(x, t) : exact_velocity(x, t);
  }
  return s;
}

// state(t)'s node 0 is at x = 0 * h = 0, observe() reads u[0] and v[0] there, and the *_exact
// observables are the same functions at x = 0: the values below are observe()'s on state(t).
std::optional<double> SignoriniBar::observable(std::string_view name, double t) const {
  const bool u = name == "u_contact" || name == "u_contact_exact", v = name == "v_contact" || name == "v_contact_exact";
  const bool force = name == "contact_force_exact";
  // A name not offered returns before bouncing_exact's lock: the caller then takes state(t).
  if (!(u || v || force) || stiff_ratio_ != 1.0 || !(t >= 0.0)) return std::nullopt;  // as state(t)
  const BouncingBarExact* bouncing = gravity_ > 0.0 ? &bouncing_exact(t) : nullptr;
  if (u) return bouncing ? bouncing->displacement(0.0, t) : exact_displacement(0.0, t);
  if (v) return bouncing ? bouncing->velocity(0.0, t) : exact_velocity(0.0, t);
  return bouncing ? bouncing->contact_force(t) : exact_contact_force(t);
}

std::vector<std::string> SignoriniBar::observable_names() const {
  return {"u_contact", "v_contact", "contact_force", "u_contact_exact", "v_contact_exact",
          "contact_force_exact", "momentum", "momentum_exact"};
}

void SignoriniBar::write_observables(double t, double u_contact, double v_contact, double momentum, bool with_exact,
                                     std::span<double> out) const {
  out[0] = u_contact;
  out[1] = v_contact;
  out[2] = 0.0;  // no step, no impulse
  out[6] = momentum;
  if (!with_exact || stiff_ratio_ != 1.0 || !(t >= 0.0)) {  // no exact solution
    out[3] = out[4] = out[5] = out[7] = NAN;
  } else if (gravity_ > 0.0) {
    const BouncingBarExact& b = bouncing_exact(t);
    out[3] = b.displacement(0.0, t);
    out[4] = b.velocity(0.0, t);
    out[5] = b.contact_force(t);
    out[7] = b.momentum(t);
  } else {
    out[3] = exact_displacement(0.0, t);
    out[4] = exact_velocity(0.0, t);
    out[5] = exact_contact_force(t);
    out[7] = exact_momentum(t);
  }
}

void SignoriniBar::observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const {
  write_observables(s.t, s.u[0], s.v[0], momentum(s.v), true, out);
  if (dt > 0.0) out[2] = impulses[0] / dt;
}

NSBENCH_PROBLEM({"signorini-bar", "1D elastic bar hitting a rigid wall, nondimensional; mass lumped|consistent|singular (exact d'Alembert solution)", &SignoriniBar::parameters_spec, &make_from_params<Problem, SignoriniBar>});
NSBENCH_PROBLEM({"signorini-bar-steel", "the Signorini bar with steel defaults (L 1 m, E 210 GPa, rho 7800, A 3.14e-4 m^2, v0 0.1 m/s, g0 5e-5 m)", &SignoriniBar::steel_parameters_spec, &SignoriniBar::make_steel});
NSBENCH_PROBLEM({"bouncing-bar", "Doyen-Ern-Piperno bouncing bar: the Signorini bar (L 10, E 900, rho 1) dropped from rest 5 m above the wall, g 10 (exact solution, period 16 L/c)", &SignoriniBar::bouncing_parameters_spec, &SignoriniBar::make_bouncing});

}  // namespace nsb
