// Reading [[table]]s: their rows, columns and the keys every table takes.
#include "studies/study_file/reader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

namespace nsb::study_files {

namespace {

std::optional<std::string> optional_string(const Checker& c, const Json& j, const std::string& path, const char* key) {
  if (const Json* v = c.find(j, key)) return c.string(*v, child(path, key));
  return std::nullopt;
}

// A number format given at `path`: a fmt format of one number, or "" (shortest round trip).
void check_number_format(const Checker& c, const std::optional<std::string>& format, const std::string& path) {
  if (format && !format->empty()) try {
      (void)fmt::format(fmt::runtime(*format), 1.0);
    } catch (const fmt::format_error& e) {
      c.fail(path, fmt::format("'{}' is no number format ({})", *format, e.what()),
             "a fmt format of one number, e.g. {:.2e}, or \"\" (shortest round-trip)");
    }
}

// A case table's integrators = [labels]: the runs of those integrators only.
void read_table_integrators(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const Json* v = c.find(j, "integrators");
  if (!v) return;
  const std::string at = child(path, "integrators");
  if (t.rows != "case" && t.rows != "impulses" && t.rows != "field")
    c.fail(at, "only a table of one row per run, or of its impulses or field, picks its integrators' runs", "rows = \"case\", \"impulses\" or \"field\"");
  c.expect(*v, at, v->is_array() && !v->empty(), "an array of one or more integrator labels");
  std::vector<std::string> labels;
  for (const auto& it : spec.integrators) labels.push_back(it.label);
  for (std::size_t k = 0; k < v->size(); ++k) t.integrators.push_back(c.choice((*v)[k], element(at, k), labels));
}

// A table's problems = [labels]: the runs (a group table's fits) on those problems only.
void read_table_problems(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  const Json* v = c.find(j, "problems");
  if (!v) return;
  const std::string at = child(path, "problems");
  if (t.rows == "ranking") c.fail(at, "a ranking ranks every problem of its measure", "rows = \"case\", \"group\", \"history\" or \"samples\"");
  c.expect(*v, at, v->is_array() && !v->empty(), "an array of one or more problem labels");
  std::vector<std::string> labels;  // a group's problem: a joint refinement's family label too
  for (const auto& p : spec.problems) labels.push_back(p.label);
  for (const auto& p : spec.problems)
    if (t.rows == "group" && !p.family.empty() && std::find(labels.begin(), labels.end(), p.family) == labels.end()) labels.push_back(p.family);
  for (std::size_t k = 0; k < v->size(); ++k) t.problems.push_back(c.choice((*v)[k], element(at, k), labels));
}

// A ranking's keys: no columns, its error column and runs' number format (the first ranking's alone).
void read_ranking_keys(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, const std::vector<FileTable>& tables,
                       FileTable& t) {
  if (c.find(j, "columns")) c.fail(child(path, "columns"), "a ranking's columns are fixed", "no columns key with rows = \"ranking\"");
  if (spec.ranked >= spec.measures.size()) c.fail(child(path, "rows"), "the study has no measure to rank by", "case, group");
  const bool first = std::none_of(tables.begin(), tables.end(), [](const FileTable& u) { return u.rows == "ranking"; });
  if (const Json* v = c.find(j, "error")) {
    const std::string at = child(path, "error");
    if (!first) c.fail(at, "the first ranking table sets the error column of every ranking", "no error key here");
    c.expect(*v, at, v->is_object(), "a table { header, unit, format, description }");
    c.keys(*v, at, {"header", "unit", "format", "description"});
    FileColumn col;
    col.header = optional_string(c, *v, at, "header");
    col.unit = optional_string(c, *v, at, "unit");
    col.format = optional_string(c, *v, at, "format");
    col.description = optional_string(c, *v, at, "description");
    check_number_format(c, col.format, child(at, "format"));
    t.error = col;
  }
  if (const Json* v = c.find(j, "runs_format")) {
    const std::string at = child(path, "runs_format");
    if (!first) c.fail(at, "the first ranking table sets the runs' format of every ranking", "no runs_format key here");
    t.runs_format = c.string(*v, at);
    if (t.runs_format->empty()) c.fail(at, "an empty format", "a fmt format of one number, e.g. {:.1e}");
    check_number_format(c, t.runs_format, at);
  }
}

// The columns of a table other than a ranking (and a ranking's keys refused).
void read_table_columns(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, FileTable& t) {
  for (const char* key : {"error", "runs_format"})
    if (c.find(j, key)) c.fail(child(path, key), fmt::format("only a ranking has {}", key), "rows = \"ranking\"");
  const std::string at = child(path, "columns");
  const Json& cols = c.require(j, path, "columns");
  c.expect(cols, at, cols.is_array() && !cols.empty(), "a non-empty array of columns");
  const auto sources = t.fit_against.empty() ? table_sources(t.rows, spec) : fitted_group_sources(spec);
  for (std::size_t k = 0; k < cols.size(); ++k) {
    t.columns.push_back(read_column(c, cols[k], element(at, k), sources));
    if (t.columns.back().missing && t.rows != "case" && !(t.rows == "pivot" && k + 1 == cols.size()))
      c.fail(child(element(at, k), "missing"), "only a table of one row per run shows its missing cells otherwise",
             "rows = \"case\", or a pivot's value column (the last)");
  }
  read_not_ok(c, j, path, spec, t);
  if (t.rows == "pivot" && cols.size() < 2)
    c.fail(at, "a pivot needs the columns naming a row and the value column last", "two or more columns");
}

// A declared table's caption: each ${COLUMN} in it names a case-table column (the engine puts
// that column's values over the table's runs in its place: FileTable::caption).
void check_caption_placeholders(const Checker& c, const std::string& caption, const std::string& path, const StudySpec& spec) {
  const std::vector<std::string> columns = table_sources("case", spec);
  for (const CaptionPlaceholder& p : caption_placeholders(caption)) {
    if (p.size == std::string::npos)
      c.fail(path, fmt::format("'${{{}' has no closing }}", p.column), "${COLUMN} with COLUMN a case-table column");
    if (std::find(columns.begin(), columns.end(), p.column) == columns.end())
      c.fail(path, fmt::format("'${{{}}}' names no case-table column (nearest: {})", p.column, nearest_name(p.column, columns)),
             fmt::format("${{COLUMN}} with COLUMN one of {}", fmt::join(columns, ", ")));
  }
}

// [[table]] j (`tables`: those before it).
FileTable read_table(const Checker& c, const Json& j, const std::string& path, const StudySpec& spec, const std::vector<FileTable>& tables) {
  c.keys(j, path, {"id", "title", "caption", "rows", "columns", "error", "runs_format", "problems", "declined", "declined_reason", "integrators",
                   "where", "drop_above", "across", "measure", "observable", "exact", "last", "points", "spacing", "relative",
                   "not_ok", "fit_against", "except", "order", "scale", "exact_per", "exact_in", "component", "exact_times", "metadata"});
  FileTable t;
  t.id = c.string(c.require(j, path, "id"), child(path, "id"));
  if (!is_file_stem(t.id)) c.fail(child(path, "id"), fmt::format("'{}' is not a file name of a-z, 0-9 and _", t.id), "[a-z0-9_]+");
  for (const auto& u : tables)
    if (u.id == t.id) c.fail(child(path, "id"), fmt::format("id '{}' used twice", t.id), "distinct ids");
  t.title = c.string(c.require(j, path, "title"), child(path, "title"));
  t.caption = optional_string(c, j, path, "caption");
  if (t.caption) check_caption_placeholders(c, *t.caption, child(path, "caption"), spec);
  if (const Json* v = c.find(j, "rows")) t.rows = c.choice(*v, child(path, "rows"), {"case", "group", "ranking", "history", "samples", "pivot", "periodic", "trajectory", "flights", "impulses", "field"});
  read_some_runs(c, j, path, spec, t);
  read_impulses_and_field(c, j, path, spec, t);
  if (const Json* v = c.find(j, "metadata")) t.metadata = read_metadata_lines(c, *v, child(path, "metadata"), spec);
  if (const Json* v = c.find(j, "declined")) {
    if (t.rows != "case") c.fail(child(path, "declined"), "only a table of one row per run shows declined runs", "rows = \"case\"");
    const std::string shown = c.choice(*v, child(path, "declined"), {"as run", "n/a", "empty"});
    t.declined_blank = shown != "as run";
    t.declined_empty = shown == "empty";
  }
  read_table_problems(c, j, path, spec, t);
  read_table_integrators(c, j, path, spec, t);
  read_group_fit(c, j, path, spec, t);
  read_except_and_order(c, j, path, spec, t);
  if (t.rows == "ranking")
    read_ranking_keys(c, j, path, spec, tables, t);
  else
    read_table_columns(c, j, path, spec, t);
  if (const Json* v = c.find(j, "declined_reason")) {
    const std::string at = child(path, "declined_reason");
    if (!t.declined_blank) c.fail(at, "a declined run's reason replaces one of its blanked cells", "declined = \"n/a\" or \"empty\"");
    std::vector<std::string> measured;
    for (const FileColumn& col : t.columns)
      if (!asked_column(col.of)) measured.push_back(col.of);
    t.declined_reason = c.choice(*v, at, measured);
  }
  return t;
}

}  // namespace

// The columns a declared table of `rows` may show, by source name.
std::vector<std::string> table_sources(const std::string& rows, const StudySpec& spec) {
  const std::vector<FileMeasure>& measures = spec.measures;
  std::vector<std::string> sources{"problem", "integrator"};
  if (rows == "case") {
    sources.insert(sources.end(), {"dt", "tol"});
    for (const auto& m : measures) sources.push_back(m.label);
    sources.insert(sources.end(), {"CPU", "steps", "F_int evals", "status", "factorizations", "LCP its"});
    for (const auto& m : measures)
      if (measure_converges(m)) sources.push_back("pairwise order of " + m.label);
    const auto& run = run_column_names();
    sources.insert(sources.end(), run.begin(), run.end());
    sources.insert(sources.end(), spec.counters.begin(), spec.counters.end());
    const auto work = sweep_work_column_names(spec);
    sources.insert(sources.end(), work.begin(), work.end());
  } else if (rows == "group") {
    for (const auto& m : measures)
      if (measure_converges(m))
        for (const char* what : {"order", "CI low", "CI high", "points"}) sources.push_back(fmt::format("{} of {}", what, m.label));
    sources.push_back("note");  // why a group's fits are n/a (group_note, study_file/sweep_tables.cpp)
  } else if (rows == "history" || rows == "samples") {
    sources = rows == "history" ? history_column_names() : samples_column_names();
  } else if (rows == "periodic" || rows == "trajectory" || rows == "flights") {
    sources = rows == "periodic" ? periodic_column_names() : rows == "flights" ? flights_column_names() : trajectory_column_names();
  } else if (rows == "impulses" || rows == "field") {
    sources = rows == "impulses" ? impulses_column_names() : field_column_names();
  } else if (rows == "pivot") {
    return table_sources("case", spec);
  }
  const auto parameters = parameter_column_names(spec);
  sources.insert(sources.end(), parameters.begin(), parameters.end());
  return sources;
}

FileColumn read_column(const Checker& c, const Json& j, const std::string& path, const std::vector<std::string>& sources) {
  FileColumn col;
  if (j.is_string()) {
    col.of = c.choice(j, path, sources);
    return col;
  }
  c.expect(j, path, j.is_object(), "a column name or a table { of = NAME, header, unit, format, description }");
  c.keys(j, path, {"of", "header", "unit", "format", "description", "missing"});
  col.of = c.choice(c.require(j, path, "of"), child(path, "of"), sources);
  col.missing = optional_string(c, j, path, "missing");
  col.header = optional_string(c, j, path, "header");
  col.unit = optional_string(c, j, path, "unit");
  col.format = optional_string(c, j, path, "format");
  col.description = optional_string(c, j, path, "description");
  check_number_format(c, col.format, child(path, "format"));
  return col;
}

// [[table]]: the tables the study writes instead of the engine's own.
// [[table]]: the tables the study writes instead of the engine's own.
std::vector<FileTable> read_tables(const Checker& c, const Json& root, const StudySpec& spec) {
  std::vector<FileTable> tables;
  if (!c.find(root, "table")) return tables;  // the engine's own tables, their figures unchecked here
  const Json& list = optional_tables(c, root, "table");
  for (std::size_t i = 0; i < list.size(); ++i) tables.push_back(read_table(c, list[i], element("table", i), spec, tables));
  check_table_figures(c, spec, tables);
  return tables;
}

}  // namespace nsb::study_files
