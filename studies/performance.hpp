#pragma once
// The `performance` report: each benchmarked step next to its limit, read from the JSON
// that Google Benchmark writes (--benchmark_out=FILE --benchmark_out_format=json) for the
// nsbench-bench-* binaries, which follow studies/benchmarks/limit.hpp. One row per
// benchmark: the min over its repetitions when they were aggregated, else the least
// repetition; the ratio is the step's time over its limit's, both measured in the same
// process; the speed-up compares a row with the same benchmark run on one thread (another
// file, NSBENCH_THREADS=1), when one was given.
//
//   nsbench-study performance BENCH.json... [--out DIR]
#include <filesystem>
#include <vector>

#include "studies/table.hpp"

namespace nsb {

// Throws InputError naming the file for one that is unreadable or not benchmark output.
Table performance_table(const std::vector<std::filesystem::path>& benchmark_files);

}  // namespace nsb
