// The verdict rules of studies/claims.hpp, as the properties matrix (studies/properties.cpp)
// applies them to every scheme. The claims study itself is studies/builtin/claims.py, on the
// talk's own conditions and the rules its caption states.
#include "studies/claims.hpp"

#include <algorithm>
#include <cmath>

namespace nsb {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Holds: return "holds";
    case Verdict::Conditional: return "holds under the stated conditions";
    case Verdict::Fails: return "fails";
  }
  return "";
}

Verdict explicit_verdict(long runs, long steps, long force_evaluations, long factorizations, long linear_solves) {
  return steps > 0 && factorizations == 0 && linear_solves == 0 && force_evaluations <= steps + runs ? Verdict::Holds : Verdict::Fails;
}

bool hausdorff_converges(const OrderFit& fit) { return fit.order >= kHausdorffMinOrder && fit.low > 0.0; }

Verdict hausdorff_verdict(const std::vector<OrderFit>& per_problem) {
  const auto n = std::count_if(per_problem.begin(), per_problem.end(), hausdorff_converges);
  if (n == 0) return Verdict::Fails;
  return n == static_cast<long>(per_problem.size()) ? Verdict::Holds : Verdict::Conditional;
}

Verdict conditions_verdict(const std::vector<bool>& met) {
  const auto n = std::count(met.begin(), met.end(), true);
  if (n == 0) return Verdict::Fails;
  return n == static_cast<long>(met.size()) ? Verdict::Holds : Verdict::Conditional;
}

Verdict momentum_verdict(double linear_residual, double angular_residual) {
  return linear_residual <= kMomentumTolerance && angular_residual <= kMomentumTolerance ? Verdict::Holds : Verdict::Fails;
}

bool energy_no_drift(double fixed_first_half, double fixed_second_half) {
  return fixed_first_half <= kEnergyBounded && fixed_second_half <= kEnergyBounded &&
         fixed_second_half <= kEnergyDriftFactor * fixed_first_half + kEnergyRoundOff;
}

bool impact_energy_kept(long phases, double worst_jump) { return phases > 0 && worst_jump <= kImpactEnergy; }

Verdict energy_verdict(double fixed_first_half, double fixed_second_half, double adaptive_max) {
  const bool fixed = energy_no_drift(fixed_first_half, fixed_second_half);
  const bool adaptive = adaptive_max <= kEnergyExact;
  return fixed && adaptive ? Verdict::Holds : fixed || adaptive ? Verdict::Conditional : Verdict::Fails;
}

Verdict adaptive_verdict(bool completed, double largest_step_over_stable, double largest_step, double smallest_step,
                         long collapsed_steps) {
  return completed && largest_step_over_stable <= 1.0 && largest_step > (1.0 + 1e-6) * smallest_step && collapsed_steps == 0
             ? Verdict::Holds
             : Verdict::Fails;
}

Verdict lcp_verdict(long contact_steps, long lcp_iterations, long factorizations, long linear_solves) {
  return contact_steps > 0 && lcp_iterations == 0 && factorizations == 0 && linear_solves == 0 ? Verdict::Holds : Verdict::Fails;
}

Verdict robustness_verdict(bool completed, long impacts, long target, double energy_error, double penetration_over_step) {
  return completed && impacts >= target && std::abs(energy_error) <= kRobustEnergy && penetration_over_step <= 1.0 ? Verdict::Holds
                                                                                                                   : Verdict::Fails;
}

}  // namespace nsb
