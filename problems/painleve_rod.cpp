#include "problems/painleve_rod.hpp"
#include "core/deterministic_math.hpp"
#include "problems/floor_contacts.hpp"
#include "problems/registry.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace nsb {

namespace {

PainleveRodSpec painleve_spec(const Params& p) {
  PainleveRodSpec s;
  s.s = p.real("s");
  s.m = p.real("m");
  s.phi0_degrees = p.real("phi0");
  s.v0 = p.real("v0");
  s.mu = p.real("mu");
  s.g = p.real("g");
  return s;
}

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

}  // namespace

ParamSpecs PainleveRod::parameters_spec() {
  return {
      ParamSpec::real("s", 1.0, 0.0, 1e308, "half length [m]", true),
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass [kg]", true),
      ParamSpec::real("phi0", 31.0, 0.0, 90.0, "initial angle to the floor [degrees]", true, true),
      ParamSpec::real("v0", 30.0, -1e308, 1e308, "initial horizontal velocity of the centre [m/s] (not 0: sliding)"),
      ParamSpec::real("mu", 5.0 / 3.0, 0.0, 1e308, "Coulomb friction coefficient of end A (0: frictionless)"),
      ParamSpec::real("g", 10.0, 0.0, 1e308, "gravity [m/s^2]", true),
  };
}

PainleveRod::PainleveRod(const Params& params) : params_(params), s_(params.real("s")), exact_(painleve_spec(params)) {
  const double m = params.real("m");
  mass_ = Vec(3);
  mass_ << m, m, m * s_ * s_ / 3.0;
  load_ = Vec::Zero(3);
  load_[1] = -m * params.real("g");

  const Vec u0 = initial_state().u;
  contacts_ = floor_contacts({end_contact(u0)}, u0, 0.0, params.real("mu"));
}

void PainleveRod::evaluate_contacts(ConstVecRef u, ContactGeometry& out) const { write_floor_contact(0, end_contact(u), out); }

void PainleveRod::contact_slide(ConstVecRef u, VecRef s) const { s[0] = u[0] + s_ * nsb::dmath::cos(u[2]); }

State PainleveRod::initial_state() const { return *state(0.0); }

std::optional<double> PainleveRod::event_time(ExactEvent event) const {
  if (event == ExactEvent::jam && exact_.ending() == PainleveRodExact::Ending::jam) return exact_.end_time();
  return std::nullopt;
}

std::optional<State> PainleveRod::state(double t) const {
  const auto s = exact_.state(t);
  if (!s) return std::nullopt;
  State out;
  out.t = t;
  out.u = Vec(3);
  out.v = Vec(3);
  out.u << s->x, s->y, s->phi;
  out.v << s->vx, s->vy, s->vphi;
  return out;
}

std::vector<std::string> PainleveRod::observable_names() const {
  return {"phi", "x_end", "normal_force", "normal_force_exact"};
}

void PainleveRod::observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const {
  const auto ex = exact_.state(s.t);
  out[0] = s.u[2];
  out[1] = s.u[0] + s_ * nsb::dmath::cos(s.u[2]);
  out[2] = dt > 0.0 && impulses.size() > 0 ? impulses[0] / dt : 0.0;
  out[3] = ex ? exact_.normal_force(ex->phi, ex->vphi) : nan;
}

std::optional<FieldMesh> PainleveRod::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 2;
  mesh.add_vertex(0.0, s_ * nsb::dmath::sin(params_.real("phi0") * std::numbers::pi / 180.0), {0, 1}, 0);
  mesh.body_arrays = {{"half_length", 1}, {"angle", 1}, {"angular_velocity", 1}, {"orientation", 3}};
  return mesh;
}

void PainleveRod::body_data(const State& s, Eigen::Ref<Eigen::MatrixXd> out) const {
  const double phi = s.u[2];
  out.row(0) << s_, phi, s.v[2], nsb::dmath::cos(phi), -nsb::dmath::sin(phi), 0.0;
}

NSBENCH_PROBLEM({"painleve-rod", "rod sliding on one end on a rough floor up to its dynamic jam (moving contact; exact: Genot-Brogliato sliding phase)", &PainleveRod::parameters_spec, &make_from_params<Problem, PainleveRod>});

}  // namespace nsb
