#pragma once
// The 0.1.0 integrator API, kept compiling for one minor version (CHANGELOG.md, "Plugin API:
// what to change"). A plugin class written for 0.1.0 overrides what 0.2.0 moved elsewhere:
//
//   0.1.0 override                       0.2.0 replacement
//   std::string name() const             none: the registry entry names the integrator
//   bool conditionally_stable() const    .explicit_step = true in the entry's capabilities
//   bool treats_friction() const         .friction = true in the entry's capabilities
//   StepInfo step(double)                StepInfo advance(double): Integrator::step() keeps
//                                        state_.t and work_.steps around it
//
// make_from_params<Integrator, T> (core/registry.hpp) instantiates PluginCompat for the
// plugin's class: each such override found is a deprecation warning in the plugin's build,
// naming the replacement, and the two capability overrides are read once, when the entry
// builds the integrator, into what it declares (IntegratorEntry::make). The overrides are
// found by the class that declares them (`owner`): T's own, not Integrator's defaults.
#include <concepts>
#include <string>

#include "core/registry.hpp"
#include "integrators/integrator.hpp"

namespace nsb {

namespace compat_0_1 {

template <class C>
C* owner(std::string (C::*)() const);
template <class C>
C* owner(bool (C::*)() const);
template <class C>
C* owner(StepInfo (C::*)(double));

template <class T>
concept overrides_name = requires { { owner(&T::name) } -> std::same_as<T*>; };
template <class T>
concept overrides_conditionally_stable = requires { { owner(&T::conditionally_stable) } -> std::same_as<T*>; };
template <class T>
concept overrides_treats_friction = requires { { owner(&T::treats_friction) } -> std::same_as<T*>; };
template <class T>
concept overrides_step = requires { { owner(&T::step) } -> std::same_as<T*>; };

template <class T>
[[deprecated("nsbench 0.2.0: remove the name() override; an integrator is named after its NSBENCH_INTEGRATOR "
             "entry (CHANGELOG.md, 'Plugin API: what to change')")]]
void name_overridden() {}
template <class T>
[[deprecated("nsbench 0.2.0: replace the conditionally_stable() override by .explicit_step = true in the "
             "NSBENCH_INTEGRATOR entry's capabilities (CHANGELOG.md, 'Plugin API: what to change')")]]
void conditionally_stable_overridden() {}
template <class T>
[[deprecated("nsbench 0.2.0: replace the treats_friction() override by .friction = true in the "
             "NSBENCH_INTEGRATOR entry's capabilities (CHANGELOG.md, 'Plugin API: what to change')")]]
void treats_friction_overridden() {}
template <class T>
[[deprecated("nsbench 0.2.0: override advance(dt) instead of step(dt), without state_.t += dt and ++work_.steps "
             "(Integrator::step does both) (CHANGELOG.md, 'Plugin API: what to change')")]]
void step_overridden() {}

}  // namespace compat_0_1

template <class T>
struct PluginCompat<Integrator, T> {
  static void adapt(T& made) {
    if constexpr (compat_0_1::overrides_name<T>) compat_0_1::name_overridden<T>();
    if constexpr (compat_0_1::overrides_step<T>) compat_0_1::step_overridden<T>();
    if constexpr (compat_0_1::overrides_conditionally_stable<T>) {
      compat_0_1::conditionally_stable_overridden<T>();
      made.legacy_explicit_ = made.T::conditionally_stable();
    }
    if constexpr (compat_0_1::overrides_treats_friction<T>) {
      compat_0_1::treats_friction_overridden<T>();
      made.legacy_friction_ = made.T::treats_friction();
    }
  }
};

}  // namespace nsb
