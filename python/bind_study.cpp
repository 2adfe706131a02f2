// nsbench.run_study: a study file (studies/study_file.hpp; docs/study_files.md) run as
// `nsbench-study run FILE --out DIR` runs it, its cases in parallel without the GIL (an
// integrator written in Python takes it for its own steps, so those cases run one at a time).
#include <pybind11/stl.h>

#include <optional>
#include <string>

#include "core/environment.hpp"
#include "python/bindings.hpp"
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

}  // namespace

void bind_study(py::module_& m) {
  m.def("run_study", &run_study, "study"_a = py::none(), "out"_a, py::kw_only(), "text"_a = py::none(),
        "Runs a study file (TOML, or JSON with the same schema) as\n"
        "`nsbench-study run FILE --out OUT` and writes its report into `out` (tables as .csv/.md/.tex,\n"
        "figures.json for scripts/figures.py, index.md). Integrators registered from Python may be named in\n"
        "it; their rows are marked (python). `study`: a path (pathlib.Path, or a str of one line), or\n"
        "the text itself as a str of several lines; text=: the text, whatever its length (one-line JSON).\n"
        "Returns the tables' ids; ValueError for a bad file, a missing one, a directory or a FIFO.");
}

}  // namespace nsb::python
