#include "run/run_case.hpp"

#include <fmt/format.h>

#include <cmath>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"

namespace nsb {

RunCase make_run_case(const std::string& problem, const std::string& integrator, const std::vector<std::string>& sets) {
  const auto& pe = find_problem(problem);
  const auto& ie = find_integrator(integrator);
  const auto routed = route_overrides(sets, pe.parameters(), ie.parameters());
  return {pe.make(Params(pe.parameters(), routed.problem)), ie.make(Params(ie.parameters(), routed.integrator))};
}

RunOptions parse_run_options(const std::string& dt, const std::string& t_end, const std::string& sample_every,
                             OptionStyle style) {
  const bool cli = style == OptionStyle::CommandLine;
  const std::string dt_name = cli ? "--dt" : "dt", t_end_name = cli ? "--t-end" : "t_end",
                    every_name = cli ? "--sample-every" : "sample_every";
  RunOptions options;
  options.dt = parse_real(dt, dt_name);
  options.t_end = parse_real(t_end, t_end_name);
  const double every = parse_real(sample_every, every_name);
  // Bounded before the cast (1e20 overflowed it); beyond any run's step limit (RunOptions::max_steps).
  constexpr double kMaxEvery = 1e15;
  if (!(every >= 1 && every <= kMaxEvery) || every != std::floor(every))
    throw InputError(fmt::format("{} {}: must be an integer >= 1 (at most {:g})", every_name, sample_every, kMaxEvery));
  options.sample_every = static_cast<long>(every);
  options.state_every = options.sample_every;
  if (!(options.dt > 0.0)) throw InputError(fmt::format("{} {}: must be > 0", dt_name, dt));
  if (!(options.t_end > 0.0)) throw InputError(fmt::format("{} {}: must be > 0", t_end_name, t_end));
  if (options.dt > options.t_end)
    throw InputError(fmt::format("{} {} is larger than {} {}; valid: dt <= t_end", dt_name, dt, t_end_name, t_end));
  return options;
}

}  // namespace nsb
