#include "reference/modal_exact.hpp"
#include "core/deterministic_math.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <list>
#include <mutex>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace nsb {

namespace {

// Events at one instant beyond this mean the event logic cycles (a bug, not physics: a
// Zeno sequence is cut by zeno_velocity long before).
constexpr long kMaxModalEventsPerStep = 100000;
// A signal (or one of its derivatives) is zero when within this of its round-off scale.
constexpr double kRoundoff = 1e-12;
// Rigid modes: w^2 <= kRigid max w^2. The eigenvalues carry an absolute error of about
// eps max w^2; treating such a mode as oscillating would turn that error into qs = f / w^2.
constexpr double kRigid = 1e-12;
constexpr double kEps = std::numeric_limits<double>::epsilon();

bool is_diagonal(const Eigen::MatrixXd& A) {
  for (Index j = 0; j < A.cols(); ++j)
    for (Index i = 0; i < A.rows(); ++i)
      if (i != j && A(i, j) != 0.0) return false;
  return true;
}

}  // namespace

ParamSpecs ModalExact::parameters_spec() {
  return {
      ParamSpec::real("zeno_velocity", 1e-4, 0.0, 1e308, "rebound speed below which an impact is made plastic and the contact closes"),
      ParamSpec::integer("samples_per_period", 16, 4, 1'000'000, "event search samples per period of the fastest mode"),
      ParamSpec::integer("max_dofs", 2000, 1, 100'000,
                         "largest problem accepted (dense eigendecompositions: O(n^3) per contact mode, about 3 s at n = 1600)"),
  };
}

ModalExact::ModalExact(const Params& params)
    : Integrator(params),
      zeno_velocity_(params.real("zeno_velocity")),
      samples_per_period_(params.integer("samples_per_period")) {}

void ModalExact::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const Index n = problem.ndof();

  SpMat K;
  problem.tangent_stiffness(initial.u, K);
  K_ = Eigen::MatrixXd(K);
  K_ = 0.5 * (K_ + K_.transpose());
  M_ = Eigen::MatrixXd(mass_);
  F_ = Vec::Zero(n);
  problem.external_force(initial.t, F_);

  // Massless dofs: a zero mass row (and column).
  massless_.assign(static_cast<std::size_t>(n), 0);
  std::vector<Index> massive;
  for (Index k = 0; k < n; ++k) {
    if (M_(k, k) == 0.0) {
      if (M_.row(k).cwiseAbs().maxCoeff() != 0.0 || M_.col(k).cwiseAbs().maxCoeff() != 0.0)
        throw InputError(fmt::format("modal-exact: dof {} has zero mass but off-diagonal mass entries; valid: a massless dof has a zero mass row", k));
      massless_[k] = 1;
    } else if (!(M_(k, k) > 0.0)) {
      throw InputError(fmt::format("modal-exact: dof {} has mass {}; valid: >= 0", k, M_(k, k)));
    } else {
      massive.push_back(k);
    }
  }

  contacts_ = node_contacts(problem);
  const Index p = static_cast<Index>(contacts_.size());
  contact_of_.assign(static_cast<std::size_t>(n), -1);
  for (Index i = 0; i < p; ++i) contact_of_[contacts_[i].dof] = i;

  // M_SS^{-1} L^T for the impacts (massive contacts only: a massless one takes no impulse).
  cholesky_ = decompositions_ = 0;
  const Eigen::MatrixXd Mss = M_(massive, massive);
  const Eigen::LLT<Eigen::MatrixXd> mass_llt(Mss);
  ++cholesky_;
  if (mass_llt.info() != Eigen::Success)
    throw InputError("modal-exact: the mass matrix of the massive dofs is not positive definite; valid: M >= 0 with a zero row for each massless dof");
  minv_lt_ = Eigen::MatrixXd::Zero(n, p);
  std::vector<Index> massive_index(static_cast<std::size_t>(n), -1);
  for (std::size_t k = 0; k < massive.size(); ++k) massive_index[massive[k]] = static_cast<Index>(k);
  for (Index i = 0; i < p; ++i) {
    const Contact& c = contacts_[i];
    if (massless_[c.dof]) continue;
    Vec rhs = Vec::Zero(static_cast<Index>(massive.size()));
    rhs[massive_index[c.dof]] = c.a;
    const Vec col = mass_llt.solve(rhs);
    for (std::size_t k = 0; k < massive.size(); ++k) minv_lt_(massive[k], i) = col[static_cast<Index>(k)];
  }

  e_ = problem.restitution();
  events_ = impacts_ = arrivals_ = releases_ = zeno_stops_ = root_evaluations_ = forced_events_ = force_equivalents_ = 0;
  event_log_.clear();
  modes_.clear();
  for (Vec* v : {&q_, &qd_, &qt_, &qdt_, &qint_, &work_a_, &work_b_}) *v = Vec::Zero(n);
  for (Vec* v : {&signal_prev_, &signal_now_, &vertex_}) *v = Vec::Zero(p);
  hits_.reserve(static_cast<std::size_t>(p));
  restitution_.reserve(static_cast<std::size_t>(p));
  rate_before_.reserve(static_cast<std::size_t>(p));
  lcp_set_.reserve(static_cast<std::size_t>(p));
  published_.clear();
  for (const auto& [key, counter] : {std::pair<const char*, const long*>{"events", &events_}, {"impacts", &impacts_},
                                     {"arrivals", &arrivals_}, {"releases", &releases_}, {"eigen_decompositions", &decompositions_},
                                     {"root_evaluations", &root_evaluations_}, {"zeno_stops", &zeno_stops_},
                                     {"forced_events", &forced_events_}, {"force_equivalents", &force_equivalents_}})
    published_.emplace_back(&work_.extra[key], counter);

  // The all-open mode first: K >= 0 iff K_ZZ > 0 and its K~ >= 0, which build_mode checks.
  closed_work_.assign(static_cast<std::size_t>(p), 0);
  mode_ = &mode_for(closed_work_);
  project();
  for (Index i = 0; i < p; ++i) {
    double gap, scale;
    signal_derivative(i, 0, gap, scale);
    if (gap < -kRoundoff * scale)
      throw InputError(fmt::format("modal-exact: the initial state penetrates contact {} (gap {}); valid: gap >= 0", i, gap));
  }
  // Contacts touching at t0 impact or close before the first step; an impulse there belongs
  // to no step (as in event-driven).
  handle_events(-1, false);
  impulses_.setZero();
  publish_work();
}

