#include "integrators/moreau_jean.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace nsb {

ParamSpecs MoreauJean::parameters_spec() {
  ParamSpecs specs = {
      ParamSpec::real("theta", 0.5, 0.5, 1.0, "theta of the theta-method"),
      ParamSpec::optional_real("gamma", 0.0, 1.0, "contacts with g_k + gamma h g'_k <= 0 are active (unset: 1 - theta)"),
      ParamSpec::choice("projection", "none", {"none", "position"}, "position: project U_{k+1} onto g >= 0 after the step (Acary 2013)"),
  };
  const ParamSpecs lcp = lcp_parameter_specs();
  specs.insert(specs.end(), lcp.begin(), lcp.end());
  return specs;
}

MoreauJean::MoreauJean(const Params& params)
    : Integrator(params),
      theta_(params.real("theta")),
      gamma_(params.optional_real("gamma").value_or(1.0 - theta_)),
      project_positions_(params.choice("projection") == "position") {
  lcp_ = lcp_options(params);
}

void MoreauJean::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const Index n = problem.ndof();
  problem.tangent_stiffness(state_.u, K_);
  ++work_.tangent_evaluations;
  moving_ = problem.contacts_move();
  if (moving_ && project_positions_)
    throw InputError(fmt::format("integrator moreau-jean: projection = position needs contacts with constant rows (it "
                                 "projects onto g0 + L U >= 0); problem {} has moving contacts (valid: projection = none)",
                                 problem.name()));
  rows_ = problem.contact_geometry();
  responses_.bind(rows_.normal.rows());
  friction_ = problem.contacts().has_friction();
  cone_ = problem.contacts().has_cone();
  if (cone_) tangent2_responses_.bind(rows_.normal.rows());
  if (friction_) {
    tangent_responses_.bind(rows_.normal.rows());
    mu_active_ = Vec::Zero(rows_.normal.rows());
    restitution_rate_ = Vec::Zero(rows_.normal.rows());
  }
  f_int_ = Vec::Zero(n);
  f_ext_now_ = Vec::Zero(n);
  f_ext_next_ = Vec::Zero(n);
  rhs_ = Vec::Zero(n);
  v_next_ = Vec::Zero(n);
  gap_ = Vec::Zero(rows_.normal.rows());
  gdot_ = Vec::Zero(rows_.normal.rows());
  problem.external_force(state_.t, f_ext_now_);
  f_ext_next_ = f_ext_now_;
  lcp_max_residual_ = nullptr;
  h_factored_ = 0.0;
  // W's pattern (M + K for every h) is analysed here, so that a W too large for the memory
  // is refused before the run starts.
  W_.bind(mass_, K_);
  chol_.analyze(W_.matrix(), "integrator moreau-jean", "W");
}

void MoreauJean::factorize(double h) {
  const SpMat& W = W_.assemble(mass_, h * h * theta_ * theta_, K_);
  chol_.factorize(W, true);
  ++work_.factorizations;
  if (chol_.uses_lu()) ++work_.extra["lu_fallbacks"];
  h_factored_ = h;
  responses_.invalidate();
  tangent_responses_.invalidate();
  tangent2_responses_.invalidate();
}

const Vec& MoreauJean::contact_response(Index i) {
  return responses_.get(rows_.normal, i, [this](Vec& r) {
    chol_.solve(r, r);
    ++work_.linear_solves;
  });
}

const Vec& MoreauJean::tangent_response(Index i) {
  return tangent_responses_.get(rows_.tangent, i, [this](Vec& r) {
    chol_.solve(r, r);
    ++work_.linear_solves;
  });
}

const Vec& MoreauJean::tangent2_response(Index i) {
  return tangent2_responses_.get(rows_.tangent2, i, [this](Vec& r) {
    chol_.solve(r, r);
    ++work_.linear_solves;
  });
}

LcpResult MoreauJean::solve_frictionless(Index a, double e) {
  auto& [D, q, x] = lcp_storage_.of_size(a);
  for (Index c = 0; c < a; ++c) {
    const Vec& r = contact_response(active_[c]);
    for (Index row = 0; row < a; ++row) D(row, c) = rows_.normal.row(active_[row]).dot(r);
  }
  for (Index row = 0; row < a; ++row)
    q[row] = rows_.normal.row(active_[row]).dot(v_next_) + e * gdot_[active_[row]];
  const LcpResult res = solve_lcp(D, q, x, lcp_);
  for (Index c = 0; c < a; ++c) {
    if (x[c] == 0.0) continue;
    impulses_[active_[c]] = x[c];
    v_next_.noalias() += x[c] * contact_response(active_[c]);
  }
  return res;
}

