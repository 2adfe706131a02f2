#pragma once
// One run as its users name it, shared by the command line (`nsbench run`) and the Python
// module (`nsbench.run`): a problem and an integrator by name with "key=value" items routed
// between their parameters (route_overrides, core/parameters.hpp), and the run options as
// text. Both front ends go through here, so they accept and refuse the same input with the
// same messages (the options named as each front end spells them).
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"
#include "run/run.hpp"

namespace nsb {

struct RunCase {
  std::unique_ptr<Problem> problem;
  std::unique_ptr<Integrator> integrator;
};

// Throws InputError on an unknown name or a bad, unknown or ambiguous parameter.
RunCase make_run_case(const std::string& problem, const std::string& integrator, const std::vector<std::string>& sets);

// How the messages name the options: "--dt", "--t-end", "--sample-every" (command line) or
// "dt", "t_end", "sample_every" (Python keyword arguments).
enum class OptionStyle { CommandLine, Python };

// dt > 0, t_end > 0, dt <= t_end (refused, not clipped: the run would end at t = dt) and
// sample_every an integer >= 1; throws InputError naming the option and its valid range.
// The other fields keep RunOptions' defaults; state_every = sample_every.
RunOptions parse_run_options(const std::string& dt, const std::string& t_end, const std::string& sample_every,
                             OptionStyle style);

}  // namespace nsb
