// symplectic-euler: an nsbench plugin (built out of tree against an installed nsbench).
//
// Symplectic Euler (velocity first) with Moreau's velocity-level impulse contact:
//
//     v_free    = v_k + h M^{-1} (F_ext(t_k) - F_int(q_k))
//     q_pred    = q_k + h v_free                      (contacts closing within the step)
//     Lambda_i  = 0 where g_i(q_pred) > 0; on the others
//                 0 <= Lambda  _|_  g'_free + H Lambda + e g'_k >= 0,   H = L M^{-1} L^T
//     v_{k+1}   = v_free + M^{-1} L^T Lambda
//     q_{k+1}   = q_k + h v_{k+1}
//
// Without contact this is the symplectic Euler method (first order, symplectic: its energy
// error stays O(h) over long times); the contact step is Moreau's impulse law with Newton
// restitution on the contacts the free motion would close, so Lambda >= 0 acts only on
// closed or closing contacts. Needs a diagonal mass with positive entries (the impulse
// law divides by H_ii).
//
// References: E. Hairer, C. Lubich, G. Wanner, Geometric Numerical Integration, 2nd ed.,
// Springer 2006, section VI.3 (symplectic Euler); J.J. Moreau, Unilateral contact and dry
// friction in finite freedom dynamics, CISM Courses 302, Springer 1988 (impulse contact);
// M. Jean, The non-smooth contact dynamics method, CMAME 177 (1999) 235-257.
#include <fmt/format.h>

#include <nsbench/integrators/impulse_contact.hpp>
#include <nsbench/integrators/registry.hpp>

namespace {

using namespace nsb;

class SymplecticEuler final : public Integrator {
 public:
  explicit SymplecticEuler(const Params& params) : Integrator(params), lcp_(lcp_options(params)) {}
  static ParamSpecs parameters_spec() { return lcp_parameter_specs(); }

  std::string name() const override { return "symplectic-euler"; }
  // Explicit: stable only for h below the problem's stable step (nsbench run warns above it).
  bool conditionally_stable() const override { return true; }

  void init(const Problem& problem, const State& initial) override {
    bind(problem, initial);
    const auto m = diagonal_mass(mass_);
    if (!m || !(m->array() > 0.0).all())
      throw InputError(fmt::format("integrator symplectic-euler needs a diagonal mass with positive entries; "
                                   "problem {} has another", problem.name()));
    minv_ = m->cwiseInverse();
    const Index n = problem.ndof();
    f_int_ = Vec::Zero(n);
    f_ext_ = Vec::Zero(n);
    problem.external_force(state_.t, f_ext_);
    u_prev_ = state_.u;
    v_prev_ = state_.v;
    contact_ = ImpulseContact(problem, minv_, lcp_);
  }

  StepInfo step(double h) override {
    StepInfo info;
    info.dt = h;
    problem_->internal_force(state_.u, f_int_);
    ++work_.force_evaluations;
    if (!problem_->external_force_is_constant()) problem_->external_force(state_.t, f_ext_);
    std::swap(v_prev_, state_.v);
    state_.v.noalias() = v_prev_ + h * minv_.cwiseProduct(f_ext_ - f_int_);  // v_free
    std::swap(u_prev_, state_.u);
    state_.u.noalias() = u_prev_ + h * state_.v;  // q_pred
    info.iterations = contact_.apply(state_.u, v_prev_, state_.v, impulses_, tangential_impulses_, info, work_);
    state_.u.noalias() = u_prev_ + h * state_.v;
    state_.t += h;
    work_.lcp_iterations += info.iterations;
    ++work_.steps;
    return info;
  }

 private:
  LcpOptions lcp_;
  ImpulseContact contact_;
  Vec minv_, f_int_, f_ext_, u_prev_, v_prev_;
};

}  // namespace

NSBENCH_INTEGRATOR({"symplectic-euler", "plugin example: symplectic Euler, velocity-level impulse contact (Moreau)",
                    &SymplecticEuler::parameters_spec, &nsb::make_from_params<nsb::Integrator, SymplecticEuler>, false});