const ModalExact::Mode& ModalExact::mode_for(const std::vector<char>& closed) {
  auto it = modes_.find(closed);
  if (it == modes_.end()) {
    std::optional<Mode> shared = shared_mode(closed);
    if (shared) {
      if (!shared->massless.empty()) ++cholesky_;  // build_mode's K_ZZ factorisation, counted as if made
    } else {
      shared = build_mode(closed);
      share_mode(*shared);
    }
    it = modes_.emplace(closed, std::move(*shared)).first;
    ++decompositions_;
  }
  return it->second;
}

namespace {
constexpr std::size_t kSharedModeBytes = std::size_t{256} << 20;

bool same_bits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}
bool same_bits(const Vec& a, const Vec& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), static_cast<std::size_t>(a.size()) * sizeof(double)) == 0;
}
bool same_bits(const std::vector<NodeContact>& a, const std::vector<NodeContact>& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](const NodeContact& x, const NodeContact& y) {
           return x.dof == y.dof && std::memcmp(&x.a, &y.a, sizeof(double)) == 0 &&
                  std::memcmp(&x.position, &y.position, sizeof(double)) == 0;
         });
}
std::size_t matrix_bytes(const Eigen::MatrixXd& m) { return static_cast<std::size_t>(m.size()) * sizeof(double); }
}  // namespace

// One system's inputs and its modes, most recently used first; guarded by one mutex.
struct ModalExact::SharedModes {
  Eigen::MatrixXd K, M;
  Vec F;
  std::vector<NodeContact> contacts;
  long samples_per_period = 0;
  std::map<std::vector<char>, Mode> modes;
  std::size_t bytes = 0;
  bool holds(const ModalExact& x) const {
    return samples_per_period == x.samples_per_period_ && same_bits(K, x.K_) && same_bits(M, x.M_) && same_bits(F, x.F_) &&
           same_bits(contacts, x.contacts_);
  }
};

