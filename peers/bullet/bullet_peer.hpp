#pragma once
// Bullet (Debian libbullet-dev 3.24, its double-precision build bullet-float64) as an nsbench
// peer on the rigid problems (the scenes of peers/engine_scene.hpp): btDiscreteDynamicsWorld's
// own stepper (stepSimulation(dt, 0): one step of exactly dt, no substeps, no interpolation)
// and Bullet's own contact model.
//
// Model. One btRigidBody (btSphereShape, btBoxShape or btCylinderShape along y) over a
// btStaticPlaneShape z = 0. Each step: collision detection, the points at distance <= 0
// (contact processing threshold 0: Bullet's speculative points, found ahead within the
// breaking threshold, aim at a rebound of e |v| - d / dt and at small steps take all of it:
// e = 1 came to rest at dt = 1e-4 with them), then the sequential-impulse solver
// (projected Gauss-Seidel, `iterations` sweeps) on the velocities, per contact point
//     normal:   0 <= P_N,  target normal velocity  e_c max(-v_N(-), 0)  (restitution)
//     friction: two directions (SOLVER_USE_2_FRICTION_DIRECTIONS), each |P_T,i| <= mu_c P_N
//               (a friction pyramid: exact for the planar motions here, slip along x only),
// then semi-implicit Euler on the positions. Penetration is removed by split impulse
// (m_splitImpulse, threshold 0: every penetration), a separate position correction at
// ERP `split_erp` that adds no velocity, so no energy (Bullet's recommended setting for
// stacking and resting contact): a corner that penetrates before it is found (the rocking
// block's, by up to |omega| b dt) is pushed out without a rebound velocity. Rotations: the
// bouncing sphere and the sliding box are locked (angular factor 0; the problems are point
// masses), the disk and the rocking block turn about y only; linear factor (1, 0, 1)
// (bouncing: (0, 0, 1)); the sphere (3D) is free (factors (1, 1, 1)), its friction Bullet's
// two directions, the first along the contact's slip. The rocking block's box keeps Bullet's margin: its support points,
// and so its contact points, are the box's sharp corners (btBoxShape adds the margin back). Deactivation (sleeping) is disabled: a
// sleeping body would hide its creep. No CCD: the fastest case moves v dt <= 0.05 m per step,
// less than the body's half size.
//
// Mapping from e and mu (stated here, not hidden): Bullet combines the two bodies'
// coefficients by product (btManifoldResult), so the floor gets restitution 1 and friction 1,
// the body e and mu; Bullet caps the combined friction at 10, so mu > 10 is declined
// (InputError naming mu). The restitution threshold
// (m_restitutionVelocityThreshold, default 0.2 m/s: no bounce below it) is set to 0, so the
// Newton law applies at every speed. Inertia about y is set to kappa m R^2 exactly.
//
// Settings (parameters, defaults): iterations 100 [1, 10^6]; split_erp 0.8 [0, 1] (m_erp2);
// size 0.1 m (engine_scene.hpp). Bullet's defaults otherwise (warm starting, erp 0.2,
// contact breaking threshold 0.02 m, margins: the sphere's is its radius, the box's 0.04 m
// inside its half sides).
//
// Impulses: btManifoldPoint::getAppliedImpulse (normal) and m_appliedImpulseLateral1/2 along
// m_lateralFrictionDir1/2 (friction), summed over the manifold's points per problem contact
// (the rocking block: per corner, by the point's side of the centre); already impulses.
// Work: one step and one force evaluation per stepSimulation; Bullet does not report the
// sweeps it took (the iterations column is 0).
//
// Reference: E. Coumans, "Bullet 2.80 Physics SDK Manual", 2012 (split impulse, solver
// settings); E. Catto, "Iterative dynamics with temporal coherence", GDC 2005 (sequential
// impulses).
// Moving contacts (Problem::contacts_move): the rocking block is Bullet's own box, whose
// corners it finds every step (peers/engine_scene.hpp); the Painleve rod is declined.
#include <memory>
#include <string>

#include "peers/engine_scene.hpp"

namespace nsb {

class BulletPeer final : public EnginePeer {
 public:
  explicit BulletPeer(const Params& params);
  ~BulletPeer() override;
  static ParamSpecs parameters_spec();

 private:
  struct World;
  void build(const engines::Scene& scene) override;
  engines::StepResult engine_step(double dt) override;

  std::unique_ptr<World> world_;
};

// Bullet's version (pkg-config's, e.g. "3.24") and precision.
std::string bullet_version();

}  // namespace nsb
