#include "python/python_integrator.hpp"

#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "core/plugin.hpp"
#include "integrators/registry.hpp"
#include "python/bindings.hpp"

namespace nsb::python {

using namespace pybind11::literals;

namespace {

// "TypeName: message" of the Python exception being handled.
std::string describe(const py::error_already_set& e) {
  return fmt::format("{}: {}", py::str(e.type().attr("__name__")).cast<std::string>(), py::str(e.value()).cast<std::string>());
}

}  // namespace

PythonIntegrator::PythonIntegrator(Params params, const py::object& cls, const py::dict& parameters)
    : Integrator(std::move(params)) {
  // __new__, then _core, then __init__: the instance reaches this object from its constructor on.
  instance_ = cls.attr("__new__")(cls);
  instance_.attr("_core") = py::cast(this, py::return_value_policy::reference);
  instance_.attr("__init__")(parameters);
  has_energy_ = py::hasattr(instance_, "energy");
  accuracy_.lag_steps = py::getattr(instance_, "impact_lag_steps", py::float_(accuracy_.lag_steps)).cast<double>();
  accuracy_.restitution_exact = py::getattr(instance_, "restitution_exact", py::bool_(true)).cast<bool>();
}

PythonIntegrator::~PythonIntegrator() {
  if (!Py_IsInitialized()) {  // the interpreter is gone: nothing left to release
    instance_.release();
    return;
  }
  py::gil_scoped_acquire gil;
  if (PyObject_SetAttrString(instance_.ptr(), "_core", Py_None) != 0) PyErr_Clear();  // a kept instance: no dangling view
  instance_ = py::object();
}

void PythonIntegrator::init(const Problem& problem, const State& initial) {
  py::gil_scoped_acquire gil;
  try {
    instance_.attr("init")(py::cast(&problem, py::return_value_policy::reference), initial);
  } catch (const py::error_already_set& e) {
    if (e.matches(PyExc_ValueError)) throw InputError(fmt::format("{}: {}", name(), py::str(e.value()).cast<std::string>()));
    throw std::runtime_error(fmt::format("{}.init raised {}", name(), describe(e)));
  }
  if (problem_ != &problem) throw std::runtime_error(fmt::format("{}.init did not call self.bind(problem, initial)", name()));
}

StepInfo PythonIntegrator::advance(double dt_requested) {
  py::gil_scoped_acquire gil;
  StepInfo info;
  try {
    const py::object r = instance_.attr("step")(dt_requested);
    if (py::isinstance<StepInfo>(r))
      info = r.cast<StepInfo>();
    else
      info.dt = r.cast<double>();
  } catch (const py::error_already_set& e) {
    throw std::runtime_error(fmt::format("{}.step raised {}", name(), describe(e)));
  } catch (const py::cast_error&) {
    throw std::runtime_error(fmt::format("{}.step returned neither the step taken (a float) nor a StepInfo", name()));
  }
  if (!std::isfinite(info.dt) || !(info.dt > 0.0))
    throw std::runtime_error(fmt::format("{}.step returned the step dt = {}; valid: a finite dt > 0", name(), info.dt));
  return info;
}

Energy PythonIntegrator::energy() const {
  if (!has_energy_) return Integrator::energy();
  py::gil_scoped_acquire gil;
  try {
    const auto [kinetic, potential] = instance_.attr("energy")().cast<std::pair<double, double>>();
    return {kinetic, potential};
  } catch (const py::error_already_set& e) {
    throw std::runtime_error(fmt::format("{}.energy raised {}", name(), describe(e)));
  }
}

namespace {

// The registry's entries hold plain function pointers (the plugin ABI): a class registered
// from Python takes one of kSlots pairs of functions, each reading its own slot.
constexpr std::size_t kSlots = 64;

struct Slot {
  py::object cls;
  ParamSpecs specs;
};

// Never destroyed: the registry's entries outlive the interpreter, after whose end no Python
// object may be released.
std::array<Slot, kSlots>& slots() {
  static auto* s = new std::array<Slot, kSlots>();
  return *s;
}
std::size_t used_slots = 0;  // changed with the GIL held

// Every call into the class takes the GIL (above): a study runs one case of such an integrator
// at a time (IntegratorEntry::shared_lock).
constexpr const char* kPythonLock = "Python (GIL)";

template <std::size_t K>
ParamSpecs slot_parameters() {
  return slots()[K].specs;
}

template <std::size_t K>
std::unique_ptr<Integrator> slot_make(const Params& params) {
  py::gil_scoped_acquire gil;
  const Slot& s = slots()[K];
  return std::make_unique<PythonIntegrator>(params, s.cls, typed_params(s.specs, params));
}

struct SlotFunctions {
  ParamSpecs (*parameters)();
  std::unique_ptr<Integrator> (*make)(const Params&);
};

template <std::size_t... K>
constexpr std::array<SlotFunctions, kSlots> slot_table(std::index_sequence<K...>) {
  return {SlotFunctions{&slot_parameters<K>, &slot_make<K>}...};
}
constexpr auto kSlotFunctions = slot_table(std::make_index_sequence<kSlots>{});

void register_python_integrator(const std::string& name, const py::object& cls, const std::string& description,
                                const ParamSpecs& parameters, bool reference) {
  if (used_slots == kSlots)
    throw InputError(fmt::format("register_integrator '{}': at most {} integrators written in Python per process", name, kSlots));
  for (const auto& spec : parameters)  // the defaults in their ranges
    if (!spec.default_value.empty()) spec.validate(spec.default_value);
  const std::string source = fmt::format("python:{}.{}", py::str(cls.attr("__module__")).cast<std::string>(),
                                         py::str(cls.attr("__qualname__")).cast<std::string>());
  const std::size_t k = used_slots;
  slots()[k] = {cls, parameters};
  try {
    register_as_plugin(source, [&] {
      Capabilities capabilities;
      capabilities.friction = py::getattr(cls, "treats_friction", py::bool_(false)).cast<bool>();
      capabilities.friction_cone = py::getattr(cls, "treats_friction_cone", py::bool_(false)).cast<bool>();
      capabilities.moving_contacts = py::getattr(cls, "treats_moving_contacts", py::bool_(false)).cast<bool>();
      capabilities.explicit_step = py::getattr(cls, "conditionally_stable", py::bool_(false)).cast<bool>();
      register_integrator({name, description, kSlotFunctions[k].parameters, kSlotFunctions[k].make, reference, false, capabilities,
                           {}, kPythonLock},
                          NSBENCH_PLUGIN_ABI);
    });
  } catch (...) {
    slots()[k] = {};
    throw;
  }
  ++used_slots;
}

}  // namespace

void bind_integrator(py::module_& m) {
  py::class_<StepInfo>(m, "StepInfo", "What step() returns when there is more to say than the step taken.")
      .def(py::init([](double dt, long iterations, bool converged) { return StepInfo{dt, iterations, converged}; }), "dt"_a,
           "iterations"_a = 0, "converged"_a = true)
      .def_readwrite("dt", &StepInfo::dt)
      .def_readwrite("iterations", &StepInfo::iterations)
      .def_readwrite("converged", &StepInfo::converged);
  py::class_<WorkCounters>(m, "WorkCounters", "Work done since init (integrators/integrator.hpp).")
      .def_readwrite("steps", &WorkCounters::steps)
      .def_readwrite("force_evaluations", &WorkCounters::force_evaluations)
      .def_readwrite("tangent_evaluations", &WorkCounters::tangent_evaluations)
      .def_readwrite("factorizations", &WorkCounters::factorizations)
      .def_readwrite("linear_solves", &WorkCounters::linear_solves)
      .def_readwrite("lcp_iterations", &WorkCounters::lcp_iterations)
      .def_readwrite("lcp_unconverged", &WorkCounters::lcp_unconverged);
  py::class_<PythonIntegrator>(m, "_IntegratorCore", "The C++ side of an nsbench.Integrator (its `_core`).")
      .def("bind", &PythonIntegrator::bind_problem, "problem"_a, "initial"_a)
      .def_property_readonly("state", &PythonIntegrator::live_state, py::return_value_policy::reference_internal)
      .def_property_readonly("impulses", [](py::object self) { return vector_view(self.cast<PythonIntegrator&>().live_impulses(), self); })
      .def_property_readonly("tangential_impulses",
                             [](py::object self) { return vector_view(self.cast<PythonIntegrator&>().live_tangential_impulses(), self); })
      .def_property_readonly("tangential_impulses2",
                             [](py::object self) { return vector_view(self.cast<PythonIntegrator&>().live_tangential_impulses2(), self); })
      .def_property_readonly("work", &PythonIntegrator::live_work, py::return_value_policy::reference_internal)
      .def_property_readonly("mass", [](const PythonIntegrator& i) { return to_scipy(i.mass()); })
      .def_property_readonly("problem", &PythonIntegrator::problem, py::return_value_policy::reference);
  m.def("_register_integrator", &register_python_integrator, "name"_a, "cls"_a, "description"_a, "parameters"_a,
        "reference"_a);
}

}  // namespace nsb::python
