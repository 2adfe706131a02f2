#include "integrators/cd_lagrange.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>


namespace nsb {

ParamSpecs CdLagrange::parameters_spec() { return lcp_parameter_specs(); }

CdLagrange::CdLagrange(const Params& params) : Integrator(params), lcp_(lcp_options(params)) {}

void CdLagrange::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  // Massless dofs get minv = 0: the free velocity and the impulses leave them alone.
  cd_.reset(problem, state_, mass_.diagonal());
  const Vec& m = cd_.m;

  const Index n = problem.ndof();
  massless_.clear();
  column_rows_.clear();
  column_values_.clear();
  if ((m.array() == 0.0).any()) {
    const auto fail = [&](const std::string& why) {
      throw InputError(fmt::format("integrator cd-lagrange: problem {} has massless dofs, which need {}", problem.name(), why));
    };
    if (!problem.is_linear()) fail("a linear problem");
    if (problem.contacts_move()) fail("contacts with constant rows (the quasi-static solve uses g0 + l u_i)");
    if (problem.contacts().has_friction()) fail("mu = 0 (friction on a quasi-static dof is not treated)");
    SpMat K;
    problem.tangent_stiffness(state_.u, K);
    ++work_.tangent_evaluations;
    const Eigen::SparseMatrix<double, Eigen::RowMajor> L = problem.gap_operator();
    const SpMat Lc = problem.gap_operator();  // column access: the contacts touching a dof
    for (Index i = 0; i < n; ++i) {
      if (m[i] != 0.0) continue;
      MasslessDof q{i, -1, 0.0, 0.0, column_rows_.size(), 0};
      for (SpMat::InnerIterator it(K, i); it; ++it) {
        if (it.row() == i) q.k_ii = it.value();
        else if (m[it.row()] == 0.0 && it.value() != 0.0) fail("a diagonal tangent block on them (dofs coupled by K)");
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
  cone_ = problem.contacts().has_cone();
  if (cone_) {
    cone_contact_ = ConeContact(problem, cd_.minv, lcp_);
  } else {
    contact_ = ImpulseContact(problem, cd_.minv, lcp_);
  }
}

StepInfo CdLagrange::advance(double tau) {
  StepInfo info;
  info.dt = tau;
  cd_.drift(*problem_, state_, tau, work_);
  if (!massless_.empty()) solve_massless(tau);
  cd_.kick(state_, tau);

  info.iterations = cone_ ? cone_contact_.apply(state_.u, cd_.v_prev, state_.v, impulses_, tangential_impulses_,
                                                tangential_impulses2_, info, work_)
                         : contact_.apply(state_.u, cd_.v_prev, state_.v, impulses_, tangential_impulses_, info, work_);
  for (std::size_t q = 0; q < massless_.size(); ++q) {
    const MasslessDof& d = massless_[q];
    state_.v[d.dof] = (state_.u[d.dof] - cd_.u_prev[d.dof]) / tau;
    if (d.contact >= 0) impulses_[d.contact] = massless_impulse_[static_cast<Index>(q)];
  }
  work_.lcp_iterations += info.iterations;
  return info;
}

void CdLagrange::solve_massless(double tau) {
  const Vec& g0 = problem_->gap_offset();
  for (std::size_t q = 0; q < massless_.size(); ++q) {
    const MasslessDof& d = massless_[q];
    double& u = state_.u[d.dof];
    double du = -(cd_.f_int[d.dof] - cd_.f_ext[d.dof]) / d.k_ii;  // to the free equilibrium
    if (d.contact >= 0) {
      const double gap = g0[d.contact] + d.l * (u + du);
      if (gap < 0.0) du -= gap / d.l;  // held on the obstacle
    }
    u += du;
    for (std::size_t e = d.begin; e < d.end; ++e) cd_.f_int[column_rows_[e]] += column_values_[e] * du;
    // The force the contact exerts is what holds the node: its residual, >= 0 by construction
    // (zero when free); max() only clears round-off of the free case.
    massless_impulse_[static_cast<Index>(q)] =
        d.contact >= 0 ? std::max(0.0, tau * (cd_.f_int[d.dof] - cd_.f_ext[d.dof]) / d.l) : 0.0;
  }
}

Energy CdLagrange::energy() const {
  return cd_.started ? cd_.energy(*problem_, state_) : Integrator::energy();
}

NSBENCH_INTEGRATOR({"cd-lagrange", "explicit variational CD-Lagrange, fixed step, impulse contact", &CdLagrange::parameters_spec, &make_from_params<Integrator, CdLagrange>, false, false,
                    {.friction = true, .moving_contacts = true, .friction_cone = true, .explicit_step = true, .mass = MassNeed::Diagonal}});

}  // namespace nsb
