#include "integrators/cd_lagrange.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "core/threads.hpp"

namespace nsb {

ParamSpecs CdLagrange::parameters_spec() { return lcp_parameter_specs(); }

CdLagrange::CdLagrange(const Params& params) : Integrator(params), lcp_(lcp_options(params)) {}

void CdLagrange::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const auto diag = diagonal_mass(mass_);
  if (!diag)
    throw InputError(fmt::format("integrator cd-lagrange needs a diagonal mass matrix; problem {} has a non-diagonal one", problem.name()));
  m_ = *diag;
  if ((m_.array() < 0.0).any())
    throw InputError(fmt::format("integrator cd-lagrange needs non-negative masses; problem {} has a negative one", problem.name()));
  // Massless dofs get minv = 0: the free velocity and the impulses leave them alone.
  minv_ = (m_.array() > 0.0).select(m_.cwiseInverse(), 0.0);

  const Index n = problem.ndof();
  massless_.clear();
  column_rows_.clear();
  column_values_.clear();
  if ((m_.array() == 0.0).any()) {
    const auto fail = [&](const std::string& why) {
      throw InputError(fmt::format("integrator cd-lagrange: problem {} has massless dofs, which need {}", problem.name(), why));
    };
    if (!problem.is_linear()) fail("a linear problem");
    SpMat K;
    problem.tangent_stiffness(state_.u, K);
    ++work_.tangent_evaluations;
    const Eigen::SparseMatrix<double, Eigen::RowMajor> L = problem.gap_operator();
    const SpMat Lc = problem.gap_operator();  // column access: the contacts touching a dof
    for (Index i = 0; i < n; ++i) {
      if (m_[i] != 0.0) continue;
      MasslessDof q{i, -1, 0.0, 0.0, column_rows_.size(), 0};
      for (SpMat::InnerIterator it(K, i); it; ++it) {
        if (it.row() == i) q.k_ii = it.value();
        else if (m_[it.row()] == 0.0 && it.value() != 0.0) fail("a diagonal tangent block on them (dofs coupled by K)");
        column_rows_.push_back(it.row());
        column_values_.push_back(it.value());
      }
      q.end = column_rows_.size();
      if (!(q.k_ii > 0.0)) fail(fmt::format("K_ii > 0 (dof {} has K_ii = {})", i, q.k_ii));
      for (SpMat::InnerIterator it(Lc, i); it; ++it) {
        if (it.value() == 0.0) continue;
        if (q.contact >= 0) fail(fmt::format("at most one contact per dof (dof {})", i));
        if (L.row(it.row()).nonZeros() != 1) fail(fmt::format("contacts on that dof only (contact {})", it.row()));
        q.contact = it.row();
        q.l = it.value();
      }
      massless_.push_back(q);
    }
  }
  massless_impulse_ = Vec::Zero(static_cast<Index>(massless_.size()));
  u_prev_ = state_.u;
  v_prev_ = state_.v;
  f_int_ = Vec::Zero(n);
  f_ext_ = Vec::Zero(n);
  problem.external_force(state_.t, f_ext_);
  contact_ = ImpulseContact(problem, minv_, lcp_);
  started_ = false;
}

StepInfo CdLagrange::step(double tau) {
  StepInfo info;
  info.dt = tau;
  if (!started_) {
    problem_->internal_force(state_.u, f_int_);
    ++work_.force_evaluations;
    state_.v += 0.5 * tau * minv_.cwiseProduct(f_ext_ - f_int_);
    started_ = true;
  }
  std::swap(u_prev_, state_.u);
  parallel_ranges(state_.u.size(), [&](Index b, Index e) {
    state_.u.segment(b, e - b).noalias() = u_prev_.segment(b, e - b) + tau * state_.v.segment(b, e - b);
  });
  state_.t += tau;

  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  if (!problem_->external_force_is_constant()) problem_->external_force(state_.t, f_ext_);

  if (!massless_.empty()) solve_massless(tau);

  std::swap(v_prev_, state_.v);
  parallel_ranges(state_.v.size(), [&](Index b, Index e) {  // v_free
    const Index k = e - b;
    state_.v.segment(b, k).noalias() =
        v_prev_.segment(b, k) + tau * minv_.segment(b, k).cwiseProduct(f_ext_.segment(b, k) - f_int_.segment(b, k));
  });

  info.iterations = contact_.apply(state_.u, v_prev_, state_.v, impulses_, info, work_);
  for (std::size_t q = 0; q < massless_.size(); ++q) {
    const MasslessDof& d = massless_[q];
    state_.v[d.dof] = (state_.u[d.dof] - u_prev_[d.dof]) / tau;
    if (d.contact >= 0) impulses_[d.contact] = massless_impulse_[static_cast<Index>(q)];
  }
  work_.lcp_iterations += info.iterations;
  ++work_.steps;
  return info;
}

void CdLagrange::solve_massless(double tau) {
  const Vec& g0 = problem_->gap_offset();
  for (std::size_t q = 0; q < massless_.size(); ++q) {
    const MasslessDof& d = massless_[q];
    double& u = state_.u[d.dof];
    double du = -(f_int_[d.dof] - f_ext_[d.dof]) / d.k_ii;  // to the free equilibrium
    if (d.contact >= 0) {
      const double gap = g0[d.contact] + d.l * (u + du);
      if (gap < 0.0) du -= gap / d.l;  // held on the obstacle
    }
    u += du;
    for (std::size_t e = d.begin; e < d.end; ++e) f_int_[column_rows_[e]] += column_values_[e] * du;
    // The force the contact exerts is what holds the node: its residual, >= 0 by construction
    // (zero when free); max() only clears round-off of the free case.
    massless_impulse_[static_cast<Index>(q)] =
        d.contact >= 0 ? std::max(0.0, tau * (f_int_[d.dof] - f_ext_[d.dof]) / d.l) : 0.0;
  }
}

Energy CdLagrange::energy() const {
  if (!started_) return Integrator::energy();
  return {0.5 * v_prev_.dot(m_.cwiseProduct(v_prev_)),
          0.5 * (problem_->potential(u_prev_) + problem_->potential(state_.u))};
}

NSBENCH_INTEGRATOR({"cd-lagrange", "explicit variational CD-Lagrange, fixed step, impulse contact", &CdLagrange::parameters_spec, &make_from_params<Integrator, CdLagrange>, false});

}  // namespace nsb
