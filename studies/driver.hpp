#pragma once
// The study driver: runs selected studies' cases in one pool and writes, shards, merges or
// verifies their reports. Both front ends go through here: the command line (`nsbench-study`,
// app/nsbench_study.cpp) and Python studies (nsbench.study.Study.main, python/bind_study.cpp),
// so a study behaves the same whatever it is written in.
//
//   run     every case of every study (this shard's with --shard I/N), in one pool
//           (studies/parallel.hpp): a study's longest case does not leave the other cores idle;
//   shard   the results written to OUT/shards/<study>-I-of-N.json (studies/shard.hpp);
//   merge   the shards read back instead of running;
//   verify  the tables recomputed and compared with the report in a directory (studies/verify.hpp);
//   report  otherwise: tables, figures.json and index.md staged and swapped into OUT whole
//           (core/output.hpp), each study's index entries kept (studies/report_index.hpp).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "studies/shard.hpp"
#include "studies/study.hpp"
#include "studies/verify.hpp"

namespace nsb {

struct StudySpec;

struct DriverOptions {
  std::string out = "reports";
  bool full = false;
  Shard shard = {};
  bool merge = false;
  std::string verify_dir = {};  // non-empty: verify against it, write nothing
  VerifyTolerance tolerance = {};
  // A study's own check of its results read back from shards (studies/shard.hpp), or unset.
  std::function<std::string(const StudyEntry&, const Json& the_case, const Json& result)> result_check = {};
  // Called with the report's staging directory before it is committed (a study file's copy).
  std::function<void(const std::filesystem::path& report)> before_commit = {};
};

// Checks the options (--rtol and --atol finite and >= 0) and against each other (--shard with
// --merge, --verify with either, a missing --verify directory): InputError naming them.
void check_driver_options(const DriverOptions& options);

// Runs the studies as the options say; returns the exit status: 0, or 1 when --verify found
// differences (printed one per line, then a summary line). Throws InputError on bad input.
int drive_studies(const std::vector<const StudyEntry*>& studies, const DriverOptions& options);

}  // namespace nsb
