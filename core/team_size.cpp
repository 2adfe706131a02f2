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
  if (probed_++ == 0) return;  // the window's first step wakes or starts the team: not counted
  if (phase_ == Phase::ProbeMany) {
    many_ += seconds;
    if (one_step_ > 0.0 && many_ > kProbeSteps * one_step_) return decide(1, one_step_);
    if (probed_ <= kProbeSteps) return;
    phase_ = Phase::ProbeOne;
    current_ = 1;
    probed_ = 0;
    return;
  }
  one_ += seconds;
  one_step_ = one_ / (probed_ - 1);
  if (one_ > many_) return decide(most_, many_ / kProbeSteps);
  if (probed_ <= kProbeSteps) return;
  decide(1, one_step_);  // one thread as fast as the team, or faster
}

void TeamSize::decide(int threads, double step_seconds) {
  window_seconds_ = threads == choice_ ? std::min(2.0 * window_seconds_, kMaxExploitSeconds) : kFirstExploitSeconds;
  choice_ = threads;
  current_ = threads;
  phase_ = Phase::Exploit;
  exploit_left_ = std::max(1L, std::lround(std::min(window_seconds_ / std::max(step_seconds, 1e-9), 1e9)));
}

}  // namespace nsb
