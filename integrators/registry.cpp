#include "integrators/registry.hpp"

#include <fmt/format.h>

#include "integrators/cd_lagrange.hpp"
#include "integrators/moreau_jean.hpp"

namespace nsb {

namespace {
template <class I>
std::unique_ptr<Integrator> make(const Params& p) {
  return std::make_unique<I>(p);
}
}  // namespace

const std::vector<IntegratorEntry>& integrator_registry() {
  static const std::vector<IntegratorEntry> entries = {
      {"cd-lagrange", "explicit variational CD-Lagrange, fixed step, impulse contact", &CdLagrange::parameters_spec, &make<CdLagrange>},
      {"moreau-jean", "Moreau-Jean theta-method, velocity-level LCP with Newton restitution", &MoreauJean::parameters_spec, &make<MoreauJean>},
  };
  return entries;
}

const IntegratorEntry& find_integrator(const std::string& name) {
  std::vector<std::string> names;
  for (const auto& e : integrator_registry()) {
    if (e.name == name) return e;
    names.push_back(e.name);
  }
  throw InputError(fmt::format("--integrator '{}': unknown integrator (valid: {})", name, fmt::join(names, ", ")));
}

std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const std::map<std::string, std::string>& overrides) {
  const auto& entry = find_integrator(name);
  return entry.make(Params(entry.parameters(), overrides));
}

}  // namespace nsb
