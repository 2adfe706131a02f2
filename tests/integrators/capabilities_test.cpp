// The capabilities an integrator declares in its registry entry (integrators/capabilities.hpp):
// one refusal per kind, each "integrator X needs ...; problem Y has ... (valid: ...)", every
// one the problem misses in one line, raised when the integrator binds the problem, and the
// non-virtual step() that keeps the time and the step count for every scheme.
#include <catch2/catch.hpp>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "tests/problems/forwarding_problem.hpp"

namespace {

using Strings = std::map<std::string, std::string>;

// The message of the InputError that binding `problem` to the integrator raises; "" if none.
std::string refusal(const std::string& integrator, const Strings& overrides, const nsb::Problem& problem) {
  auto integ = nsb::make_integrator(integrator, overrides);
  try {
    integ->init(problem, problem.initial_state());
  } catch (const nsb::InputError& e) {
    return e.what();
  }
  return "";
}

std::string refusal(const std::string& integrator, const Strings& overrides, const std::string& problem,
                    const Strings& problem_overrides) {
  return refusal(integrator, overrides, *nsb::make_problem(problem, problem_overrides));
}

// A problem as registered, but with a time-dependent external force (the same values).
class TimeDependentLoad final : public ForwardingProblem {
 public:
  using ForwardingProblem::ForwardingProblem;
  std::string name() const override { return "time-dependent-" + held().name(); }
  bool external_force_is_constant() const override { return false; }
};

}  // namespace

TEST_CASE("capabilities: friction refused by a scheme that does not treat it, one line", "[integrators][capabilities]") {
  CHECK(refusal("newmark-lm", {}, "sliding-mass", {{"mu", "0.3"}}) ==
        "integrator newmark-lm needs mu = 0 (it does not treat Coulomb friction); problem sliding-mass has mu = 0.3 "
        "(valid: a problem with mu = 0, or an integrator `nsbench list` marks as treating friction)");
  CHECK(refusal("moreau-jean", {}, "sliding-mass", {{"mu", "0.3"}}).empty());
}

TEST_CASE("capabilities: a diagonal mass (entries >= 0) refused a consistent mass, one line", "[integrators][capabilities]") {
  CHECK(refusal("cd-lagrange", {}, "signorini-bar", {{"N", "10"}, {"mass", "consistent"}}) ==
        "integrator cd-lagrange needs a diagonal mass matrix with entries >= 0; problem signorini-bar has a non-diagonal "
        "mass matrix (valid: a problem with a lumped mass, e.g. mass=lumped)");
  CHECK(refusal("cd-lagrange", {}, "signorini-bar", {{"N", "10"}, {"mass", "singular"}}).empty());
}

TEST_CASE("capabilities: a diagonal mass with entries > 0 refused a massless dof, one line", "[integrators][capabilities]") {
  CHECK(refusal("cd-penalty", {}, "signorini-bar", {{"N", "10"}, {"mass", "singular"}}) ==
        "integrator cd-penalty needs a diagonal mass matrix with entries > 0 (M^{-1} in the update); problem signorini-bar "
        "has a massless dof (dof 0 has mass 0) (valid: a problem with a lumped mass, e.g. mass=lumped)");
}

TEST_CASE("capabilities: no massless dof (any pattern), one line", "[integrators][capabilities]") {
  const auto bar = nsb::make_problem("signorini-bar", {{"N", "10"}, {"mass", "singular"}});
  const nsb::DeclaredCapabilities invertible{{.mass = nsb::MassNeed::NoMasslessDofs}, {}};
  try {
    nsb::check_capabilities(invertible, "dense", nsb::Params(nsb::ParamSpecs{}), *bar, bar->mass_matrix());
    FAIL("accepted a massless dof");
  } catch (const nsb::InputError& e) {
    CHECK(std::string(e.what()) ==
          "integrator dense needs an invertible mass matrix (every diagonal entry > 0); problem signorini-bar has a massless "
          "dof (dof 0 has mass 0) (valid: a problem with a lumped mass, e.g. mass=lumped)");
  }
  const auto consistent = nsb::make_problem("signorini-bar", {{"N", "10"}, {"mass", "consistent"}});
  CHECK_NOTHROW(nsb::check_capabilities(invertible, "dense", nsb::Params(nsb::ParamSpecs{}), *consistent, consistent->mass_matrix()));
}

TEST_CASE("capabilities: a parameter switches them (schatzman-paoli's theta), and the line says which", "[integrators][capabilities]") {
  CHECK(refusal("schatzman-paoli", {{"theta", "0"}}, "signorini-bar", {{"N", "10"}, {"mass", "consistent"}}) ==
        "integrator schatzman-paoli with theta = 0 needs a diagonal mass matrix with entries > 0 (M^{-1} in the update); "
        "problem signorini-bar has a non-diagonal mass matrix (valid: a problem with a lumped mass, e.g. mass=lumped)");
  CHECK(refusal("schatzman-paoli", {{"theta", "0.25"}}, "signorini-bar", {{"N", "10"}, {"mass", "consistent"}}).empty());
  CHECK(nsb::make_integrator("schatzman-paoli", {{"theta", "0"}})->conditionally_stable());
  CHECK_FALSE(nsb::make_integrator("schatzman-paoli", {{"theta", "0.25"}})->conditionally_stable());
}

