#pragma once
// MuJoCo (Debian libmujoco-dev 2.2) as an nsbench peer on the rigid problems (the scenes of
// peers/engine_scene.hpp): MuJoCo's own stepper (mj_step) and its own soft contact model.
//
// Model. Generalized coordinates are the problem's dofs: slide joints along x (sliding mass,
// disk, block) and z, a hinge about y (disk, block); the sphere (3D) is a free joint, whose
// angular velocity MuJoCo keeps in the body frame (turned to the world's with the body's
// quaternion, mju_rotVecQuat); the floor is a plane geom. A contact is a soft
// constraint: with r the signed distance (< 0: penetration), the solver sets the contact's
// acceleration to
//     r'' = d a_ref + (1 - d) r''_free,    a_ref = -b r' - k r,   0 <= f_N,
// inside the friction cone, elliptic |f_T| <= mu f_N (cone = elliptic, the default) or
// MuJoCo's pyramid of 2 (condim - 1) edges (cone = pyramidal) (condim 3; 1 when mu = 0),
// solved by MuJoCo's Newton solver (`iterations`, `tolerance`), then the noslip
// post-processor (`noslip_iterations`), which removes the slip the soft cone allows (MuJoCo's
// documented remedy for creep on slopes).
//
// Mapping from e and mu (stated here, not hidden): mu is the geoms' sliding friction (both
// geoms get mu; MuJoCo takes the max). Restitution is the reference spring-damper's: solref
// given as (-k, -b), MuJoCo's direct stiffness and damping, with
//     k = omega^2,   b = 2 zeta omega,   omega = 1 / tau,   tau = timeconst_steps * dt,
//     zeta = -ln e / sqrt(pi^2 + ln^2 e)   (e > 0; zeta = 1 at e = 0: critical, no rebound),
// the damping ratio of a linear oscillator whose half period returns e times the speed. The
// impedance d = solimp = (impedance, impedance, 0.001) is near 1 so that r'' ~ a_ref (MuJoCo
// scales k by 1/d^2 and b by 1/d). The contact lasts about half a damped period,
// pi tau / sqrt(1 - zeta^2) (= pi tau at e = 1), with penetration ~ tau times the impact speed:
// the softness the tests bound. Restitution is only that of the continuous oscillator: the
// discrete one (semi-implicit steps at omega dt = 1 / timeconst_steps, the unilateral force
// cut at f_N = 0) differs by O(omega dt); the peers' tests and the studies measure it.
// MuJoCo's documentation: timeconst at least 2 timesteps (the default here; smaller is
// unstable), elliptic cones and noslip for accurate friction, the implicit integrator (or
// RK4) for stability.
//
// Settings (parameters, defaults): integrator implicit {euler, implicit, rk4}; cone elliptic
// {elliptic, pyramidal}; timeconst_steps
// 2 [1, 1000]; impedance 0.9999 [0.9, 0.9999]; iterations 100 [1, 10^6]; tolerance 1e-10
// [0, 1e-2]; noslip_iterations 20 [0, 10^6]; size 0.1 m (engine_scene.hpp).
//
// Impulses: mj_contactForce (the contact frame's normal and tangential force, at the step's
// start state, where mj_step computes it; mj_contactForce decodes the pyramid's edge forces
// into it) x dt, summed over the contact points per problem contact (a box has up to four;
// the rocking block's are split per corner by the point's side of the centre). Work: one step and one force evaluation per mj_step; the iterations are MuJoCo's
// solver_iter.
//
// Reference: E. Todorov, T. Erez, Y. Tassa, "MuJoCo: A physics engine for model-based
// control", IROS 2012; MuJoCo's documentation, "Computation" and "Modeling: solver parameters".
// Moving contacts (Problem::contacts_move): the rocking block is MuJoCo's own box geom on
// slide joints x, z and a hinge about y, its corners found every step
// (peers/engine_scene.hpp); the Painleve rod is declined. A corner found penetrating (by up to
// |omega| b dt: detection is at the step's start) is pushed out by the reference spring, a
// separation velocity the block keeps as a hop after an impact.
#include <memory>
#include <string>

#include "peers/engine_scene.hpp"

namespace nsb {

class MujocoPeer final : public EnginePeer {
 public:
  explicit MujocoPeer(const Params& params);
  ~MujocoPeer() override;
  static ParamSpecs parameters_spec();
  // A compliant contact: its restitution is the discrete spring's, and each impact lags by
  // about the contact's half period pi tau (2 pi steps at the defaults) plus the detection step.
  ImpactAccuracy impact_accuracy() const override;

 private:
  struct World;
  void build(const engines::Scene& scene) override;
  engines::StepResult engine_step(double dt) override;
  void set_contact_spring(double dt);

  std::unique_ptr<World> world_;
};

// MuJoCo's version as its library reports it (mj_versionString, e.g. "2.2.2").
std::string mujoco_version();

}  // namespace nsb
