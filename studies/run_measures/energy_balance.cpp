// Run measure "energy-balance": the discrete energy balance of the scheme per step (EnergyBalance,
// studies/measures.hpp: the change of the scheme's own energy minus the work of the loads and of
// the contact impulses along its velocities), the envelope of its running sum per `window`
// seconds (Envelope: max |sum| over each window) and the drift rule on it (drift_rule: the
// envelope's slope with its 95 % interval; no drift when the interval holds 0 or the drift over
// the run is below the measure's round-off bound). Result: cumulative (the sum at the end),
// largest (the largest |residual| of a step), round_off, closed (steps balanced), the envelope
// (times, maxima) and drift {drift, low, high, over_run, windows, no_drift}. A scheme whose
// balance the measure does not derive declines the case.
#include "studies/measures.hpp"
#include "studies/run_measure.hpp"

#include <cmath>

namespace nsb {

namespace {

class EnergyBalanceMeasure final : public RunMeasure {
 public:
  EnergyBalanceMeasure(const Params& params, const Problem& problem, const Integrator& integrator)
      : balance_(problem, integrator), envelope_(integrator.state().t, params.real("window")) {}
  void add(const Integrator& integrator, const StepInfo&) override {
    balance_.add(integrator);
    envelope_.add(integrator.state().t, balance_.cumulative());
  }
  Json result() const override {
    const Drift d = drift_rule(envelope_.times(), envelope_.maxima(), balance_.round_off());
    return {{"cumulative", real(balance_.cumulative())},
            {"largest", real(balance_.largest())},
            {"round_off", real(balance_.round_off())},
            {"closed", balance_.closed()},
            {"envelope", {{"times", reals(envelope_.times())}, {"maxima", reals(envelope_.maxima())}}},
            {"drift", {{"drift", real(d.drift)}, {"low", real(d.low)}, {"high", real(d.high)}, {"over_run", real(d.over_run)},
                       {"windows", d.windows}, {"no_drift", d.no_drift}}}};
  }

 private:
  EnergyBalance balance_;
  Envelope envelope_;
};

ParamSpecs energy_balance_parameters() {
  return {ParamSpec::real("window", 1.0, 0.0, 1e12, "the envelope's window [s] (e.g. a period of the motion)", true)};
}

std::unique_ptr<RunMeasure> make_energy_balance(const Params& params, const Problem& problem, const Integrator& integrator) {
  return std::make_unique<EnergyBalanceMeasure>(params, problem, integrator);
}

}  // namespace

extern const RunMeasureEntry energy_balance_measure;
const RunMeasureEntry energy_balance_measure{"energy-balance",
                                             "the scheme's discrete energy balance per step, its envelope per window and its drift",
                                             &energy_balance_parameters, &make_energy_balance};

}  // namespace nsb