std::list<ModalExact::SharedModes>& ModalExact::shared_modes(std::mutex*& guard) {
  static std::mutex mutex;
  static std::list<SharedModes> systems;
  guard = &mutex;
  return systems;
}

std::optional<ModalExact::Mode> ModalExact::shared_mode(const std::vector<char>& closed) const {
  std::mutex* guard = nullptr;
  auto& systems = shared_modes(guard);
  const std::lock_guard lock(*guard);
  for (auto s = systems.begin(); s != systems.end(); ++s) {
    if (!s->holds(*this)) continue;
    systems.splice(systems.begin(), systems, s);  // most recently used first
    const auto m = s->modes.find(closed);
    if (m == s->modes.end()) return std::nullopt;
    return m->second;
  }
  return std::nullopt;
}

void ModalExact::share_mode(const Mode& md) const {
  const std::size_t bytes = matrix_bytes(md.phi) + matrix_bytes(md.phi_t_m) + matrix_bytes(md.cond) + matrix_bytes(md.signal);
  std::mutex* guard = nullptr;
  auto& systems = shared_modes(guard);
  const std::lock_guard lock(*guard);
  auto s = std::find_if(systems.begin(), systems.end(), [&](const SharedModes& x) { return x.holds(*this); });
  if (s == systems.end()) {
    SharedModes fresh{K_, M_, F_, contacts_, samples_per_period_, {}, matrix_bytes(K_) + matrix_bytes(M_)};
    systems.push_front(std::move(fresh));
    s = systems.begin();
  } else {
    systems.splice(systems.begin(), systems, s);
  }
  if (s->modes.emplace(md.closed, md).second) s->bytes += bytes;
  std::size_t total = 0;
  for (const auto& x : systems) total += x.bytes;
  while (systems.size() > 1 && total > kSharedModeBytes) {  // the least recently used out, never the one just stored
    total -= systems.back().bytes;
    systems.pop_back();
  }
}

