#include "python/python_integrator.hpp"

#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "core/plugin.hpp"
#include "integrators/registry.hpp"
#include "python/bindings.hpp"
#include "run/run.hpp"

namespace nsb::python {

using namespace pybind11::literals;

namespace {

// The counters of WorkCounters as Python attributes, each through usable(): a kept self.work
// raises once its run ended.
const std::array<std::pair<const char*, long WorkCounters::*>, 7> kCounters{{
    {"steps", &WorkCounters::steps},
    {"force_evaluations", &WorkCounters::force_evaluations},
    {"tangent_evaluations", &WorkCounters::tangent_evaluations},
    {"factorizations", &WorkCounters::factorizations},
    {"linear_solves", &WorkCounters::linear_solves},
    {"lcp_iterations", &WorkCounters::lcp_iterations},
    {"lcp_unconverged", &WorkCounters::lcp_unconverged},
}};

// "TypeName: message" of the Python exception being handled.
std::string describe(const py::error_already_set& e) {
  return fmt::format("{}: {}", py::str(e.type().attr("__name__")).cast<std::string>(), py::str(e.value()).cast<std::string>());
}

// What a Problem wrapper kept past its run points at: every member raises (kExpiredUse), the
// members bound through a pointer to a member function too, which a null object would crash.
class ExpiredProblem final : public Problem {
 public:
  std::string name() const override { expired(); }
  const Params& parameters() const override { expired(); }
  Index ndof() const override { expired(); }
  SpMat mass_matrix() const override { expired(); }
  void internal_force(ConstVecRef, VecRef) const override { expired(); }
  void tangent_stiffness(ConstVecRef, SpMat&) const override { expired(); }
  bool is_linear() const override { expired(); }
  void external_force(double, VecRef) const override { expired(); }
  bool external_force_is_constant() const override { expired(); }
  double strain_energy(ConstVecRef) const override { expired(); }
  double load_potential(ConstVecRef) const override { expired(); }
  const Contacts& contacts() const override { expired(); }
  bool contacts_move() const override { expired(); }
  State initial_state() const override { expired(); }
  double stable_step() const override { expired(); }
  std::vector<std::string> observable_names() const override { expired(); }

