#include "studies/claims_conditions.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "integrators/registry.hpp"
#include "problems/block_2d.hpp"
#include "problems/bouncing_bar.hpp"
#include "problems/registry.hpp"
#include "problems/signorini_bar.hpp"
#include "run/run.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"

namespace nsb {

namespace {

constexpr double kBarStepFraction = 0.9;

using Overrides = std::map<std::string, std::string>;

// A Signorini bar registered as `problem` (signorini-bar, bouncing-bar: its registry entry's
// parameters), built as itself: the studies read its exact_* functions.
std::unique_ptr<SignoriniBar> make_bar(const std::string& problem, const Overrides& p) {
  return std::make_unique<SignoriniBar>(Params(find_problem(problem).parameters(), p), problem);
}

double bar_horizon(const SignoriniBar& bar) {
  if (bar.gravity() == 0.0) return bar.contact_start() + 1.5 * bar.contact_duration();
  const BouncingBarExact exact(bar.parameters(), 1e3);
  return exact.impact_time() + 16.0 * exact.wave_time();
}

// The observable k of bar_graph_observables() of a state after a step (dt, impulses).
std::array<double, 4> bar_values(const SignoriniBar& bar, const State& s, const Vec& impulses, double dt) {
  const Index mid = (bar.ndof() - 1) / 2;
  return {s.u[0], s.v[0], s.v[mid], dt > 0.0 ? impulses[0] / dt : 0.0};
}

// The exact observable k at t (the d'Alembert solution for g = 0, else the bouncing bar's).
std::function<double(double)> exact_value(const SignoriniBar& bar, std::size_t k, double t_end) {
  const double half = 0.5 * bar.parameters().real("L");
  if (bar.gravity() == 0.0) {
    switch (k) {
      case 0: return [&bar](double t) { return bar.exact_displacement(0.0, t); };
      case 1: return [&bar](double t) { return bar.exact_velocity(0.0, t); };
      case 2: return [&bar, half](double t) { return bar.exact_velocity(half, t); };
      default: return [&bar](double t) { return bar.exact_contact_force(t); };
    }
  }
  const auto exact = std::make_shared<BouncingBarExact>(bar.parameters(), t_end);
  switch (k) {
    case 0: return [exact](double t) { return exact->displacement(0.0, t); };
    case 1: return [exact](double t) { return exact->velocity(0.0, t); };
    case 2: return [exact, half](double t) { return exact->velocity(half, t); };
    default: return [exact](double t) { return exact->contact_force(t); };
  }
}

// One run of `integrator` on the bar: the graphs of the four observables, or the reason
// there are none (declined, failed).
std::string bar_graphs(const std::string& integrator, const SignoriniBar& bar, double dt, double t_end,
                       std::array<Polyline, 4>& graphs) {
  auto it = make_integrator(integrator);
  if (const auto why = init_or_decline(*it, bar)) return "declined: " + *why;
  const auto add = [&](const State& s, const Vec& impulses, double h) {
    const auto v = bar_values(bar, s, impulses, h);
    for (std::size_t k = 0; k < v.size(); ++k) graphs[k].add(s.t, v[k]);
  };
  add(it->state(), Vec::Zero(1), 0.0);
  RunOptions o;
  o.dt = dt;
  o.t_end = t_end;
  o.record_series = false;
  const RunResult r = run(bar, *it, o, [&](const Integrator& in, const StepInfo& info) { add(in.state(), in.impulses(), info.dt); });
  return r.status == RunStatus::Ok ? std::string() : std::string(status_name(r.status)) + ": " + r.message;
}

}  // namespace

const std::vector<std::string>& bar_graph_observables() {
  static const std::vector<std::string> names = {"u_contact", "v_contact", "v_mid", "contact_force"};
  return names;
}

std::vector<BarGraphFit> bar_hausdorff(const std::string& integrator, const std::vector<std::string>& masses) {
  std::vector<BarGraphFit> out;
  for (const std::string problem : {"signorini-bar", "bouncing-bar"})
    for (const auto& mass : masses) {
      const std::size_t first = out.size();
      for (const auto& obs : bar_graph_observables()) out.push_back({problem, mass, obs, {}, {}, {}, ""});
      for (int level = 0; level < kHausdorffLevels; ++level) {
        const auto bar = make_bar(problem, {{"mass", mass}, {"N", fmt::format("{}", 25L << level)}});
        const double dt = kBarStepFraction * bar->stable_step(), t_end = bar_horizon(*bar);
        std::array<Polyline, 4> graphs;
        const std::string why = bar_graphs(integrator, *bar, dt, t_end, graphs);
        for (std::size_t k = 0; k < graphs.size(); ++k) {
          BarGraphFit& f = out[first + k];
          if (f.note.empty()) f.note = why;
          f.dt.push_back(dt);
          if (!why.empty()) {
            f.distance.push_back(kNaN);
            continue;
          }
          const auto exact = exact_value(*bar, k, t_end);
          const Polyline reference = sampled_graph(exact, t_end, kHausdorffExactSamples, bar->gravity() == 0.0 ? bar->impact_times(t_end) : std::vector<double>{}, kHausdorffJumpFraction);
          f.distance.push_back(graph_errors(graphs[k], reference, exact, t_end).hausdorff);
        }
      }
      for (std::size_t k = first; k < out.size(); ++k) {
        std::vector<double> e = out[k].distance;
        for (double& x : e) x = x > 1e-11 ? x : kNaN;  // round-off, as in the hausdorff study
        out[k].fit = fit_order(out[k].dt, e);
      }
    }
  return out;
}

namespace {

// Contact phases of a run: the energy before the first impulse and after the last one,
// phases closer than `merge` in time joined.
struct PhaseTracker {
  double merge, scale;
  double before = kNaN, last_energy = kNaN, last_contact = -1e300, start_energy = kNaN;
  bool open = false;
  ImpactEnergy* out = nullptr;
  void close() {
    if (!open) return;
    const double jump = (last_energy - start_energy) / scale;
    ++out->phases;
    if (std::abs(jump) > out->worst_jump) out->worst_jump = std::abs(jump), out->worst_signed = jump;
    open = false;
  }
  void step(double t, double energy, bool contact) {
    if (contact) {
      if (open && t - last_contact > merge) close();
      if (!open) open = true, start_energy = before;
      last_contact = t;
      last_energy = energy;
      ++out->contact_steps;
    } else if (open && t - last_contact > merge) {
      close();
    }
    before = energy;
  }
};

}  // namespace

namespace {

std::string impact_remark(const SignoriniBar& bar, const WorkCounters& work, double dt, double node_speed) {
  std::string remark;
  const auto stable = work.extra.find("stable_step_with_contacts");
  if (stable != work.extra.end() && stable->second < dt)
    remark = fmt::format("dt {:.3g} s above the scheme's stable step with its contacts, {:.3g} s", dt, stable->second);
  const double impact_speed = std::sqrt(2.0 * bar.parameters().real("g") * bar.parameters().real("g0"));
  if (node_speed > 100.0 * impact_speed)
    remark += fmt::format("{}contact node's speed up to {:.3g} x the impact speed", remark.empty() ? "" : "; ", node_speed / impact_speed);
  return remark;
}

}  // namespace

ImpactEnergy bar_impact_energy(const std::string& integrator, const std::string& mass, double restitution) {
  ImpactEnergy out;
  const auto bar = make_bar("bouncing-bar", {{"mass", mass}, {"e", fmt::format("{}", restitution)}});
  const BouncingBarExact exact(bar->parameters(), 1e3);
  auto it = make_integrator(integrator);
  if (const auto why = init_or_decline(*it, *bar)) {
    out.note = "declined: " + *why;
    return out;
  }
  PhaseTracker phases{exact.wave_time(), exact.impact_energy()};
  phases.out = &out;
  phases.before = it->energy().total();
  const double e0 = phases.before;
  long steps = 0;
  double node_speed = 0.0;
  RunOptions o;
  o.dt = kBarStepFraction * bar->stable_step();
  o.t_end = exact.impact_time() + 3 * 16.0 * exact.wave_time();
  o.record_series = false;
  const RunResult r = run(*bar, *it, o, [&](const Integrator& in, const StepInfo&) {
    phases.step(in.state().t, in.energy().total(), in.impulses()[0] > 0.0);
    if (++steps % 10 == 0) out.history.emplace_back(in.state().t, (in.energy().total() - e0) / exact.impact_energy());
    node_speed = std::max(node_speed, std::abs(in.state().v[0]));
  });
  out.remark = impact_remark(*bar, it->work(), o.dt, node_speed);
  phases.close();
  out.work = it->work();
  if (r.status != RunStatus::Ok) out.note = std::string(status_name(r.status)) + ": " + r.message;
  return out;
}

namespace {

// Sum over the nodes of m_a |x_a| |v_a| and of m_a |v_a|: the scales of round-off.
std::pair<double, double> momentum_scales(const Block2d& b, const State& s) {
  double p = 0.0, j = 0.0;
  for (Index a = 0; a < b.nodes(); ++a) {
    const double m = b.lumped_mass()[2 * a], v = s.v.segment<2>(2 * a).norm();
    p += m * v;
    j += m * v * (b.reference_position(a) + s.u.segment<2>(2 * a)).norm();
  }
  return {p, j};
}

Block2d spinning(Overrides extra) {
  Overrides p = {{"vx", "0.3"}, {"spin", "3"}};
  p.insert(extra.begin(), extra.end());
  return Block2d(Params(Block2d::parameters_spec(), p));
}

void free_flight(const std::string& integrator, long steps, SpinningBlock& out) {
  const Block2d b = spinning({{"g", "0"}, {"height", "10"}, {"vy", "0.2"}});
  auto it = make_integrator(integrator);
  if (const auto why = init_or_decline(*it, b)) {
    out.note = "declined: " + *why;
    return;
  }
  const auto [p_scale, j_scale] = momentum_scales(b, b.initial_state());
  const Eigen::Vector2d P0 = b.linear_momentum(b.initial_state().v);
  const double J0 = b.angular_momentum(b.initial_state().u, b.initial_state().v), dt = 0.5 * b.stable_step();
  for (out.free_steps = 0; out.free_steps < steps; ++out.free_steps) {
    it->step(dt);
    const State& s = it->state();
    if (!s.u.allFinite() || !s.v.allFinite()) {
      out.free_linear = out.free_angular = kNaN;
      out.note = "free flight: non-finite state";
      return;
    }
    out.free_linear = std::max(out.free_linear, (b.linear_momentum(s.v) - P0).norm() / p_scale);
    out.free_angular = std::max(out.free_angular, std::abs(b.angular_momentum(s.u, s.v) - J0) / j_scale);
  }
}

// The moment about the origin of w F_ext + L^T Lambda, acting at the positions of s.
double step_moment(const Block2d& b, const State& s, const Vec& impulses, double w, double& impulse_moment) {
  const double g = b.parameters().real("g");
  const Vec force = b.gap_operator().transpose() * impulses;
  double moment = 0.0;
  for (Index a = 0; a < b.nodes(); ++a) {
    const double x = b.reference_position(a).x() + s.u[2 * a];
    const double m = x * force[2 * a + 1];
    moment += w * x * (-b.lumped_mass()[2 * a + 1] * g) + m;
    impulse_moment += std::abs(m);
  }
  return moment;
}

void on_floor(const std::string& integrator, long steps, SpinningBlock& out) {
  const Block2d b = spinning({});
  auto it = make_integrator(integrator);
  if (const auto why = init_or_decline(*it, b)) {
    out.note = "declined: " + *why;
    return;
  }
  const double tau = 0.5 * b.stable_step();
  it->step(tau);  // the start's half kick acts at U_0: the balance begins after it
  double J_prev = b.angular_momentum(it->state().u, it->state().v), moments = 0.0;
  const double j_scale = momentum_scales(b, b.initial_state()).second;
  for (out.floor_steps = 1; out.floor_steps < steps; ++out.floor_steps) {
    // Gravity's impulse is weighted as the scheme's momentum update weights it: the adaptive
    // variant's (tau_{k+1} + tau_{k+2})/2, not the requested tau (variable_step_weight).
    const double w = variable_step_weight(*it, it->step(tau).dt).value_or(tau);
    const State& s = it->state();
    const double J = b.angular_momentum(s.u, s.v);
    const double residual = std::abs(J - J_prev - step_moment(b, s, it->impulses(), w, moments));
    out.floor_angular = std::isfinite(residual) ? std::max(out.floor_angular, residual / j_scale) : kNaN;
    out.floor_history.emplace_back(s.t, residual / j_scale);
    out.contact_steps += it->impulses().sum() > 0.0;
    J_prev = J;
  }
  out.impulse_moment = moments / j_scale;
  out.work = it->work();
}

}  // namespace

SpinningBlock spinning_block(const std::string& integrator, long free_steps, long floor_steps) {
  SpinningBlock out;
  free_flight(integrator, free_steps, out);
  if (out.note.empty()) on_floor(integrator, floor_steps, out);
  return out;
}

namespace {

void energy_run(const std::string& scheme, const std::string& name, const Overrides& params, double dt, double t_end,
                EnergyFigures& e) {
  const auto problem = make_problem(name, params);
  RunOptions o;
  o.dt = dt;
  o.t_end = t_end;
  o.record_series = false;
  const bool adaptive = scheme == "cd-lagrange-adaptive";
  auto it = make_integrator(scheme);
  if (const auto why = init_or_decline(*it, *problem)) {
    e.note = "declined: " + *why;
    e.first = e.second = e.adaptive = kNaN;
    e.adaptive_ok = false;
    return;
  }
  double e1 = kNaN;
  const double tau_min = adaptive ? it->parameters().real("tau_min_ratio") * dt : 0.0;
  const RunResult r = run(*problem, *it, o, [&](const Integrator& in, const StepInfo& info) {
    const double energy = in.energy().total();
    if (std::isnan(e1)) e1 = energy;
    const double err = std::abs(energy - e1) / std::abs(e1);
    if (adaptive) {
      e.adaptive = std::max(e.adaptive, err);
      e.cfl = std::max(e.cfl, info.dt / problem->stable_step());
      e.collapsed += info.dt <= tau_min * (1.0 + 1e-12);
      if (in.state().t < t_end * (1 - 1e-12)) {  // the last step is cut to land on t_end
        e.dt_min = std::min(e.dt_min, info.dt);
        e.dt_max = std::max(e.dt_max, info.dt);
      }
    } else {
      double& half = in.state().t <= 0.5 * t_end ? e.first : e.second;
      half = std::max(half, err);
    }
  });
  if (adaptive) {
    e.adaptive_ok = e.adaptive_ok && r.status == RunStatus::Ok;
    const auto nr = r.work.extra.find("no_root_steps");
    e.no_root += nr == r.work.extra.end() ? 0.0 : nr->second;
  } else if (r.status != RunStatus::Ok) {
    e.first = e.second = kNaN;
    e.note = std::string(status_name(r.status)) + ": " + r.message;
  }
}

}  // namespace

EnergyFigures energy_runs(const std::string& integrator) {
  EnergyFigures e;
  const double period = 2.0 * std::sqrt(2.0 / 9.81);
  energy_run(integrator, "bouncing-mass", {{"e", "1"}, {"h0", "1"}}, 1e-3, 100 * period, e);
  energy_run(integrator, "spring-chain", {{"wall", "both"}, {"gap", "0.5"}}, 0.02, 40.0, e);
  return e;
}

LongRun long_run(const std::string& integrator, long target) {
  const auto problem = make_problem("bouncing-mass", {{"e", "1"}, {"h0", "1"}});
  const double g = 9.81, period = 2.0 * std::sqrt(2.0 * 1.0 / g), v_impact = std::sqrt(2.0 * g * 1.0), dt = 0.02;
  LongRun l;
  l.target = target;
  auto it = make_integrator(integrator);
  if (const auto why = init_or_decline(*it, *problem)) {
    l.note = "declined: " + *why;
    return l;
  }
  const long max_steps = static_cast<long>(2.0 * static_cast<double>(target) * period / dt), every = std::max(1L, target / 100);
  const double g0 = problem->gap_offset()[0];
  const SpMat& L = problem->gap_operator();
  double e1 = kNaN, penetration = 0.0;
  bool in_contact = false;
  l.ok = true;
  // Past the target-th impact until its contact phase ends: a scheme's reported energy within a
  // contact step can be a transient (schatzman-paoli's falls to 0, cd-penalty's by the spring's
  // share), the energy after the impact is the one the claim is about.
  while ((l.impacts < l.target || in_contact) && l.steps < max_steps) {
    it->step(dt);
    ++l.steps;
    const State& s = it->state();
    if (!s.u.allFinite() || !s.v.allFinite()) {
      l.ok = false;
      break;
    }
    if (std::isnan(e1)) e1 = it->energy().total();
    penetration = std::max(penetration, -(g0 + L.row(0).dot(s.u)));
    const bool contact = it->impulses()[0] > 0.0;
    if (contact && !in_contact && ++l.impacts % every == 0) l.history.emplace_back(l.impacts, (it->energy().total() - e1) / e1);
    in_contact = contact;
  }
  l.t_end = it->state().t;
  l.energy = (it->energy().total() - e1) / e1;
  l.penetration = penetration / (v_impact * dt);
  return l;
}

namespace {

RunWork counted_run(const std::string& integrator, const Problem& problem, double dt, double t_end) {
  RunWork out;
  auto it = make_integrator(integrator);
  if (const auto why = init_or_decline(*it, problem)) {
    out.note = "declined: " + *why;
    return out;
  }
  RunOptions o;
  o.dt = dt;
  o.t_end = t_end;
  o.record_series = false;
  const RunResult r = run(problem, *it, o, [&](const Integrator& in, const StepInfo&) { out.contact_steps += in.impulses().sum() > 0.0; });
  out.work = it->work();
  if (r.status != RunStatus::Ok) out.note = std::string(status_name(r.status)) + ": " + r.message;
  return out;
}

}  // namespace

RunWork signorini_bar_work(const std::string& integrator) {
  const auto bar = make_bar("signorini-bar", {{"mass", "lumped"}, {"N", "100"}});
  return counted_run(integrator, *bar, kBarStepFraction * bar->stable_step(), bar->contact_start() + 1.5 * bar->contact_duration());
}

RunWork bodies_contact_cost(const std::string& integrator) {
  const auto problem = make_problem("two-blocks", {{"g", "0"}, {"upper_vx", "0.5"}, {"upper_vy", "-1"}, {"e", "0"}});
  return counted_run(integrator, *problem, 1e-4, 0.1);
}

RunWork two_bars_contact_cost(const std::string& integrator) {
  const auto problem = make_problem("two-bars", {});
  const Params& p = problem->parameters();
  return counted_run(integrator, *problem, kBarStepFraction * problem->stable_step(),
                     2.0 * p.real("L2") / std::sqrt(p.real("E") / p.real("rho")));
}

}  // namespace nsb
