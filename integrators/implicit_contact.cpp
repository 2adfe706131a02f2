#include "integrators/implicit_contact.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace nsb {

void ImplicitContact::bind(const Problem& problem, const SpMat& M, const Vec& u0, WorkCounters& work, const LcpOptions& lcp,
                           const NewtonOptions& newton, const char* who) {
  problem_ = &problem;
  M_ = &M;
  work_ = &work;
  who_ = who;
  lcp_ = lcp;
  newton_ = newton;
  c_factored_ = 0.0;
  problem.tangent_stiffness(u0, K_);  // the pattern; values refilled per step if nonlinear
  ++work.tangent_evaluations;
  f_int_ = Vec::Zero(problem.ndof());
  L_ = problem.gap_operator();
  responses_.bind(L_.rows());
  if (problem.contacts().has_friction()) {
    T_ = problem.contacts().tangent;
    tangent_responses_.bind(L_.rows());
    mu_active_ = Vec::Zero(L_.rows());
  }
  cone_ = problem.contacts().has_cone();
  if (cone_) {
    T2_ = problem.contacts().tangent2;
    tangent2_responses_.bind(L_.rows());
  }
  if (problem.contacts_move()) geometry_ = problem.contact_geometry();
  S_.bind(M, K_);  // S's pattern for every c, analysed now: a factor too large is refused up front
  chol_.analyze(S_.matrix(), fmt::format("integrator {}", who), "S");
}

void ImplicitContact::factorize(double c) {
  chol_.factorize(S_.assemble(*M_, c, K_), true);
  ++work_->factorizations;
  if (chol_.uses_lu()) ++work_->extra["lu_fallbacks"];
  c_factored_ = c;
  responses_.invalidate();
  tangent_responses_.invalidate();
  tangent2_responses_.invalidate();
}

void ImplicitContact::solve_step(const Vec& u_hat, const Vec& f_ext, double c, bool with_contact, Vec& u, Vec& mu,
                                 StepInfo& info) {
  const bool linear = problem_->is_linear();
  mu.setZero(L_.rows());
  for (long it = 0;; ++it) {
    // The iterate: U_hat itself on the first iteration (no copy), where M (U - U_hat) = 0.
    const Vec& x = it == 0 ? u_hat : u;
    if (!linear) {
      problem_->tangent_stiffness(x, K_);
      ++work_->tangent_evaluations;
    }
    if (!linear || c != c_factored_) factorize(c);
    problem_->internal_force(x, f_int_);
    ++work_->force_evaluations;
    if (it == 0) {
      r_.noalias() = c * (f_int_ - f_ext);
    } else {
      du_ = u - u_hat;
      r_.noalias() = *M_ * du_;
      r_ += c * (f_int_ - f_ext);
    }
    chol_.solve(r_, du_);
    ++work_->linear_solves;
    du_ = x - du_;  // the next iterate before the contact correction
    if (with_contact) {
      const LcpResult res = correct(problem_->gap_offset(), du_, mu, {}, true);
      info.iterations += res.iterations;
      if (!res.converged) info.converged = false;
    }
    if (linear) {
      std::swap(u, du_);
      return;
    }
    const double change = (du_ - x).lpNorm<Eigen::Infinity>();
    std::swap(u, du_);
    ++info.iterations;
    // The increment cannot fall below the round-off of U: |U - U_hat| = O(h^2) can be far
    // smaller than eps |U| (a small step on a body away from the origin).
    const double floor = 100.0 * std::numeric_limits<double>::epsilon() * u.lpNorm<Eigen::Infinity>();
    if (change <= newton_.tolerance * (u - u_hat).lpNorm<Eigen::Infinity>() + floor) return;
    if (it + 1 >= newton_.max_iterations) {
      info.converged = false;
      ++work_->extra["newton_unconverged"];
      return;
    }
  }
}