ModalExact::Mode ModalExact::build_mode(const std::vector<char>& closed) {
  const Index n = K_.rows(), p = static_cast<Index>(contacts_.size());
  Mode md;
  md.closed = closed;
  md.slot.assign(static_cast<std::size_t>(n), -1);
  for (Index k = 0; k < n; ++k) {
    const Index i = contact_of_[k];
    if (i >= 0 && closed[i]) {
      md.held.push_back(k);
    } else if (massless_[k]) {
      md.slot[k] = static_cast<Index>(md.massless.size());
      md.massless.push_back(k);
    } else {
      md.slot[k] = static_cast<Index>(md.active.size());
      md.active.push_back(k);
    }
  }
  const auto& A = md.active;
  const auto& Z = md.massless;
  const auto& H = md.held;
  Vec uH(static_cast<Index>(H.size()));
  for (std::size_t k = 0; k < H.size(); ++k) uH[static_cast<Index>(k)] = contacts_[contact_of_[H[k]]].position;

  // Static condensation of the free massless dofs: u_Z = x0 - X u_A.
  Eigen::MatrixXd Kt = K_(A, A);
  Vec Ft = F_(A) - K_(A, H) * uH;
  Eigen::MatrixXd X(static_cast<Index>(Z.size()), static_cast<Index>(A.size()));
  Vec x0(static_cast<Index>(Z.size()));
  if (!Z.empty()) {
    const Eigen::LLT<Eigen::MatrixXd> kzz(K_(Z, Z));
    ++cholesky_;
    if (kzz.info() != Eigen::Success || !(kzz.rcond() > 1e-13))
      throw InputError("modal-exact: the stiffness block of the free massless dofs (K_ZZ) is singular; valid: each massless dof "
                       "held by stiffness to the massive ones");
    X = kzz.solve(K_(Z, A));
    x0 = kzz.solve(F_(Z) - K_(Z, H) * uH);
    Kt -= K_(A, Z) * X;
    Ft -= K_(A, Z) * x0;
  }
  Kt = 0.5 * (Kt + Kt.transpose());

  const Index m = static_cast<Index>(A.size());
  const Eigen::MatrixXd Maa = M_(A, A);
  Vec lambda(m);
  if (m > 0 && is_diagonal(Maa)) {
    const Vec d = Maa.diagonal().cwiseSqrt();
    const Vec s = d.cwiseInverse();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(s.asDiagonal() * Kt * s.asDiagonal());
    if (es.info() != Eigen::Success) throw std::runtime_error("modal-exact: the eigensolver failed");
    md.phi = s.asDiagonal() * es.eigenvectors();
    md.phi_t_m = es.eigenvectors().transpose() * d.asDiagonal();
    lambda = es.eigenvalues();
  } else if (m > 0) {
    const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Kt, Maa);
    if (es.info() != Eigen::Success) throw std::runtime_error("modal-exact: the generalised eigensolver failed");
    md.phi = es.eigenvectors();
    md.phi_t_m = md.phi.transpose() * Maa;
    lambda = es.eigenvalues();
  } else {
    md.phi.resize(0, 0);
    md.phi_t_m.resize(0, 0);
  }
  const double lambda_max = m > 0 ? lambda.cwiseAbs().maxCoeff() : 0.0;
  md.omega.resize(m);
  for (Index j = 0; j < m; ++j) {
    if (lambda[j] < -kRigid * lambda_max)
      throw InputError(fmt::format("modal-exact: the condensed stiffness has a negative eigenvalue {}; valid: K positive "
                                   "semidefinite", lambda[j]));
    md.omega[j] = lambda[j] > kRigid * lambda_max ? std::sqrt(lambda[j]) : 0.0;
    if (md.omega[j] == 0.0) md.rigid.push_back(j);
  }
  md.force = md.phi.transpose() * Ft;
  md.q_static = Vec::Zero(m);
  for (Index j = 0; j < m; ++j)
    if (md.omega[j] > 0.0) md.q_static[j] = md.force[j] / (md.omega[j] * md.omega[j]);
  md.cond = -X * md.phi;
  md.cond0 = x0;

  // Signals: the gap of each open contact, the reaction of each closed one.
  std::vector<Index> where(static_cast<std::size_t>(n), -1);  // position in A or in Z
  for (Index k = 0; k < m; ++k) where[A[k]] = k;
  for (std::size_t k = 0; k < Z.size(); ++k) where[Z[k]] = static_cast<Index>(k);
  md.signal.resize(p, m);
  md.signal0.resize(p);
  const Vec omega2 = md.omega.cwiseAbs2();
  for (Index i = 0; i < p; ++i) {
    const Contact& c = contacts_[i];
    const Index d = c.dof;
    if (closed[i]) {
      // lambda_i = (M_dA Phi (f - W^2 q) + K_dA Phi q + K_dZ (cond0 + cond q) + K_dH u_H - F_d) / a
      const Eigen::RowVectorXd mphi = M_(d, A) * md.phi;
      md.signal.row(i) = (-mphi.cwiseProduct(omega2.transpose()) + K_(d, A) * md.phi + K_(d, Z) * md.cond) / c.a;
      md.signal0[i] = (mphi.dot(md.force) + K_(d, Z).dot(md.cond0) + K_(d, H).dot(uH) - F_[d]) / c.a;
    } else if (massless_[c.dof]) {
      md.signal.row(i) = c.a * md.cond.row(where[d]);
      md.signal0[i] = c.a * (md.cond0[where[d]] - c.position);
    } else {
      md.signal.row(i) = c.a * md.phi.row(where[d]);
      md.signal0[i] = -c.a * c.position;
    }
  }
  const double w_max = m > 0 ? md.omega.maxCoeff() : 0.0;
  md.sample_step = w_max > 0.0 ? 2.0 * std::numbers::pi / (w_max * static_cast<double>(samples_per_period_))
                               : std::numeric_limits<double>::infinity();
  return md;
}

void ModalExact::modal_at(double tau, Vec& qt, Vec* qdt) const {
  const Mode& md = *mode_;
  for (Index j = 0; j < md.size(); ++j) {
    const double w = md.omega[j];
    if (w > 0.0) {
      const double c = nsb::dmath::cos(w * tau), s = nsb::dmath::sin(w * tau), d = q_[j] - md.q_static[j];
      qt[j] = md.q_static[j] + d * c + qd_[j] / w * s;
      if (qdt) (*qdt)[j] = -d * w * s + qd_[j] * c;
    } else {
      qt[j] = q_[j] + tau * (qd_[j] + 0.5 * tau * md.force[j]);
      if (qdt) (*qdt)[j] = qd_[j] + tau * md.force[j];
    }
  }
}

