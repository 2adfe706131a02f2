// Benchmark: one time step of the implicit schemes with contact, against the bare CHOLMOD
// cost of the matrix each one factorises (limit.hpp's convention):
//
//   BM_Step/<integrator>/<mass>/N   the Signorini bar (problems/signorini_bar.hpp),
//                                   N = 1e3 .. 1e5, dt = 0.9 h/c, one step in contact (10
//                                   steps taken first, so the factorisation and the contact
//                                   responses are cached; the problem, the scheme, those
//                                   steps and the bare kernels' W built once per benchmark,
//                                   later calls step on). K is constant: each scheme
//                                   factorises once and then does one solve per step plus
//                                   the contact, so the limit is the bare solve (one
//                                   right-hand side); the bare factorisation is the counter
//                                   factorise_ns.
//   BM_Step/moreau-jean/block-2d/n  the block (problems/block_2d.hpp), n x n elements,
//                                   dt = 1e-4 (as the block study): F_int is nonlinear, so
//                                   moreau-jean assembles K(U_k) and refactorises W every
//                                   step; the limit is the bare factorisation + solve.
//
// The bare kernels: CHOLMOD's C API on the same matrix M + c K (K at the state the step
// starts from), configured as solvers/sparse_cholesky.hpp configures it (simplicial
// LL^T, final_ll, default ordering; symbolic analysis outside the timing), solves through
// cholmod_solve2 with its workspace kept. c is each scheme's own coefficient at its default
// parameters: moreau-jean h^2 theta^2 (theta = 1/2), nsga beta h^2 (1 - alpha_f) / (1 -
// alpha_m) (rho_inf = 1), newmark-lm beta h^2 (beta = 1/4), schatzman-paoli theta h^2
// (theta = 1/4): all h^2 / 4, but computed per scheme. units = dofs.
// Measured (min of 5, 2-core machine shared with other work, default NSBENCH_THREADS = 2;
// under load the ratios at N = 1e5 rise by up to 0.1, nsga's to 1.57), step / limit: on the bar at N = 1e3, 1e4, 1e5 moreau-jean 1.23, 1.25, 1.29 (projected
// 1.24, 1.26, 1.30), nsga lumped 1.27, 1.37, 1.46 (singular 1.26, 1.36, 1.45), newmark-lm
// lumped 1.18, 1.18, 1.21 (singular 1.17, 1.19, 1.25), schatzman-paoli 1/4 1.12, 1.13, 1.15;
// the bare solve alone costs 15.5 ns per dof (CHOLMOD's simplicial solve of a tridiagonal
// W: permutation, forward and backward sweeps on a 4-wide workspace), the factorisation
// 20 ns. moreau-jean on block-2d: 32x32 2.39 ms against 1.87 (1.28), 64x64 16.5 ms
// against 14.8 (1.11). Before this work (Eigen's CholmodDecomposition, allocating on every
// solve, and more vector passes) moreau-jean at N = 1e5 took 2.05 ms (1.32x).
// The machine is shared: run with --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
// and read the min rows.
#include <benchmark/benchmark.h>
#include <cholmod.h>

#include <fmt/format.h>

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

#include "integrators/registry.hpp"
#include "problems/block_2d.hpp"
#include "problems/signorini_bar.hpp"
#include "studies/benchmarks/limit.hpp"

