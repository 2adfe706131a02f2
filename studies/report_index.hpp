#pragma once
// The index.md of a report (nsbench-study, nsbench.run_study from Python): a header with the
// build stamp, the lead tables (the claims) in full with the lead figures (one per claim), and
// the headline tables (the rankings) in full,
// then a section per study listing its tables and figures, and the environment footer.
// Each study's entries (and its figures) are kept in the report as .index/STUDY.json, so that a
// later run of other studies into the same report lists them all in index.md and figures.json,
// not only its own.
#include <filesystem>
#include <string>
#include <vector>

#include "studies/study.hpp"
#include "studies/table.hpp"

namespace nsb {

class ReportIndex {
 public:
  // `report`: the directory being written (a ReportDirectory's staging path); `rewritten`: the
  // studies this run writes, whose earlier entries are dropped first (a table that moved from
  // one of them to another is no clash).
  ReportIndex(bool full, std::filesystem::path report, const std::vector<std::string>& rewritten = {});
  // Writes the study's tables into the report and keeps its entries (.index/STUDY.json);
  // returns its section of index.md. Throws InputError, before writing, when a table's id is
  // reserved ("index": index.md) or a table's or figure's id is another study's of the report
  // (its files would overwrite that study's).
  std::string add_study(const StudyEntry& study, const std::vector<Table>& tables) const;
  // Writes index.md and figures.json from the entries the report holds, read once: every
  // study's (the registered studies in their order, then the others by name), and index.md's
  // footer (machine, libraries, build, the command that ran). A damaged entry is left out,
  // with a warning.
  void write() const;

 private:
  std::string header_;
  std::filesystem::path report_;
};

}  // namespace nsb