const Vec& ImplicitContact::evaluate_contacts_at(ConstVecRef u) {
  problem_->evaluate_contacts(u, geometry_);
  L_ = geometry_.normal;
  responses_.invalidate();
  if (T_.rows() > 0) {
    T_ = geometry_.tangent;
    tangent_responses_.invalidate();
  }
  if (cone_) {
    T2_ = geometry_.tangent2;
    tangent2_responses_.invalidate();
  }
  return geometry_.gap;
}

const Vec& ImplicitContact::response(Index i) {
  return responses_.get(L_, i, [this](Vec& r) {
    chol_.solve(r, r);
    ++work_->linear_solves;
  });
}

const Vec& ImplicitContact::tangent_response(Index i) {
  return tangent_responses_.get(T_, i, [this](Vec& r) {
    chol_.solve(r, r);
    ++work_->linear_solves;
  });
}

const Vec& ImplicitContact::tangent2_response(Index i) {
  return tangent2_responses_.get(T2_, i, [this](Vec& r) {
    chol_.solve(r, r);
    ++work_->linear_solves;
  });
}

LcpResult ImplicitContact::correct_with_friction(const Vec& b, Vec& x, Vec& normal, Vec& tangential, Vec& tangential2,
                                                 const std::vector<Index>& active) {
  const FrictionalCorrection c{L_,
                               T_,
                               problem_->contacts(),
                               [this](Index i) -> const Vec& { return response(i); },
                               [this](Index i) -> const Vec& { return tangent_response(i); },
                               cone_ ? &T2_ : nullptr,
                               [this](Index i) -> const Vec& { return tangent2_response(i); },
                               &tangential2};
  const LcpResult res = frictional_correction(c, b, x, normal, tangential, active, lcp_, buffers_.lcp, mu_active_);
  work_->lcp_iterations += res.iterations;
  if (!res.converged) ++work_->lcp_unconverged;
  return res;
}

LcpResult frictional_correction(const FrictionalCorrection& c, const Vec& b, Vec& x, Vec& normal, Vec& tangential,
                                const std::vector<Index>& active, const LcpOptions& lcp, LcpStorage& storage,
                                Vec& mu_active) {
  const bool cone = c.T2 != nullptr;
  normal.setZero();
  tangential.setZero();
  if (cone) c.tangential2->setZero();
  const Index a = static_cast<Index>(active.size());
  if (a == 0) return {};
  const Index m = cone ? 3 : 2;  // rows per contact: N, T (, T2)
  const ContactRows* rows[3] = {&c.L, &c.T, c.T2};
  const std::function<const Vec&(Index)>* responses[3] = {&c.normal_response, &c.tangent_response, &c.tangent2_response};
  auto& [D, q, z] = storage.of_size(m * a);
  for (Index col = 0; col < a; ++col)
    for (Index l = 0; l < m; ++l) {
      const Vec& r = (*responses[l])(active[col]);
      for (Index row = 0; row < a; ++row)
        for (Index k = 0; k < m; ++k) D(m * row + k, m * col + l) = rows[k]->row(active[row]).dot(r);
    }
  for (Index row = 0; row < a; ++row) {
    const Index i = active[row];
    q[m * row] = b[i] + c.L.row(i).dot(x);
    q[m * row + 1] = c.T.row(i).dot(x) - c.contacts.tangent_velocity[i];
    if (cone) q[m * row + 2] = c.T2->row(i).dot(x) - c.contacts.tangent2_velocity[i];
    mu_active[row] = c.contacts.mu[i];
  }
  const LcpResult res = cone ? solve_coulomb_cone(D, q, mu_active.head(a), z, lcp) : solve_coulomb(D, q, mu_active.head(a), z, lcp);
  Vec* outputs[3] = {&normal, &tangential, c.tangential2};
  for (Index k = 0; k < a; ++k) {
    const Index i = active[k];
    for (Index l = 0; l < m; ++l) {
      (*outputs[l])[i] = z[m * k + l];
      if (z[m * k + l] != 0.0) x.noalias() += z[m * k + l] * (*responses[l])(i);
    }
  }
  return res;
}