namespace {

using nsb::bench::min_of;

// CHOLMOD alone on W = M + c K: analysed at construction, then factorise() and solve().
class BareCholmod {
 public:
  BareCholmod(const nsb::SpMat& M, double c, const nsb::SpMat& K) : W_(M + c * K), b_(nsb::Vec::Ones(M.rows())) {
    W_.makeCompressed();
    cholmod_start(&common_);
    common_.final_asis = 0;
    common_.supernodal = CHOLMOD_SIMPLICIAL;
    common_.final_ll = 1;
    A_ = cholmod_sparse{};
    A_.nrow = A_.ncol = static_cast<std::size_t>(W_.rows());
    A_.nzmax = static_cast<std::size_t>(W_.nonZeros());
    A_.p = W_.outerIndexPtr();
    A_.i = W_.innerIndexPtr();
    A_.x = W_.valuePtr();
    A_.packed = A_.sorted = 1;
    A_.stype = -1;
    A_.itype = CHOLMOD_INT;
    A_.xtype = CHOLMOD_REAL;
    A_.dtype = CHOLMOD_DOUBLE;
    B_ = cholmod_dense{};
    B_.nrow = B_.nzmax = B_.d = static_cast<std::size_t>(W_.rows());
    B_.ncol = 1;
    B_.x = b_.data();
    B_.xtype = CHOLMOD_REAL;
    B_.dtype = CHOLMOD_DOUBLE;
    L_ = cholmod_analyze(&A_, &common_);
    factorise();
    if (L_->minor != L_->n) throw std::runtime_error("bare CHOLMOD: the matrix is not positive definite");
  }
  ~BareCholmod() {
    cholmod_free_dense(&X_, &common_);
    cholmod_free_dense(&Y_, &common_);
    cholmod_free_dense(&E_, &common_);
    cholmod_free_factor(&L_, &common_);
    cholmod_finish(&common_);
  }
  BareCholmod(const BareCholmod&) = delete;
  BareCholmod& operator=(const BareCholmod&) = delete;

  void factorise() {
    cholmod_factorize(&A_, L_, &common_);
    benchmark::ClobberMemory();
  }
  void solve() {
    if (Y_) {  // as sparse_cholesky.cpp: Y back to the 4 x n shape, else CHOLMOD reallocates it
      Y_->nrow = Y_->d = 4;
      Y_->ncol = B_.nrow;
    }
    cholmod_solve2(CHOLMOD_A, L_, &B_, nullptr, &X_, nullptr, &Y_, &E_, &common_);
    benchmark::DoNotOptimize(X_->x);
    benchmark::ClobberMemory();
  }

