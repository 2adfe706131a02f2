// Reading the keys of particular kinds of [[table]] (tables of some runs, group fits, pivots,
// impulses and fields, metadata lines), checked against the study.
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "problems/problem_output.hpp"
#include "problems/registry.hpp"
#include "problems/state.hpp"
#include "studies/table.hpp"

namespace nsb::study_files {

namespace {

// A text that goes on one line of a report (a metadata line's name or value): no control character.
void check_one_line(const Checker& c, const std::string& text, const std::string& path) {
  const auto control = std::find_if(text.begin(), text.end(), [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; });
  if (control != text.end())
    c.fail(path, fmt::format("holds the control character 0x{:02x}", static_cast<unsigned char>(*control)), "a text of one line");
}

}  // namespace

// The keys of a table of some runs (FileTable::of_some_runs) into `t`: where, drop_above (a
// case-table column each; a case table takes them too), a pivot's across, a periodic or flights
// table's measure, a trajectory's observable, exact, last, points, spacing and relative (its
// observables checked against the problems later: check_trajectory_observables); refused on the
// other tables.
void read_some_runs(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const std::vector<std::string> runs = table_sources("case", spec);
  const std::map<std::string, std::vector<std::string>> own = {
      {"across", {"pivot"}}, {"measure", {"periodic", "flights"}}, {"observable", {"trajectory"}}, {"exact", {"trajectory", "impulses"}},
      {"last", {"trajectory"}}, {"points", {"trajectory"}}, {"spacing", {"trajectory"}}, {"relative", {"trajectory"}}};
  for (const char* key : {"where", "drop_above", "across", "measure", "observable", "exact", "last", "points", "spacing", "relative"}) {
    const auto whose = own.find(key);
    const bool taken = whose == own.end() ? t.of_some_runs() || t.rows == "case"
                                          : std::find(whose->second.begin(), whose->second.end(), t.rows) != whose->second.end();
    if (c.find(j, key) && !taken)
      c.fail(child(path, key), fmt::format("a table of rows = \"{}\" has no {}", t.rows, key),
             whose == own.end() ? "rows = \"case\", \"pivot\", \"periodic\", \"trajectory\" or \"flights\""
                                : fmt::format("rows = \"{}\"", fmt::join(whose->second, "\" or \"")));
  }
  const auto conditions = [&](const char* key, const auto& read) {
    const Json* v = c.find(j, key);
    if (!v) return;
    const std::string at = child(path, key);
    c.expect(*v, at, v->is_object() && !v->empty(), "a table of case-table column = value");
    for (const auto& [name, value] : v->items()) read(c.choice(Json(name), child(at, name), runs), value, child(at, name));
  };
  conditions("where", [&](const std::string& name, const Json& value, const std::string& at) {
    c.expect(value, at, value.is_number() || value.is_string(), "a number or a text");
    t.where.emplace_back(name, value.is_number() ? Cell{value.get<double>()} : Cell{value.get<std::string>()});
  });
  conditions("drop_above", [&](const std::string& name, const Json& value, const std::string& at) {
    t.drop_above.emplace_back(name, c.positive(value, at));
  });
  if (t.rows == "pivot") t.across = c.choice(c.require(j, path, "across"), child(path, "across"), runs);
  if (t.rows == "periodic") {
    std::vector<std::string> sampled;
    for (const auto& m : spec.measures)
      if (m.kind == MeasureKind::Energy && m.every > 0.0) sampled.push_back(m.label);
    if (sampled.empty()) c.fail(child(path, "rows"), "the study has no energy measure sampled every period", "an energy [[measure]] with every");
    t.measure = c.choice(c.require(j, path, "measure"), child(path, "measure"), sampled);
  }
  if (t.rows == "flights") {
    std::vector<std::string> flights;
    for (const auto& m : spec.measures)
      if (m.kind == MeasureKind::FlightEnergy) flights.push_back(m.label);
    if (flights.empty()) c.fail(child(path, "rows"), "the study has no flight-energy measure", "a [[measure]] with kind = \"flight-energy\"");
    t.measure = c.choice(c.require(j, path, "measure"), child(path, "measure"), flights);
  }
  if (t.rows == "trajectory") {
    t.observable = c.string(c.require(j, path, "observable"), child(path, "observable"));
    if (const Json* v = c.find(j, "exact")) t.exact = c.string(*v, child(path, "exact"));
    if (const Json* v = c.find(j, "spacing")) t.step_spacing = c.choice(*v, child(path, "spacing"), {"times", "steps"}) == "steps";
    if (t.step_spacing && c.find(j, "last"))
      c.fail(child(path, "last"), "a trajectory of spacing = \"steps\" spans the whole run", "no last (or spacing = \"times\")");
    if (!t.step_spacing) t.last = c.positive(c.require(j, path, "last"), child(path, "last"));
    if (const Json* v = c.find(j, "points")) t.points = static_cast<int>(c.integer(*v, child(path, "points"), 1, 100000));
    if (const Json* v = c.find(j, "relative")) t.relative = c.boolean(*v, child(path, "relative"));
  }
}

// A group table's fit_against = "1/KEY" (FileTable::fit_against): KEY a numeric parameter of
// every problem it shows.
void read_group_fit(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const Json* v = c.find(j, "fit_against");
  if (!v) return;
  const std::string at = child(path, "fit_against");
  if (t.rows != "group") c.fail(at, "only a table of fitted orders fits", "rows = \"group\"");
  t.fit_against = c.string(*v, at);
  const std::string key = t.fit_against.rfind("1/", 0) == 0 ? t.fit_against.substr(2) : "";
  for (const FileProblem& p : spec.problems) {
    if (!t.applies_to(p.label) && !t.applies_to(p.family_label())) continue;
    std::vector<std::string> numeric;
    for (const ParamSpec& s : find_problem(p.name).parameters())
      if (s.kind != ParamSpec::Kind::Choice) numeric.push_back("1/" + s.name);
    if (std::find(numeric.begin(), numeric.end(), "1/" + key) == numeric.end() || key.empty())
      c.fail(at, fmt::format("'{}' is not 1/KEY, KEY a numeric parameter of problem '{}'", t.fit_against, p.label),
             fmt::format("{}", fmt::join(numeric, ", ")));
  }
}

// The columns of a group table with fit_against: its fits of every measure, the sweep's stable
// steps (its first run's) and the parameters.
std::vector<std::string> fitted_group_sources(const StudySpec& spec) {
  std::vector<std::string> sources{"problem", "integrator", "stable steps"};
  for (const auto& m : spec.measures)
    for (const char* what : {"order", "CI low", "CI high", "points"}) sources.push_back(fmt::format("{} of {}", what, m.label));
  const auto parameters = parameter_column_names(spec);
  sources.insert(sources.end(), parameters.begin(), parameters.end());
  return sources;
}

// except = { column = value, ... } (a case table or a table of some runs: the runs left out) and
// a pivot's order = { of = COLUMN, header, unit, format, description } (FileTable::except, order).
void read_except_and_order(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const std::vector<std::string> runs = table_sources("case", spec);
  if (const Json* v = c.find(j, "except")) {
    const std::string at = child(path, "except");
    if (!t.of_some_runs() && t.rows != "case")
      c.fail(at, fmt::format("a table of rows = \"{}\" has no except", t.rows), "rows = \"case\", \"pivot\", \"periodic\", \"trajectory\" or \"flights\"");
    c.expect(*v, at, v->is_object() && !v->empty(), "a table of case-table column = value");
    for (const auto& [name, value] : v->items()) {
      const std::string column = c.choice(Json(name), child(at, name), runs);
      c.expect(value, child(at, name), value.is_number() || value.is_string(), "a number or a text");
      t.except.emplace_back(column, value.is_number() ? Cell{value.get<double>()} : Cell{value.get<std::string>()});
    }
  }
  if (const Json* v = c.find(j, "order")) {
    const std::string at = child(path, "order");
    if (t.rows != "pivot") c.fail(at, "only a pivot fits the values of its rows", "rows = \"pivot\"");
    c.expect(*v, at, v->is_object(), "a table { of = COLUMN, header, unit, format, description }");
    if (v->contains("missing")) c.fail(child(at, "missing"), "an order is fitted, never missing", "of, header, unit, format, description");
    t.order = read_column(c, *v, at, runs);
  }
}

// A case table's not_ok = "outcome" (FileTable::outcome_columns: the measures it shows) or
// "values" (the default: the values a run reports).
void read_not_ok(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const Json* v = c.find(j, "not_ok");
  if (!v) return;
  const std::string at = child(path, "not_ok");
  if (t.rows != "case") c.fail(at, "only a table of one row per run shows a run's outcome", "rows = \"case\"");
  if (c.choice(*v, at, {"values", "outcome"}) == "values") return;
  for (const FileColumn& col : t.columns)
    if (std::any_of(spec.measures.begin(), spec.measures.end(), [&](const FileMeasure& m) { return m.label == col.of; }))
      t.outcome_columns.push_back(col.of);
  if (t.outcome_columns.empty()) c.fail(at, "the table shows no measure's column", "a measure's label among its columns, or no not_ok");
}

// A trajectory table's observable and exact: observables of the state of every problem it shows.
void check_trajectory_observables(const Checker& c, const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances) {
  for (std::size_t i = 0; i < spec.tables.size(); ++i) {
    const FileTable& t = spec.tables[i];
    if (t.rows != "trajectory") continue;
    for (std::size_t p = 0; p < spec.problems.size(); ++p) {
      if (!t.applies_to(spec.problems[p].label)) continue;
      const std::vector<std::string> names = state_observable_names(*instances[p]);
      for (const auto& [key, name] : {std::pair{"observable", t.observable}, std::pair{"exact", t.exact}})
        if (!name.empty()) check_observable(c, child(element("table", i), key), name, names, spec.problems[p].label);
    }
  }
}

// metadata = [{ line = NAME, of = COLUMN }, { line = NAME, text = TEXT }, ...] (MetadataLine):
// `of` a column of the case table; each name once.
std::vector<MetadataLine> read_metadata_lines(const Checker& c, const Json& v, const std::string& path, const StudySpec& spec) {
  c.expect(v, path, v.is_array() && !v.empty(), "an array of one or more { line, of } or { line, text }");
  std::vector<MetadataLine> lines;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const std::string at = element(path, k);
    const Json& j = v[k];
    c.expect(j, at, j.is_object(), "a table { line, of } or { line, text }");
    c.keys(j, at, {"line", "of", "text"});
    MetadataLine m;
    m.line = c.string(c.require(j, at, "line"), child(at, "line"));
    if (m.line.empty()) c.fail(child(at, "line"), "an empty name", "the name of the line, e.g. N");
    check_one_line(c, m.line, child(at, "line"));
    for (const auto& other : lines)
      if (other.line == m.line) c.fail(child(at, "line"), fmt::format("line '{}' given twice", m.line), "each name once");
    if (!c.find(j, "of") == !c.find(j, "text")) c.fail(at, "give one of of = COLUMN (its values over the runs) or text = TEXT");
    if (const Json* o = c.find(j, "of")) m.of = c.choice(*o, child(at, "of"), table_sources("case", spec));
    if (const Json* t = c.find(j, "text")) {
      m.text = c.string(*t, child(at, "text"));
      check_one_line(c, m.text, child(at, "text"));
    }
    lines.push_back(m);
  }
  return lines;
}

