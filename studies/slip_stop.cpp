#include "studies/slip_stop.hpp"

#include <cmath>

#include "studies/measures.hpp"

namespace nsb {

namespace {
double finite_or_nan(double x) { return std::isfinite(x) ? x : kNaN; }
}  // namespace

ExactStop exact_stop(const Problem& problem) {
  const ExactSolution* exact = problem.exact();
  if (!exact) return {};
  if (const auto stop = exact->event_time(ExactEvent::slip_stop)) {
    const double distance = exact->value(ExactValue::stop_distance).value_or(kNaN);
    return {finite_or_nan(*stop), finite_or_nan(distance), exact->value(ExactValue::stays_stopped) == 1.0, std::isinf(*stop), false};
  }
  const auto onset = exact->event_time(ExactEvent::roll_onset), rest = exact->event_time(ExactEvent::rest);
  if (onset && rest) return {*onset > *rest || *rest == 0.0 ? finite_or_nan(*onset) : kNaN, kNaN, true, std::isinf(*onset), true};
  return {};
}

SlipStop::SlipStop(const Problem& problem, const State& initial)
    : contacts_(problem.contacts()),
      w_(contacts_.tangent_velocity.size() ? contacts_.tangent_velocity : Vec::Zero(contacts_.size())),
      slip_(contacts_.tangent * initial.v - w_),
      u_prev_(initial.u) {
  sign0_ = slip_.size() ? (slip_[0] > 0.0) - (slip_[0] < 0.0) : 0.0;
  const bool at_rest0 = slip_.size() && slip_.cwiseAbs().maxCoeff() <= kSlipTol;
  t_rest_ = path_rest_ = t_first_stop_ = path_first_stop_ = at_rest0 ? 0.0 : kNaN;
}

void SlipStop::add(const State& s) {
  slip_.noalias() = contacts_.tangent * s.v;
  slip_ -= w_;
  if (slip_.size()) path_ += std::abs(contacts_.tangent.row(0).dot(s.u - u_prev_));
  u_prev_ = s.u;
  if (slip_.size() && slip_.cwiseAbs().maxCoeff() > kSlipTol) {
    t_rest_ = path_rest_ = kNaN;
  } else if (std::isnan(t_rest_)) {
    t_rest_ = s.t;
    path_rest_ = path_;
  }
  if (std::isnan(t_first_stop_) && slip_.size() && sign0_ * slip_[0] <= kSlipTol) {
    t_first_stop_ = s.t;
    path_first_stop_ = path_;
  }
}

}  // namespace nsb
