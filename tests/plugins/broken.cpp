// A deliberately broken integrator for `nsbench check` (tests/app/check_test.cpp): CD-Lagrange
// underneath, so its motion is right, but it reports its impulses with the sign convention
// inverted (a push apart as Lambda < 0) and never counts its steps (work().steps stays 0, so
// budgets and tables would read nothing).
#include "integrators/registry.hpp"

namespace {

class Broken final : public nsb::Integrator {
 public:
  explicit Broken(const nsb::Params& params) : Integrator(params), inner_(nsb::make_integrator("cd-lagrange")) {}
  static nsb::ParamSpecs parameters_spec() { return {}; }
  std::string name() const override { return "broken"; }
  bool conditionally_stable() const override { return true; }

  void init(const nsb::Problem& problem, const nsb::State& initial) override {
    bind(problem, initial);
    inner_->init(problem, initial);
  }

  nsb::StepInfo step(double dt) override {
    const nsb::StepInfo info = inner_->step(dt);
    state_ = inner_->state();
    impulses_ = -inner_->impulses();
    tangential_impulses_ = inner_->tangential_impulses();
    work_.force_evaluations = inner_->work().force_evaluations;
    return info;
  }

 private:
  std::unique_ptr<nsb::Integrator> inner_;
};

}  // namespace

NSBENCH_INTEGRATOR({"broken", "test plugin: inverted impulse sign, no step count", &Broken::parameters_spec,
                    &nsb::make_from_params<nsb::Integrator, Broken>, false});
