#include "studies/study.hpp"

namespace nsb {

std::vector<Table> run_bouncing_study(const StudyOptions&);
std::vector<Table> run_block_study(const StudyOptions&);

const std::vector<StudyEntry>& study_registry() {
  static const std::vector<StudyEntry> entries = {
      {"bouncing", "bouncing mass: impact times, flight energies, Zeno time, orders, against the exact solution", &run_bouncing_study},
      {"block", "2D hyperelastic block on a rigid floor: momentum and energy errors, error against a reference, cost growth", &run_block_study},
  };
  return entries;
}

}  // namespace nsb
