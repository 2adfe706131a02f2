#include "studies/run_measure.hpp"

namespace nsb {

// The built-in kinds (studies/run_measures/), listed here as the studies are in registry.cpp: a
// static library keeps an object file only when something refers to it.
extern const RunMeasureEntry contact_phases_measure;
extern const RunMeasureEntry energy_balance_measure;
extern const RunMeasureEntry mesh_momentum_measure;
extern const RunMeasureEntry momentum_balance_measure;

namespace {

struct ByName {
  bool operator()(const RunMeasureEntry& a, const RunMeasureEntry& b) const { return a.name < b.name; }
};

Registry<RunMeasureEntry, ByName>& run_measures() {
  static Registry<RunMeasureEntry, ByName> registry = [] {
    Registry<RunMeasureEntry, ByName> built_in;
    for (const RunMeasureEntry* e : {&contact_phases_measure, &energy_balance_measure, &mesh_momentum_measure, &momentum_balance_measure}) built_in.add(*e, NSBENCH_PLUGIN_ABI, "run measure");
    return built_in;
  }();
  return registry;
}

}  // namespace

const std::vector<RunMeasureEntry>& run_measure_registry() { return run_measures().entries(); }

const RunMeasureEntry& find_run_measure(const std::string& name) {
  return find_entry(run_measure_registry(), name, "observe kind", "run measure");
}

}  // namespace nsb
