// The study file's model (studies/study_file.hpp): what its measures, tables and sweeps say of
// themselves.
#include "studies/study_file/engine.hpp"

#include <algorithm>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace nsb {

bool FileTable::applies_to(const std::string& problem_label) const {
  return problems.empty() || std::find(problems.begin(), problems.end(), problem_label) != problems.end();
}

bool asked_column(const std::string& source) {
  static const std::vector<std::string> names = {"problem", "problem name", "integrator", "integrator name", "parameters", "dt", "tol",
                                                 "stable steps", "t_end", "budget", "penetration limit", "energy blow-up limit",
                                                 "status", "outcome", "note"};
  return source.rfind("parameter ", 0) == 0 || std::find(names.begin(), names.end(), source) != names.end();
}

bool is_event_time(const FileMeasure& m) {
  return (m.kind == MeasureKind::ImpactTime && m.norm != "count") || m.kind == MeasureKind::StopTime || m.kind == MeasureKind::OnsetTime ||
         ((m.kind == MeasureKind::RestTime || m.kind == MeasureKind::PeakTime || m.kind == MeasureKind::RestStart ||
           m.kind == MeasureKind::ContactDuration) && m.exact);
}

bool measure_converges(const FileMeasure& m) {
  return m.kind == MeasureKind::Error || (m.kind == MeasureKind::Hausdorff && m.norm != "value scale") || is_event_time(m) ||
         (m.kind == MeasureKind::FlightEnergy && m.norm == "max");
}

std::vector<CaptionPlaceholder> caption_placeholders(const std::string& caption) {
  std::vector<CaptionPlaceholder> out;
  for (std::size_t at = caption.find("${"); at != std::string::npos; at = caption.find("${", at)) {
    const std::size_t end = caption.find('}', at);
    if (end == std::string::npos) {
      out.push_back({at, std::string::npos, caption.substr(at + 2)});
      break;
    }
    out.push_back({at, end + 1 - at, caption.substr(at + 2, end - at - 2)});
    at = end + 1;
  }
  return out;
}

bool FileMeasure::applies_to(const std::string& problem_label) const {
  return problems.empty() || std::find(problems.begin(), problems.end(), problem_label) != problems.end();
}

const std::string& FileMeasure::observable_for(const std::string& problem_label) const {
  const auto it = problem_observables.find(problem_label);
  return it == problem_observables.end() ? observable : it->second;
}

std::pair<double, double> FileMeasure::window_for(const std::string& problem_label) const {
  const auto it = problem_windows.find(problem_label);
  if (it != problem_windows.end()) return it->second;
  return problem_windows.empty() ? std::pair{window_start, window_end} : std::pair{0.0, std::numeric_limits<double>::infinity()};
}

bool FileMeasure::rankable() const {
  if (kind >= MeasureKind::ImpactRatio || kind == MeasureKind::RestStart) return !law.empty() || exact;  // a difference from a closed form, not a value
  if (kind == MeasureKind::Hausdorff) return norm != "value scale";  // a scale, not an error
  if (kind == MeasureKind::ContactDuration) return exact;
  return (kind != MeasureKind::Energy && kind != MeasureKind::FlightEnergy && kind != MeasureKind::ImpactTime) || norm == "max";
}

const FileSweep& FileIntegrator::sweep_for(const std::string& problem_label) const {
  const auto it = per_problem.find(problem_label);
  return it == per_problem.end() ? sweep : it->second;
}

}  // namespace nsb
