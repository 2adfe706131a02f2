#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "core/parameters.hpp"
#include "studies/study.hpp"

namespace nsb {

std::vector<Json> study_cases(const StudyEntry& study, const StudyOptions& options) {
  if (study.run) return {Json::object()};
  return study.cases(options);
}

Json real(double v) { return std::isnan(v) ? Json(nullptr) : Json(v); }
double real(const Json& j) { return j.is_null() ? std::numeric_limits<double>::quiet_NaN() : j.get<double>(); }
Json reals(const std::vector<double>& v) {
  Json a = Json::array();
  for (double x : v) a.push_back(std::isfinite(x) ? Json(x) : Json(nullptr));
  return a;
}
Cell number_cell(double v) { return std::isnan(v) ? Cell{} : Cell{v}; }
Cell number_cell(const Json& j) { return j.is_number() ? number_cell(j.get<double>()) : Cell{}; }

Json run_study_case(const StudyEntry& study, const Json& the_case, const StudyOptions& options) {
  if (!study.run) {
    try {
      return study.run_case(the_case);
    } catch (const InputError& e) {  // a bad study definition: say which study and case
      throw InputError(fmt::format("study {}, case {}: {}", study.name, the_case.dump(), e.what()));
    }
  }
  Json tables = Json::array();
  for (const auto& t : study.run(options)) tables.push_back(table_to_json_text(t));
  return tables;
}

std::vector<Table> study_tables(const StudyEntry& study, const std::vector<Json>& cases,
                                const std::vector<Json>& results, const StudyOptions& options) {
  if (!study.run) return study.tables(cases, results, options);
  if (results.size() != 1) throw std::logic_error("single-function study " + study.name + " has one result");
  std::vector<Table> tables;
  for (const auto& text : results[0]) tables.push_back(table_from_json_text(text.get<std::string>()));
  return tables;
}

}  // namespace nsb
