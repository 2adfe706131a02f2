#include "integrators/cd_penalty.hpp"
#include "core/deterministic_math.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "integrators/impulse_contact.hpp"
#include "integrators/spring_dashpot.hpp"

namespace nsb {

namespace {
constexpr double kMaxDampingRatio = 1e3;
constexpr long kMaxContactSteps = 10'000'000;
// An undamped rebound this close to e needs no dashpot (at an integer half period, e = 1
// at every phase to round-off: kept undamped bit for bit).
constexpr double kUndampedTolerance = 1e-12;
// The coupled normal and tangential impulses of a moving contact (header): sweeps until the
// tangential impulse changes by at most this, relative.
constexpr double kCoupledContactTolerance = 1e-13;
constexpr int kCoupledContactMaxSweeps = 200;
}  // namespace

double cd_penalty_restitution(double phase, double penalty_factor, double zeta) {
  const double a = 1.0 / (1.0 + 2.0 * zeta * std::sqrt(penalty_factor));
  double x = -phase, s = -1.0;
  for (long n = 0; n < kMaxContactSteps; ++n) {
    s = std::max(s, a * (s - penalty_factor * x));
    x += s;
    if (x >= 0.0) return s;
  }
  return 0.0;
}

double cd_penalty_damping_ratio(double phase, double penalty_factor, double e) {
  const auto restitution = [&](double zeta) { return cd_penalty_restitution(phase, penalty_factor, zeta); };
  const double undamped = restitution(0.0);
  if (std::abs(undamped - e) <= kUndampedTolerance) return 0.0;
  if (undamped > e)
    return e <= 0.0 ? kMaxDampingRatio  // the bisection's answer too, without its cost
                    : damping_ratio_for_restitution(e, kMaxDampingRatio, restitution);
  // The switch lost energy at this phase: a negative dashpot, 1 + beta > 0 (restitution
  // grows without bound as beta -> -1), bisection on (-1 / (2 sqrt(p)), 0).
  double lo = -0.5 / std::sqrt(penalty_factor), hi = 0.0;
  for (int it = 0; it < 200 && lo < hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (restitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ParamSpecs CdPenalty::parameters_spec() {
  return {
      ParamSpec::real("penalty_factor", 2.0, 0.0, 4.0,
                      "kappa_i tau^2 / m_i (dimensionless); stable below 4, contact resolved in ~2 steps at 2", true, true),
      ParamSpec::real("friction_velocity", 1e-3, 0.0, 1e308,
                      "v_reg [m/s] of the regularised Coulomb law: viscous below, Coulomb above; creep v_reg F_T / (mu F_N)", true),
  };
}

CdPenalty::CdPenalty(const Params& params)
    : Integrator(params), factor_(params.real("penalty_factor")), v_reg_(params.real("friction_velocity")) {}

void CdPenalty::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  cd_.reset(problem, state_, mass_.diagonal());
  moving_ = problem.contacts_move();
  rows_ = problem.contact_geometry();
  if (moving_) problem.evaluate_contacts(state_.u, rows_);
  const Contacts& c = problem.contacts();
  friction_ = c.has_friction();
  cone_ = c.has_cone();
  const Index p = rows_.normal.rows();
  h_diag_ = Vec::Zero(p);
  if (friction_) {
    mu_ = c.mu;
    w_ = c.tangent_velocity;
    ht_diag_ = Vec::Zero(p);
  }
  if (cone_) {
    w2_ = c.tangent2_velocity;
    ht_blocks_.assign(static_cast<std::size_t>(p), Eigen::Matrix2d::Zero());
  }
  for (Index i = 0; i < p; ++i) {
    contact_masses(i);
    if (!(h_diag_[i] > 0.0)) throw InputError(fmt::format("integrator cd-penalty: problem {} has a contact ({}) with an empty row of L", problem.name(), i));
  }
  e_ = problem.restitution();
  zeta_ = Vec::Constant(p, cd_penalty_damping_ratio(1.0, factor_, e_));
  if (moving_) {
    gap_ = rows_.gap;
  } else {
    gap_ = rows_.normal * state_.u + problem.gap_offset();
  }
  gap_prev_ = gap_;
  gap_prev2_ = gap_;
  spring_force_ = Vec::Zero(p);
  stored_ = Vec::Zero(p);
  if (std::isfinite(stable_step_with_contacts())) work_.extra["stable_step_with_contacts"] = stable_step_with_contacts();
}

void CdPenalty::contact_masses(Index i) {
  const Vec& minv = cd_.minv;
  const auto self_product = [&](const RowSpMat& rows) {
    double sum = 0.0;
    for (RowSpMat::InnerIterator it(rows, i); it; ++it) sum += it.value() * it.value() * minv[it.col()];
    return sum;
  };
  h_diag_[i] = self_product(rows_.normal);
  if (!friction_) return;
  ht_diag_[i] = self_product(rows_.tangent);
  if (!cone_) return;
  Eigen::Matrix2d& h = ht_blocks_[static_cast<std::size_t>(i)];
  h(0, 0) = ht_diag_[i];
  h(0, 1) = h(1, 0) = weighted_row_dot(rows_.tangent, i, rows_.tangent2, i, minv);
  h(1, 1) = weighted_row_dot(rows_.tangent2, i, rows_.tangent2, i, minv);
}

double CdPenalty::stable_step_with_contacts() const { return problem_->stable_step() * std::sqrt(1.0 - factor_ / 4.0); }

ImpactAccuracy CdPenalty::impact_accuracy() const {
  return {std::numbers::pi / (2.0 * nsb::dmath::asin(std::sqrt(factor_) / 2.0)) + 1.0, false};
}

StepInfo CdPenalty::advance(double tau) {
  StepInfo info;
  info.dt = tau;
  cd_.drift(*problem_, state_, tau, work_);
  cd_.kick(state_, tau);

  // Penalty forces, contact by contact (H diagonal: independent; otherwise one Gauss-Seidel
  // sweep, each contact seeing the velocity the previous ones left).
  std::swap(gap_prev2_, gap_prev_);
  std::swap(gap_prev_, gap_);
  if (moving_) {
    problem_->evaluate_contacts(state_.u, rows_);
    gap_ = rows_.gap;
  } else {
    gap_.noalias() = rows_.normal * state_.u;
    gap_ += problem_->gap_offset();
  }
  store_spring_work();
  impulses_.setZero();
  if (friction_) tangential_impulses_.setZero();
  if (cone_) tangential_impulses2_.setZero();
  const RowSpMat& L = rows_.normal;
  const RowSpMat& T = rows_.tangent;
  for (Index i = 0; i < L.rows(); ++i) {
    if (!(gap_[i] < 0.0)) continue;
    if (moving_) contact_masses(i);  // H_ii, h_T,i at U_{k+1}
    if (!(gap_prev_[i] < 0.0)) zeta_[i] = cd_penalty_damping_ratio(-gap_[i] / (gap_prev_[i] - gap_[i]), factor_, e_);
    const double mi = 1.0 / h_diag_[i];
    const double kappa = factor_ * mi / (tau * tau);
    const double c = 2.0 * zeta_[i] * std::sqrt(kappa * mi);
    double gdot = 0.0;
    for (RowSpMat::InnerIterator it(L, i); it; ++it) gdot += it.value() * state_.v[it.col()];
    if (moving_ && friction_ && !cone_ && mu_[i] != 0.0) {
      apply_coupled_contact(i, kappa, c, gdot, tau);
      continue;
    }
    const double f = std::max(0.0, (-kappa * gap_[i] - c * gdot) / (1.0 + c * tau * h_diag_[i]));
    if (f == 0.0) continue;
    spring_force_[i] = -kappa * gap_[i];
    impulses_[i] = tau * f;
    for (RowSpMat::InnerIterator it(L, i); it; ++it) state_.v[it.col()] += cd_.minv[it.col()] * it.value() * tau * f;
    if (!friction_ || mu_[i] == 0.0) continue;
    if (cone_) {
      apply_cone_friction(i);
      continue;
    }
    double slip = -w_[i];
    for (RowSpMat::InnerIterator it(T, i); it; ++it) slip += it.value() * state_.v[it.col()];
    const double lambda_t = implicit_regularised_friction(mu_[i], impulses_[i], slip, ht_diag_[i], v_reg_);
    tangential_impulses_[i] = lambda_t;
    for (RowSpMat::InnerIterator it(T, i); it; ++it) state_.v[it.col()] += cd_.minv[it.col()] * it.value() * lambda_t;
  }
  return info;
}

void CdPenalty::apply_coupled_contact(Index i, double kappa, double c, double gdot, double tau) {
  const RowSpMat& L = rows_.normal;
  const RowSpMat& T = rows_.tangent;
  const double w_nt = weighted_row_dot(L, i, T, i, cd_.minv);
  double slip = -w_[i];
  for (RowSpMat::InnerIterator it(T, i); it; ++it) slip += it.value() * state_.v[it.col()];
  double f = 0.0, lambda_t = 0.0;
  for (int it = 0; it < kCoupledContactMaxSweeps; ++it) {
    f = std::max(0.0, (-kappa * gap_[i] - c * (gdot + w_nt * lambda_t)) / (1.0 + c * tau * h_diag_[i]));
    const double next = implicit_regularised_friction(mu_[i], tau * f, slip + w_nt * tau * f, ht_diag_[i], v_reg_);
    const bool settled = std::abs(next - lambda_t) <= kCoupledContactTolerance * std::abs(next);
    lambda_t = next;
    if (settled) break;
  }
  if (f == 0.0) return;
  spring_force_[i] = -kappa * gap_[i];
  impulses_[i] = tau * f;
  tangential_impulses_[i] = lambda_t;
  for (RowSpMat::InnerIterator it(L, i); it; ++it) state_.v[it.col()] += cd_.minv[it.col()] * it.value() * tau * f;
  for (RowSpMat::InnerIterator it(T, i); it; ++it) state_.v[it.col()] += cd_.minv[it.col()] * it.value() * lambda_t;
}

void CdPenalty::apply_cone_friction(Index i) {
  Eigen::Vector2d slip(-w_[i], -w2_[i]);
  for (RowSpMat::InnerIterator it(rows_.tangent, i); it; ++it) slip[0] += it.value() * state_.v[it.col()];
  for (RowSpMat::InnerIterator it(rows_.tangent2, i); it; ++it) slip[1] += it.value() * state_.v[it.col()];
  const Eigen::Vector2d lambda =
      implicit_regularised_cone_friction(mu_[i], impulses_[i], slip, ht_blocks_[static_cast<std::size_t>(i)], v_reg_);
  tangential_impulses_[i] = lambda[0];
  tangential_impulses2_[i] = lambda[1];
  for (RowSpMat::InnerIterator it(rows_.tangent, i); it; ++it) state_.v[it.col()] += cd_.minv[it.col()] * it.value() * lambda[0];
  for (RowSpMat::InnerIterator it(rows_.tangent2, i); it; ++it) state_.v[it.col()] += cd_.minv[it.col()] * it.value() * lambda[1];
}

void CdPenalty::store_spring_work() {
  for (Index i = 0; i < gap_.size(); ++i) {
    stored_[i] -= 0.5 * spring_force_[i] * (gap_[i] - gap_prev2_[i]);
    if (!(gap_[i] < 0.0)) stored_[i] = 0.0;  // open: its spring holds nothing
    spring_force_[i] = 0.0;                  // set again where a force acts at U_{k+1}
  }
}

Energy CdPenalty::energy() const {
  if (!cd_.started) return Integrator::energy();
  Energy E = cd_.energy(*problem_, state_);
  E.potential += stored_.sum();
  return E;
}

NSBENCH_INTEGRATOR({"cd-penalty", "explicit central difference with penalty contact (spring-dashpot, kappa = penalty_factor m / dt^2)", &CdPenalty::parameters_spec, &make_from_params<Integrator, CdPenalty>, false, false,
                    {.friction = true, .moving_contacts = true, .friction_cone = true, .explicit_step = true, .mass = MassNeed::DiagonalPositive}});

}  // namespace nsb
