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
// them through its `_core` attribute (an IntegratorCore pointing here), so there is
// no copy between the two. (Not a pybind11 trampoline: the registry's factories return a
// std::unique_ptr the C++ side owns, which a Python-owned trampoline object cannot be.)
//
// Lifetimes: what a run hands to Python outlives it safely: the Problem given to init (one C++
// owns) and self._core raise on use once the run has ended (RuntimeError), a State or
// WorkCounters kept from it reads as an empty one, and a NumPy view (self.state.u,
// self.impulses) holds the run's last values, its buffer kept alive with it; bind() is
// refused outside init (it reallocates what the views point into).
//
// Every call into Python takes the GIL (the run releases it). A Python exception in step() ends
// the run as diverged with the exception's type and message (nsb::run records a step's
// exception so), but a KeyboardInterrupt or SystemExit, which reaches nsbench.run's caller
// (RunCancelled, run/run.hpp); in init(), a ValueError is the scheme declining the problem (InputError), any
// other exception an error. A step that returns a non-finite dt, or one below kMinStepFraction
// of the requested step, is diverged too (a step past t_end: nsb::run, RunOptions).
#include <pybind11/pybind11.h>

#include "integrators/integrator.hpp"

namespace nsb::python {

namespace py = pybind11;

class PythonIntegrator;

// What the Python object reaches this one through (its `_core`, nsbench._IntegratorCore): owned
// by Python, so that it may outlive the run; `target` is cleared when the run ends, and live()
// raises then (kExpiredUse).
struct IntegratorCore {
  PythonIntegrator* target = nullptr;
  PythonIntegrator& live() const;
};

// The least step a Python step() may return, as a fraction of the one requested.
inline constexpr double kMinStepFraction = 1e-9;

class PythonIntegrator final : public Integrator {
 public:
  // Called with the GIL held: makes the instance cls(parameters as a dict).
  PythonIntegrator(Params params, const py::object& cls, const py::dict& parameters);
  ~PythonIntegrator() override;

  void init(const Problem& problem, const State& initial) override;
  Energy energy() const override;
  ImpactAccuracy impact_accuracy() const override { return accuracy_; }

  // For the Python side (nsbench._IntegratorCore).
  // Throws InputError outside init() or for another problem than init's.
  void bind_problem(const Problem& problem, const State& initial);
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
  py::object core_;  // the IntegratorCore of instance_._core, which the views keep alive
  const Problem* binding_ = nullptr;  // init's problem, during init (bind_problem)
  bool has_energy_ = false;
  ImpactAccuracy accuracy_;
};

}  // namespace nsb::python
