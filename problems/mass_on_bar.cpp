#include "problems/mass_on_bar.hpp"
#include "core/deterministic_math.hpp"

#include "problems/bar_memory.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <fmt/format.h>

namespace nsb {

namespace {

// Polynomials in tau, coefficients lowest degree first.
using Poly = std::vector<double>;

double eval(const Poly& p, double x) {
  double y = 0.0;
  for (auto it = p.rbegin(); it != p.rend(); ++it) y = y * x + *it;
  return y;
}

// int_0^tau p
Poly antiderivative(const Poly& p) {
  Poly q(p.size() + 1, 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) q[k + 1] = p[k] / static_cast<double>(k + 1);
  return q;
}

// a p + b q
Poly combine(double a, const Poly& p, double b, const Poly& q) {
  Poly r(std::max(p.size(), q.size()), 0.0);
  for (std::size_t k = 0; k < p.size(); ++k) r[k] += a * p[k];
  for (std::size_t k = 0; k < q.size(); ++k) r[k] += b * q[k];
  return r;
}

// p(x + d), coefficients by repeated synthetic division (Taylor shift).
Poly shift(Poly p, double d) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = n - 1; k > i; --k) p[k - 1] += d * p[k];
  return p;
}

// int_0^x e^{-s} p(s) ds = S(0) - e^{-x} S(x), S = p + p' + p'' + ...
double exp_integral(const Poly& p, double x) {
  Poly d = p, sum(p.size(), 0.0);
  while (!d.empty()) {
    for (std::size_t k = 0; k < d.size(); ++k) sum[k] += d[k];
    Poly next(d.size() > 1 ? d.size() - 1 : 0);
    for (std::size_t k = 1; k < d.size(); ++k) next[k - 1] = d[k] * static_cast<double>(k);
    d = std::move(next);
  }
  return eval(sum, 0.0) - nsb::dmath::exp(-x) * eval(sum, x);
}

// The first x in (0, end] where f(x) < 0, or nullopt: sampled, then bisected.
template <class F>
std::optional<double> first_negative(const F& f, double end) {
  constexpr int samples = 512;
  double lo = 0.0;
  for (int i = 1; i <= samples; ++i) {
    const double hi = end * i / samples;
    if (f(hi) < 0.0) {
      double a = lo, b = hi;
      for (int k = 0; k < 200 && b - a > 1e-15 * end; ++k) {
        const double m = 0.5 * (a + b);
        (f(m) >= 0.0 ? a : b) = m;
      }
      return 0.5 * (a + b);
    }
    lo = hi;
  }
  return std::nullopt;
}

// A safeguard on the sweep (the M range keeps it far below: a few hundred pieces at most).
constexpr std::size_t max_pieces = 20000;

}  // namespace

ParamSpecs MassOnBar::parameters_spec() {
  constexpr double inf = 1e308;
  ParamSpecs specs{
      ParamSpec::real("M", 1.0, 0.0, inf, "striking mass [kg] (1: the default bar's mass; first contact over before 4L/c iff M < 1.728 rho A L)", true),
      ParamSpec::real("v0", 1.0, 0.0, inf, "the mass's initial speed towards the bar [m/s]", true),
      ParamSpec::real("L", 1.0, 0.0, inf, "bar length [m]", true),
  };
  const ParamSpecs material = bar_material_specs(1.0, 1.0, 1.0);
  specs.insert(specs.end(), material.begin(), material.end());
  specs.push_back(ParamSpec::integer("N", 100, 2, 100'000'000, "number of linear elements"));
  specs.push_back(bar_mass_spec());
  return specs;
}

