// The problem contract (problems/problem.hpp) checked where it is cheap, when a scheme binds
// (issue 56: moreau-jean and nsga returned ok on a non-symmetric mass and a negative diagonal,
// cd-lagrange and moreau-jean on a gap closed at t = 0).
#include <catch2/catch.hpp>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "tests/problems/forwarding_problem.hpp"

namespace {

// A registered problem whose mass matrix is the one given.
class WithMass final : public ForwardingProblem {
 public:
  WithMass(const std::string& name, nsb::SpMat mass) : ForwardingProblem(nsb::make_problem(name)), mass_(std::move(mass)) {}
  nsb::SpMat mass_matrix() const override { return mass_; }

 private:
  nsb::SpMat mass_;
};

// The bouncing mass released from below its floor.
class BelowFloor final : public ForwardingProblem {
 public:
  BelowFloor() : ForwardingProblem(nsb::make_problem("bouncing-mass")) {}
  nsb::State initial_state() const override {
    nsb::State s = held().initial_state();
    s.u[0] = -0.5;
    return s;
  }
};

nsb::SpMat tweaked_mass(const std::string& problem, nsb::Index row, nsb::Index col, double value) {
  nsb::SpMat m = nsb::make_problem(problem)->mass_matrix();
  m.coeffRef(row, col) = value;
  return m;
}

void check_refused(const nsb::Problem& p, const std::string& message) {
  for (const char* name : {"cd-lagrange", "moreau-jean", "nsga"}) {
    INFO(name);
    auto it = nsb::make_integrator(name);
    CHECK_THROWS_WITH(it->init(p, p.initial_state()), Catch::StartsWith(message));
  }
}

}  // namespace

TEST_CASE("problem contract: a non-symmetric mass, a negative diagonal and a gap closed at t = 0 are refused by name",
          "[problems][contract][bad-input]") {
  check_refused(WithMass("spring-chain", tweaked_mass("spring-chain", 0, 1, 0.25)),
                "problem spring-chain: mass_matrix() is not symmetric; valid: M = M^T (the problem contract");
  check_refused(WithMass("bouncing-mass", tweaked_mass("bouncing-mass", 0, 0, -1.0)),
                "problem bouncing-mass: mass_matrix() has -1 on its diagonal at dof 0; valid: finite, >= 0");
  check_refused(BelowFloor(),
                "problem bouncing-mass: contact 0 is closed at the initial state (gap -0.5); valid: initial gaps >= 0");
  // Every registered problem keeps the contract at its defaults.
  for (const auto& entry : nsb::problem_registry()) {
    INFO(entry.name);
    const auto p = nsb::make_problem(entry.name);
    CHECK_NOTHROW(nsb::check_problem_contract(*p, p->mass_matrix(), p->initial_state()));
  }
}
