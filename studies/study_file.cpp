// A study file as a StudyEntry (its cases, the run of one case, its tables: studies/study_file/)
// and its report written as `nsbench-study run FILE` writes it.
#include "studies/study_file/engine.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/output.hpp"
#include "studies/parallel.hpp"
#include "studies/report_index.hpp"

namespace nsb {

StudyEntry file_study(const StudySpec& spec) {
  StudyEntry e;
  e.name = spec.name;
  e.description = fmt::format("{} (study file {}, FNV-1a 64 {})", spec.title, spec.file, spec.hash);
  e.cases = [spec](const StudyOptions& options) { return study_files::file_cases(spec, options.full); };
  e.run_case = [spec](const Json& c) { return study_files::run_file_case(spec, c); };
  e.case_integrators = [spec](const Json& c) {
    return std::vector<std::string>{spec.integrators[c["integrator"].get<std::size_t>()].name};
  };
  e.tables = [spec](const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions&) {
    return study_files::file_tables(spec, cases, study_files::with_next_run_estimates(spec, cases, results));
  };
  return e;
}

void write_study_copy(const StudySpec& spec, const std::filesystem::path& out) {
  ensure_directory(out);
  const std::string ext = std::filesystem::path(spec.file).extension() == ".json" ? "json" : "toml";
  write_file_atomic(out / fmt::format("{}.study.{}", spec.name, ext), spec.text);
  write_file_atomic(out / fmt::format("{}.study.hash", spec.name), fmt::format("FNV-1a 64 {}  {}\n", spec.hash, spec.file));
}

std::vector<std::string> run_study_file(const StudySpec& spec, const std::filesystem::path& out) {
  const StudyEntry study = file_study(spec);
  const StudyOptions options{false};
  const std::vector<Json> cases = study_cases(study, options);
  std::vector<std::string> locks;
  for (const Json& c : cases) locks.push_back(case_lock(study, c));
  const auto results = parallel_map<Json>(cases.size(), [&](std::size_t k) { return run_study_case(study, cases[k], options); },
                                          study.name, locks);
  const auto tables = study_tables(study, cases, results, options);
  claim_output_directory(out, "out");  // a directory the suite did not write is refused
  ReportDirectory report(out, "out");
  const ReportIndex index(false, report.path());
  index.add_study(study, tables);
  write_study_copy(spec, report.path());
  index.write();
  report.commit();
  std::vector<std::string> ids;
  for (const auto& t : tables) ids.push_back(t.id);
  return ids;
}

}  // namespace nsb
