#pragma once
// Measures a run takes as it steps, one registered entry per kind: its name, its typed
// parameters and its factory, in the registry of the problems and integrators (core/registry.hpp),
// so that a kind is one file (studies/run_measures/, listed in run_measure.cpp). Not yet open to
// plugins: the registry lives in the studies library, which plugins do not link. nsbench.study's cases name them (observe=[{"kind": "mesh-momentum",
// "component": "jx"}], studies/case_run.hpp); each observer is fed after every step of the run
// and gives its figures as JSON at the end. The kinds are the measures library's observers
// (studies/measures.hpp) with the keys that choose what they observe.
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "integrators/integrator.hpp"
#include "studies/study.hpp"

namespace nsb {

class RunMeasure {
 public:
  virtual ~RunMeasure() = default;
  virtual void add(const Integrator& integrator, const StepInfo& step) = 0;  // after each step
  virtual Json result() const = 0;                                          // at the run's end
};

struct RunMeasureEntry {
  std::string name;
  std::string description;
  ParamSpecs (*parameters)();
  // After the integrator's init, before its first step; InputError when the kind does not
  // apply to the problem or the scheme (the case is then declined, n/a, with the reason).
  std::unique_ptr<RunMeasure> (*make)(const Params& params, const Problem& problem, const Integrator& integrator);
};

const std::vector<RunMeasureEntry>& run_measure_registry();
// InputError naming the nearest kind and the valid ones for an unknown name.
const RunMeasureEntry& find_run_measure(const std::string& name);


}  // namespace nsb