TEST_CASE("capabilities: linear problems only refused a nonlinear F_int, one line", "[integrators][capabilities]") {
  CHECK(refusal("schatzman-paoli", {{"theta", "0.25"}}, "block-2d", {}) ==
        "integrator schatzman-paoli with theta != 0 needs a linear F_int (F_int = K u, K constant); problem block-2d has a "
        "nonlinear F_int (valid: a linear problem)");
}

TEST_CASE("capabilities: a constant F_ext only refused a time-dependent one, one line", "[integrators][capabilities]") {
  const TimeDependentLoad ball(nsb::make_problem("bouncing-mass", {}));
  CHECK(refusal("modal-exact", {}, ball) ==
        "integrator modal-exact needs a constant F_ext; problem time-dependent-bouncing-mass has a time-dependent F_ext "
        "(valid: a problem with a constant load)");
}

TEST_CASE("capabilities: the largest size, read from the parameter that bounds it, one line", "[integrators][capabilities]") {
  CHECK(refusal("modal-exact", {{"max_dofs", "5"}}, "signorini-bar", {{"N", "10"}}) ==
        "integrator modal-exact needs at most max_dofs = 5 dofs; problem signorini-bar has 11 dofs "
        "(valid: max_dofs >= 11, or a smaller problem)");
  CHECK(refusal("modal-exact", {{"max_dofs", "11"}}, "signorini-bar", {{"N", "10"}}).empty());
}

TEST_CASE("capabilities: node-to-rigid contacts only refused contacts between bodies, one line", "[integrators][capabilities]") {
  CHECK(refusal("event-driven", {}, "ball-chain", {}) ==
        "integrator event-driven needs node-to-rigid contacts (each contact on one dof, one contact per dof); problem "
        "ball-chain has contact 0 acting on 2 dofs (valid: a problem whose contacts each hold one dof against a fixed obstacle)");
}

TEST_CASE("capabilities: every requirement a problem misses is named at once, in one line", "[integrators][capabilities]") {
  // rolling-disk (mu = 0.3, e = 0.5 on a disk with mass): newmark-lm misses two; both named, so
  // that a user does not meet them one try at a time.
  const std::string why = refusal("newmark-lm", {}, "rolling-disk", {});
  CHECK(why.find('\n') == std::string::npos);
  CHECK_THAT(why, Catch::StartsWith("integrator newmark-lm needs mu = 0 (it does not treat Coulomb friction); problem rolling-disk "
                                    "has mu = 0.3 (valid: a problem with mu = 0, or an integrator `nsbench list` marks as treating "
                                    "friction)"));
  CHECK_THAT(why, Catch::EndsWith("; it also needs e = 0 on contacts with mass (it has no velocity-level impact law); problem "
                                  "rolling-disk has restitution e = 0.5 on a contact with mass (valid: e = 0, or a problem whose "
                                  "contact dofs are massless, e.g. mass=singular)"));
  // One requirement missed: the line is the one wording alone, with no "it also".
  CHECK(refusal("newmark-lm", {}, "bouncing-mass", {{"e", "1"}}) ==
        "integrator newmark-lm needs e = 0 on contacts with mass (it has no velocity-level impact law); problem bouncing-mass "
        "has restitution e = 1 on a contact with mass (valid: e = 0, or a problem whose contact dofs are massless, e.g. "
        "mass=singular)");
  CHECK(refusal("newmark-lm", {}, "bouncing-mass", {{"e", "0"}}).empty());
}

TEST_CASE("capabilities: nsbench list reads them from the entries", "[integrators][capabilities]") {
  CHECK(nsb::find_integrator("cd-lagrange").declared().text() == "explicit; diagonal mass >= 0");
  CHECK(nsb::find_integrator("schatzman-paoli").declared().text() ==
        "with theta != 0: linear F_int; with theta = 0: explicit; diagonal mass > 0");
  CHECK(nsb::find_integrator("moreau-jean").declared().text() == "none");
  CHECK(nsb::find_integrator("newmark-lm").declared().text() == "e = 0 on contacts with mass");
}

TEST_CASE("step(): the time and the step count are kept around every scheme's advance()", "[integrators][capabilities]") {
  const auto ball = nsb::make_problem("bouncing-mass", {{"e", "0"}});  // e = 0: newmark-lm runs it too
  for (const auto& entry : nsb::integrator_registry()) {
    if (entry.reference || entry.peer) continue;
    INFO(entry.name);
    auto integ = entry.make(nsb::Params(entry.parameters()));
    CHECK(integ->name() == entry.name);
    integ->init(*ball, ball->initial_state());
    double t = ball->initial_state().t;
    for (int k = 1; k <= 5; ++k) {
      const nsb::StepInfo info = integ->step(1e-3);
      t += info.dt;
      CHECK(integ->state().t == t);
      CHECK(integ->work().steps == k);
    }
  }
}
