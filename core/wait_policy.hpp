#pragma once
// How the OpenMP team's threads (core/threads.hpp) wait between parallel regions.
// libgomp's default spins for GOMP_SPINCOUNT = 300000 turns (of the order of a millisecond)
// before it sleeps, so a thread that is done keeps its core busy while a team member that
// shares a core with another process has yet to finish, or while another process waits for
// that core (issue 36). Spinning kWaitSpinCount turns (microseconds) and then sleeping frees
// the core almost at once, while a wake-up that follows closely (the next loop of the same
// step) still finds its thread spinning. Which team size a run then uses is measured as it
// goes (core/team_size.hpp); studies/benchmarks/threads_busy.cpp measures both together.
// libgomp reads OMP_WAIT_POLICY and GOMP_SPINCOUNT once, when it is loaded (before main):
// so when the user set neither, choose_openmp_wait_policy sets GOMP_SPINCOUNT and executes
// the program again (/proc/self/exe, the same arguments); it returns when there is nothing
// to do, or when the exec failed (the run then keeps libgomp's default). Call it before any
// thread starts, in the programs whose runs start threads: `nsbench run` and `check` (a
// study's cases run on one thread each, in nsbench-study's own pool, so it needs none).

namespace nsb {

inline constexpr const char* kWaitSpinCount = "10000";

void choose_openmp_wait_policy(char** argv);

}  // namespace nsb
