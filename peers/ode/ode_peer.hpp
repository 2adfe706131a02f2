#pragma once
// ODE, the Open Dynamics Engine (Debian libode-dev 0.16, double precision), as an nsbench
// peer on the rigid problems (the scenes of peers/engine_scene.hpp): ODE's own stepper
// dWorldStep and its own contact joints.
//
// Model. One dBody (dSphere, dBox, or dCylinder turned along y) over the plane z = 0. Each
// step: dCollide(body, plane) (at most 4 points), one contact joint per point, then
// dWorldStep: a first-order step whose velocity update solves the contacts' LCP directly
// (Dantzig pivoting, ODE's "big matrix" stepper, the accurate one of dWorldStep and
// dWorldQuickStep), per contact
//     normal:   0 <= f_N,  with constraint force mixing `cfm` (a compliance: CFM = 0 is a
//               hard contact) and error reduction `erp` (the share of the penetration pushed
//               out per step, through the velocity);
//     bounce:   target normal velocity e |v_N(-)| when the contact is closing (dContactBounce,
//               bounce_vel = 0: at every speed);
//     friction: dContactApprox1 (|f_T,i| <= mu f_N per direction: a pyramid, ODE's Coulomb
//               model; without it ODE's mu is a force bound), directions fixed along x
//               (dContactFDir1) and y: exact for the planar motions here.
// The sphere of the bouncing mass and the box of the sliding mass do not turn
// (dBodySetMaxAngularSpeed 0: the problems are point masses); the disk turns freely (about
// y, by symmetry), as does the rocking block's box; the sphere (3D) is free, and its friction
// ODE's pyramid along x and y (not a cone: a slip at an angle to x meets a bound up to
// sqrt(2) mu f_N). Auto-disable is off.
//
// Mapping from e and mu (stated here, not hidden): surface.bounce = e, surface.mu = mu
// (Approx1: a coefficient), soft_erp = erp, soft_cfm = cfm. ODE's documentation: dWorldStep
// for accuracy, ERP 0.1 to 0.8 (0.2 by default), CFM small for a stiff contact (1e-10 is
// ODE's double-precision default); the inertia about y is kappa m R^2 (dMassSetSphereTotal,
// dMassSetCylinderTotal).
//
// Settings (parameters, defaults): erp 0.2 [0, 1]; cfm 1e-10 [0, 1]; size 0.1 m.
//
// Impulses: dJointFeedback's force on the body (f1) x dt, summed over the contact joints per
// problem contact (the rocking block: per corner, by the point's side of the centre);
// the plane is z = 0, so f1's z component is the normal force and its x component the
// friction along T. Work: one step and one force evaluation per dWorldStep; a direct
// solve: no iterations (0).
//
// Reference: R. Smith, "Open Dynamics Engine v0.5 User Guide", 2006 (ERP and CFM, contact
// surface parameters, dWorldStep).
// Moving contacts (Problem::contacts_move): the rocking block is ODE's own box, whose corners
// dCollide finds every step (peers/engine_scene.hpp); the Painleve rod is declined. A corner
// found penetrating (by up to |omega| b dt: detection is at the step's start) is pushed out by
// erp through the velocity, a separation velocity the block keeps as a hop after an impact.
#include <memory>
#include <string>

#include "peers/engine_scene.hpp"

namespace nsb {

class OdePeer final : public EnginePeer {
 public:
  explicit OdePeer(const Params& params);
  ~OdePeer() override;
  static ParamSpecs parameters_spec();

 private:
  struct World;
  void build(const engines::Scene& scene) override;
  engines::StepResult engine_step(double dt) override;

  std::unique_ptr<World> world_;
};

// ODE's version (pkg-config's, e.g. "0.16.2") and its precision.
std::string ode_version();

}  // namespace nsb