double ModalExact::signal_value(Index i, const Vec& q) const {
  const Mode& md = *mode_;
  const Index m = md.size();
  return md.signal0[i] + md.signal.row(i).dot(q.head(m));
}

void ModalExact::signal_derivative(Index i, int r, double& value, double& scale) const {
  const Mode& md = *mode_;
  value = scale = 0.0;
  if (r == 0) {
    value = md.signal0[i];
    scale = std::abs(value);
  }
  for (Index j = 0; j < md.size(); ++j) {
    const double l = md.signal(i, j), w2 = md.omega[j] * md.omega[j];
    double term = 0.0, size = 0.0;
    switch (r) {
      case 0: term = q_[j]; size = std::abs(term); break;
      case 1: term = qd_[j]; size = std::abs(term); break;
      case 2: term = md.force[j] - w2 * q_[j]; size = std::abs(md.force[j]) + w2 * std::abs(q_[j]); break;
      default: term = -w2 * qd_[j]; size = std::abs(term); break;
    }
    value += l * term;
    scale += std::abs(l) * size;
  }
}

int ModalExact::leading_sign(Index i, int r0) const {
  for (int r = r0; r <= 3; ++r) {
    double value, scale;
    signal_derivative(i, r, value, scale);
    if (std::abs(value) > kRoundoff * scale) return value > 0.0 ? 1 : -1;
  }
  return 0;
}

ModalExact::Found ModalExact::find_event(double tau_max) {
  const Mode& md = *mode_;
  const Index p = static_cast<Index>(contacts_.size());
  const Found none{tau_max + 1.0, -1, false};
  if (p == 0) return none;
  // Vertex of each signal's rigid-mode part c0 + c1 tau + c2 tau^2 (its only extremum), so
  // that a polynomial dip between two samples is sampled too.
  for (Index i = 0; i < p; ++i) {
    double c1 = 0.0, c2 = 0.0;
    for (Index j : md.rigid) {
      c1 += md.signal(i, j) * qd_[j];
      c2 += 0.5 * md.signal(i, j) * md.force[j];
    }
    vertex_[i] = c2 != 0.0 ? -c1 / (2.0 * c2) : -1.0;
    signal_prev_[i] = signal_value(i, q_);
  }
  root_evaluations_ += p;
  double a = 0.0;
  while (a < tau_max) {
    const double b = a + md.sample_step > a ? std::min(a + md.sample_step, tau_max) : tau_max;
    modal_at(b, qt_, nullptr);
    root_evaluations_ += p;
    Found first = none;
    for (Index i = 0; i < p; ++i) {
      const double fa = signal_prev_[i], fb = signal_now_[i] = signal_value(i, qt_);
      double lo = a, flo = fa, hi = b, fhi = fb;
      if (vertex_[i] > a && vertex_[i] < b) {
        modal_at(vertex_[i], qint_, nullptr);
        ++root_evaluations_;
        const double fv = signal_value(i, qint_);
        if (fv < 0.0) {
          hi = vertex_[i];
          fhi = fv;
        } else {
          lo = vertex_[i];
          flo = fv;
        }
      }
      if (!(fhi < 0.0)) continue;
      const Found found = locate(i, lo, flo, hi, fhi);
      if (found.tau < first.tau) first = found;
    }
    if (first.contact >= 0) return first;
    a = b;
    signal_prev_.swap(signal_now_);
  }
  return none;
}

ModalExact::Found ModalExact::locate(Index i, double lo, double flo, double hi, double fhi) {
  if (lo > 0.0) return {refine(i, lo, flo, hi, fhi), i, false};
  // From the start, where an event may have left the signal at zero (to round-off).
  double value, scale;
  signal_derivative(i, 0, value, scale);
  if (std::abs(value) > kRoundoff * scale) return flo < 0.0 ? Found{0.0, i, true} : Found{refine(i, lo, flo, hi, fhi), i, false};
  if (leading_sign(i, 1) < 0) return {0.0, i, false};  // going down now: the handler acts on it
  // Its derivatives send it up first: the excursion above zero ends before hi. Halve towards
  // the start until a sample is on it.
  for (int k = 0; k < 64; ++k) {
    const double x = 0.5 * hi;
    modal_at(x, qint_, nullptr);
    ++root_evaluations_;
    const double fx = signal_value(i, qint_);
    if (fx >= 0.0) return {refine(i, x, fx, hi, fhi), i, false};
    hi = x;
    fhi = fx;
  }
  return {0.0, i, true};
}