// The keys of an impulses table (scale, exact, exact_per, exact_in) and of a field table
// (component, exact_times) into `t`, refused on the other tables; what they name in the
// problems is checked once the problems exist (check_impulses_and_fields).
void read_impulses_and_field(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const std::vector<std::pair<std::string, std::string>> own = {
      {"scale", "impulses"}, {"exact_per", "impulses"}, {"exact_in", "impulses"}, {"component", "field"}, {"exact_times", "field"}};
  for (const auto& [key, rows] : own)
    if (c.find(j, key) && t.rows != rows)
      c.fail(child(path, key), fmt::format("a table of rows = \"{}\" has no {}", t.rows, key), fmt::format("rows = \"{}\"", rows));
  if (t.rows == "impulses") {
    if (const Json* v = c.find(j, "scale")) t.scale = c.positive(*v, child(path, "scale"));
    if (const Json* v = c.find(j, "exact")) t.exact = c.string(*v, child(path, "exact"));
    std::vector<std::string> columns = table_sources("impulses", spec);  // of one run: not its values
    columns.erase(std::remove_if(columns.begin(), columns.end(), [](const std::string& n) { return n == "t" || n == "value"; }), columns.end());
    for (const char* key : {"exact_per", "exact_in"})
      if (const Json* v = c.find(j, key)) {
        if (t.exact.empty()) c.fail(child(path, key), "where the exact rows go, without exact rows", "exact = OBSERVABLE beside it");
        (std::string(key) == "exact_per" ? t.exact_per : t.exact_in) = c.choice(*v, child(path, key), columns);
      }
  }
  if (t.rows == "field") {
    if (const Json* v = c.find(j, "component")) t.component = c.string(*v, child(path, "component"));
    if (const Json* v = c.find(j, "exact_times")) t.exact_times = static_cast<int>(c.integer(*v, child(path, "exact_times"), 1, 100000));
  }
}

