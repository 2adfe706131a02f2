// moreau-midpoint: an integrator plugin as nsbench 0.1.0 documented them, kept as it was so
// that CI shows when a change breaks such a plugin (scripts/plugin-example.sh builds it against
// the installed nsbench and runs it on a friction problem). It overrides what 0.1.0 asked
// for (name, conditionally_stable, treats_friction, step) and includes 0.1.0's header paths.
//
// Moreau's midpoint scheme with the velocity-level impulse law and Coulomb friction:
//     u_m      = u_k + h/2 v_k
//     v_free   = v_k + h M^{-1} (F_ext(t_k + h/2) - F_int(u_m))
//     Lambda   from the impulse law at u_m + h/2 v_free (ImpulseContact)
//     v_{k+1}  = v_free + M^{-1} (L^T Lambda + T^T Lambda_T),   u_{k+1} = u_m + h/2 v_{k+1}
// Reference: J.J. Moreau, Numerical aspects of the sweeping process, CMAME 177 (1999) 329-349.
#include <fmt/format.h>

#include <nsbench/integrators/impulse_contact.hpp>
#include <nsbench/integrators/lcp.hpp>
#include <nsbench/integrators/registry.hpp>

namespace {

using namespace nsb;

class MoreauMidpoint final : public Integrator {
 public:
  explicit MoreauMidpoint(const Params& params) : Integrator(params), lcp_(lcp_options(params)) {}
  static ParamSpecs parameters_spec() { return lcp_parameter_specs(); }

  std::string name() const override { return "moreau-midpoint"; }
  bool conditionally_stable() const override { return true; }
  bool treats_friction() const override { return true; }

  void init(const Problem& problem, const State& initial) override {
    bind(problem, initial);
    const auto m = diagonal_mass(mass_);
    if (!m || !(m->array() > 0.0).all())
      throw InputError(fmt::format("integrator moreau-midpoint needs a diagonal mass with positive entries; "
                                   "problem {} has another", problem.name()));
    minv_ = m->cwiseInverse();
    f_int_ = Vec::Zero(problem.ndof());
    f_ext_ = Vec::Zero(problem.ndof());
    contact_ = ImpulseContact(problem, minv_, lcp_);
  }

  StepInfo step(double h) override {
    StepInfo info;
    info.dt = h;
    u_mid_ = state_.u + 0.5 * h * state_.v;
    problem_->internal_force(u_mid_, f_int_);
    ++work_.force_evaluations;
    problem_->external_force(state_.t + 0.5 * h, f_ext_);
    v_prev_ = state_.v;
    state_.v += h * minv_.cwiseProduct(f_ext_ - f_int_);
    info.iterations = contact_.apply(u_mid_ + 0.5 * h * state_.v, v_prev_, state_.v, impulses_, tangential_impulses_,
                                     info, work_);
    state_.u = u_mid_ + 0.5 * h * state_.v;
    state_.t += h;
    work_.lcp_iterations += info.iterations;
    ++work_.steps;
    return info;
  }

 private:
  LcpOptions lcp_;
  ImpulseContact contact_;
  Vec minv_, f_int_, f_ext_, u_mid_, v_prev_;
};

}  // namespace

NSBENCH_INTEGRATOR({"moreau-midpoint", "0.1.0 plugin: Moreau's midpoint scheme, impulse contact with Coulomb friction",
                    &MoreauMidpoint::parameters_spec, &nsb::make_from_params<nsb::Integrator, MoreauMidpoint>, false});
