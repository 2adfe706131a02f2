#pragma once
// The index.md of a report (nsbench-study, nsbench.run_study from Python): a header with the
// build stamp, the lead tables (the claims) and the headline tables (the rankings) in full,
// then a section per study listing its tables and figures, and the environment footer.
#include <filesystem>
#include <string>
#include <vector>

#include "studies/study.hpp"
#include "studies/table.hpp"

namespace nsb {

class ReportIndex {
 public:
  explicit ReportIndex(bool full);
  // Writes the study's tables into `dir` and lists them.
  void add_study(const StudyEntry& study, const std::vector<Table>& tables, const std::filesystem::path& dir);
  // The whole index, the footer (machine, libraries, build, the command that ran) included.
  std::string text() const;

 private:
  std::string header_;
  std::string studies_;   // a section per study, after the headline
  std::string headline_;  // the headline tables, shown first
  std::string lead_;      // the lead tables (the claims), shown before the headline
};

}  // namespace nsb
