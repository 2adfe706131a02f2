// nsbench.run_study: a study file (studies/study_file.hpp; docs/study_files.md) run as
// `nsbench-study run FILE --out DIR` runs it, its cases in parallel without the GIL (an
// integrator written in Python takes it for its own steps, so those cases run one at a time).
#include <pybind11/stl.h>

#include <filesystem>

#include "core/environment.hpp"
#include "python/bindings.hpp"
#include "studies/study_file.hpp"

namespace nsb::python {

using namespace pybind11::literals;

namespace {

std::vector<std::string> run_study(const std::string& path_or_text, const std::string& out) {
  const bool is_file = path_or_text.find('\n') == std::string::npos && std::filesystem::is_regular_file(path_or_text);
  const std::string first = path_or_text.substr(path_or_text.find_first_not_of(" \t\r\n") == std::string::npos
                                                    ? 0 : path_or_text.find_first_not_of(" \t\r\n"), 1);
  const StudySpec spec = is_file ? read_study_file(path_or_text) : parse_study_text(path_or_text, "<text>", first == "{");
  const std::string call = is_file ? "import nsbench; nsbench.run_study(" + py::repr(py::str(path_or_text)).cast<std::string>() +
                                         ", out=" + py::repr(py::str(out)).cast<std::string>() + ")"
                                   : "nsbench.run_study(<study text>)";
  const char* argv[] = {"python3", "-c", call.c_str()};
  set_command_line(3, argv);
  py::gil_scoped_release free;
  return run_study_file(spec, out);
}

}  // namespace

void bind_study(py::module_& m) {
  m.def("run_study", &run_study, "path_or_text"_a, "out"_a,
        "Runs a study file (TOML, or JSON with the same schema; a path, or the text itself) as\n"
        "`nsbench-study run FILE --out OUT` and writes its report into `out` (tables as .csv/.md/.tex,\n"
        "figures.json for scripts/figures.py, index.md). Integrators registered from Python may be named in\n"
        "it; their rows are marked (python). Returns the tables' ids; ValueError for a bad file.");
}

}  // namespace nsb::python