 private:
  nsb::SpMat W_;
  nsb::Vec b_;
  cholmod_common common_;
  cholmod_sparse A_;
  cholmod_dense B_;
  cholmod_factor* L_ = nullptr;
  cholmod_dense *X_ = nullptr, *Y_ = nullptr, *E_ = nullptr;
};

// The scheme's iteration-matrix coefficient c (W = M + c K) at step h, default parameters.
using Coefficient = std::function<double(double)>;
const Coefficient kMoreauJean = [](double h) { return h * h * 0.25; };  // h^2 theta^2, theta = 1/2
const Coefficient kNsga = [](double h) {                                // rho_inf = 1
  const double alpha_m = 0.5, alpha_f = 0.5, beta = 0.25;
  return beta * h * h * (1.0 - alpha_f) / (1.0 - alpha_m);
};
const Coefficient kNewmark = [](double h) { return 0.25 * h * h; };  // beta = 1/4
const Coefficient kSchatzmanPaoli = [](double h) { return 0.25 * h * h; };  // theta h^2, theta = 1/4

// A problem, its step, a scheme on it 10 steps in (so the factorisation and the contact
// responses are cached) and the bare CHOLMOD on the W of the state reached: built once per
// benchmark (limit.hpp's reused_setup), the kernels and the steps timed at every call.
struct ImplicitStep {
  struct Made {
    std::unique_ptr<const nsb::Problem> problem;
    double dt;
  };
  Made made;
  std::unique_ptr<nsb::Integrator> integ;
  std::optional<BareCholmod> bare;
  ImplicitStep(const std::function<Made()>& make, const std::string& integrator,
               const std::map<std::string, std::string>& overrides, const Coefficient& c)
      : made(make()), integ(nsb::make_integrator(integrator, overrides)) {
    integ->init(*made.problem, made.problem->initial_state());
    for (int k = 0; k < 10; ++k) integ->step(made.dt);
    nsb::SpMat K;
    made.problem->tangent_stiffness(integ->state().u, K);
    bare.emplace(made.problem->mass_matrix(), c(made.dt), K);
  }
};

// The limit measured, then the timed steps. refactorised: the scheme factorises every step
// (the limit is factorise + solve), else once (the limit is the solve).
void time_against_bare(benchmark::State& state, ImplicitStep& setup, bool refactorised) {
  const double factorise_ns = nsb::bench::least_ns([&] { setup.bare->factorise(); });
  const double solve_ns = nsb::bench::least_ns([&] { setup.bare->solve(); });
  nsb::bench::time_steps(state, *setup.integ, setup.made.dt);
  state.counters["factorise_ns"] = factorise_ns;
  state.counters["solve_ns"] = solve_ns;
  const auto units = static_cast<double>(setup.made.problem->ndof());
  if (refactorised)
    nsb::bench::report_limit(state, units, factorise_ns + solve_ns, "CHOLMOD simplicial factorise + solve, same W");
  else
    nsb::bench::report_limit(state, units, solve_ns, "CHOLMOD simplicial solve, same W");
}

void bar_step(benchmark::State& state, const std::string& label, const std::string& integrator,
              const std::map<std::string, std::string>& overrides, const std::string& mass, const Coefficient& c) {
  const long N = state.range(0);
  const auto make = [&]() -> ImplicitStep::Made {
    auto bar = std::make_unique<nsb::SignoriniBar>(
        nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", std::to_string(N)}, {"mass", mass}}));
    const double dt = 0.9 * bar->stable_step();
    return {std::move(bar), dt};
  };
  auto& setup = nsb::bench::reused_setup<ImplicitStep>(fmt::format("BM_Step/{}/{}", label, N), make, integrator, overrides, c);
  time_against_bare(state, setup, false);
}

void block_step(benchmark::State& state) {
  const long n = state.range(0);
  const auto make = [&]() -> ImplicitStep::Made {
    return {std::make_unique<nsb::Block2d>(
                nsb::Params(nsb::Block2d::parameters_spec(), {{"nx", std::to_string(n)}, {"ny", std::to_string(n)}})),
            1e-4};
  };
  auto& setup = nsb::bench::reused_setup<ImplicitStep>(fmt::format("BM_Step/moreau-jean/block-2d/{}", n), make,
                                                       "moreau-jean", std::map<std::string, std::string>{}, kMoreauJean);
  time_against_bare(state, setup, true);
}

void register_all() {
  struct Case {
    const char* label;
    const char* integrator;
    std::map<std::string, std::string> overrides;
    const char* mass;
    Coefficient c;
  };
  const std::vector<Case> cases = {
      {"moreau-jean/lumped", "moreau-jean", {}, "lumped", kMoreauJean},
      {"moreau-jean-projected/lumped", "moreau-jean", {{"projection", "position"}}, "lumped", kMoreauJean},
      {"nsga/lumped", "nsga", {}, "lumped", kNsga},
      {"nsga/singular", "nsga", {}, "singular", kNsga},
      {"newmark-lm/lumped", "newmark-lm", {}, "lumped", kNewmark},
      {"newmark-lm/singular", "newmark-lm", {}, "singular", kNewmark},
      {"schatzman-paoli-1/4/lumped", "schatzman-paoli", {{"theta", "0.25"}}, "lumped", kSchatzmanPaoli},
  };
  for (const auto& c : cases)
    benchmark::RegisterBenchmark((std::string("BM_Step/") + c.label).c_str(), bar_step, c.label, c.integrator,
                                 c.overrides, c.mass, c.c)
        ->RangeMultiplier(10)
        ->Range(1000, 100000)
        ->ComputeStatistics("min", min_of)
        ->UseRealTime();
  benchmark::RegisterBenchmark("BM_Step/moreau-jean/block-2d", block_step)
      ->Arg(32)
      ->Arg(64)
      ->ComputeStatistics("min", min_of)
      ->UseRealTime();
}

}  // namespace

int main(int argc, char** argv) { return nsb::bench::run_benchmarks(argc, argv, register_all); }
