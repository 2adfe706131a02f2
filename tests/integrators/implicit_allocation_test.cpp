// The implicit schemes allocate nothing per step (issue 16): once their caches are built
// (the factorisation, the contact responses, the LCP storage: the steps up to the first
// contact and one more), the following steps, through the contact phase and the release,
// make no heap allocation at all (malloc, operator new, Eigen and CHOLMOD alike:
// tests/support/allocation_counter.hpp).
#include <catch2/catch.hpp>

#include "integrators/registry.hpp"
#include "problems/block_2d.hpp"
#include "problems/signorini_bar.hpp"
#include "tests/support/allocation_counter.hpp"

namespace {

struct Counted {
  long allocations = 0;
  int contact_steps = 0, free_steps = 0;  // steps of the counted window with / without an impulse
};

bool impulse(const nsb::Integrator& integ) { return integ.impulses().size() > 0 && integ.impulses().maxCoeff() > 0.0; }

// Steps to the first impulse, `settle` more steps, then counts over `steps` steps.
Counted count_allocations(const std::string& integrator, const std::map<std::string, std::string>& params,
                          const nsb::Problem& problem, double dt, int steps, int settle = 1) {
  auto integ = nsb::make_integrator(integrator, params);
  integ->init(problem, problem.initial_state());
  for (int k = 0; k < 100000 && !impulse(*integ); ++k) integ->step(dt);
  for (int k = 0; k < settle; ++k) integ->step(dt);
  Counted c;
  std::vector<char> in_contact(static_cast<std::size_t>(steps));  // allocated before counting
  {
    nsb::test::CountAllocations count;
    for (int k = 0; k < steps; ++k) {
      integ->step(dt);
      in_contact[static_cast<std::size_t>(k)] = impulse(*integ);
    }
    c.allocations = count.count();
  }
  for (const char s : in_contact) (s ? c.contact_steps : c.free_steps) += 1;
  return c;
}

nsb::SignoriniBar alloc_bar(const std::string& mass) {
  return nsb::SignoriniBar(nsb::Params(nsb::SignoriniBar::parameters_spec(), {{"N", "40"}, {"mass", mass}}));
}

}  // namespace

TEST_CASE("allocation counter: counts this thread's allocations in its scope only", "[allocation]") {
  static double* volatile sink = nullptr;  // volatile: the new/delete pair cannot be elided
  long n = 0;
  {
    nsb::test::CountAllocations count;
    sink = new double[100];
    delete[] sink;
    Eigen::VectorXd v(1000);
    sink = v.data();
    n = count.count();
  }
  CHECK(n == 2);
}

TEST_CASE("implicit schemes: no heap allocation per step on the Signorini bar, through contact and release",
          "[allocation]") {
  struct Case {
    const char* integrator;
    std::map<std::string, std::string> params;
  };
  const std::vector<Case> cases = {{"moreau-jean", {}},
                                   {"moreau-jean", {{"theta", "1"}}},
                                   {"nsga", {}},
                                   {"newmark-lm", {}},
                                   {"schatzman-paoli", {{"theta", "0.25"}}}};
  for (const std::string mass : {"lumped", "singular"})
    for (const auto& c : cases) {
      const auto problem = alloc_bar(mass);
      const Counted n = count_allocations(c.integrator, c.params, problem, 0.9 * problem.stable_step(), 200);
      INFO(c.integrator << (c.params.empty() ? "" : " theta = " + c.params.begin()->second) << ", " << mass << " mass");
      CHECK(n.contact_steps > 0);
      CHECK(n.free_steps > 0);
      CHECK(n.allocations == 0);
    }
}

// On the block the contact set changes while the block lands: the first time a contact is
// active its response W^{-1} L_i^T gets its storage (kept for the run: at most one vector
// per contact), and a number of active contacts not seen before gets its LCP storage. Both
// are cache growth, not per-step work: the steps after the landing (1000 steps after the
// first impulse), K(U) assembled and W refactorised every step, allocate nothing. Nor do the
// problem's F_int and K(U) on one thread (core/threads.hpp: no OpenMP region there, whose
// team libgomp allocates even when the region's if clause keeps it on one thread).
TEST_CASE("moreau-jean: no heap allocation per step on block-2d at rest, F_int and K(U) included", "[allocation]") {
  const nsb::Block2d block(nsb::Params(nsb::Block2d::parameters_spec(), {{"nx", "4"}, {"ny", "2"}}));
  const Counted n = count_allocations("moreau-jean", {}, block, 1e-3, 100, 1000);
  CHECK(n.contact_steps > 0);
  CHECK(n.allocations == 0);

  const nsb::State s = block.initial_state();
  nsb::Vec f(block.ndof());
  nsb::SpMat K;
  block.tangent_stiffness(s.u, K);
  nsb::test::CountAllocations count;
  block.internal_force(s.u, f);
  block.tangent_stiffness(s.u, K);
  CHECK(count.count() == 0);
}

// With friction (the block sliding on the floor, mu = 0.5): the Coulomb solve works in the
// same kept storage (per-size D, q, x; the tangent responses W^{-1} T_i^T cached like the
// normal ones), so after the landing the frictional steps allocate nothing either, for the
// explicit schemes (closed form per contact) and the implicit ones (Gauss-Seidel).
// cd-lagrange-adaptive is not in the list: it allocates once per step on this block with mu = 0
// as well (measured: 200 in 200 steps), which is not friction's doing.
TEST_CASE("friction: no heap allocation per step on the sliding block", "[allocation][friction]") {
  const nsb::Block2d block(nsb::Params(nsb::Block2d::parameters_spec(),
                                       {{"nx", "4"}, {"ny", "2"}, {"mu", "0.5"}, {"vx", "3"}, {"tilt", "0"}, {"height", "0.001"}}));
  for (const char* integrator : {"cd-lagrange", "d1-minus-linear", "moreau-jean", "nsga"}) {
    INFO(integrator);
    const Counted n = count_allocations(integrator, {}, block, 1e-4, 200, 2000);
    CHECK(n.contact_steps > 0);
    CHECK(n.allocations == 0);
  }
}
