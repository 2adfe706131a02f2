// Run measure "momentum-balance": the momentum balance of a 1D problem per step (MomentumBalance,
// studies/measures.hpp: P - P0 - the impulses of the external forces and of the contacts, P =
// 1^T M v). Result: largest, the largest |residual| over the steps; momentum, the largest |P|;
// relative = largest / momentum (largest / speed_scale where P stays 0).
#include "studies/measures.hpp"
#include "studies/run_measure.hpp"

#include <algorithm>
#include <cmath>

namespace nsb {

namespace {

class MomentumBalanceMeasure final : public RunMeasure {
 public:
  MomentumBalanceMeasure(const Problem& problem, const Integrator& integrator)
      : balance_(problem, integrator.state().v), largest_p_(std::abs(balance_.initial())) {}
  void add(const Integrator& integrator, const StepInfo& step) override {
    balance_.add(integrator, step.dt);
    largest_ = std::max(largest_, balance_.residual(integrator.state().v));
    largest_p_ = std::max(largest_p_, std::abs(balance_.momentum(integrator.state().v)));
  }
  Json result() const override {
    const double scale = largest_p_ > 0.0 ? largest_p_ : balance_.speed_scale();
    return {{"largest", real(largest_)}, {"momentum", real(largest_p_)}, {"relative", real(largest_ / scale)}};
  }

 private:
  MomentumBalance balance_;
  double largest_ = 0.0, largest_p_;
};

ParamSpecs no_parameters() { return {}; }

std::unique_ptr<RunMeasure> make_momentum_balance(const Params&, const Problem& problem, const Integrator& integrator) {
  return std::make_unique<MomentumBalanceMeasure>(problem, integrator);
}

}  // namespace

extern const RunMeasureEntry momentum_balance_measure;
const RunMeasureEntry momentum_balance_measure{"momentum-balance", "the momentum balance of a 1D problem per step: its largest residual",
                     &no_parameters, &make_momentum_balance};

}  // namespace nsb
