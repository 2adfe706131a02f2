#include "studies/registry.hpp"

#include <map>

#include "studies/study.hpp"

namespace nsb {

extern const StudyEntry bouncing_study;
extern const StudyEntry hard_cases_study;
extern const StudyEntry work_precision_study;
extern const StudyEntry energy_study;
extern const StudyEntry reference_study;
extern const StudyEntry bar_study;
extern const StudyEntry block_study;
extern const StudyEntry peers_study;
extern const StudyEntry bouncing_bar_study;
extern const StudyEntry friction_study;
extern const StudyEntry bodies_study;
extern const StudyEntry hausdorff_study;
extern const StudyEntry claims_study;
extern const StudyEntry properties_study;

const std::vector<StudyEntry>& study_registry() {
  static const std::vector<StudyEntry> entries = {
      bouncing_study,
      hard_cases_study,
      work_precision_study,
      energy_study,
      reference_study,
      bar_study,
      block_study,
      peers_study,
      bouncing_bar_study,
      friction_study,
      bodies_study,
      hausdorff_study,
      claims_study,
      properties_study,
  };
  return entries;
}

std::string study_source(const std::string& name) {
  static const std::map<std::string, std::string> sources = {
      {"bouncing", "studies/bouncing.cpp"},   {"hard", "studies/hard_cases.cpp"},
      {"precision", "studies/work_precision.cpp"}, {"energy", "studies/energy.cpp"},
      {"reference", "studies/reference.cpp"}, {"bar", "studies/bar.cpp"},
      {"block", "studies/block.cpp"},         {"peers", "studies/peers.cpp"},
      {"bouncing-bar", "studies/bouncing_bar.cpp"}, {"friction", "studies/friction.cpp"},
      {"bodies", "studies/bodies.cpp"},       {"hausdorff", "studies/hausdorff_study.cpp"},
      {"claims", "studies/claims.cpp"},       {"properties", "studies/properties.cpp"}};
  const auto it = sources.find(name);
  return it == sources.end() ? "" : it->second;
}

}  // namespace nsb
