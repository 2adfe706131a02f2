#pragma once
// The Python module nsbench._nsbench, re-exported by the package nsbench (nsbench/__init__.py).
// One file per part of the module; each adds its functions and classes to `m`. Conventions
// shared by all: names as on the command line (problems, integrators, parameters), vectors and
// matrices as NumPy arrays and scipy.sparse matrices, nsb::InputError as ValueError (module.cpp),
// the GIL released while C++ computes (runs, checks, studies).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <map>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "integrators/integrator.hpp"
#include "problems/problem.hpp"

namespace nsb::python {

namespace py = pybind11;

void bind_registry(py::module_& m);    // problems(), integrators(), load_plugin(), Parameter
void bind_problem(py::module_& m);     // Problem, State, Contacts
void bind_run(py::module_& m);         // _run(), check()
void bind_integrator(py::module_& m);  // _IntegratorCore, StepInfo, register_integrator()
void bind_study(py::module_& m);       // run_study(), _run_cases(), _drive_study()
void bind_tables(py::module_& m);      // Table, Column, Figure, the writers, the measures of a run's numbers

// A parameter's value as Python sees it: float (real), int (integer), str (choice), None (an
// unset optional real).
py::object typed_value(const ParamSpec& spec, const std::string& text);
// Every parameter of `params` (declared by `specs`) by name, typed.
py::dict typed_params(const ParamSpecs& specs, const Params& params);
// A keyword argument's value as the text `--set key=value` would give: str() of a number
// (Python's shortest round trip, so the double is the one the command line reads) or a string.
// Throws InputError naming `key` for another type (bool, None, a sequence ...).
std::string value_text(const std::string& key, const py::handle& value);
// "key=value" items from keyword arguments, in their order.
std::vector<std::string> assignments(const py::dict& kwargs);

// The message of a use of what a run handed to Python once the run has ended
// (python_integrator.hpp), or of None where an nsbench object is expected.
inline constexpr const char* kExpiredUse =
    "an nsbench object used after the run it belonged to ended (the Problem handed to init, self._core, self.state, "
    "self.work), or None where one is expected: keep copies instead (problem.name and problem.parameters, state.u.copy())";

// `s` itself, or kExpiredUse raised when it is the State a kept self.state points at once its
// run ended (python_integrator.cpp): read as an empty one, it passed for a valid result.
State& usable(State& s);
const State& usable(const State& s);
// The same for the WorkCounters a kept self.work points at.
WorkCounters& usable(WorkCounters& w);

// A NumPy view of v (no copy), kept alive by `owner`, the Python object that holds v.
py::array_t<double> vector_view(Vec& v, const py::handle& owner);

// Eigen's compressed column storage as scipy.sparse.csc_matrix (a copy).
py::object to_scipy(const SpMat& matrix);

}  // namespace nsb::python
