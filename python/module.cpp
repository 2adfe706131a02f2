// PYBIND11_MODULE of nsbench._nsbench: the parts (bindings.hpp) and the exception mapping.
// nsb::InputError (bad input: a name, a parameter outside its range, a file) arrives in Python
// as ValueError with the command line's one-line message; any other C++ exception as
// RuntimeError (pybind11's default; a use of an object whose run has ended says so). None of
// them ends the interpreter.
#include "python/bindings.hpp"

PYBIND11_MODULE(_nsbench, m) {
  m.doc() = "nsbench's C++ core (problems, integrators, runs, study files); use the package nsbench.";
  pybind11::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const nsb::InputError& e) {
      PyErr_SetString(PyExc_ValueError, e.what());
    } catch (const pybind11::reference_cast_error&) {  // a wrapper pointing at nothing (python_integrator.hpp) or None
      PyErr_SetString(PyExc_RuntimeError, nsb::python::kExpiredUse);
    }
  });
  nsb::python::bind_registry(m);
  nsb::python::bind_problem(m);
  nsb::python::bind_run(m);
  nsb::python::bind_integrator(m);
  nsb::python::bind_study(m);
  nsb::python::bind_tables(m);
}
