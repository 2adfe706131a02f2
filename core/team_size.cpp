#include "core/team_size.hpp"

#include <algorithm>
#include <cmath>

namespace nsb {

TeamSize::TeamSize(int threads) : most_(std::max(1, threads)), current_(most_) {
  if (most_ == 1) {  // nothing to choose: never probes
    phase_ = Phase::Exploit;
    exploit_left_ = -1;
  }
}

void TeamSize::start_probe() {
  phase_ = Phase::ProbeMany;
  current_ = most_;
  probed_ = 0;
  many_ = one_ = 0.0;
}

void TeamSize::step_done(double seconds) {
  if (phase_ == Phase::Exploit) {
    if (exploit_left_ > 0 && --exploit_left_ == 0) start_probe();
    return;
  }
  if (probed_++ > 0) (phase_ == Phase::ProbeMany ? many_ : one_) += seconds;
  if (probed_ <= kProbeSteps) return;
  if (phase_ == Phase::ProbeMany) {
    phase_ = Phase::ProbeOne;
    current_ = 1;
    probed_ = 0;
    return;
  }
  const int decision = many_ < one_ ? most_ : 1;
  window_seconds_ = decision == choice_ ? std::min(2.0 * window_seconds_, kMaxExploitSeconds) : kFirstExploitSeconds;
  choice_ = decision;
  current_ = decision;
  phase_ = Phase::Exploit;
  const double step_seconds = std::max(std::min(many_, one_) / kProbeSteps, 1e-9);
  exploit_left_ = std::max(1L, std::lround(std::min(window_seconds_ / step_seconds, 1e9)));
}

}  // namespace nsb
