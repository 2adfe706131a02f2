#include "studies/study.hpp"

namespace nsb {

std::vector<Table> run_bouncing_study(const StudyOptions&);
std::vector<Table> run_hard_cases_study(const StudyOptions&);

const std::vector<StudyEntry>& study_registry() {
  static const std::vector<StudyEntry> entries = {
      {"bouncing", "bouncing mass: impact times, flight energies, Zeno time, orders, against the exact solution", &run_bouncing_study},
      {"hard", "hard cases: Zeno, chattering, 10^4 impacts, resting and grazing contact; ok / diverged / penetration / energy blow-up", &run_hard_cases_study},
  };
  return entries;
}

}  // namespace nsb
