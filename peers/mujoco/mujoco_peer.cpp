#include "peers/mujoco/mujoco_peer.hpp"

#include <fmt/format.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <mutex>
#include <numbers>

#include "integrators/registry.hpp"

namespace nsb {

namespace {

// The damping ratio whose linear oscillator rebounds with e (1 at e = 0: no rebound).
double damping_ratio(double e) {
  if (e <= 0.0) return 1.0;
  const double l = std::log(e);
  return -l / std::sqrt(std::numbers::pi * std::numbers::pi + l * l);
}

std::string g17(double x) { return fmt::format("{:.17g}", x); }

// The body's joints: a free joint for a spatial scene (qpos: position, quaternion (w, x, y, z);
// qvel: linear velocity (world), angular velocity (body frame)), else slide joints along x
// (when it moves in x) and z and a hinge about y (when it rotates): qpos the planar pose.
std::string mjcf_joints(const engines::Scene& s) {
  if (s.spatial) return R"(<freejoint name="free"/>)";
  std::string joints;
  if (s.moves_x) joints += R"(<joint name="x" type="slide" axis="1 0 0" damping="0"/>)";
  joints += R"(<joint name="z" type="slide" axis="0 0 1" damping="0"/>)";
  if (s.rotates) joints += R"(<joint name="a" type="hinge" axis="0 1 0" damping="0"/>)";
  return joints;
}

// The scene as MJCF. The body sits at the origin: its joints' qpos are the pose itself.
std::string mjcf(const engines::Scene& s, const Params& p) {
  const bool friction = s.mu > 0.0;
  const double imp = p.real("impedance");
  // solref is set per step (set_contact_spring); solimp and friction here, on both geoms.
  const std::string contact = fmt::format(R"(condim="{}" friction="{} 0 0" solimp="{} {} 0.001")", friction ? 3 : 1,
                                          g17(s.mu), g17(imp), g17(imp));
  std::string geom;
  switch (s.shape) {
    case engines::Shape::Sphere: geom = fmt::format(R"(type="sphere" size="{}")", g17(s.radius)); break;
    case engines::Shape::Box:
      geom = fmt::format(R"(type="box" size="{} {} {}")", g17(s.radius), g17(s.radius), g17(s.half_height));
      break;
    case engines::Shape::Cylinder:  // MuJoCo's cylinders run along z: turned to run along y
      geom = fmt::format(R"(type="cylinder" size="{} {}" euler="90 0 0")", g17(s.radius), g17(s.half_height));
      break;
  }
  const std::string joints = mjcf_joints(s);
  return fmt::format(
      R"(<mujoco model="nsbench">
  <compiler angle="degree" inertiafromgeom="true"/>
  <option timestep="0.001" gravity="{} 0 {}" integrator="{}" cone="{}" iterations="{}" tolerance="{}"
          noslip_iterations="{}" noslip_tolerance="{}"/>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1" {}/>
    <body name="body" pos="0 0 0">
      {}
      <geom name="body" {} mass="{}" {}/>
    </body>
  </worldbody>
</mujoco>
)",
      g17(s.gx), g17(s.gz), p.choice("integrator") == "rk4" ? "RK4" : (p.choice("integrator") == "euler" ? "Euler" : "implicit"),
      p.choice("cone"), p.integer("iterations"), g17(p.real("tolerance")), p.integer("noslip_iterations"), g17(p.real("tolerance")), contact,
      joints, geom, g17(s.mass), contact);
}

// The joints' qpos and qvel from the pose (mjcf_joints' layout).
void set_pose(const engines::Scene& s, const engines::Pose& p, mjData* d) {
  if (s.spatial) {
    const mjtNum x[3] = {p.x, p.y, p.z}, v[3] = {p.vx, p.vy, p.vz}, omega[3] = {p.wx, p.wy, p.wz};
    const mjtNum quat[4] = {std::cos(p.angle / 2), 0, std::sin(p.angle / 2), 0}, inverse[4] = {quat[0], 0, -quat[2], 0};
    mju_copy3(d->qpos, x);
    mju_copy4(d->qpos + 3, quat);
    mju_copy3(d->qvel, v);
    mju_rotVecQuat(d->qvel + 3, omega, inverse);  // the free joint's spin is in the body frame
    return;
  }
  int q = 0;
  if (s.moves_x) {
    d->qpos[q] = p.x;
    d->qvel[q++] = p.vx;
  }
  d->qpos[q] = p.z;
  d->qvel[q++] = p.vz;
  if (s.rotates) {
    d->qpos[q] = p.angle;
    d->qvel[q] = p.wy;
  }
}

// The pose from the joints' qpos and qvel (mjcf_joints' layout; a spatial scene's angle is
// not read: the problem does not use the orientation).
engines::Pose pose_of(const engines::Scene& s, const mjData* d) {
  engines::Pose p;
  if (s.spatial) {
    mjtNum omega[3];
    mju_rotVecQuat(omega, d->qvel + 3, d->qpos + 3);  // body frame -> world
    p.x = d->qpos[0], p.y = d->qpos[1], p.z = d->qpos[2];
    p.vx = d->qvel[0], p.vy = d->qvel[1], p.vz = d->qvel[2];
    p.wx = omega[0], p.wy = omega[1], p.wz = omega[2];
    return p;
  }
  int q = 0;
  if (s.moves_x) {
    p.x = d->qpos[q];
    p.vx = d->qvel[q++];
  }
  p.z = d->qpos[q];
  p.vz = d->qvel[q++];
  if (s.rotates) {
    p.angle = d->qpos[q];
    p.wy = d->qvel[q];
  }
  return p;
}

// MuJoCo's XML parser keeps global state: one model is compiled at a time.
std::mutex& loader_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace

struct MujocoPeer::World {
  mjModel* m = nullptr;
  mjData* d = nullptr;
  int body_geom = -1;
  double spring_dt = 0.0;  // the step the contact spring was set for
  ~World() {
    if (d) mj_deleteData(d);
    if (m) mj_deleteModel(m);
  }
};

std::string mujoco_version() { return mj_versionString(); }

ParamSpecs MujocoPeer::parameters_spec() {
  return {ParamSpec::choice("integrator", "implicit", {"euler", "implicit", "rk4"}, "MuJoCo's integrator (option integrator)"),
          ParamSpec::real("timeconst_steps", 2.0, 1.0, 1000.0, "contact spring's time constant tau over dt (MuJoCo: at least 2)"),
          ParamSpec::real("impedance", 0.9999, 0.9, 0.9999, "solimp d (dmin = dmax): how closely the contact follows its reference spring"),
          ParamSpec::choice("cone", "elliptic", {"elliptic", "pyramidal"}, "MuJoCo's friction cone (option cone)"),
          ParamSpec::integer("iterations", 100, 1, 1000000, "MuJoCo's constraint solver iterations (option iterations)"),
          ParamSpec::real("tolerance", 1e-10, 0.0, 1e-2, "MuJoCo's solver and noslip tolerance (option tolerance, noslip_tolerance)"),
          ParamSpec::integer("noslip_iterations", 20, 0, 1000000, "noslip post-processor iterations (0: off)"),
          engines::size_spec()};
}

MujocoPeer::MujocoPeer(const Params& params) : EnginePeer(params) {}
MujocoPeer::~MujocoPeer() = default;

ImpactAccuracy MujocoPeer::impact_accuracy() const {
  const double zeta = damping_ratio(scene().restitution);
  const double half_period = std::numbers::pi * params_.real("timeconst_steps") / std::sqrt(std::max(1.0 - zeta * zeta, 1e-12));
  return {half_period + 2.0, false};
}

void MujocoPeer::build(const engines::Scene& s) {
  const std::string xml = mjcf(s, params_);
  auto w = std::make_unique<World>();
  {
    const std::lock_guard lock(loader_mutex());
    auto vfs = std::make_unique<mjVFS>();
    mj_defaultVFS(vfs.get());
    if (mj_makeEmptyFileVFS(vfs.get(), "nsbench.xml", static_cast<int>(xml.size())) != 0)
      throw std::runtime_error("mujoco: could not make the in-memory model file");
    std::memcpy(vfs->filedata[vfs->nfile - 1], xml.data(), xml.size());
    char error[1000] = "";
    w->m = mj_loadXML("nsbench.xml", vfs.get(), error, sizeof(error));
    mj_deleteVFS(vfs.get());
    if (!w->m) throw std::runtime_error(fmt::format("mujoco: the scene did not compile: {}", error));
  }
  w->d = mj_makeData(w->m);
  w->body_geom = 1;  // the floor is geom 0
  set_pose(s, s.start, w->d);
  world_ = std::move(w);
}

void MujocoPeer::set_contact_spring(double dt) {
  const double omega = 1.0 / (params_.real("timeconst_steps") * dt);
  const double zeta = damping_ratio(scene().restitution);
  mjModel* m = world_->m;
  for (int g = 0; g < m->ngeom; ++g) {
    m->geom_solref[mjNREF * g] = -omega * omega;
    m->geom_solref[mjNREF * g + 1] = -2.0 * zeta * omega;
  }
  m->opt.timestep = dt;
  world_->spring_dt = dt;
}

engines::StepResult MujocoPeer::engine_step(double dt) {
  if (dt != world_->spring_dt) set_contact_spring(dt);
  mjModel* m = world_->m;
  mjData* d = world_->d;
  const engines::Scene& s = scene();
  const double centre_x = s.moves_x ? d->qpos[0] : 0.0;
  mj_step(m, d);
  engines::StepResult r;
  // mj_step computed the contacts and their forces at the step's start: the step's impulses.
  for (int i = 0; i < d->ncon; ++i) {
    const mjContact& c = d->contact[i];
    if (c.efc_address < 0) continue;
    mjtNum f[6];
    mj_contactForce(m, d, i, f);
    // f acts on geom2 along the frame's rows (normal, t1, t2) when geom2 is the body.
    const double sign = c.geom2 == world_->body_geom ? 1.0 : -1.0;
    r.add(s, c.pos[0], centre_x, f[0] * dt, sign * (f[1] * c.frame[3] + f[2] * c.frame[6]) * dt,
          sign * (f[1] * c.frame[4] + f[2] * c.frame[7]) * dt);
  }
  r.iterations = d->solver_iter;
  r.pose = pose_of(s, d);
  return r;
}

NSBENCH_INTEGRATOR({"mujoco", "peer: MuJoCo's mj_step (implicit, elliptic cone, noslip), soft contact with the spring-damper of e" + engines::scenes_only(),
                    &MujocoPeer::parameters_spec, &make_from_params<Integrator, MujocoPeer>, false, true,
                    {.friction = true, .moving_contacts = true, .friction_cone = true, .node_to_rigid_only = true}});

}  // namespace nsb
