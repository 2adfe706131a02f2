// Two Moreau-Jean runs at once must not change each other's numbers. On the 32x32 block
// (2178 dofs) CHOLMOD's automatic mode picked its supernodal factorisation, whose BLAS
// calls went to Debian's serial OpenBLAS: its work buffers sit in one process-wide table
// taken without a lock, so concurrent factorisations wrote into each other's buffers and the
// studies' results depended on what ran beside them (issue 11). Here a run alone and two
// runs in parallel threads must agree bit for bit (with the supernodal factorisation, most
// concurrent pairs differed from the lone run, by up to 1e-8 after 50 steps). Whether a
// pair overlaps in the unlocked window depends on the machine's load, so the root is also
// tested directly: the run makes no BLAS call at all, counted by wrappers of the BLAS and
// LAPACK routines CHOLMOD and UMFPACK call (this executable's definitions take precedence
// over the BLAS library's; each forwards to it).
#include <dlfcn.h>

#include <atomic>
#include <catch2/catch.hpp>
#include <latch>
#include <thread>

#include "integrators/moreau_jean.hpp"
#include "problems/block_2d.hpp"

namespace {
std::atomic<long> blas_calls{0};

template <class Fn>
Fn next_definition(const char* name) {
  static_assert(sizeof(Fn) == sizeof(void*));
  return reinterpret_cast<Fn>(dlsym(RTLD_NEXT, name));
}
}  // namespace

// Fortran calling convention: every argument by address, then the lengths of the character
// arguments.
#define NSB_COUNTED_BLAS(name, params, args)                                    \
  extern "C" void name params {                                                 \
    using Fn = void(*) params;                                                  \
    static const Fn real = next_definition<Fn>(#name);                          \
    ++blas_calls;                                                               \
    real args;                                                                  \
  }
using C = const char*;
using I = const int*;
using D = const double*;
using L = std::size_t;
NSB_COUNTED_BLAS(dgemm_, (C ta, C tb, I m, I n, I k, D al, D a, I la, D b, I lb, D be, double* c, I lc, L l1, L l2),
                 (ta, tb, m, n, k, al, a, la, b, lb, be, c, lc, l1, l2))
NSB_COUNTED_BLAS(dsyrk_, (C u, C t, I n, I k, D al, D a, I la, D be, double* c, I lc, L l1, L l2),
                 (u, t, n, k, al, a, la, be, c, lc, l1, l2))
NSB_COUNTED_BLAS(dtrsm_, (C s, C u, C t, C d, I m, I n, D al, D a, I la, double* b, I lb, L l1, L l2, L l3, L l4),
                 (s, u, t, d, m, n, al, a, la, b, lb, l1, l2, l3, l4))
NSB_COUNTED_BLAS(dpotrf_, (C u, I n, double* a, I la, int* info, L l1), (u, n, a, la, info, l1))
NSB_COUNTED_BLAS(dgemv_, (C t, I m, I n, D al, D a, I la, D x, I ix, D be, double* y, I iy, L l1),
                 (t, m, n, al, a, la, x, ix, be, y, iy, l1))
NSB_COUNTED_BLAS(dtrsv_, (C u, C t, C d, I n, D a, I la, double* x, I ix, L l1, L l2, L l3),
                 (u, t, d, n, a, la, x, ix, l1, l2, l3))
NSB_COUNTED_BLAS(dger_, (I m, I n, D al, D x, I ix, D y, I iy, double* a, I la), (m, n, al, x, ix, y, iy, a, la))
#undef NSB_COUNTED_BLAS

namespace {

// State and work counters after `steps` steps of 1e-4 s on the n x n sliding block; with
// `start`, the stepping waits for the other run's set-up so that the two overlap.
std::vector<double> block_run(int n, int steps, std::latch* start = nullptr) {
  const nsb::Block2d block(nsb::Params(nsb::Block2d::parameters_spec(),
                                       {{"nx", std::to_string(n)}, {"ny", std::to_string(n)}, {"vx", "0.5"}}));
  nsb::MoreauJean mj(nsb::Params(nsb::MoreauJean::parameters_spec()));
  mj.init(block, block.initial_state());
  if (start) start->arrive_and_wait();
  for (int k = 0; k < steps; ++k) mj.step(1e-4);
  const nsb::State& s = mj.state();
  std::vector<double> out(s.u.data(), s.u.data() + s.u.size());
  out.insert(out.end(), s.v.data(), s.v.data() + s.v.size());
  out.push_back(static_cast<double>(mj.work().factorizations));
  return out;
}

}  // namespace

TEST_CASE("moreau-jean: a run gives the same bits alone and beside another (32x32 block)",
          "[integrators][moreau-jean][concurrency]") {
  constexpr int kN = 32, kSteps = 40;
  const std::vector<double> alone = block_run(kN, kSteps);
  for (int pair = 0; pair < 2; ++pair) {
    std::vector<double> first, second;
    std::latch start(2);
    std::thread other([&] { first = block_run(kN, kSteps, &start); });
    second = block_run(kN, kSteps, &start);
    other.join();
    CHECK(first == alone);
    CHECK(second == alone);
  }
}

TEST_CASE("moreau-jean: no BLAS call on the 32x32 block", "[integrators][moreau-jean][concurrency]") {
  blas_calls = 0;
  block_run(32, 2);
  CHECK(blas_calls == 0);
}
