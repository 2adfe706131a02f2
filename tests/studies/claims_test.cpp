#include <catch2/catch.hpp>
#include <limits>

#include "studies/claims.hpp"

using namespace nsb;

namespace {
constexpr double kFailedFit = std::numeric_limits<double>::quiet_NaN();
OrderFit fit(double order, double low) { return {order, low, 2 * order - low, 4}; }
}  // namespace

TEST_CASE("claims: explicit and matrix-free rules fail on any factorisation, solve or LCP iteration", "[claims]") {
  CHECK(explicit_verdict(1, 100, 101, 0, 0) == Verdict::Holds);
  CHECK(explicit_verdict(3, 100, 103, 0, 0) == Verdict::Holds);
  CHECK(explicit_verdict(1, 100, 103, 0, 0) == Verdict::Fails);
  CHECK(explicit_verdict(1, 100, 200, 0, 0) == Verdict::Fails);  // two F_int per step: not the claimed scheme
  CHECK(explicit_verdict(1, 100, 101, 1, 0) == Verdict::Fails);
  CHECK(explicit_verdict(1, 100, 101, 0, 5) == Verdict::Fails);
  CHECK(explicit_verdict(1, 0, 0, 0, 0) == Verdict::Fails);  // nothing ran
  CHECK(lcp_verdict(10, 0, 0, 0) == Verdict::Holds);
  CHECK(lcp_verdict(0, 0, 0, 0) == Verdict::Fails);  // no contact: nothing shown
  CHECK(lcp_verdict(10, 3, 0, 0) == Verdict::Fails);
}

TEST_CASE("claims: Hausdorff convergence holds on all, under conditions on some, fails on none", "[claims]") {
  CHECK(hausdorff_verdict({fit(1.0, 0.8), fit(0.9, 0.2)}) == Verdict::Holds);
  CHECK(hausdorff_verdict({fit(1.0, 0.8), fit(0.0, -0.3)}) == Verdict::Conditional);
  CHECK(hausdorff_verdict({fit(0.1, -0.1), fit(0.0, -0.3)}) == Verdict::Fails);
  CHECK(hausdorff_verdict({fit(1.0, -0.5)}) == Verdict::Fails);  // the interval reaches 0
  CHECK(hausdorff_verdict({fit(kFailedFit, kFailedFit)}) == Verdict::Fails);  // a failed fit is no convergence
}

TEST_CASE("claims: momentum, energy, adaptive step and robustness rules", "[claims]") {
  CHECK(momentum_verdict(1e-15, 1e-14) == Verdict::Holds);
  CHECK(momentum_verdict(1e-15, 1e-3) == Verdict::Fails);
  CHECK(momentum_verdict(kFailedFit, 0.0) == Verdict::Fails);
  CHECK(energy_verdict(1e-4, 1.2e-4, 1e-12) == Verdict::Holds);
  CHECK(energy_verdict(1e-4, 5e-4, 1e-12) == Verdict::Conditional);  // drifting fixed step
  CHECK(energy_verdict(1e-4, 1e-4, 1e-6) == Verdict::Conditional);   // inexact adaptive step
  CHECK(energy_verdict(1e-4, 5e-4, 1e-6) == Verdict::Fails);
  CHECK(adaptive_verdict(true, 0.9, 0.02, 0.01, 0) == Verdict::Holds);
  CHECK(adaptive_verdict(true, 1.1, 0.02, 0.01, 0) == Verdict::Fails);  // beyond the CFL limit
  CHECK(adaptive_verdict(true, 0.9, 0.01, 0.01, 0) == Verdict::Fails);  // never adapted
  CHECK(adaptive_verdict(false, 0.9, 0.02, 0.01, 0) == Verdict::Fails);
  CHECK(adaptive_verdict(true, 0.9, 0.02, 0.01, 1) == Verdict::Fails);  // a step pinned at tau_min
  CHECK(robustness_verdict(true, 100000, 100000, 1e-3, 0.5) == Verdict::Holds);
  CHECK(robustness_verdict(true, 99999, 100000, 1e-3, 0.5) == Verdict::Fails);
  CHECK(robustness_verdict(true, 100000, 100000, -0.5, 0.5) == Verdict::Fails);
  CHECK(robustness_verdict(true, 100000, 100000, 1e-3, 2.0) == Verdict::Fails);
  CHECK(robustness_verdict(false, 100000, 100000, 1e-3, 0.5) == Verdict::Fails);
  CHECK(std::string(verdict_name(Verdict::Conditional)) == "holds under the stated conditions");
}

TEST_CASE("claims: a claim under several conditions holds on all, under conditions on some, fails on none", "[claims]") {
  CHECK(conditions_verdict({true, true}) == Verdict::Holds);
  CHECK(conditions_verdict({true, false}) == Verdict::Conditional);
  CHECK(conditions_verdict({false, false}) == Verdict::Fails);
  CHECK(conditions_verdict({}) == Verdict::Fails);  // nothing tested: no verdict in its favour
  CHECK(energy_no_drift(1e-4, 2e-4));
  CHECK_FALSE(energy_no_drift(1e-4, 2.1e-4));
}

TEST_CASE("claims: an energy error of the order of E is not bounded, however steady", "[claims]") {
  // The schatzman-paoli and cd-penalty figures of the long runs: the reported energy falls to
  // 0 (or by half) at the impact steps, the same in both halves, so no drift alone passed them.
  CHECK_FALSE(energy_no_drift(1.0, 1.0));
  CHECK_FALSE(energy_no_drift(0.499, 0.499));
  CHECK(energy_no_drift(0.0225, 0.0303));  // cd-lagrange's: bounded, no drift
  CHECK(energy_no_drift(kEnergyBounded, kEnergyBounded));
  CHECK_FALSE(energy_no_drift(0.05, 1.01 * kEnergyBounded));  // bounded first half, then past the bound
  CHECK(energy_verdict(1.0, 1.0, 1e-12) == Verdict::Conditional);
}

TEST_CASE("claims: energy at impact is kept within 1e-2 per contact phase, and only when a phase happened", "[claims]") {
  CHECK(impact_energy_kept(3, 0.99e-2));
  CHECK_FALSE(impact_energy_kept(3, 1.01e-2));
  CHECK_FALSE(impact_energy_kept(0, 0.0));  // no contact: nothing shown
  CHECK_FALSE(impact_energy_kept(3, kFailedFit));
}