// Impulses and field tables against the problems they show: an impulses table's problems have
// contacts (and, with exact, an exact solution with that observable); a field table's have one
// 1D mesh of bar elements with the stress component (each cell's header naming its position:
// {} in a field column's header) and, with exact_times, the first of them an exact field.
void check_impulses_and_fields(const Checker& c, const StudySpec& spec, const std::vector<std::unique_ptr<Problem>>& instances) {
  for (std::size_t i = 0; i < spec.tables.size(); ++i) {
    const FileTable& t = spec.tables[i];
    const std::string path = element("table", i);
    if (t.rows != "impulses" && t.rows != "field") continue;
    std::vector<double> centres;  // of the first problem shown
    std::string first;
    for (std::size_t p = 0; p < spec.problems.size(); ++p) {
      const std::string& label = spec.problems[p].label;
      const Problem& problem = *instances[p];
      if (!t.applies_to(label)) continue;
      if (t.rows == "impulses") {
        if (problem.ncontacts() == 0)
          c.fail(child(path, "rows"), fmt::format("problem '{}' has no contacts, hence no impulses", label), "problems with contacts (or problems = [...])");
        if (!t.exact.empty() && !problem.exact())
          c.fail(child(path, "exact"), fmt::format("problem '{}' has no exact solution", label), "problems with one (or problems = [...])");
        if (!t.exact.empty()) check_observable(c, child(path, "exact"), t.exact, state_observable_names(problem), label);
        continue;
      }
      const std::optional<FieldMesh> mesh = problem.field_mesh();
      bool bars = mesh && mesh->dimension == 1 && !mesh->stress_components.empty() && mesh->ncells() > 0;
      for (Index e = 0; bars && e < mesh->ncells(); ++e) bars = mesh->cell_size(e) == 2;
      if (!bars)
        c.fail(child(path, "rows"), fmt::format("problem '{}' has no 1D field mesh of bar elements with a stress", label),
               "problems of bar elements, e.g. signorini-bar (or problems = [...])");
      const auto& names = mesh->stress_components;
      if (!t.component.empty() && std::find(names.begin(), names.end(), t.component) == names.end())
        c.fail(child(path, "component"), fmt::format("'{}' is not a stress component of problem '{}'", t.component, label),
               fmt::format("{}", fmt::join(names, ", ")));
      std::vector<double> own;
      for (Index e = 0; e < mesh->ncells(); ++e) own.push_back(0.5 * (mesh->points(mesh->cells(e, 0), 0) + mesh->points(mesh->cells(e, 1), 0)));
      if (first.empty()) {
        first = label;
        centres = own;
        Eigen::MatrixXd stress(mesh->ncells(), static_cast<Index>(names.size()));
        if (t.exact_times > 0 && !(problem.exact() && problem.exact()->exact_cell_stress(0.0, stress)))
          c.fail(child(path, "exact_times"), fmt::format("problem '{}' has no exact field", label),
                 "a first problem whose exact solution gives its element stresses (signorini-bar with g = 0), or no exact_times");
      } else if (own != centres) {
        c.fail(child(path, "problems"), fmt::format("problems '{}' and '{}' have different field meshes ({} and {} cells)", first, label,
                                                    centres.size(), own.size()),
               "problems of one mesh: problems = [...]");
      }
    }
    for (std::size_t k = 0; k < t.columns.size(); ++k)
      if (t.columns[k].of == "field" && t.columns[k].header && t.columns[k].header->find("{}") == std::string::npos)
        c.fail(child(element(child(path, "columns"), k), "header"), fmt::format("'{}' does not name the cell", *t.columns[k].header),
               "a header with {} where each cell's centre x goes, e.g. sigma(x = {})");
  }
}

}  // namespace nsb::study_files
