#include "peers/bullet/bullet_peer.hpp"

#include <btBulletDynamicsCommon.h>
#include <fmt/format.h>

#include <cmath>

#include "integrators/registry.hpp"

#ifndef NSBENCH_BULLET_VERSION
#define NSBENCH_BULLET_VERSION "unknown"
#endif

namespace nsb {

namespace {
// btManifoldResult::calculateCombinedFriction clamps the product of the two coefficients to it.
constexpr double kMaxCombinedFriction = 10.0;
}  // namespace

struct BulletPeer::World {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &config};
  btStaticPlaneShape plane{btVector3(0, 0, 1), 0};
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btRigidBody> floor, body;
  double angle = 0.0;  // the disk's unwrapped angle about y

  ~World() {
    if (body) world.removeRigidBody(body.get());
    if (floor) world.removeRigidBody(floor.get());
  }
};

std::string bullet_version() { return fmt::format("{} (double precision)", NSBENCH_BULLET_VERSION); }

ParamSpecs BulletPeer::parameters_spec() {
  return {ParamSpec::integer("iterations", 100, 1, 1000000, "sequential-impulse sweeps per step (m_numIterations)"),
          ParamSpec::real("split_erp", 0.8, 0.0, 1.0, "split impulse's error reduction (m_erp2): the share of a penetration removed per step"),
          engines::size_spec()};
}

BulletPeer::BulletPeer(const Params& params) : EnginePeer(params) {}
BulletPeer::~BulletPeer() = default;

void BulletPeer::build(const engines::Scene& s) {
  if (s.mu > kMaxCombinedFriction)
    throw InputError(fmt::format("--integrator bullet: problem '{}' has mu = {}, above Bullet's cap on the combined friction (valid: mu <= {})",
                                 s.problem, s.mu, kMaxCombinedFriction));
  auto w = std::make_unique<World>();
  btContactSolverInfo& info = w->world.getSolverInfo();
  info.m_numIterations = static_cast<int>(params_.integer("iterations"));
  info.m_splitImpulse = 1;
  info.m_splitImpulsePenetrationThreshold = 0;
  info.m_erp2 = params_.real("split_erp");
  info.m_restitutionVelocityThreshold = 0;
  info.m_solverMode |= SOLVER_USE_2_FRICTION_DIRECTIONS;
  w->world.setGravity(btVector3(s.gx, 0, s.gz));

  btRigidBody::btRigidBodyConstructionInfo floor_info(0, nullptr, &w->plane);
  floor_info.m_restitution = 1;
  floor_info.m_friction = 1;
  w->floor = std::make_unique<btRigidBody>(floor_info);
  w->world.addRigidBody(w->floor.get());

  btVector3 inertia(0, 0, 0);
  switch (s.shape) {
    case engines::Shape::Sphere: w->shape = std::make_unique<btSphereShape>(s.radius); break;
    case engines::Shape::Box: w->shape = std::make_unique<btBoxShape>(btVector3(s.radius, s.radius, s.half_height)); break;
    case engines::Shape::Cylinder: w->shape = std::make_unique<btCylinderShape>(btVector3(s.radius, s.half_height, s.radius)); break;
  }
  w->shape->calculateLocalInertia(s.mass, inertia);
  if (s.rotates) inertia.setY(s.kappa * s.mass * s.radius * s.radius);
  btRigidBody::btRigidBodyConstructionInfo body_info(s.mass, nullptr, w->shape.get(), inertia);
  body_info.m_restitution = s.restitution;
  body_info.m_friction = s.mu;
  body_info.m_startWorldTransform.setIdentity();
  body_info.m_startWorldTransform.setOrigin(btVector3(s.start.x, 0, s.start.z));
  body_info.m_startWorldTransform.setRotation(btQuaternion(btVector3(0, 1, 0), s.start.angle));
  w->body = std::make_unique<btRigidBody>(body_info);
  w->body->setActivationState(DISABLE_DEACTIVATION);
  // Only touching or penetrating points reach the solver: a speculative point (found ahead,
  // within the breaking threshold) aims at e |v| - d / dt, d its distance, and over a few small
  // steps takes all of the rebound (e = 1 came to rest at dt = 1e-4).
  w->body->setContactProcessingThreshold(0);
  const double across = s.spatial ? 1 : 0;
  w->body->setLinearFactor(btVector3(s.moves_x ? 1 : 0, across, 1));
  w->body->setAngularFactor(s.rotates ? btVector3(across, 1, across) : btVector3(0, 0, 0));
  w->body->setLinearVelocity(btVector3(s.start.vx, s.start.vy, s.start.vz));
  w->body->setAngularVelocity(btVector3(s.start.wx, s.start.wy, s.start.wz));
  w->world.addRigidBody(w->body.get());
  w->angle = s.start.angle;
  world_ = std::move(w);
}

engines::StepResult BulletPeer::engine_step(double dt) {
  World& w = *world_;
  const double centre_x = w.body->getWorldTransform().getOrigin().x();
  w.world.stepSimulation(dt, 0);
  engines::StepResult r;
  for (int k = 0; k < w.dispatcher.getNumManifolds(); ++k) {
    const btPersistentManifold* m = w.dispatcher.getManifoldByIndexInternal(k);
    // The solver applies +impulse along the normal and friction directions to body 0.
    const double sign = m->getBody0() == w.body.get() ? 1.0 : -1.0;
    for (int j = 0; j < m->getNumContacts(); ++j) {
      const btManifoldPoint& p = m->getContactPoint(j);
      // A point the solver skipped (beyond the processing threshold) keeps its last impulse.
      if (p.getDistance() > m->getContactProcessingThreshold()) continue;
      const btVector3& at = sign > 0 ? p.getPositionWorldOnA() : p.getPositionWorldOnB();
      const btVector3 friction = sign * (p.m_appliedImpulseLateral1 * p.m_lateralFrictionDir1 + p.m_appliedImpulseLateral2 * p.m_lateralFrictionDir2);
      r.add(scene(), at.x(), centre_x, p.getAppliedImpulse(), friction.x(), friction.y());
    }
  }
  const btTransform& T = w.body->getWorldTransform();
  const btVector3 &x = T.getOrigin(), v = w.body->getLinearVelocity(), omega = w.body->getAngularVelocity();
  const btQuaternion q = T.getRotation();
  // A rotation about y only: q = (0, sin(a/2), 0, cos(a/2)) (the spatial sphere's angle is unused).
  w.angle = engines::unwrap(w.angle, 2.0 * std::atan2(q.y(), q.w()));
  r.pose = {x.x(), x.z(), w.angle, v.x(), v.z(), omega.y(), x.y(), v.y(), omega.x(), omega.z()};
  return r;
}

NSBENCH_INTEGRATOR({"bullet", "peer: Bullet's btDiscreteDynamicsWorld (sequential impulses, split impulse, e and mu per body)" + engines::scenes_only(),
                    &BulletPeer::parameters_spec, &make_from_params<Integrator, BulletPeer>, false, true,
                    {.friction = true, .moving_contacts = true, .friction_cone = true, .node_to_rigid_only = true}});

}  // namespace nsb
