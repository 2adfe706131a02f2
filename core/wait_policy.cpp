#include "core/wait_policy.hpp"

#include <unistd.h>

#include <cstdlib>

namespace nsb {

void choose_openmp_wait_policy(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;  // the user's choice
  setenv("GOMP_SPINCOUNT", kWaitSpinCount, 1);
  execv("/proc/self/exe", argv);  // returns only when it failed
}

}  // namespace nsb
