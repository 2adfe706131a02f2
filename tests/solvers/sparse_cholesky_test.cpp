#include <catch2/catch.hpp>

#include <cstdlib>

#include "integrators/registry.hpp"
#include "solvers/sparse_cholesky.hpp"
#include "problems/signorini_bar.hpp"
#include "studies/study.hpp"

using Catch::Detail::Approx;

namespace {

// NSBENCH_MEMORY_LIMIT set for the scope of one test.
struct MemoryLimit {
  explicit MemoryLimit(const char* value) { setenv("NSBENCH_MEMORY_LIMIT", value, 1); }
  ~MemoryLimit() { unsetenv("NSBENCH_MEMORY_LIMIT"); }
};

nsb::SignoriniBar bar_with(long n) {
  return nsb::SignoriniBar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", std::to_string(n)}, {"mass", "singular"}}));
}

}  // namespace

TEST_CASE("NSBENCH_MEMORY_LIMIT: bytes or K/M/G (powers of 1024); anything else is an InputError naming it",
          "[memory]") {
  std::string source;
  {
    const MemoryLimit limit("12345");
    CHECK(nsb::memory_available(source) == 12345.0);
    CHECK(source == "NSBENCH_MEMORY_LIMIT");
  }
  {
    const MemoryLimit limit("3K");
    CHECK(nsb::memory_available(source) == 3072.0);
  }
  {
    const MemoryLimit limit("2m");
    CHECK(nsb::memory_available(source) == 2.0 * 1024 * 1024);
  }
  {
    const MemoryLimit limit("1G");
    CHECK(nsb::memory_available(source) == 1024.0 * 1024 * 1024);
  }
  for (const char* bad : {"-1", "0", "1.5G", "12KB", "G", "lots", "1T", " 5"}) {
    const MemoryLimit limit(bad);
    INFO(bad);
    CHECK_THROWS_WITH(nsb::memory_available(source),
                      Catch::Contains("NSBENCH_MEMORY_LIMIT") && Catch::Contains("K, M or G") && Catch::Contains(bad));
  }
  CHECK(nsb::memory_available(source) > 0.0);  // unset: MemAvailable
}

TEST_CASE("implicit schemes refuse at init a factorisation larger than the memory, with its estimated size", "[memory]") {
  const auto problem = bar_with(2000);
  nsb::SparseCholesky chol;
  const nsb::SpMat W = problem.mass_matrix() + problem.mass_matrix();  // any pattern with a positive diagonal
  chol.analyze(W, "test", "W");
  const double bytes = chol.estimated_bytes();
  // Diagonal W of 2001 dofs: nnz(L) = n; 12 nnz(L) + 24 nnz(A) + 72 n = 108 n bytes.
  CHECK(bytes == Approx(108.0 * 2001));

  struct Case {
    const char* integrator;
    std::map<std::string, std::string> params;
    const char* matrix;
  };
  for (const Case& c : {Case{"moreau-jean", {}, "W"}, Case{"nsga", {}, "S"}, Case{"newmark-lm", {}, "S"},
                        Case{"schatzman-paoli", {{"theta", "0.25"}}, "W"}}) {
    INFO(c.integrator);
    {
      const MemoryLimit limit("10K");  // far below the ~0.2 MB the bar's factor needs
      auto integ = nsb::make_integrator(c.integrator, c.params);
      CHECK_THROWS_AS(integ->init(problem, problem.initial_state()), nsb::InputError);
      CHECK_THROWS_WITH(integ->init(problem, problem.initial_state()),
                        Catch::Contains(std::string("integrator ") + c.integrator) &&
                            Catch::Contains(std::string("factorisation of ") + c.matrix + " (2001 dofs) needs about") &&
                            Catch::Contains("more than the 9.54e-06 GiB available (NSBENCH_MEMORY_LIMIT)"));
      // A study records the refusal as its n/a row's reason.
      const auto declined = nsb::init_or_decline(*integ, problem);
      REQUIRE(declined);
      CHECK_THAT(*declined, Catch::Contains("GiB available"));
    }
    const MemoryLimit limit("1G");
    auto integ = nsb::make_integrator(c.integrator, c.params);
    CHECK_NOTHROW(integ->init(problem, problem.initial_state()));
    CHECK_NOTHROW(integ->step(0.9 * problem.stable_step()));
  }
}
