#pragma once
// An integrator written in Python (nsbench.Integrator, python/nsbench/__init__.py) as an
// nsb::Integrator: the registry owns it like any other, so it runs in nsbench.run, in study files
// and in nsbench.check (check/conformance.hpp) beside the built-ins.
//
// The Python object is an instance of the user's class (made from the registered class with its
// validated parameters, as a dict). Its `init(problem, initial)` and `step(dt)` follow the C++
// contract of integrators/integrator.hpp: init calls self.bind(problem, initial) first, step
// advances self.state's u and v (views of this object's state_) and adds to self.work; this
// object's advance() calls it, and Integrator::step around it keeps the time and the step
// count. Its class attributes conditionally_stable, treats_friction, treats_friction_cone and
// treats_moving_contacts are read once, at registration, into the registry entry's
// capabilities. This C++
// object holds the state, impulses and counters the run driver reads; the Python object reaches
// them through its `_core` attribute (this object, bound as nsbench._IntegratorCore), so there is
// no copy between the two. (Not a pybind11 trampoline: the registry's factories return a
// std::unique_ptr the C++ side owns, which a Python-owned trampoline object cannot be.)
//
// Every call into Python takes the GIL (the run releases it). A Python exception in step() ends
// the run as diverged with the exception's type and message (nsb::run records a step's
// exception so); in init(), a ValueError is the scheme declining the problem (InputError), any
// other exception an error. A step that returns a non-finite dt is diverged too.
#include <pybind11/pybind11.h>

#include "integrators/integrator.hpp"

namespace nsb::python {

namespace py = pybind11;

class PythonIntegrator final : public Integrator {
 public:
  // Called with the GIL held: makes the instance cls(parameters as a dict).
  PythonIntegrator(Params params, const py::object& cls, const py::dict& parameters);
  ~PythonIntegrator() override;

  void init(const Problem& problem, const State& initial) override;
  Energy energy() const override;
  ImpactAccuracy impact_accuracy() const override { return accuracy_; }

  // For the Python side (nsbench._IntegratorCore).
  void bind_problem(const Problem& problem, const State& initial) { bind(problem, initial); }
  State& live_state() { return state_; }
  Vec& live_impulses() { return impulses_; }
  Vec& live_tangential_impulses() { return tangential_impulses_; }
  Vec& live_tangential_impulses2() { return tangential_impulses2_; }
  WorkCounters& live_work() { return work_; }
  const SpMat& mass() const { return mass_; }
  const Problem* problem() const { return problem_; }

 private:
  StepInfo advance(double dt_requested) override;
  py::object instance_;
  bool has_energy_ = false;
  ImpactAccuracy accuracy_;
};

}  // namespace nsb::python
