// Every registered integrator on a small bar-3d (problems/bar_3d.hpp), sides held and free,
// every mass model: it either declines at init with its one-line refusal or runs through
// the contact without diverging, its state finite and the bar off the wall's far side.
#include <catch2/catch.hpp>
#include <cmath>
#include <string>

#include "integrators/registry.hpp"
#include "problems/bar_3d.hpp"
#include "run/run.hpp"
#include "tests/integrators/every_integrator.hpp"

TEST_CASE("bar-3d: every integrator declines it in one line or runs it through the contact", "[integrators][bar-3d]") {
  for (const char* lateral : {"held", "free"})
    for (const char* mass : {"lumped", "consistent", "singular"}) {
      const nsb::Bar3d bar(nsb::Params(nsb::Bar3d::parameters_spec(),
                                       {{"N", "4"}, {"N_side", "1"}, {"lateral", lateral}, {"mass", mass}, {"g0", "0.05"}}));
      long ran = 0;
      for (const auto& entry : nsb::integrator_registry()) {
        INFO(entry.name << " on bar-3d, lateral " << lateral << ", mass " << mass);
        auto integ = nsb::testing::init_or_decline(entry, bar);
        if (!integ) continue;
        nsb::RunOptions options;
        options.dt = 0.25 * bar.stable_step();
        options.t_end = 0.05 + 1.2 * 2.0 / bar.p_wave_speed();  // the gap, then the contact and the release
        options.record_series = false;
        const nsb::RunResult r = nsb::run(bar, *integ, options);
        CHECK(r.status == nsb::RunStatus::Ok);
        CHECK(integ->state().u.allFinite());
        CHECK(integ->state().v.allFinite());
        // Nothing went through the wall: the wall face stays within the step's travel of it.
        for (nsb::Index k = 0; k < bar.ncontacts(); ++k)
          CHECK(bar.gap_offset()[k] + (bar.gap_operator() * integ->state().u)[k] >= -0.1);
        ++ran;
      }
      INFO("lateral " << lateral << ", mass " << mass);
      CHECK(ran > 0);
    }
}
