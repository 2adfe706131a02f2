// Benchmark: one CD-Lagrange step of the rocking block (problems/rocking_block.hpp) with
// moving contacts, against the same step of the same block with its contacts frozen at the
// initial configuration (constant rows L(U0), T(U0), gap g0 + L U; contacts_move() false):
//
//   BM_Rocking/cd-lagrange-moving   the step evaluating g(U), L(U), T(U) at U_{k+1}
//                                   (integrators/impulse_contact.hpp) and the Delassus
//                                   matrix from them; limit: the frozen step, timed in the
//                                   same process (the moving contacts' cost is the ratio,
//                                   issue 32: at most 1.3)
//   BM_Rocking/cd-lagrange-frozen   the frozen step alone, timed the same way
//
// The block stands upright at rest (theta0 = 0, omega0 = 0, mu = 1), both corners closed at
// every step, so both steps solve the same two-contact Coulomb problem and the frozen rows
// equal the moving ones: the ratio is the evaluation's cost alone. The machine may be
// shared: run with --benchmark_repetitions=5 and read the min rows.
#include <benchmark/benchmark.h>

#include <map>
#include <string>

#include "integrators/cd_lagrange.hpp"
#include "problems/rocking_block.hpp"
#include "studies/benchmarks/limit.hpp"

namespace {

using nsb::bench::min_of;

// The rocking block with its rows frozen at U0: what every scheme read before moving contacts.
class FrozenRockingBlock final : public nsb::RockingBlock {
 public:
  using RockingBlock::RockingBlock;
  bool contacts_move() const override { return false; }
};

const std::map<std::string, std::string> kUpright = {{"theta0", "0"}, {"omega0", "0"}, {"mu", "1"}};
constexpr double kDt = 1e-4;

void BM_RockingCdLagrangeStep(benchmark::State& state) {
  const FrozenRockingBlock frozen(nsb::Params(nsb::RockingBlock::parameters_spec(), kUpright));
  nsb::CdLagrange reference(nsb::Params(nsb::CdLagrange::parameters_spec()));
  reference.init(frozen, frozen.initial_state());
  const double limit_ns = nsb::bench::least_ns([&] {
    reference.step(kDt);
    benchmark::DoNotOptimize(reference.state().v.data());
    benchmark::ClobberMemory();
  });
  const nsb::RockingBlock block(nsb::Params(nsb::RockingBlock::parameters_spec(), kUpright));
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(block, block.initial_state());
  nsb::bench::time_steps(state, integ, kDt);
  state.counters["normal_impulse"] = integ.impulses().sum();  // > 0: both corners carry the block
  nsb::bench::report_limit(state, static_cast<double>(block.ncontacts()), limit_ns,
                           "the step of the same block with contacts frozen at U0");
}

// The frozen step alone, timed as the moving one (on a shared machine compare the two rows'
// CPU times or their min rows: the limit above is the least single call, which a loaded
// machine's descheduling does not reach in the loop's mean).
void BM_RockingCdLagrangeFrozenStep(benchmark::State& state) {
  const FrozenRockingBlock frozen(nsb::Params(nsb::RockingBlock::parameters_spec(), kUpright));
  nsb::CdLagrange integ(nsb::Params(nsb::CdLagrange::parameters_spec()));
  integ.init(frozen, frozen.initial_state());
  nsb::bench::time_steps(state, integ, kDt);
  nsb::bench::report_units(state, static_cast<double>(frozen.ncontacts()));
}

}  // namespace

BENCHMARK(BM_RockingCdLagrangeStep)->Name("BM_Rocking/cd-lagrange-moving")->ComputeStatistics("min", min_of)->UseRealTime();
BENCHMARK(BM_RockingCdLagrangeFrozenStep)->Name("BM_Rocking/cd-lagrange-frozen")->ComputeStatistics("min", min_of)->UseRealTime();

BENCHMARK_MAIN();
