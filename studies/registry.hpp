#pragma once
// The built-in studies (study_registry(), studies/study.hpp) are of three kinds: C++ studies,
// each named with its source, study files, studies/builtin/<name>.toml, run by the study-file
// engine (studies/study_file.hpp), and Python studies, studies/builtin/<name>.py (nsbench.study),
// which nsbench-study runs with the Python module. The files are embedded in the binary at build time
// (studies/embed_study_files.cmake), so nsbench-study runs them from any directory and the hash
// of the text it runs is the file's. `nsbench-study list` shows each study's source.
#include <string>
#include <string_view>
#include <vector>

#include "studies/study.hpp"

namespace nsb {

struct EmbeddedStudyFile {
  std::string_view path;  // relative to the repository: studies/builtin/<name>.toml
  std::string_view text;
};

// Every file of studies/builtin/, by path (generated at build time).
const std::vector<EmbeddedStudyFile>& builtin_study_files();
// The embedded file `path`; nullptr when there is none.
const EmbeddedStudyFile* builtin_study_file(std::string_view path);

// The registry entry of the built-in study file `path`: the study-file engine's study
// (file_study of the parsed text) under the study's own `name` and `description`.
StudyEntry builtin_file_study(const std::string& name, const std::string& description, const std::string& path);
// The registry entry of the built-in Python study `path` (studies/builtin/NAME.py): its script,
// which nsbench-study runs (StudyEntry::script).
StudyEntry builtin_python_study(const std::string& name, const std::string& description, const std::string& path);

}  // namespace nsb
