#pragma once
// When a frictional contact stops slipping: the stop time (a sliding mass coming to rest) and
// the rolling onset (a disk whose contact point stops slipping), measured on a run and given by
// the problem's exact solution: the study files' stop-time and onset-time measures
// (studies/study_file/run_case.cpp). The friction study (studies/builtin/friction.py) applies the
// same rule in NumPy (tests/studies/study_file_test.cpp: one value of its report, to the bit).
//
// Measured from the slip u_T = T v - w of the contacts (T the tangent rows, w the obstacle's
// tangential velocity), after every step:
//   rest         the first step from which |u_T| <= kSlipTol on every contact and stays so
//                (NaN while it is not); with the contact's tangential path sum |T_0 (U_{k+1}
//                - U_k)| travelled by then;
//   first stop   the first step at which the first contact's slip has lost its initial sign
//                (u_T sign(u_T(0)) <= kSlipTol: stopped or reversed), with its path.
// The stop is the rest where the exact solution stays stopped once it stops (ExactStop::stays),
// else the first stop (a sliding reversal).
#include <limits>

#include "problems/problem.hpp"

namespace nsb {

inline constexpr double kSlipTol = 1e-9;  // [m/s]: at rest or rolling (the problems move at ~1 m/s)

// What a problem's exact solution says of its stop (NaN: nothing, the solution times neither
// a slip stop nor a rolling onset after rest, or it never stops).
struct ExactStop {
  double stop_time = std::numeric_limits<double>::quiet_NaN();      // sliding mass: stop; disk: rolling onset
  double stop_distance = std::numeric_limits<double>::quiet_NaN();  // sliding mass only
  bool stays = true;        // once stopped (or rolling) it stays so
  bool never_stops = false;  // it slides on for ever
  bool rolling = false;      // the stop is a disk's rolling onset
};
// A solution that times ExactEvent::slip_stop (sliding-mass): that time, ExactValue::stop_distance
// and stays_stopped. One that times roll_onset and rest (rolling-disk): the rolling onset as
// the slip sees it, from its rest time on (the disk lies on the floor) or later; when the onset
// equals a rest time > 0 the slip may have ended in a bounce before it, which the problem does
// not time: NaN.
ExactStop exact_stop(const Problem& problem);

class SlipStop {
 public:
  SlipStop(const Problem& problem, const State& initial);
  void add(const State& s);  // after each step
  const Vec& slip() const { return slip_; }
  double time(bool stays) const { return stays ? t_rest_ : t_first_stop_; }
  double path(bool stays) const { return stays ? path_rest_ : path_first_stop_; }

 private:
  const Contacts& contacts_;
  Vec w_, slip_, u_prev_;
  double sign0_ = 0.0, path_ = 0.0;
  double t_rest_, path_rest_, t_first_stop_, path_first_stop_;
};

}  // namespace nsb
