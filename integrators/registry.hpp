#pragma once
// Explicit list of the integrators, by name (integrators/registry.cpp, one line each).
// Adding an integrator: one .hpp/.cpp pair and one line there.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "integrators/integrator.hpp"

namespace nsb {

struct IntegratorEntry {
  std::string name;
  std::string description;
  ParamSpecs (*parameters)();
  std::unique_ptr<Integrator> (*make)(const Params&);
  // A reference solver (the studies' yardstick where no exact solution exists); studies
  // rank it with the others but mark it.
  bool reference;
  // A peer: another code's implementation of a scheme (peers/, e.g. Siconos), run side by
  // side with ours; rankings mark it "(peer)".
  bool peer = false;
};

const std::vector<IntegratorEntry>& integrator_registry();
// The peers' entries (peers/registry.cpp, library nsbench_peers; empty when the optional
// peers are not built). integrator_registry() lists them after its own.
std::vector<IntegratorEntry> peer_integrators();
// The peers built in and their versions, e.g. "Siconos kernel 4.4.0+dfsg-2"; "none".
std::string peer_versions();
// Throws InputError listing the valid names when `name` is unknown.
const IntegratorEntry& find_integrator(const std::string& name);
std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const std::map<std::string, std::string>& overrides = {});

}  // namespace nsb
