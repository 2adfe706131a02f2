// nsbench.run_study: a study file (studies/study_file.hpp; docs/study_files.md) run as
// `nsbench-study run FILE --out DIR` runs it, its cases in parallel without the GIL (an
// integrator written in Python takes it for its own steps, so those cases run one at a time).
// The C++ side of nsbench.study (python/nsbench/study.py): described cases run in the case pool
// (_run_cases) and a study written in Python driven as nsbench-study drives a built-in one
// (_drive_study, studies/driver.hpp). Cases and results cross as JSON text (studies/case_run.hpp).
#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include <cmath>
#include <optional>
#include <string>

#include "core/environment.hpp"
#include "python/bindings.hpp"
#include "studies/case_run.hpp"
#include "studies/driver.hpp"
#include "studies/parallel.hpp"
#include "studies/study_file.hpp"

namespace nsb::python {

using namespace pybind11::literals;

namespace {

// The study's text, read or given, and the call that the report's metadata names. A path is a
// pathlib.Path (any os.PathLike) or a str of one line that does not open a JSON object; a text
// is `text=`, or a str of several lines or opening with '{'. A path is a file, never parsed as
// TOML (a missing one, a directory or a FIFO is an error naming it).
StudySpec study_spec(const py::object& study, const std::optional<std::string>& text, const std::string& out) {
  const auto call = [&](const std::string& what) {
    const std::string line = "import nsbench; nsbench.run_study(" + what + ", out=" + py::repr(py::str(out)).cast<std::string>() + ")";
    const char* argv[] = {"python3", "-c", line.c_str()};
    set_command_line(3, argv);
  };
  const auto parse_text = [&](const std::string& t) {
    call("text=<study text>");
    const auto first = t.find_first_not_of(" \t\r\n");
    return parse_study_text(t, "<text>", first != std::string::npos && t[first] == '{');
  };
  if (text) {
    if (!study.is_none()) throw InputError("run_study: give the study as a path or as text=, not both");
    return parse_text(*text);
  }
  const bool path_like = py::isinstance(study, py::module_::import("os").attr("PathLike"));
  if (!path_like && !py::isinstance<py::str>(study))
    throw InputError("run_study: the study is a path (str or pathlib.Path) or text=STR (TOML, or JSON)");
  const std::string given = py::str(py::module_::import("os").attr("fspath")(study)).cast<std::string>();
  const auto first = given.find_first_not_of(" \t\r\n");
  if (!path_like && (given.find('\n') != std::string::npos || (first != std::string::npos && given[first] == '{')))
    return parse_text(given);
  call(py::repr(py::str(given)).cast<std::string>());
  return read_study_file(given);
}

std::vector<std::string> run_study(const py::object& study, const std::string& out, const std::optional<std::string>& text) {
  const StudySpec spec = study_spec(study, text, out);
  py::gil_scoped_release free;
  return run_study_file(spec, out);
}

// A study whose cases are described runs (studies/case_run.hpp).
StudyEntry described_study(const std::string& name) {
  StudyEntry study;
  study.name = name;
  study.run_case = run_described_case;
  study.case_integrators = integrators_named;
  return study;
}

std::vector<Json> parsed(const std::vector<std::string>& texts, const char* what) {
  std::vector<Json> items;
  for (const auto& text : texts) {
    try {
      items.push_back(Json::parse(text));
    } catch (const Json::exception& e) {
      throw InputError(fmt::format("{}: not JSON: {}", what, e.what()));
    }
  }
  return items;
}

std::vector<std::string> dumped(const std::vector<Json>& items) {
  std::vector<std::string> texts;
  for (const auto& j : items) texts.push_back(j.dump());
  return texts;
}

// The described cases run in the pool, each result as JSON text, in the cases' order.
std::vector<std::string> run_cases(const std::vector<std::string>& case_texts, const std::string& label) {
  const std::vector<Json> cases = parsed(case_texts, "case");
  const StudyEntry study = described_study(label);
  std::vector<std::string> locks;
  for (const Json& c : cases) locks.push_back(case_lock(study, c));
  py::gil_scoped_release free;
  const auto results = parallel_map<Json>(cases.size(), [&](std::size_t k) { return run_study_case(study, cases[k], {}); },
                                          label, locks);
  return dumped(results);
}

using CasesFunction = std::function<std::vector<std::string>(bool full)>;
// The cases and results as lists of JSON texts (the callee may drop each text once read).
using TablesFunction = std::function<std::vector<Table>(py::list cases, py::list results, bool full)>;

// JSON texts as a Python list, each made and handed over in turn: one text at a time in C++.
py::list texts_of(const std::vector<Json>& items) {
  py::list texts;
  for (const auto& j : items) texts.append(py::str(j.dump()));
  return texts;
}

// A Python study driven as nsbench-study drives a registered one: its cases and tables from
// Python (the GIL taken for those calls only), its runs in the pool without it.
int drive_study(const std::string& name, const std::string& description, const std::string& source, const CasesFunction& cases,
                const TablesFunction& tables, const DriverOptions& options) {
  StudyEntry study = described_study(name);
  study.description = description;
  study.source = source;
  study.cases = [&cases](const StudyOptions& o) {
    py::gil_scoped_acquire gil;
    return parsed(cases(o.full), "case");
  };
  study.tables = [&tables](const std::vector<Json>& c, const std::vector<Json>& r, const StudyOptions& o) {
    py::gil_scoped_acquire gil;
    return tables(texts_of(c), texts_of(r), o.full);
  };
  DriverOptions o = options;
  o.result_check = [](const StudyEntry&, const Json& c, const Json& result) { return described_result_damage(c, result); };
  py::gil_scoped_release free;
  return drive_studies({&study}, o);
}

DriverOptions driver_options(const std::string& out, bool full, const std::string& shard, bool merge, const std::string& verify,
                             double rtol, double atol) {
  DriverOptions options{out, full, shard.empty() ? Shard{} : parse_shard(shard), merge, verify, {rtol, atol}};
  check_driver_options(options);
  return options;
}

}  // namespace

void bind_study(py::module_& m) {
  m.def("_assignments", [](const py::dict& parameters) { return assignments(parameters); }, "parameters"_a,
        "The \"key=value\" items of keyword arguments, as nsbench.run reads them (bindings.hpp, value_text).");
  m.def("_run_cases", &run_cases, "cases"_a, "label"_a,
        "nsbench.study.run's C++ side: the cases (JSON texts, studies/case_run.hpp) run in the case pool\n"
        "without the GIL; their results as JSON texts, in order.");
  m.def("_drive_study", [](const std::string& name, const std::string& description, const std::string& source,
                           const CasesFunction& cases, const TablesFunction& tables, const std::vector<std::string>& argv,
                           const std::string& out, bool full, const std::string& shard, bool merge, const std::string& verify,
                           double rtol, double atol) {
          std::vector<const char*> args;
          for (const auto& a : argv) args.push_back(a.c_str());
          set_command_line(static_cast<int>(args.size()), args.data());  // the report's footer names it
          return drive_study(name, description, source, cases, tables, driver_options(out, full, shard, merge, verify, rtol, atol));
        },
        "name"_a, "description"_a, "source"_a, "cases"_a, "tables"_a, "argv"_a, "out"_a, "full"_a, "shard"_a, "merge"_a, "verify"_a,
        "rtol"_a, "atol"_a,
        "nsbench.study.Study.main's C++ side (studies/driver.hpp): the exit status.");
  m.def("run_study", &run_study, "study"_a = py::none(), "out"_a, py::kw_only(), "text"_a = py::none(),
        "Runs a study file (TOML, or JSON with the same schema) as\n"
        "`nsbench-study run FILE --out OUT` and writes its report into `out` (tables as .csv/.md/.tex,\n"
        "figures.json for scripts/figures.py, index.md). Integrators registered from Python may be named in\n"
        "it; their rows are marked (python). `study`: a path (pathlib.Path, or a str of one line), or\n"
        "the text itself as a str of several lines; text=: the text, whatever its length (one-line JSON).\n"
        "Returns the tables' ids; ValueError for a bad file, a missing one, a directory or a FIFO.");
}

}  // namespace nsb::python