double ModalExact::refine(Index i, double a, double fa, double b, double fb) {
  // Illinois: regula falsi halving the retained end's value; bisection whenever two
  // iterations have not halved the bracket. Keeps fa >= 0 > fb, returns b (the event has
  // happened there: the handler sees the gap closed or the reaction tensile).
  int side = 0;
  constexpr double inf = std::numeric_limits<double>::infinity();
  double width_1 = inf, width_2 = inf;  // the bracket one and two iterations ago
  for (int it = 0; it < 200 && b - a > 2.0 * kEps * b; ++it) {
    const double width = b - a;
    double x = (a * fb - b * fa) / (fb - fa);
    if (!(x > a && x < b) || width > 0.5 * width_2) x = 0.5 * (a + b);
    modal_at(x, qint_, nullptr);
    ++root_evaluations_;
    const double fx = signal_value(i, qint_);
    if (fx == 0.0) return x;
    if (fx < 0.0) {
      b = x;
      fb = fx;
      if (side == -1) fa *= 0.5;
      side = -1;
    } else {
      a = x;
      fa = fx;
      if (side == 1) fb *= 0.5;
      side = 1;
    }
    width_2 = width_1;
    width_1 = width;
  }
  return b;
}

void ModalExact::propagate(double tau) {
  const Mode& md = *mode_;
  const Index m = md.size(), p = static_cast<Index>(contacts_.size());
  bool any_closed = false;
  for (Index i = 0; i < p; ++i) any_closed = any_closed || md.closed[i];
  if (any_closed) {
    // Integral of q over [0, tau] in closed form, for the reactions' impulses.
    for (Index j = 0; j < m; ++j) {
      const double w = md.omega[j];
      if (w > 0.0) {
        const double half = nsb::dmath::sin(0.5 * w * tau);
        qint_[j] = md.q_static[j] * tau + (q_[j] - md.q_static[j]) * nsb::dmath::sin(w * tau) / w + qd_[j] * 2.0 * half * half / (w * w);
      } else {
        qint_[j] = tau * (q_[j] + tau * (0.5 * qd_[j] + tau * md.force[j] / 6.0));
      }
    }
    for (Index i = 0; i < p; ++i)
      if (md.closed[i]) impulses_[i] += md.signal0[i] * tau + md.signal.row(i).dot(qint_.head(m));
  }
  modal_at(tau, qt_, &qdt_);
  q_.swap(qt_);
  qd_.swap(qdt_);
}

void ModalExact::reconstruct() {
  const Mode& md = *mode_;
  const Index m = md.size();
  Vec& u = state_.u;
  Vec& v = state_.v;
  work_a_.head(m).noalias() = md.phi * q_.head(m);
  work_b_.head(m).noalias() = md.phi * qd_.head(m);
  for (Index k = 0; k < m; ++k) {
    u[md.active[k]] = work_a_[k];
    v[md.active[k]] = work_b_[k];
  }
  const Index z = static_cast<Index>(md.massless.size());
  work_a_.head(z).noalias() = md.cond * q_.head(m);
  work_b_.head(z).noalias() = md.cond * qd_.head(m);
  for (Index k = 0; k < z; ++k) {
    u[md.massless[k]] = md.cond0[k] + work_a_[k];
    v[md.massless[k]] = work_b_[k];
  }
  for (Index k : md.held) {
    u[k] = contacts_[contact_of_[k]].position;
    v[k] = 0.0;
  }
}

void ModalExact::project() {
  const Mode& md = *mode_;
  const Index m = md.size();
  for (Index k = 0; k < m; ++k) {
    work_a_[k] = state_.u[md.active[k]];
    work_b_[k] = state_.v[md.active[k]];
  }
  q_.head(m).noalias() = md.phi_t_m * work_a_.head(m);
  qd_.head(m).noalias() = md.phi_t_m * work_b_.head(m);
  reconstruct();
}

