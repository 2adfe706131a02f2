#pragma once
// The integrators, by name. Each registers itself in its own .cpp (built-in or plugin):
//
//   NSBENCH_INTEGRATOR({"name", "one-line description", &T::parameters_spec,
//                       &make_from_params<Integrator, T>, /*reference=*/false, /*peer=*/false,
//                       {.friction = true, .explicit_step = true, .mass = MassNeed::DiagonalPositive}});
//
// at namespace scope (inside or outside namespace nsb; outside, qualify nsb::); the last
// braces declare its Capabilities (integrators/capabilities.hpp; {} when it needs nothing and
// treats no friction), optionally followed by a CapabilitySwitch when a parameter changes
// them (schatzman-paoli: {"theta", 0.0, {.explicit_step = true, ...}}) and the name of a
// process-wide lock its runs take (shared_lock below). The listing is sorted: the schemes by
// name, then the peers by name, then the reference solvers by name.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/registry.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

struct IntegratorEntry {
  std::string name;
  std::string description;
  ParamSpecs (*parameters)();
  // Builds the integrator from its validated parameters (make() calls it).
  std::unique_ptr<Integrator> (*factory)(const Params&);
  // A reference solver (the studies' yardstick where no exact solution exists); studies
  // rank it with the others but mark it.
  bool reference;
  // A peer: another code's implementation of a scheme (peers/, e.g. Siconos), run side by
  // side with ours; rankings mark it "(peer)".
  bool peer = false;
  // What it can run, checked when it binds a problem, and how a parameter changes it.
  Capabilities capabilities = {};
  CapabilitySwitch capabilities_switch = {};
  // The name of a process-wide lock its runs take (Siconos' BLAS, Python's GIL); empty: none.
  // Two such runs at once would take turns on it, so the studies never run two cases holding
  // the same lock at once (studies/parallel.hpp).
  std::string shared_lock = {};

  DeclaredCapabilities declared() const { return {capabilities, capabilities_switch}; }
  // The integrator, named after this entry and holding its capabilities.
  std::unique_ptr<Integrator> make(const Params& params) const {
    auto integrator = factory(params);
    integrator->name_ = name;
    integrator->declared_ = declared();
    integrator->declared_->always.explicit_step |= integrator->legacy_explicit_;
    integrator->declared_->always.friction |= integrator->legacy_friction_;
    return integrator;
  }
};

// What NSBENCH_INTEGRATOR calls (`abi`: the caller's NSBENCH_PLUGIN_ABI).
bool register_integrator(const IntegratorEntry& entry, int abi);
const std::vector<IntegratorEntry>& integrator_registry();
// The peers built in and their versions, e.g. "Siconos kernel 4.4.0+dfsg-2"; "none".
std::string peer_versions();
// Where an integrator comes from: "" (built in), a plugin's file, or "python:MODULE.CLASS" for a
// class written in Python and registered by the Python module (python/).
std::string integrator_origin(const std::string& name);
// How the tables mark the rows of an integrator written in Python: " (python)"; "" for others.
std::string integrator_mark(const std::string& name);
// Throws InputError listing the valid names when `name` is unknown.
const IntegratorEntry& find_integrator(const std::string& name);
std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const std::map<std::string, std::string>& overrides = {});

}  // namespace nsb

#define NSBENCH_INTEGRATOR(...)                                  \
  [[maybe_unused]] static const bool NSBENCH_UNIQUE(nsbench_integrator_) = \
      ::nsb::register_integrator(::nsb::IntegratorEntry __VA_ARGS__, NSBENCH_PLUGIN_ABI)
