#include "problems/ball_chain.hpp"
#include "problems/registry.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>

namespace nsb {

namespace {
// A march longer than this is an inelastic collapse (infinitely many collisions in finite
// time), which the sequential law does not resolve.
constexpr std::size_t kMaxCollisions = 1'000'000;
}  // namespace

ParamSpecs BallChain::parameters_spec() {
  return {
      ParamSpec::integer("n", 3, 2, 1000, "number of balls"),
      ParamSpec::real("gap", 0.01, 0.0, 1e308, "gap between neighbours [m] (0: touching)"),
      ParamSpec::real("e", 1.0, 0.0, 1.0, "Newton restitution coefficient"),
      ParamSpec::real("v0", 1.0, -1e308, 1e308, "initial velocity of ball 1, towards the others [m/s]"),
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass of each ball [kg]", true),
  };
}

std::vector<State> BallChain::march(Index n, double gap, double e, double v0) {
  State s;
  s.u = Vec::Zero(n);
  s.v = Vec::Zero(n);
  s.v[0] = v0;
  std::vector<State> events{s};
  Vec g = Vec::Constant(n - 1, gap);
  const double still = 1e-14 * std::abs(v0);
  Index last = -1;
  for (;;) {
    // Ties (touching balls colliding at the same instant) go in cyclic order after the
    // last pair that collided: sweeps along the chain, whose cascade converges geometrically.
    Index next = -1;
    double dt = std::numeric_limits<double>::infinity();
    for (Index k = 0; k + 1 < n; ++k) {
      const Index i = (last + 1 + k) % (n - 1);
      const double w = s.v[i] - s.v[i + 1];
      if (w > still && g[i] / w < dt) {
        dt = g[i] / w;
        next = i;
      }
    }
    last = next;
    if (next < 0) return events;
    if (events.size() > kMaxCollisions)
      throw InputError(fmt::format("problem ball-chain: the binary-collision march exceeds {} collisions "
                                   "(inelastic collapse); e = {} is too small for n = {}",
                                   kMaxCollisions, e, n));
    // Round-off leaves pairs that no longer approach (w <= still) with gaps of order
    // eps g: clamped at 0, so that no collision time comes out negative.
    dt = std::max(dt, 0.0);
    s.t += dt;
    s.u += dt * s.v;
    for (Index i = 0; i + 1 < n; ++i) g[i] = std::max(0.0, g[i] + dt * (s.v[i + 1] - s.v[i]));
    g[next] = 0.0;  // the colliding pair touches (no round-off penetration)
    const double dv = 0.5 * (1.0 + e) * (s.v[next] - s.v[next + 1]);
    s.v[next] -= dv;
    s.v[next + 1] += dv;
    events.push_back(s);
  }
}

BallChain::BallChain(const Params& p)
    : params_(p), n_(p.integer("n")), gap_(p.real("gap")), e_(p.real("e")), v0_(p.real("v0")), m_(p.real("m")) {
  contacts_.normal.resize(n_ - 1, n_);
  contacts_.normal.reserve(Eigen::VectorXi::Constant(n_, 2));
  for (Index i = 0; i + 1 < n_; ++i) {
    contacts_.normal.insert(i, i) = -1.0;
    contacts_.normal.insert(i, i + 1) = 1.0;
  }
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Constant(n_ - 1, gap_);
  contacts_.restitution = e_;

  // The march depends on gap only through its time scale (see the header).
  if (gap_ > 0.0) events_ = march(n_, gap_, e_, v0_);
  sequential_ = march(n_, 1.0, e_, v0_).back().v;

  simultaneous_impulses_ = Vec::Zero(n_ - 1);
  if (v0_ > 0.0)
    for (Index i = 0; i + 1 < n_; ++i)
      simultaneous_impulses_[i] = m_ * (1.0 + e_) * v0_ * double(n_ - 1 - i) / double(n_);
  simultaneous_ = initial_state().v + contacts_.normal.transpose() * simultaneous_impulses_ / m_;
}

SpMat BallChain::mass_matrix() const {
  SpMat M(n_, n_);
  M.reserve(Eigen::VectorXi::Ones(n_));
  for (Index i = 0; i < n_; ++i) M.insert(i, i) = m_;
  M.makeCompressed();
  return M;
}

void BallChain::tangent_stiffness(ConstVecRef, SpMat& K) const {
  if (K.rows() != n_ || K.cols() != n_) K.resize(n_, n_);
  K.setZero();
}

State BallChain::initial_state() const {
  State s;
  s.u = Vec::Zero(n_);
  s.v = Vec::Zero(n_);
  s.v[0] = v0_;
  return s;
}

double BallChain::stable_step() const { return std::numeric_limits<double>::infinity(); }

std::optional<State> BallChain::state(double t) const {
  if (gap_ == 0.0) return std::nullopt;
  // The last collision at or before t (post-collision velocities at a collision time).
  const auto after = std::upper_bound(events_.begin(), events_.end(), t,
                                      [](double time, const State& s) { return time < s.t; });
  State s = after == events_.begin() ? events_.front() : *std::prev(after);
  s.u += (t - s.t) * s.v;
  s.t = t;
  return s;
}

std::vector<double> BallChain::impact_times(double t_end) const {
  if (gap_ == 0.0) return v0_ > 0.0 ? std::vector<double>{0.0} : std::vector<double>{};
  std::vector<double> times;
  for (std::size_t k = 1; k < events_.size() && events_[k].t <= t_end; ++k) times.push_back(events_[k].t);
  return times;
}

std::vector<std::string> BallChain::observable_names() const {
  std::vector<std::string> names;
  for (Index i = 1; i <= n_; ++i) names.push_back(fmt::format("v{}", i));
  for (Index i = 1; i <= n_; ++i) names.push_back(fmt::format("v{}_exact", i));
  return names;
}

void BallChain::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const Vec exact = gap_ > 0.0 ? state(s.t)->v : (s.t > 0.0 ? simultaneous_ : initial_state().v);
  for (Index i = 0; i < n_; ++i) {
    out[static_cast<std::size_t>(i)] = s.v[i];
    out[static_cast<std::size_t>(n_ + i)] = exact[i];
  }
}

std::optional<FieldMesh> BallChain::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 1;
  for (Index i = 0; i < n_; ++i) mesh.add_vertex(static_cast<double>(i) * gap_, 0.0, {static_cast<int>(i)}, static_cast<int>(i));
  return mesh;
}

NSBENCH_PROBLEM({"ball-chain", "Newton's cradle: n equal balls, contacts between bodies (sequential and simultaneous impacts)",
                 &BallChain::parameters_spec, &make_from_params<Problem, BallChain>});

}  // namespace nsb
