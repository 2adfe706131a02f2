#pragma once
// Where a report was computed, for its footer: the machine (CPU model, cores), the library
// versions the numbers depend on (Eigen, SUNDIALS, SuiteSparse as compiled against; the BLAS
// shared object the process actually loaded, since Debian's alternatives choose it at run
// time) and the command that reruns it.
#include <string>

namespace nsb {

struct Environment {
  std::string cpu;        // /proc/cpuinfo "model name"; "unknown" elsewhere
  unsigned cores = 0;     // std::thread::hardware_concurrency()
  std::string libraries;  // "Eigen 3.4.0, SUNDIALS 6.4.1, SuiteSparse 5.12.0, BLAS /usr/lib/.../libblas.so.3"
};

const Environment& environment();

// The memory a run may take, in bytes: NSBENCH_MEMORY_LIMIT if set (bytes, or with a K, M or
// G suffix: powers of 1024; InputError if malformed), else MemAvailable (/proc/meminfo), or
// the process limit RLIMIT_AS or RLIMIT_DATA (ulimit -v, -d) when lower.
// `source` gets where the figure comes from. Used to refuse, before allocating, a problem or
// factorisation that would not fit.
double memory_available(std::string& source);

// The command line of this process, as a shell would rerun it (set once by main; empty
// until then, e.g. in tests).
void set_command_line(int argc, const char* const* argv);
const std::string& command_line();

}  // namespace nsb
