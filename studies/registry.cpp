#include "studies/study.hpp"

namespace nsb {

extern const StudyEntry bouncing_study;
extern const StudyEntry hard_cases_study;
extern const StudyEntry work_precision_study;
extern const StudyEntry energy_study;
extern const StudyEntry reference_study;
extern const StudyEntry bar_study;
std::vector<Table> run_block_study(const StudyOptions&);

const std::vector<StudyEntry>& study_registry() {
  static const std::vector<StudyEntry> entries = {
      bouncing_study,
      hard_cases_study,
      work_precision_study,
      energy_study,
      reference_study,
      bar_study,
      {"block", "2D hyperelastic block on a rigid floor: momentum and energy errors, error against a reference, cost growth", &run_block_study},
  };
  return entries;
}

}  // namespace nsb