MassOnBar::MassOnBar(const Params& params)
    : params_(params),
      mass_(params.real("M")),
      v0_(params.real("v0")),
      len_(params.real("L")),
      young_(params.real("E")),
      rho_(params.real("rho")),
      area_(params.real("A")),
      n_(params.integer("N")),
      model_(parse_bar_mass_model(params.choice("mass"))) {
  require_bar_memory(static_cast<double>(n_), fmt::format("mass-on-bar: N = {}", n_), "N");  // before allocating
  c_ = std::sqrt(young_ / rho_);
  theta_ = mass_ / impedance();
  // The exact solution's sweep is checked and fast (< 0.2 s) over this range; a heavier mass
  // stays in contact for hundreds of round trips of ever higher degree.
  if (!(mass_ >= 0.01 * bar_mass() && mass_ <= 100.0 * bar_mass()))
    throw InputError(fmt::format("problem mass-on-bar: M = {} must be within [0.01, 100] x the bar's mass rho A L = "
                                 "[{}, {}]", mass_, 0.01 * bar_mass(), 100.0 * bar_mass()));

  sweep_exact();

  const double h = len_ / static_cast<double>(n_);
  ke_.assign(static_cast<std::size_t>(n_), young_ * area_ / h);
  std::vector<Eigen::Triplet<double>> kt, mt;
  add_bar_triplets(0, ke_, rho_ * area_ * h, model_, kt, mt);
  // Node N is clamped: its rows and columns go, and dof N becomes the striking mass.
  const auto clamped = [&](const Eigen::Triplet<double>& e) { return e.row() == n_ || e.col() == n_; };
  std::erase_if(kt, clamped);
  std::erase_if(mt, clamped);
  mt.emplace_back(n_, n_, mass_);
  const Index n = ndof();
  K_.resize(n, n);
  K_.setFromTriplets(kt.begin(), kt.end());
  M_.resize(n, n);
  M_.setFromTriplets(mt.begin(), mt.end());
  if (model_ == BarMassModel::Singular) make_node_massless(M_, 0, 1);
  M_.makeCompressed();

  contacts_.normal.resize(1, n);
  contacts_.normal.insert(0, 0) = 1.0;
  contacts_.normal.insert(0, n_) = -1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Zero(1);
}

double MassOnBar::strain_energy(ConstVecRef u) const {
  // Elements 0..N-2 between free nodes, then the last one to the clamp (u_N = 0).
  const double last = u[n_ - 1];
  return bar_strain_energy(u, 0, std::span<const double>(ke_).first(static_cast<std::size_t>(n_ - 1))) +
         0.5 * ke_.back() * last * last;
}

std::optional<FieldMesh> MassOnBar::field_mesh() const {
  FieldMesh mesh;
  add_bar_field_mesh(mesh, 0.0, len_ / static_cast<double>(n_), n_, 0, true, 0);
  mesh.add_vertex(0.0, 0.0, {static_cast<int>(n_)}, 1);
  return mesh;
}

void MassOnBar::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  bar_stress(u, 0, ke_, area_, true, out.col(0));
}

State MassOnBar::initial_state() const {
  State s;
  s.u = Vec::Zero(ndof());
  s.v = Vec::Zero(ndof());
  s.v[n_] = v0_;
  return s;
}

double MassOnBar::stable_step() const {
  const double h = len_ / static_cast<double>(n_);
  return model_ == BarMassModel::Consistent ? h / (std::sqrt(3.0) * c_) : h / c_;
}

