#include "integrators/registry.hpp"

namespace nsb {

namespace {

// Schemes, then peers (other codes' schemes), then reference solvers, each by name.
struct SchemesThenReferences {
  static int kind(const IntegratorEntry& e) { return e.reference ? 2 : e.peer ? 1 : 0; }
  bool operator()(const IntegratorEntry& a, const IntegratorEntry& b) const {
    return kind(a) != kind(b) ? kind(a) < kind(b) : a.name < b.name;
  }
};

Registry<IntegratorEntry, SchemesThenReferences>& integrators() {
  static Registry<IntegratorEntry, SchemesThenReferences> registry;
  return registry;
}

}  // namespace

bool register_integrator(const IntegratorEntry& entry, int abi) { return integrators().add(entry, abi, "integrator"); }

const std::vector<IntegratorEntry>& integrator_registry() { return integrators().entries(); }

std::string integrator_origin(const std::string& name) { return integrators().origin(name); }

std::string integrator_mark(const std::string& name) {
  return integrator_origin(name).starts_with("python:") ? " (python)" : "";
}

const IntegratorEntry& find_integrator(const std::string& name) {
  return find_entry(integrator_registry(), name, "--integrator", "integrator");
}

std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const std::map<std::string, std::string>& overrides) {
  return make_entry(find_integrator(name), overrides);
}

}  // namespace nsb