 private:
  [[noreturn]] static void expired() { throw std::runtime_error(kExpiredUse); }
};

// Every Python wrapper that refers to `object` (of type T, owned by C++, handed out by
// reference) is pointed at `replacement`, which lives for ever: a use after the run reaches it
// instead of freed memory (pybind11 would allocate an object behind a null pointer). A wrapper
// Python owns (a Problem built in Python) is left alone.
template <class T>
void expire_wrappers(const T* object, T* replacement) {
  const py::detail::type_info* type = py::detail::get_type_info(typeid(T));
  std::vector<py::detail::instance*> found;
  const auto range = py::detail::get_internals().registered_instances.equal_range(object);
  for (auto it = range.first; it != range.second; ++it)
    if (Py_TYPE(it->second) == type->type && !it->second->owned) found.push_back(it->second);
  for (py::detail::instance* inst : found) {
    py::detail::deregister_instance(inst, const_cast<T*>(object), type);
    inst->get_value_and_holder(type).value_ptr() = replacement;
    py::detail::register_instance(inst, replacement, type);
  }
}

// What a kept self.state and self.work point at once their run ended: every use through the
// bindings raises (usable()).
State expired_state;
WorkCounters expired_work;

// The vectors the NumPy views of a run point into (self.state.u, self.impulses ...), moved out
// of an integrator at its end (a move keeps the buffers) and kept while a view may reach them.
struct ViewedBuffers {
  Vec u, v, impulses, tangential, tangential2;
};

}  // namespace

State& usable(State& s) {
  if (&s == &expired_state) throw std::runtime_error(kExpiredUse);
  return s;
}

const State& usable(const State& s) { return usable(const_cast<State&>(s)); }

WorkCounters& usable(WorkCounters& w) {
  if (&w == &expired_work) throw std::runtime_error(kExpiredUse);
  return w;
}

PythonIntegrator& IntegratorCore::live() const {
  if (!target) throw std::runtime_error(kExpiredUse);
  return *target;
}

PythonIntegrator::PythonIntegrator(Params params, const py::object& cls, const py::dict& parameters)
    : Integrator(std::move(params)) {
  // __new__, then _core, then __init__: the instance reaches this object from its constructor on.
  instance_ = cls.attr("__new__")(cls);
  core_ = py::cast(IntegratorCore{this});
  instance_.attr("_core") = core_;
  instance_.attr("__init__")(parameters);
  has_energy_ = py::hasattr(instance_, "energy");
  accuracy_.lag_steps = py::getattr(instance_, "impact_lag_steps", py::float_(accuracy_.lag_steps)).cast<double>();
  accuracy_.restitution_exact = py::getattr(instance_, "restitution_exact", py::bool_(true)).cast<bool>();
}

PythonIntegrator::~PythonIntegrator() {
  if (!Py_IsInitialized()) {  // the interpreter is gone: nothing left to release
    instance_.release();
    core_.release();
    return;
  }
  py::gil_scoped_acquire gil;
  if (PyObject_SetAttrString(instance_.ptr(), "_core", Py_None) != 0) PyErr_Clear();  // a kept instance: no dangling view
  instance_ = py::object();
  // What Python may still hold of this run: its core, a problem C++ owns, its state and
  // counters raise on use; the views' buffers live on with the core, which every view keeps
  // alive (its base, or its State's keep-alive).
  static ExpiredProblem expired_problem;
  core_.cast<IntegratorCore&>().target = nullptr;
  if (problem_) expire_wrappers(problem_, static_cast<Problem*>(&expired_problem));
  expire_wrappers(&state_, &expired_state);
  expire_wrappers(&work_, &expired_work);
  auto* kept = new ViewedBuffers{std::move(state_.u), std::move(state_.v), std::move(impulses_), std::move(tangential_impulses_),
                                 std::move(tangential_impulses2_)};
  py::detail::keep_alive_impl(core_, py::capsule(kept, [](void* b) { delete static_cast<ViewedBuffers*>(b); }));
  core_ = py::object();
}

void PythonIntegrator::bind_problem(const Problem& problem, const State& initial) {
  // bind() replaces the vectors the views point into, and a problem bound here must outlive
  // the run: only init's own problem, during init (a temporary one bound in step() crashed).
  if (!binding_ || &problem != binding_)
    throw InputError(fmt::format("{}: bind(problem, initial) is called from init(problem, initial), with the problem init "
                                 "was given", name()));
  bind(problem, initial);
}

void PythonIntegrator::init(const Problem& problem, const State& initial) {
  py::gil_scoped_acquire gil;
  binding_ = &problem;
  const struct Done {
    const Problem*& binding;
    ~Done() { binding = nullptr; }
  } done{binding_};
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
  } catch (py::error_already_set& e) {
    if (!e.matches(PyExc_Exception)) {  // KeyboardInterrupt, SystemExit: the caller's, not a diverged run
      const std::string what = describe(e);
      e.restore();  // this thread's Python error again: nsbench.run raises it (bind_run.cpp)
      throw RunCancelled(fmt::format("{}.step raised {}", name(), what));
    }
    throw std::runtime_error(fmt::format("{}.step raised {}", name(), describe(e)));
  } catch (const py::cast_error&) {
    throw std::runtime_error(fmt::format("{}.step returned neither the step taken (a float) nor a StepInfo", name()));
  }
  // A floor relative to the requested step: a step of 1e-300 never reached t_end (the run's
  // step limit stops fixed steps, not a Python loop of 2e8 calls in reasonable time).
  if (!std::isfinite(info.dt) || !(info.dt >= kMinStepFraction * dt_requested))
    throw std::runtime_error(fmt::format("{}.step returned the step dt = {}; valid: a finite dt >= {:g} (1e-9 of the requested {:g})",
                                         name(), info.dt, kMinStepFraction * dt_requested, dt_requested));
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
  } catch (const py::cast_error&) {
    throw std::runtime_error(fmt::format("{}.energy returned no (kinetic, potential) pair of floats", name()));
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
  const bool printable = !name.empty() && std::all_of(name.begin(), name.end(), [](unsigned char ch) { return std::isgraph(ch); });
  if (!printable)
    throw InputError(fmt::format("register_integrator {}: valid: a name of printable characters without spaces, not empty",
                                 py::repr(py::str(name)).cast<std::string>()));
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
  py::class_<WorkCounters> work(m, "WorkCounters", "Work done since init (integrators/integrator.hpp).");
  for (const auto& [name, member] : kCounters)
    work.def_property(name, [member](WorkCounters& w) { return usable(w).*member; },
                      [member](WorkCounters& w, long value) { usable(w).*member = value; });
  const auto live = [](const py::handle& self) -> PythonIntegrator& { return self.cast<const IntegratorCore&>().live(); };
  py::class_<IntegratorCore>(m, "_IntegratorCore", "The C++ side of an nsbench.Integrator (its `_core`).")
      .def("bind", [](const IntegratorCore& c, const Problem& p, const State& s) { c.live().bind_problem(p, usable(s)); }, "problem"_a,
           "initial"_a)
      .def_property_readonly("state", [](const IntegratorCore& c) -> State& { return c.live().live_state(); },
                             py::return_value_policy::reference_internal)
      .def_property_readonly("impulses", [live](py::object self) { return vector_view(live(self).live_impulses(), self); })
      .def_property_readonly("tangential_impulses",
                             [live](py::object self) { return vector_view(live(self).live_tangential_impulses(), self); })
      .def_property_readonly("tangential_impulses2",
                             [live](py::object self) { return vector_view(live(self).live_tangential_impulses2(), self); })
      .def_property_readonly("work", [](const IntegratorCore& c) -> WorkCounters& { return c.live().live_work(); },
                             py::return_value_policy::reference_internal)
      .def_property_readonly("mass", [](const IntegratorCore& c) { return to_scipy(c.live().mass()); })
      .def_property_readonly("problem", [](const IntegratorCore& c) { return c.live().problem(); },
                             py::return_value_policy::reference);
  m.def("_register_integrator", &register_python_integrator, "name"_a, "cls"_a, "description"_a, "parameters"_a,
        "reference"_a);
}

}  // namespace nsb::python