void ModalExact::handle_events(Index fired, bool forced) {
  const Index p = static_cast<Index>(contacts_.size());
  const double t = state_.t;
  Vec& u = state_.u;
  Vec& v = state_.v;
  closed_work_ = mode_->closed;
  // A forced event overrules the derivatives: a closed contact opens, an open one is hit
  // plastically and stays closed through the reaction check below.
  const Index forced_closing = forced && !closed_work_[fired] ? fired : -1;
  // A rebound slower than zeno_velocity becomes a plastic impact: the contact closes.
  const auto zeno_stop = [&](double rate) { return e_ > 0.0 && rate < 0.0 && e_ * -rate < zeno_velocity_; };
  if (forced) ++forced_events_;
  if (forced && closed_work_[fired]) {
    closed_work_[fired] = 0;
    ++releases_;
    event_log_.push_back({t, fired, EventKind::Release, 0.0, 0.0, 0.0});
  }
  // Hits: open contacts touching (the root found, or a gap zero to round-off) and closing.
  hits_.clear();
  restitution_.clear();
  rate_before_.clear();
  double rate_scale = 0.0;
  for (Index i = 0; i < p; ++i) {
    if (closed_work_[i]) continue;
    double gap, scale;
    signal_derivative(i, 0, gap, scale);
    if (i != fired && gap > kRoundoff * scale) continue;
    if (i != forced_closing && leading_sign(i, 1) >= 0) continue;
    const Contact& c = contacts_[i];
    const double rate = c.a * v[c.dof];  // a massless dof's v: the rate of its condensed value
    u[c.dof] = c.position;  // the gap is zero at the event, exactly
    if (massless_[c.dof]) {
      // No inertia, no impulse: the dof arrives (its gap is continuous) and closes.
      closed_work_[i] = 1;
      ++arrivals_;
      event_log_.push_back({t, i, EventKind::Arrival, rate, 0.0, 0.0});
      continue;
    }
    const bool zeno = e_ * -rate < zeno_velocity_;
    if (zeno_stop(rate)) ++zeno_stops_;
    hits_.push_back(i);
    restitution_.push_back(zeno || i == forced_closing ? 0.0 : e_);
    rate_before_.push_back(rate);
    rate_scale = std::max(rate_scale, std::abs(rate));
  }
  if (!hits_.empty()) {
    // Newton's impulse LCP over the hits and the closed massive contacts (at rest, e = 0):
    // with a non-diagonal M an impulse elsewhere could push a held dof into its obstacle.
    lcp_set_.assign(hits_.begin(), hits_.end());
    for (Index i = 0; i < p; ++i)
      if (closed_work_[i] && !massless_[contacts_[i].dof]) lcp_set_.push_back(i);
    const Index h = static_cast<Index>(lcp_set_.size());
    const auto rate_of = [&](Index i) { return contacts_[i].a * v[contacts_[i].dof]; };
    const auto delassus = [&](Index j, Index k) { return contacts_[lcp_set_[j]].a * minv_lt_(contacts_[lcp_set_[j]].dof, lcp_set_[k]); };
    const auto q_of = [&](Index j) {
      return j < static_cast<Index>(hits_.size()) ? (1.0 + restitution_[j]) * rate_before_[j] : 0.0;
    };
    if (h == 1) {
      lcp_x_.resize(1);  // no allocation after the first impact
      lcp_x_[0] = std::max(0.0, -q_of(0) / delassus(0, 0));
    } else {
      Eigen::MatrixXd D(h, h);
      Vec q(h);
      for (Index j = 0; j < h; ++j) {
        q[j] = q_of(j);
        for (Index k = 0; k < h; ++k) D(j, k) = delassus(j, k);
      }
      lcp_x_ = Vec::Zero(h);
      const LcpResult res = solve_lcp(D, q, lcp_x_, lcp_);
      work_.lcp_iterations += res.iterations;
      if (!res.converged) ++work_.lcp_unconverged;
    }
    for (std::size_t j = 0; j < hits_.size(); ++j)
      if (restitution_[j] == 0.0) closed_work_[hits_[j]] = 1;  // plastic: a closed candidate
    for (Index k = 0; k < h; ++k) v += minv_lt_.col(lcp_set_[k]) * lcp_x_[k];
    for (std::size_t j = 0; j < hits_.size(); ++j) {
      const Index i = hits_[j];
      const Contact& c = contacts_[i];
      if (closed_work_[i]) v[c.dof] = 0.0;  // at rest on the obstacle, exactly
      impulses_[i] += lcp_x_[static_cast<Index>(j)];
      ++impacts_;
      event_log_.push_back({t, i, zeno_stop(rate_before_[j]) ? EventKind::ZenoStop : EventKind::Impact, rate_before_[j],
                            rate_of(i), lcp_x_[static_cast<Index>(j)]});
    }
    for (Index k = static_cast<Index>(hits_.size()); k < h; ++k) {
      const Index i = lcp_set_[k];
      impulses_[i] += lcp_x_[k];
      if (rate_of(i) > kRoundoff * rate_scale) {  // the impact lifts a held dof off
        closed_work_[i] = 0;
        ++releases_;
        event_log_.push_back({t, i, EventKind::Release, 0.0, rate_of(i), 0.0});
      } else {
        v[contacts_[i].dof] = 0.0;
      }
    }
  }
  // Closed contacts and candidates stay closed while their reaction is compressive (zero to
  // round-off: decided by its derivatives); the tensile ones open, and the rest is re-checked.
  for (;;) {
    mode_ = &mode_for(closed_work_);
    project();
    bool released = false;
    for (Index i = 0; i < p; ++i) {
      if (!closed_work_[i] || i == forced_closing || leading_sign(i, 0) >= 0) continue;
      closed_work_[i] = 0;
      released = true;
      ++releases_;
      event_log_.push_back({t, i, EventKind::Release, 0.0, 0.0, 0.0});
    }
    if (!released) break;
  }
}

