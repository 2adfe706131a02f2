// Run measure "momentum-balance": the momentum balance of a 1D problem per step (MomentumBalance,
// studies/measures.hpp: P - P0 - the impulses of the external forces and of the contacts, P =
// 1^T M v), from the state after the first step, as mesh-momentum's: a scheme's first step may
// start from a velocity at another time (CD-Lagrange's half kick under a load), an offset that
// is no defect of the balance. Result: largest, the largest |residual - residual after step 1|
// over the steps; momentum, the largest |P|; relative = largest / momentum (largest /
// speed_scale where P stays 0). A problem of more than one dimension declines (its 1^T M v
// mixes the directions): mesh-momentum takes each component.
#include <fmt/format.h>

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
    const double r = balance_.signed_residual(integrator.state().v);
    if (++steps_ == 1) start_ = r;
    largest_ = std::max(largest_, std::abs(r - start_));
    largest_p_ = std::max(largest_p_, std::abs(balance_.momentum(integrator.state().v)));
  }
  Json result() const override {
    const double scale = largest_p_ > 0.0 ? largest_p_ : balance_.speed_scale();
    return {{"largest", real(largest_)}, {"momentum", real(largest_p_)}, {"relative", real(largest_ / scale)}};
  }

 private:
  MomentumBalance balance_;
  double largest_ = 0.0, largest_p_, start_ = 0.0;
  long steps_ = 0;
};

ParamSpecs no_parameters() { return {}; }

std::unique_ptr<RunMeasure> make_momentum_balance(const Params&, const Problem& problem, const Integrator& integrator) {
  if (const auto mesh = problem.field_mesh(); mesh && mesh->dimension > 1)
    throw InputError(fmt::format("momentum-balance: problem {} is {}D, its 1^T M v mixes directions; valid: a 1D problem "
                                 "(mesh-momentum takes each component of a {}D one)", problem.name(), mesh->dimension, mesh->dimension));
  return std::make_unique<MomentumBalanceMeasure>(problem, integrator);
}

}  // namespace

extern const RunMeasureEntry momentum_balance_measure;
const RunMeasureEntry momentum_balance_measure{"momentum-balance", "the momentum balance of a 1D problem per step: its largest residual",
                     &no_parameters, &make_momentum_balance};

}  // namespace nsb
