#include "peers/ode/ode_peer.hpp"

#include <fmt/format.h>
#include <ode/ode.h>

#include <array>
#include <cmath>
#include <mutex>
#include <numbers>

#include "integrators/registry.hpp"

#ifndef NSBENCH_ODE_VERSION
#define NSBENCH_ODE_VERSION "unknown"
#endif

namespace nsb {

namespace {

constexpr int kMaxContacts = 4;

// ODE's global data once per process, its collision data once per thread (ODE 0.16 keeps
// collision buffers per thread: a study steps its cases on several).
void ode_thread_init() {
  static std::once_flag once;
  std::call_once(once, [] { dInitODE2(0); });
  thread_local const bool allocated = dAllocateODEDataForThread(dAllocateMaskAll) != 0;
  if (!allocated) throw std::runtime_error("ode: dAllocateODEDataForThread failed");
}

}  // namespace

struct OdePeer::World {
  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dGeomID plane = nullptr, geom = nullptr;
  dBodyID body = nullptr;
  dJointGroupID contacts = nullptr;
  dThreadingImplementationID threading = nullptr;
  dSurfaceParameters surface{};
  std::array<dJointFeedback, kMaxContacts> feedback{};
  double angle = 0.0;  // the disk's unwrapped angle about y

  ~World() {
    if (contacts) dJointGroupDestroy(contacts);
    if (space) dSpaceDestroy(space);  // and its geoms
    if (world) dWorldDestroy(world);  // and its body
    if (threading) dThreadingFreeImplementation(threading);
  }
};

std::string ode_version() {
  const bool dbl = dCheckConfiguration("ODE_double_precision") != 0;
  return fmt::format("{} ({} precision)", NSBENCH_ODE_VERSION, dbl ? "double" : "single");
}

ParamSpecs OdePeer::parameters_spec() {
  return {ParamSpec::real("erp", 0.2, 0.0, 1.0, "contact error reduction (soft_erp): the share of a penetration removed per step"),
          ParamSpec::real("cfm", 1e-10, 0.0, 1.0, "contact constraint force mixing (soft_cfm): its compliance, 0 = hard"),
          engines::size_spec()};
}

OdePeer::OdePeer(const Params& params) : EnginePeer(params) {}
OdePeer::~OdePeer() = default;

void OdePeer::build(const engines::Scene& s) {
  ode_thread_init();
  auto w = std::make_unique<World>();
  w->world = dWorldCreate();
  // A world steps through ODE's shared default threading object unless given its own, and two
  // worlds stepped at once on two threads then trip its assertion (threading_fake_sync.h):
  // each world gets its own single-threaded one.
  w->threading = dThreadingAllocateSelfThreadedImplementation();
  dWorldSetStepThreadingImplementation(w->world, dThreadingImplementationGetFunctions(w->threading), w->threading);
  dWorldSetGravity(w->world, s.gx, 0, s.gz);
  dWorldSetAutoDisableFlag(w->world, 0);
  w->space = dSimpleSpaceCreate(nullptr);
  w->contacts = dJointGroupCreate(0);
  w->plane = dCreatePlane(w->space, 0, 0, 1, 0);
  w->body = dBodyCreate(w->world);
  dMass mass;
  switch (s.shape) {
    case engines::Shape::Sphere:
      w->geom = dCreateSphere(w->space, s.radius);
      dMassSetSphereTotal(&mass, s.mass, s.radius);
      break;
    case engines::Shape::Box:
      w->geom = dCreateBox(w->space, 2 * s.radius, 2 * s.radius, 2 * s.half_height);
      dMassSetBoxTotal(&mass, s.mass, 2 * s.radius, 2 * s.radius, 2 * s.half_height);
      break;
    case engines::Shape::Cylinder:
      w->geom = dCreateCylinder(w->space, s.radius, 2 * s.half_height);
      dMassSetCylinderTotal(&mass, s.mass, 2, s.radius, 2 * s.half_height);  // axis y
      break;
  }
  dBodySetMass(w->body, &mass);
  dGeomSetBody(w->geom, w->body);
  if (s.shape == engines::Shape::Cylinder) {  // ODE's cylinders run along z: turned to run along y
    dMatrix3 R;
    dRFromAxisAndAngle(R, 1, 0, 0, std::numbers::pi / 2);
    dGeomSetOffsetRotation(w->geom, R);
  }
  if (!s.rotates) dBodySetMaxAngularSpeed(w->body, 0);
  dBodySetPosition(w->body, s.start.x, 0, s.start.z);
  dMatrix3 R0;
  dRFromAxisAndAngle(R0, 0, 1, 0, s.start.angle);
  dBodySetRotation(w->body, R0);
  dBodySetLinearVel(w->body, s.start.vx, s.start.vy, s.start.vz);
  dBodySetAngularVel(w->body, s.start.wx, s.start.wy, s.start.wz);
  w->surface.mode = dContactBounce | dContactSoftERP | dContactSoftCFM;
  if (s.mu > 0.0) w->surface.mode |= dContactApprox1 | dContactFDir1;
  w->surface.mu = s.mu;
  w->surface.bounce = s.restitution;
  w->surface.bounce_vel = 0;
  w->surface.soft_erp = params_.real("erp");
  w->surface.soft_cfm = params_.real("cfm");
  w->angle = s.start.angle;
  world_ = std::move(w);
}

engines::StepResult OdePeer::engine_step(double dt) {
  ode_thread_init();
  World& w = *world_;
  const double centre_x = dBodyGetPosition(w.body)[0];
  std::array<dContact, kMaxContacts> contact{};
  const int n = dCollide(w.geom, w.plane, kMaxContacts, &contact[0].geom, sizeof(dContact));
  for (int i = 0; i < n; ++i) {
    contact[i].surface = w.surface;
    contact[i].fdir1[0] = 1;
    contact[i].fdir1[1] = contact[i].fdir1[2] = 0;
    const dJointID j = dJointCreateContact(w.world, w.contacts, &contact[i]);
    dJointAttach(j, w.body, nullptr);
    dJointSetFeedback(j, &w.feedback[i]);
  }
  dWorldStep(w.world, dt);
  engines::StepResult r;
  for (int i = 0; i < n; ++i)
    r.add(scene(), contact[i].geom.pos[0], centre_x, w.feedback[i].f1[2] * dt, w.feedback[i].f1[0] * dt, w.feedback[i].f1[1] * dt);
  dJointGroupEmpty(w.contacts);
  const dReal* x = dBodyGetPosition(w.body);
  const dReal* v = dBodyGetLinearVel(w.body);
  const dReal* omega = dBodyGetAngularVel(w.body);
  const dReal* q = dBodyGetQuaternion(w.body);  // (w, x, y, z): a rotation about y only
  w.angle = engines::unwrap(w.angle, 2.0 * std::atan2(q[2], q[0]));
  r.pose = {x[0], x[2], w.angle, v[0], v[2], omega[1], x[1], v[1], omega[0], omega[2]};
  return r;
}

NSBENCH_INTEGRATOR({"ode", "peer: ODE's dWorldStep (direct LCP), contact joints with bounce e, mu (Approx1), ERP/CFM" + engines::scenes_only(),
                    &OdePeer::parameters_spec, &make_from_params<Integrator, OdePeer>, false, true,
                    {.friction = true, .moving_contacts = true, .friction_cone = true, .node_to_rigid_only = true}});

}  // namespace nsb