long ModalExact::advance_through_events(double target) {
  long events = 0;
  for (;;) {
    const double tau_max = target - state_.t;
    if (!(tau_max > 0.0)) break;
    const Found event = find_event(tau_max);
    if (event.contact < 0) {
      propagate(tau_max);
      break;
    }
    propagate(event.tau);
    state_.t = event.tau == tau_max ? target : state_.t + event.tau;
    reconstruct();
    handle_events(event.contact, event.forced);
    ++events_;
    if (++events > kMaxModalEventsPerStep)
      throw std::runtime_error(fmt::format("modal-exact: more than {} events in one step at t = {}", kMaxModalEventsPerStep, state_.t));
  }
  state_.t = target;
  return events;
}

StepInfo ModalExact::advance(double dt) {
  StepInfo info;
  impulses_.setZero();
  const double target = state_.t + dt;
  info.iterations = advance_through_events(target);
  reconstruct();
  force_equivalents_ += 1 + info.iterations;  // a reconstruction per event and per step
  info.dt = dt;
  publish_work();
  return info;
}

void ModalExact::advance_to(double t) {
  if (!(t >= state_.t))
    throw InputError(fmt::format("modal-exact: advance_to({}) is behind the solution's time {}; valid: t >= it", t, state_.t));
  advance_through_events(t);
  publish_work();
}

double ModalExact::displacement(Index dof) const {
  const Mode& md = *mode_;
  const Index k = md.slot[static_cast<std::size_t>(dof)];
  if (k < 0) return contacts_[contact_of_[dof]].position;
  const Index m = md.size();
  if (massless_[dof]) return md.cond0[k] + md.cond.row(k).dot(q_.head(m));
  return md.phi.row(k).dot(q_.head(m));
}

void ModalExact::publish_work() {
  work_.factorizations = decompositions_ + cholesky_;
  for (const auto& [slot, counter] : published_) *slot = static_cast<double>(*counter);
}

NSBENCH_INTEGRATOR({ModalExact::kName, "reference: exact modal solution of linear problems between contact events, closed-form event signals (node-to-rigid contacts)", &ModalExact::parameters_spec, &make_from_params<Integrator, ModalExact>, true, false,
                    {.linear_only = true, .constant_force_only = true, .node_to_rigid_only = true, .max_dofs_parameter = "max_dofs"}});

}  // namespace nsb
