#pragma once
// The team size of one run, chosen by measuring it. On a machine whose other cores are busy,
// a team of T threads can take longer per step than one thread: the team member that shares
// its core with another process gets its time slices late, and the whole team waits for it
// at the end of every parallel region (issue 36). No waiting policy cures that
// (core/wait_policy.hpp makes the waiting cheap, not the waited-for thread faster), so the run
// loop (run/run.cpp) measures:
//   probe     kProbeSteps steps on T threads, then as many on one (the first step of each
//             window, which wakes or starts the team, not counted); their wall times summed.
//             A probe stops early once its sum exceeds the other size's whole probe (this
//             cycle's T-thread probe, or the last cycle's one-thread probe): it has lost.
//   exploit   the faster of the two until kFirstExploitSeconds of wall time have passed (as
//             the probes timed the steps), then probe again; a decision the next probe
//             confirms doubles the window (up to kMaxExploitSeconds), a changed one resets it
// A run is then never much slower than on one thread: the probes of the slower size cost
// about one probe of the faster one per window. Results do not depend on the choice (every
// parallel loop gives bit-identical numbers for any thread count: core/threads.hpp), only the
// wall time does. With T = 1 (NSBENCH_THREADS=1, a study's worker) there is nothing to choose.

namespace nsb {

class TeamSize {
 public:
  static constexpr int kProbeSteps = 8;
  static constexpr double kFirstExploitSeconds = 0.5, kMaxExploitSeconds = 8.0;

  explicit TeamSize(int threads);  // T: the run's threads (run_threads())
  int threads() const { return current_; }  // the team for the next step
  bool timing() const { return phase_ != Phase::Exploit; }  // whether the next step must be timed
  // After every step: its wall time in seconds when timing() was true before it (else ignored).
  void step_done(double seconds);

 private:
  enum class Phase { ProbeMany, ProbeOne, Exploit };
  void start_probe();
  void decide(int threads, double step_seconds);  // exploit `threads`, steps of step_seconds
  int most_;
  int current_;
  Phase phase_ = Phase::ProbeMany;
  int probed_ = 0;                // steps of the current probe window so far (the first not counted)
  double many_ = 0.0, one_ = 0.0;  // summed wall times of the counted probe steps
  double one_step_ = 0.0;          // a one-thread step's time at the last probe (0: none yet)
  int choice_ = 0;                // the last decision (0: none yet)
  double window_seconds_ = kFirstExploitSeconds;
  long exploit_left_ = 0;          // steps before the next probe
};

}  // namespace nsb
