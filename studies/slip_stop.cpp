#include "studies/slip_stop.hpp"

#include <cmath>

#include "problems/rolling_disk.hpp"
#include "problems/sliding_mass.hpp"
#include "studies/measures.hpp"

namespace nsb {

namespace {
double finite_or_nan(double x) { return std::isfinite(x) ? x : kNaN; }
}  // namespace

ExactStop exact_stop(const Problem& problem) {
  if (const auto* s = dynamic_cast<const SlidingMass*>(&problem))
    return {finite_or_nan(s->stop_time()), finite_or_nan(s->stop_distance()), s->sticks(), std::isinf(s->stop_time()), false};
  if (const auto* d = dynamic_cast<const RollingDisk*>(&problem)) {
    const double onset = d->rolling_onset_time(), rest = d->rest_time();
    return {onset > rest || rest == 0.0 ? finite_or_nan(onset) : kNaN, kNaN, true, std::isinf(onset), true};
  }
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