LcpResult MoreauJean::solve_with_friction() {
  const FrictionalCorrection c{rows_.normal,
                               rows_.tangent,
                               problem_->contacts(),
                               [this](Index i) -> const Vec& { return contact_response(i); },
                               [this](Index i) -> const Vec& { return tangent_response(i); },
                               cone_ ? &rows_.tangent2 : nullptr,
                               [this](Index i) -> const Vec& { return tangent2_response(i); },
                               &tangential_impulses2_};
  return frictional_correction(c, restitution_rate_, v_next_, impulses_, tangential_impulses_, active_, lcp_,
                               lcp_storage_, mu_active_);
}

StepInfo MoreauJean::advance(double h) {
  StepInfo info;
  info.dt = h;
  if (problem_->is_linear()) {
    if (h != h_factored_) factorize(h);
  } else {
    problem_->tangent_stiffness(state_.u, K_);
    ++work_.tangent_evaluations;
    factorize(h);
  }
  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  const bool constant_force = problem_->external_force_is_constant();  // then f_ext_next_ == f_ext_now_
  if (!constant_force) problem_->external_force(state_.t + h, f_ext_next_);

  rhs_.noalias() = h * (theta_ * f_ext_next_ + (1.0 - theta_) * f_ext_now_ - f_int_);
  rhs_.noalias() -= (h * h * theta_) * (K_ * state_.v);
  chol_.solve(rhs_, v_next_);
  v_next_ += state_.v;  // V_free; the impulses are added to it below
  ++work_.linear_solves;

  // Active set from the forecast gap.
  const Vec& g0 = problem_->gap_offset();
  const double e = problem_->restitution();
  if (moving_) {
    // The rows at U_k, as Siconos' LagrangianScleronomousR at the first Newton iterate.
    problem_->evaluate_contacts(state_.u, rows_);
    gap_ = rows_.gap;
    responses_.invalidate();
    tangent_responses_.invalidate();
    tangent2_responses_.invalidate();
  } else {
    gap_.noalias() = rows_.normal * state_.u;
    gap_ += g0;
  }
  gdot_.noalias() = rows_.normal * state_.v;
  active_.clear();
  for (Index i = 0; i < rows_.normal.rows(); ++i)
    if (gap_[i] + h * gamma_ * gdot_[i] <= 0.0) active_.push_back(i);

  impulses_.setZero();
  if (friction_) {
    tangential_impulses_.setZero();
    if (cone_) tangential_impulses2_.setZero();  // the local solves write the active contacts' only
    restitution_rate_.noalias() = e * gdot_;
  }
  if (!active_.empty()) {
    const Index a = static_cast<Index>(active_.size());
    const LcpResult res = friction_ ? solve_with_friction() : solve_frictionless(a, e);
    info.iterations = res.iterations;
    work_.lcp_iterations += res.iterations;
    if (!lcp_max_residual_) lcp_max_residual_ = &work_.extra["lcp_max_residual"];
    *lcp_max_residual_ = std::max(*lcp_max_residual_, res.residual);
    if (!res.converged) {
      info.converged = false;
      ++work_.lcp_unconverged;
    }
  }
  state_.u.noalias() += h * (theta_ * v_next_ + (1.0 - theta_) * state_.v);
  if (project_positions_) {
    const LcpResult res = contact_correction(rows_.normal, g0, state_.u, nu_, {}, true,
                                             [this](Index i) -> const Vec& { return contact_response(i); }, lcp_, work_,
                                             correction_);
    info.iterations += res.iterations;
    if (!res.converged) info.converged = false;
  }
  std::swap(state_.v, v_next_);
  if (!constant_force) std::swap(f_ext_now_, f_ext_next_);
  return info;
}

NSBENCH_INTEGRATOR({"moreau-jean", "Moreau-Jean theta-method, velocity-level LCP with Newton restitution", &MoreauJean::parameters_spec, &make_from_params<Integrator, MoreauJean>, false, false, {.friction = true, .moving_contacts = true, .friction_cone = true}});

}  // namespace nsb
