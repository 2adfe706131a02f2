#pragma once
// What an integrator can run, declared in its registry entry (integrators/registry.hpp) and
// checked once, by check_capabilities, when the integrator binds a problem
// (Integrator::bind): a problem outside them is refused with one line naming every
// requirement it misses, each as
//
//   integrator X needs <requirement>; problem Y has <what it has> (valid: <what would run>)
//
// joined by "; it also needs ..." (all at once, so that a user does not meet them one try at a
// time), so that no scheme writes its own refusal of a kind below, and `nsbench list` reads
// them without building an integrator.
#include <string>

#include "core/parameters.hpp"
#include "problems/problem.hpp"

namespace nsb {

// What a scheme needs of the mass matrix M.
enum class MassNeed {
  Any,
  // M diagonal with entries >= 0 (massless dofs allowed: the scheme treats them itself).
  Diagonal,
  // M diagonal with entries > 0: M^{-1} appears in the update.
  DiagonalPositive,
  // Every diagonal entry > 0 (no massless dof), M of any pattern: M invertible.
  NoMasslessDofs,
};

struct Capabilities {
  // Treats Coulomb friction (Contacts::mu > 0): fills tangential_impulses. Without it a
  // problem with mu > 0 is refused, so that no scheme ignores friction silently.
  bool friction = false;
  // Treats contacts that move with the configuration (Problem::contacts_move: g(U), L(U),
  // T(U)), as its header's formula block states. Without it such a problem is refused, so
  // that no scheme runs frozen rows silently.
  bool moving_contacts = false;
  // Treats 3D contacts with friction (Contacts::has_cone: two tangent rows, the Coulomb cone
  // |Lambda_T| <= mu Lambda_N with maximal dissipation), fills tangential_impulses2, as its
  // header's formula block states. Without it such a problem is refused, so that no scheme
  // drops the second tangent row silently.
  bool friction_cone = false;
  // Explicit: only conditionally stable at a fixed step, dt below Problem::stable_step
  // (nsbench run warns above it). Not a refusal.
  bool explicit_step = false;
  MassNeed mass = MassNeed::Any;
  // Linear problems only: F_int = K u with K constant.
  bool linear_only = false;
  // A constant external force F_ext only.
  bool constant_force_only = false;
  // Restitution e = 0 only, unless every contact row acts on massless dofs: the scheme has no
  // velocity-level impact law (newmark-lm), so an e > 0 on a dof with mass would be ignored.
  bool inelastic_only = false;
  // Node-to-rigid contacts only: each row of the gap operator L acts on one dof, and no two
  // rows on the same dof (g_i = a_i (u_d - position_i): a node against a fixed obstacle).
  // Judged on constant rows only: moving rows (one rigid body's corners: translation and
  // rotation in each row) reach an integrator that treats them, which declines what it cannot
  // run itself (the engine peers: peers/engine_scene.hpp).
  bool node_to_rigid_only = false;
  // The integer parameter bounding the number of dofs (e.g. "max_dofs" for a scheme with
  // dense matrices); empty: no bound.
  std::string max_dofs_parameter = {};
};

// Capabilities that depend on a parameter: with the real parameter `parameter` equal to
// `value`, `when_equal` replaces the entry's capabilities (schatzman-paoli: theta = 0 is
// explicit with a diagonal mass, any other theta implicit on a linear problem). Empty
// `parameter`: no switch.
struct CapabilitySwitch {
  std::string parameter = {};
  double value = 0.0;
  Capabilities when_equal = {};
};

// What a registry entry declares: its capabilities and their switch.
struct DeclaredCapabilities {
  Capabilities always;
  CapabilitySwitch when;

  // The capabilities that hold for the parameters `params`.
  const Capabilities& resolved(const Params& params) const;
  // " with theta = 0" / " with theta != 0" for `params`; "" without a switch.
  std::string condition(const Params& params) const;
  // For `nsbench list`: "explicit; diagonal mass > 0; ..." ("none" when it needs nothing),
  // then "; with theta = 0: ..." for the switch. Friction is not in it (listed apart).
  std::string text() const;
};

// "any mass", "diagonal mass >= 0", "diagonal mass > 0", "no massless dof".
const char* mass_need_name(MassNeed need);

// Throws InputError (the one line above) naming every requirement `problem` (of mass matrix
// `mass`) does not meet, for the integrator named `integrator` with parameters `params`.
void check_capabilities(const DeclaredCapabilities& declared, const std::string& integrator, const Params& params,
                        const Problem& problem, const SpMat& mass);

}  // namespace nsb
