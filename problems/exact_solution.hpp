#pragma once
// A problem's exact solution, apart from its model (problems/problem.hpp): what studies and
// checks compare a scheme against. Problem::exact() gives it where the solution is known
// (derived and tested on its own; each problem's header states the formulas), nullptr
// otherwise. Studies ask it for what they need through the typed queries below instead of
// casting a Problem to its concrete class.
//
// Conventions: a query the solution cannot answer (an event it does not have or does not
// time, a value it does not define) gives nullopt or an empty vector; an event it knows will
// never happen is +inf. Every query is const and may be called from several threads.
#include <optional>
#include <string_view>
#include <vector>

#include "problems/state.hpp"

namespace nsb {

// Events an exact solution may time (each problem's header says which it knows).
enum class ExactEvent {
  contact_start,  // the first impact, which opens the contact phase (signorini-bar: g0 / v0; with gravity t1)
  slip_stop,      // the slip stops (sliding-mass)
  rest,           // at rest from here on (rolling-disk: on the floor; rocking-block)
  roll_onset,     // rolling without slip starts (rolling-disk, sphere)
  jam,            // dynamic jam: the normal force grows without bound (painleve-rod)
};

// Scalars of an exact solution that are no time and no state.
enum class ExactValue {
  contact_duration,     // length of the contact phase (signorini-bar: 2 L / c)
  stop_distance,        // path slid up to slip_stop (sliding-mass; +inf when it never stops)
  stays_stopped,        // 1 when, once stopped, it stays so (static friction holds), else 0
  first_rebound_speed,  // the speed just after the first impact (rolling-disk)
  impact_ratio,         // omega+ / omega- at an impact under the suite's law (rocking-block: Moreau's)
  housner_ratio,        // omega+ / omega- under Housner's law, 1 - (3/2) sin^2 alpha (rocking-block)
  wave_time,            // L / c, the time a wave takes to cross the bar (signorini-bar, bouncing-bar)
};

class ExactSolution {
 public:
  virtual ~ExactSolution() = default;

  // The exact state at t; nullopt where the solution does not hold (it ended: a jam, a slip
  // the closed form excludes) or, for some parameters, is not known.
  virtual std::optional<State> state(double t) const = 0;
  // Exact times of the impacts in [0, t_end], in order (impact-time errors of study files);
  // empty where not known. A solution that lists a bounded number of an endless sequence
  // gives them all for t_end = +inf and refuses (InputError naming t_end and its valid range)
  // a finite t_end past the last: never a shorter list that passes for the whole.
  virtual std::vector<double> impact_times(double /*t_end*/) const { return {}; }
  // The exact energy after each of those impacts (the flight that follows it); empty where
  // not known.
  virtual std::vector<double> energies_after_impacts(double /*t_end*/) const { return {}; }
  // The amplitude (largest |angle| of the motion that follows) after each impact, in order,
  // for a solution that rocks; empty otherwise.
  virtual std::vector<double> amplitudes_after_impacts() const { return {}; }
  virtual std::optional<double> event_time(ExactEvent /*event*/) const { return std::nullopt; }
  virtual std::optional<double> value(ExactValue /*what*/) const { return std::nullopt; }
  // The exact stress of each element cell of the problem's field_mesh() at t, at the cell's
  // centre (the mean of its points), written into out as Problem::cell_stress() writes a
  // state's (a study's exact field beside the schemes' element stresses); false where not known.
  virtual bool exact_cell_stress(double /*t*/, Eigen::Ref<Eigen::MatrixXd> /*out*/) const { return false; }
  // The problem's observable `name` (Problem::observable_names) on state(t), bit for bit what
  // Problem::observe gives there, where a few points of the solution make it: a study's error
  // of one observable then costs O(1) per step against the exact solution, not O(ndof).
  // nullopt where not offered or where state(t) is (callers then observe state(t)).
  virtual std::optional<double> observable(std::string_view /*name*/, double /*t*/) const { return std::nullopt; }
};

}  // namespace nsb
