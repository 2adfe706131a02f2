#include "integrators/registry.hpp"

namespace nsb {

namespace {

struct SchemesThenReferences {
  bool operator()(const IntegratorEntry& a, const IntegratorEntry& b) const {
    return a.reference != b.reference ? b.reference : a.name < b.name;
  }
};

Registry<IntegratorEntry, SchemesThenReferences>& integrators() {
  static Registry<IntegratorEntry, SchemesThenReferences> registry;
  return registry;
}

}  // namespace

bool register_integrator(const IntegratorEntry& entry, int abi) { return integrators().add(entry, abi, "integrator"); }

const std::vector<IntegratorEntry>& integrator_registry() { return integrators().entries(); }

const IntegratorEntry& find_integrator(const std::string& name) {
  return find_entry(integrator_registry(), name, "--integrator", "integrator");
}

std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const std::map<std::string, std::string>& overrides) {
  return make_entry(find_integrator(name), overrides);
}

}  // namespace nsb
