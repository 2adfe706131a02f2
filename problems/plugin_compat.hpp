#pragma once
// The 0.1.0 problem API, kept compiling for one minor version (CHANGELOG.md, "Plugin API:
// what to change"). A plugin class written for 0.1.0 overrides what 0.2.0 replaced:
//
//   0.1.0 override                                   0.2.0 replacement
//   void observe(const State&, std::span<double>)    observe(s, impulses, dt, out): one
//   void observe_step(s, impulses, dt, out)          function, for the initial sample too
//   std::optional<State> exact_state(double)         exact(): an ExactSolution
//   std::vector<double> impact_times(double)         (problems/exact_solution.hpp)
//
// make_from_params<Problem, T> (core/registry.hpp) instantiates PluginCompat for the
// plugin's class: each such override found is a deprecation warning in the plugin's build,
// naming the replacement. The old observation functions still run, through the default of
// the new one; the exact ones through Problem::exact()'s default, which hands out a view of
// them once PluginCompat has found them.
#include <concepts>
#include <optional>
#include <span>
#include <type_traits>
#include <vector>

#include "core/registry.hpp"
#include "problems/problem.hpp"

namespace nsb {

namespace compat_0_1 {

// The class that declares the member a pointer names: T's own override, or a base's default.
// One function per signature, so that an overload set (observe) deduces from the one member
// of that signature.
template <class C>
C* observe_state_owner(void (C::*)(const State&, std::span<double>) const);
template <class C>
C* observe_step_owner(void (C::*)(const State&, const Vec&, double, std::span<double>) const);
template <class C>
C* exact_state_owner(std::optional<State> (C::*)(double) const);
template <class C>
C* impact_times_owner(std::vector<double> (C::*)(double) const);

template <class T>
concept overrides_observe_state = requires { { observe_state_owner(&T::observe) } -> std::same_as<T*>; };
template <class T>
concept overrides_observe_step = requires { { observe_step_owner(&T::observe_step) } -> std::same_as<T*>; };
// A problem that is its own ExactSolution (most built-ins) has impact_times() for that
// interface, not 0.1.0's.
template <class T>
concept overrides_exact_state = requires { { exact_state_owner(&T::exact_state) } -> std::same_as<T*>; };
template <class T>
concept overrides_impact_times = !std::is_base_of_v<ExactSolution, T> &&
                                 requires { { impact_times_owner(&T::impact_times) } -> std::same_as<T*>; };

template <class T>
[[deprecated("nsbench 0.2.0: override observe(s, impulses, dt, out) instead of observe(s, out) "
             "(CHANGELOG.md, 'Plugin API: what to change')")]]
void observe_state_overridden() {}
template <class T>
[[deprecated("nsbench 0.2.0: rename the observe_step(s, impulses, dt, out) override to observe "
             "(CHANGELOG.md, 'Plugin API: what to change')")]]
void observe_step_overridden() {}
template <class T>
[[deprecated("nsbench 0.2.0: move exact_state() and impact_times() into an ExactSolution that exact() hands out "
             "(problems/exact_solution.hpp; CHANGELOG.md, 'Plugin API: what to change')")]]
void exact_overridden() {}

}  // namespace compat_0_1

template <class T>
struct PluginCompat<Problem, T> {
  static void adapt(T& made) {
    if constexpr (compat_0_1::overrides_observe_state<T>) compat_0_1::observe_state_overridden<T>();
    if constexpr (compat_0_1::overrides_observe_step<T>) compat_0_1::observe_step_overridden<T>();
    if constexpr (compat_0_1::overrides_exact_state<T> || compat_0_1::overrides_impact_times<T>) {
      compat_0_1::exact_overridden<T>();
      made.Problem::legacy_exact_.enabled = true;
    }
  }
};

}  // namespace nsb