void MassOnBar::sweep_exact() {
  // a(t) = v0 e^{-(t - t0)/theta} poly((t - t0)/theta) on [t0, t1): the wave leaving x = 0.
  struct Piece {
    double t0, t1;
    Poly poly;
  };
  std::vector<Piece> out;
  const double T = round_trip();
  const double reach = std::sqrt(2.0 * len_ * exact_energy() / (young_ * area_));  // max |u(0, t)|
  double t = 0.0, V = v0_, X = 0.0, gap = 0.0;
  bool contact = true;
  for (;;) {
    if (out.size() > max_pieces)
      throw std::logic_error(fmt::format("mass-on-bar exact solution: more than {} pieces (M = {})", max_pieces, mass_));
    // The incoming wave b(t) = -a(t - T) on the piece holding t (zero before the first return).
    double end = T;
    Poly B{0.0};
    const auto it = std::upper_bound(out.begin(), out.end(), t - T, [&](double x, const Piece& p) { return x < p.t1; });
    if (t >= T && it != out.end()) {
      const double d = (t - T - it->t0) / theta_;
      B = combine(-nsb::dmath::exp(-d), shift(it->poly, d), 0.0, {});
      end = it->t1 + T;
    }
    const double width = (end - t) / theta_;
    if (contact) {
      const Poly P = combine(1.0, Poly{V / v0_}, 2.0, antiderivative(B));
      Poly force = combine(1.0, P, -2.0, B);
      const auto zero = first_negative([&](double x) { return eval(force, x); }, width);
      const double x = zero.value_or(width);
      out.push_back({t, t + x * theta_, combine(1.0, P, -1.0, B)});
      segments_.push_back({t, true, P, std::move(force), 0.0});
      X += v0_ * theta_ * exp_integral(P, x);
      V = v0_ * nsb::dmath::exp(-x) * eval(P, x);
      t += x * theta_;
      if (zero) {
        contact = false;
        gap = 0.0;
        if (first_separation_ == 0.0) first_separation_ = t;
        segments_.push_back({t, false, {}, {}, V});
      }
      continue;
    }
    // Free: a = b; the gap grows by int (2 b - V).
    const auto gap_at = [&](double x) { return gap + 2.0 * v0_ * theta_ * exp_integral(B, x) - V * theta_ * x; };
    // (A round-off margin: the gap leaves 0 quadratically at a separation.)
    const auto touch = first_negative([&](double x) { return gap_at(x) + 1e-14 * v0_ * T; }, width);
    const double x = touch.value_or(width);
    out.push_back({t, t + x * theta_, B});
    X += V * theta_ * x;
    gap = touch ? 0.0 : gap_at(x);
    t += x * theta_;
    if (touch) {
      contact = true;
      continue;
    }
    if (V < 0.0 && X < -reach) break;  // moving away beyond the bar's reach: no more contact
  }
}

const MassOnBar::Segment& MassOnBar::segment_at(double t) const {
  const auto it = std::upper_bound(segments_.begin(), segments_.end(), t, [](double x, const Segment& s) { return x < s.t0; });
  return it == segments_.begin() ? segments_.front() : *std::prev(it);
}

double MassOnBar::exact_contact_force(double t) const {
  if (t < 0.0) return 0.0;
  const Segment& s = segment_at(t);
  if (!s.contact) return 0.0;
  const double x = (t - s.t0) / theta_;
  return impedance() * v0_ * nsb::dmath::exp(-x) * eval(s.force, x);
}

double MassOnBar::exact_mass_velocity(double t) const {
  if (t < 0.0) return v0_;
  const Segment& s = segment_at(t);
  if (!s.contact) return s.v_free;
  const double x = (t - s.t0) / theta_;
  return v0_ * nsb::dmath::exp(-x) * eval(s.velocity, x);
}

std::vector<double> MassOnBar::impact_times(double t_end) const {
  std::vector<double> times;
  for (std::size_t i = 0; i < segments_.size() && segments_[i].t0 <= t_end; ++i)
    if (segments_[i].contact && (i == 0 || !segments_[i - 1].contact)) times.push_back(segments_[i].t0);
  return times;
}

std::vector<std::string> MassOnBar::observable_names() const {
  return {"contact_force", "v_mass", "contact_force_exact", "v_mass_exact"};
}

void MassOnBar::observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const {
  out[0] = dt > 0.0 ? impulses[0] / dt : 0.0;  // dt = 0: no step, no impulse
  out[1] = s.v[n_];
  out[2] = exact_contact_force(s.t);
  out[3] = exact_mass_velocity(s.t);
}

NSBENCH_PROBLEM({"mass-on-bar", "rigid mass striking the free end of a clamped elastic bar (Saint-Venant; contact row on two bodies); mass lumped|consistent|singular (exact piecewise force)", &MassOnBar::parameters_spec, &make_from_params<Problem, MassOnBar>});

}  // namespace nsb