LcpResult ImplicitContact::correct(const Vec& b, Vec& x, Vec& mu, const std::vector<Index>& active, bool grow) {
  return contact_correction(L_, b, x, mu, active, grow, [this](Index i) -> const Vec& { return response(i); }, lcp_,
                            *work_, buffers_);
}

LcpResult contact_correction(const ContactRows& L, const Vec& b, Vec& x, Vec& mu, const std::vector<Index>& fixed, bool grow,
                             const std::function<const Vec&(Index)>& response, const LcpOptions& lcp,
                             WorkCounters& work, CorrectionBuffers& buffers) {
  const Index p = L.rows();
  mu.setZero(p);
  LcpResult total;
  std::vector<Index>& active = buffers.active;
  active.assign(fixed.begin(), fixed.end());
  auto violated = [&](Index i) { return b[i] + L.row(i).dot(x) < 0.0; };
  if (grow)
    for (Index i = 0; i < p; ++i)
      if (violated(i)) active.push_back(i);
  if (active.empty()) return total;
  Vec& x0 = buffers.x0;
  x0 = x;
  // Each further pass adds at least one contact, so at most p + 1 passes.
  for (;;) {
    const Index a = static_cast<Index>(active.size());
    auto& [D, q, z] = buffers.lcp.of_size(a);
    for (Index c = 0; c < a; ++c) {
      const Vec& r = response(active[c]);
      for (Index row = 0; row < a; ++row) D(row, c) = L.row(active[row]).dot(r);
      q[c] = b[active[c]] + L.row(active[c]).dot(x0);
      z[c] = mu[active[c]];
    }
    const LcpResult res = solve_lcp(D, q, z, lcp);
    total.iterations += res.iterations;
    total.residual = res.residual;
    total.converged = res.converged;
    x = x0;
    for (Index c = 0; c < a; ++c) {
      mu[active[c]] = z[c];
      if (z[c] != 0.0) x.noalias() += z[c] * response(active[c]);
    }
    if (!grow) break;
    for (Index i = 0; i < p; ++i)
      if (violated(i) && std::find(active.begin(), active.end(), i) == active.end()) active.push_back(i);
    if (static_cast<Index>(active.size()) == a) break;
  }
  work.lcp_iterations += total.iterations;
  if (!total.converged) ++work.lcp_unconverged;
  return total;
}

void add_implicit_contact_specs(ParamSpecs& specs) {
  specs.push_back(ParamSpec::real("newton_tol", 1e-10, 0.0, 1e-2,
                                  "Newton tolerance (nonlinear F_int): |dU|_inf <= tol |U - U_hat|_inf + 100 eps |U|_inf", true));
  specs.push_back(ParamSpec::integer("newton_max_iter", 25, 1, 1000, "Newton iteration cap (nonlinear F_int)"));
  const ParamSpecs lcp = lcp_parameter_specs();
  specs.insert(specs.end(), lcp.begin(), lcp.end());
}

NewtonOptions newton_options(const Params& params) {
  return {params.real("newton_tol"), params.integer("newton_max_iter")};
}

Vec initial_acceleration(const Problem& problem, const State& s, const SpMat& M, const char* who) {
  const Index n = problem.ndof();
  Vec f_ext(n), f_int(n);
  problem.external_force(s.t, f_ext);
  problem.internal_force(s.u, f_int);
  const Vec r = f_ext - f_int;
  if (const auto m = diagonal_mass(M)) {
    Vec a = Vec::Zero(n);
    for (Index i = 0; i < n; ++i)
      if ((*m)[i] > 0.0) a[i] = r[i] / (*m)[i];
    return a;
  }
  SparseCholesky chol;
  chol.analyze(M, fmt::format("integrator {}", who), "M");
  if (!chol.factorize(M, false))
    throw InputError(fmt::format("{}: problem '{}' has a non-diagonal mass matrix that is not positive definite "
                                 "(massless dofs are handled only with a diagonal mass)", who, problem.name()));
  Vec a;
  chol.solve(r, a);
  return a;
}

}  // namespace nsb
