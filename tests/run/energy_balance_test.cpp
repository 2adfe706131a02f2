// What `nsbench run` reports of the discrete energy balance (run/energy_balance.hpp): the energy
// change is the loads' work plus the contact impulses' plus the residual, on a dissipative and a
// conservative contact; the residual is round-off where EnergyBalance's header derives it so
// (moreau-jean theta = 1/2 on a linear problem, cd-lagrange on a rigid one); a scheme without a
// derived balance is named; summary.json gains the figures and keeps every other key. The
// per-scheme residuals themselves: tests/studies/measures_test.cpp.
#include "run/energy_balance.hpp"

#include <catch2/catch.hpp>
#include <cmath>
#include <nlohmann/json.hpp>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "run/run.hpp"

namespace {

struct BalancedRun {
  nsb::RunEnergyBalance figures;
  nsb::RunResult result;
  long impulse_steps = 0;  // steps with a contact impulse
};

// `integrator` on `problem` to t_end at dt, a RunBalance fed after every step as nsbench run feeds it.
BalancedRun balanced_run(const nsb::Problem& problem, nsb::Integrator& integrator, double dt, double t_end) {
  integrator.init(problem, problem.initial_state());
  nsb::RunBalance balance(problem, integrator);
  BalancedRun out;
  nsb::RunOptions options{dt, t_end, 1, false};
  out.result = nsb::run(problem, integrator, options, [&](const nsb::Integrator& it, const nsb::StepInfo&) {
    balance.add(it);
    out.impulse_steps += it.impulses().sum() > 0.0;
  });
  out.figures = balance.figures();
  return out;
}

// energy change = work of the loads + work of the contact impulses + residual, to the rounding of
// the three sums.
void check_sum(const nsb::RunEnergyBalance& b) {
  REQUIRE(b.not_derived.empty());
  CHECK(b.steps_closed > 0);
  CHECK(std::abs(b.energy_change - (b.load_work + b.contact_work + b.residual)) <= b.round_off);
}

}  // namespace

TEST_CASE("RunBalance: moreau-jean theta = 1/2 on the Signorini bar, e = 0 and e = 1: the contact work is the energy change",
          "[run][energy_balance]") {
  for (const char* e : {"0", "1"}) {
    CAPTURE(e);
    const auto bar = nsb::make_problem("signorini-bar", {{"N", "20"}, {"e", e}});
    auto mj = nsb::make_integrator("moreau-jean");
    const BalancedRun r = balanced_run(*bar, *mj, 0.5 * bar->stable_step(), 4.0);
    REQUIRE(r.result.status == nsb::RunStatus::Ok);
    const nsb::RunEnergyBalance& b = r.figures;
    check_sum(b);
    CHECK(r.impulse_steps > 0);
    CHECK(b.steps_closed == r.result.steps);  // a step-end scheme closes every step...
    CHECK(std::abs(b.energy_change - (r.result.final_energy - r.result.initial_energy)) <= b.round_off);  // ...so E_end - E0
    CHECK(b.load_work == 0.0);                  // no gravity, no load
    CHECK(std::abs(b.residual) <= b.round_off);  // the trapezoidal rule on a linear body: round-off
    const double e0 = r.result.initial_energy;
    if (e[0] == '0') {
      CHECK(b.energy_change < -1e-3 * e0);  // the plastic node impacts dissipate...
      CHECK(std::abs(b.contact_work - b.energy_change) <= b.round_off);  // ...through the impulses alone
    } else {
      CHECK(std::abs(b.energy_change) <= b.round_off);  // elastic impacts keep it
      CHECK(std::abs(b.contact_work) <= b.round_off);
    }
  }
}

TEST_CASE("RunBalance: cd-lagrange on the bouncing mass, e = 0.5: the loads work nothing beyond their potential, the impulses the rest",
          "[run][energy_balance]") {
  const auto mass = nsb::make_problem("bouncing-mass", {{"e", "0.5"}});
  auto cd = nsb::make_integrator("cd-lagrange");
  const BalancedRun r = balanced_run(*mass, *cd, 1e-3, 1.5);
  REQUIRE(r.result.status == nsb::RunStatus::Ok);
  const nsb::RunEnergyBalance& b = r.figures;
  check_sum(b);
  CHECK(r.impulse_steps > 0);
  CHECK(b.steps_closed == r.result.steps - 2);  // staggered: from the second report, the last jump unclosed
  CHECK(b.contact_work < -0.1 * r.result.initial_energy);  // the impacts take (1 - e^2) of the energy each
  CHECK(std::abs(b.load_work) <= b.round_off);   // gravity's potential is in E
  CHECK(std::abs(b.residual) <= b.round_off);    // a rigid body: the staggered residual is 0
}

TEST_CASE("RunBalance: a scheme without a derived balance is named, and summary.json says so", "[run][energy_balance]") {
  const auto mass = nsb::make_problem("bouncing-mass");
  auto nsga = nsb::make_integrator("nsga");
  nsga->init(*mass, mass->initial_state());
  const nsb::RunBalance balance(*mass, *nsga);
  CHECK_FALSE(balance.derived());
  const nsb::RunEnergyBalance b = balance.figures();
  CHECK_THAT(b.not_derived, Catch::StartsWith("energy balance: not derived for integrator 'nsga'"));
  nsb::RunOptions options{1e-3, 0.1, 1, false};
  const nsb::RunResult result = nsb::run(*mass, *nsga, options);
  const std::string plain = nsb::summary_to_json(*mass, *nsga, options, result);
  const auto with = nlohmann::json::parse(nsb::with_energy_balance(plain, b));
  CHECK(with["energy_balance"]["derived"] == false);
  CHECK(with["energy_balance"]["reason"] == b.not_derived);
  auto rest = with;
  rest.erase("energy_balance");
  CHECK(rest == nlohmann::json::parse(plain));  // every other key as summary_to_json wrote it
}

TEST_CASE("with_energy_balance: the figures under energy_balance, every other key unchanged", "[run][energy_balance]") {
  const auto bar = nsb::make_problem("signorini-bar", {{"N", "20"}});
  auto mj = nsb::make_integrator("moreau-jean");
  const BalancedRun r = balanced_run(*bar, *mj, 0.5 * bar->stable_step(), 4.0);
  nsb::RunOptions options{0.5 * bar->stable_step(), 4.0, 1, false};
  const std::string plain = nsb::summary_to_json(*bar, *mj, options, r.result);
  const auto with = nlohmann::json::parse(nsb::with_energy_balance(plain, r.figures));
  const auto& b = with["energy_balance"];
  CHECK(b["derived"] == true);
  CHECK(b["steps_closed"] == r.figures.steps_closed);
  CHECK(b["energy_change"].get<double>() == r.figures.energy_change);
  CHECK(b["load_work"].get<double>() == r.figures.load_work);
  CHECK(b["contact_work"].get<double>() == r.figures.contact_work);
  CHECK(b["residual"].get<double>() == r.figures.residual);
  CHECK(b["round_off"].get<double>() == r.figures.round_off);
  auto rest = with;
  rest.erase("energy_balance");
  CHECK(rest == nlohmann::json::parse(plain));
}
