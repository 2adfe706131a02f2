#include "check/conformance.hpp"
#include "core/deterministic_math.hpp"

#include <fmt/format.h>

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <random>

#include "core/threads.hpp"
#include "run/field_output.hpp"
#include "run/run.hpp"
#include "problems/block_2d.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/signorini_bar.hpp"
#include "problems/sliding_mass.hpp"
#include "problems/spring_chain.hpp"
#include "reference/modal_exact.hpp"

namespace nsb {

std::unique_ptr<Integrator> init_or_decline(const IntegratorEntry& entry, const Problem& problem) {
  auto integrator = entry.make(Params(entry.parameters()));
  try {
    integrator->init(problem, problem.initial_state());
  } catch (const InputError&) {
    return nullptr;
  }
  return integrator;
}

BounceObservation observe_bounces(const IntegratorEntry& entry, const BouncingMass& problem, double dt, int impacts) {
  auto integrator = entry.make(Params(entry.parameters()));
  integrator->init(problem, problem.initial_state());
  RunOptions options;
  options.dt = dt;
  options.t_end = problem.impact_time(impacts) + 0.5 * (problem.impact_time(impacts + 1) - problem.impact_time(impacts));
  if (problem.restitution() == 0.0) options.t_end += 0.1;  // no flight after it: watch the impact and the rest
  options.record_series = false;

  BounceObservation obs;
  obs.accuracy = integrator->impact_accuracy();
  const double g = 9.81;
  double q_prev = problem.initial_state().u[0], v_prev = problem.initial_state().v[0];
  bool in_contact = false;
  std::size_t next_mid = 1;
  run(problem, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const double lambda = it.impulses()[0];
    const double q = it.state().u[0], v = it.state().v[0];
    obs.min_impulse = std::min(obs.min_impulse, lambda);
    // A contact open at both ends of the step, by more than it can close in one step.
    const double reach = info.dt * std::max(std::abs(v_prev), std::abs(v)) + g * info.dt * info.dt;
    if (lambda != 0.0 && std::min(q_prev, q) > reach) ++obs.impulses_on_open_gap;
    if (lambda > 0.0 && !in_contact) obs.impact_times.push_back(it.state().t);
    in_contact = lambda > 0.0;
    if (next_mid <= static_cast<std::size_t>(impacts) &&
        it.state().t >= 0.5 * (problem.impact_time(next_mid) + problem.impact_time(next_mid + 1))) {
      obs.flight_energy.push_back(it.energy().total());
      ++next_mid;
    }
    q_prev = q;
    v_prev = v;
  });
  return obs;
}

BounceRatios bounce_ratios(const BounceObservation& obs, const BouncingMass& problem, double dt, int impacts) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  const auto n = static_cast<std::size_t>(impacts);
  BounceRatios r{obs.impact_times.size() < n ? inf : 0.0, obs.flight_energy.size() < n ? inf : 0.0};
  const double lag = obs.accuracy.lag_steps, e = problem.restitution(), g = 9.81;
  for (int i = 1; i <= impacts; ++i) {
    const auto k = static_cast<std::size_t>(i - 1);
    // Each impact adds at most the phase lag the scheme's own law implies (ImpactAccuracy:
    // 2 steps for a one-step impulse law).
    if (k < obs.impact_times.size())
      r.impact_time = std::max(r.impact_time, std::abs(obs.impact_times[k] - problem.impact_time(i)) / (lag * i * dt));
    // That phase error changes the impact speed by at most lag g dt per impact, an absolute
    // error carried into flight i whose speed is e^i w1: relative energy error
    // <= 2 (lag g dt i) / (e^i w1).
    if (k < obs.flight_energy.size()) {
      const double rel = std::abs(obs.flight_energy[k] / problem.energy_after_impact(i) - 1.0);
      r.flight_energy = std::max(r.flight_energy, rel / (2.0 * lag * g * dt * i / (nsb::dmath::pow(e, i) * problem.first_impact_speed())));
    }
  }
  return r;
}

namespace {

Block2d block(const std::map<std::string, std::string>& overrides) {
  return Block2d(Params(Block2d::parameters_spec(), overrides));
}

// sum_a m_a |v_a|: the scale of the linear momentum's round-off.
double momentum_scale(const Block2d& b, const State& s) {
  double p = 0.0;
  for (Index a = 0; a < b.nodes(); ++a) p += b.lumped_mass()[2 * a] * s.v.segment<2>(2 * a).norm();
  return p;
}

double final_error(const IntegratorEntry& entry, const Problem& chain, const State& initial, double dt, int steps) {
  auto integ = entry.make(Params(entry.parameters()));
  integ->init(chain, initial);
  for (int k = 0; k < steps; ++k) integ->step(dt);
  ModalExact exact(Params(ModalExact::parameters_spec()));
  exact.init(chain, initial);
  exact.step(integ->state().t - initial.t);
  return (integ->state().u - exact.state().u).lpNorm<Eigen::Infinity>();
}

// The chain's own velocities with the masses displaced by U_i = 0.05 sin(1 + i): the springs
// accelerate them from the first step. From the chain's own start, U = 0 and so F_int = 0, a
// first-order scheme whose error is led by the initial acceleration (symplectic Euler's
// velocity lagging half a step) measured 2. The displacement is small beside the velocities
// (about 0.05 against 1): cd-lagrange-adaptive shortens its steps below the requested one where
// the energy balance asks it to, and against the requested step it measures 2.03 here, 1.5 at
// 0.2 sin(1 + i) and 0.9 at 0.5 sin(1 + i).
State accelerated_start(const SpringChain& chain) {
  State s = chain.initial_state();
  for (Index i = 0; i < s.u.size(); ++i) s.u[i] = 0.05 * nsb::dmath::sin(1.0 + static_cast<double>(i));
  return s;
}

}  // namespace

std::optional<double> free_flight_momentum_drift(const IntegratorEntry& entry, int steps) {
  // Far above the floor, translating and spinning (the spin loads the block, so the internal
  // forces are not zero).
  const auto b = block({{"g", "0"}, {"height", "10"}, {"vx", "0.3"}, {"vy", "0.2"}, {"spin", "3"}, {"nx", "6"}, {"ny", "3"}});
  auto integ = init_or_decline(entry, b);
  if (!integ) return std::nullopt;
  const Eigen::Vector2d P0 = b.linear_momentum(b.initial_state().v);
  double worst = 0.0;
  for (int k = 0; k < steps; ++k) {
    integ->step(0.5 * b.stable_step());
    worst = std::max(worst, (b.linear_momentum(integ->state().v) - P0).norm());
  }
  return worst / momentum_scale(b, b.initial_state());
}

std::optional<SmoothOrder> smooth_order(const IntegratorEntry& entry) {
  const SpringChain chain(Params(SpringChain::parameters_spec(), {{"n", "5"}, {"wall", "none"}}));
  if (!init_or_decline(entry, chain)) return std::nullopt;
  const double dt = chain.stable_step() / 8.0;
  const int steps = 64;  // about 1.3 periods of the slowest mode at the coarsest step
  const State initial = accelerated_start(chain);
  SmoothOrder s;
  s.error_half = final_error(entry, chain, initial, dt / 2.0, 2 * steps);
  s.error_quarter = final_error(entry, chain, initial, dt / 4.0, 4 * steps);
  s.order = std::log2(s.error_half / s.error_quarter);
  return s;
}

double deformable_rise_bound() {
  const double p = kDeformableStepRatio;  // omega_max dt / 2
  return p / (1.0 - p);
}

std::optional<DeformableEnergy> deformable_energy(const IntegratorEntry& entry) {
  const SignoriniBar bar(Params(SignoriniBar::parameters_spec(), {{"N", "20"}}));
  auto integ = init_or_decline(entry, bar);
  if (!integ) return std::nullopt;
  const double e0 = integ->energy().total();  // the rigid motion's rho A L v0^2 / 2 > 0
  DeformableEnergy d;
  RunOptions options{kDeformableStepRatio * bar.stable_step(), kDeformableEnd, 1, false};
  const RunResult result = run(bar, *integ, options, [&](const Integrator& it, const StepInfo&) {
    d.worst_rise = std::max(d.worst_rise, (it.energy().total() - e0) / e0);
  });
  d.final_change = (integ->energy().total() - e0) / e0;
  d.t_final = integ->state().t;
  d.finished = result.status == RunStatus::Ok;
  d.message = result.message;
  return d;
}

const char* outcome_name(CheckVerdict::Outcome o) {
  switch (o) {
    case CheckVerdict::Outcome::Pass: return "pass";
    case CheckVerdict::Outcome::Fail: return "FAIL";
    case CheckVerdict::Outcome::NotMeasured: return "not measured";
  }
  return "?";
}

namespace {

using Outcome = CheckVerdict::Outcome;

CheckVerdict verdict(std::string property, bool pass, std::string figure) {
  return {std::move(property), pass ? Outcome::Pass : Outcome::Fail, std::move(figure)};
}

std::unique_ptr<BouncingMass> bouncing_mass(double e) {
  return std::make_unique<BouncingMass>(Params(BouncingMass::parameters_spec(), {{"e", fmt::format("{}", e)}}));
}

// A compliant contact's restitution (ImpactAccuracy::restitution_exact false) depends on the
// impact's phase within its few steps: held to kCompliantRestitution of e per impact, its flight
// energies so to 2 i kCompliantRestitution (E_i ~ e^2i). A dashpot tuned for e^2 misses by 10 %.
constexpr double kCompliantRestitution = 0.02;

// The flight energies observed on the bouncing mass `problem` (e = 0.9 for every scheme with a
// velocity-level impact law, whatever it declares; the declaration sets the bound).
CheckVerdict flight_energies(const BounceObservation& obs, const BouncingMass& problem, double dt, int impacts) {
  const double e = problem.restitution();
  if (obs.accuracy.restitution_exact) {
    const double ratio = bounce_ratios(obs, problem, dt, impacts).flight_energy;
    return verdict("flight energies", ratio <= 1.0, fmt::format("worst |E_i / (E0 e^2i) - 1| / bound = {:.3g} (<= 1)", ratio));
  }
  double worst = obs.flight_energy.size() < static_cast<std::size_t>(impacts) ? std::numeric_limits<double>::infinity() : 0.0;
  for (std::size_t k = 0; k < obs.flight_energy.size(); ++k)
    worst = std::max(worst, std::abs(obs.flight_energy[k] / problem.energy_after_impact(static_cast<int>(k) + 1) - 1.0) /
                                (2.0 * static_cast<double>(k + 1) * kCompliantRestitution));
  return verdict("flight energies", worst <= 1.0,
                 fmt::format("e = {}: worst |E_i / (E0 e^2i) - 1| / (2 i {:g}) = {:.3g} (<= 1): a compliant contact "
                             "(restitution_exact false) held to its restitution within {:g} %", e, kCompliantRestitution, worst,
                             100.0 * kCompliantRestitution));
}

void contact_law(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  const double dt = 1e-4;
  int impacts = 5;
  double e = 0.9;
  auto problem = bouncing_mass(e);
  std::string declined;
  bool compliant = false;
  if (auto integ = init_or_decline(entry, *problem); !integ) {
    // No velocity-level impact law (newmark-lm): the plastic impact, its first impact only.
    try {
      entry.make(Params(entry.parameters()))->init(*problem, problem->initial_state());
    } catch (const InputError& err) {
      declined = err.what();
    }
    e = 0.0;
    impacts = 1;
    problem = bouncing_mass(e);
  } else if (!integ->impact_accuracy().restitution_exact) {
    // A compliant contact's impact times drift with its restitution's error: timed at e = 1
    // (its flight energies at e = 0.9 all the same, below).
    compliant = true;
    problem = bouncing_mass(1.0);
  }
  const std::string where = fmt::format("bouncing-mass e = {}, dt = {:g}", compliant ? 1.0 : e, dt);
  if (!init_or_decline(entry, *problem)) {
    for (const char* p : {"impulse sign", "open contacts", "impact times", "flight energies"})
      out.push_back({p, Outcome::NotMeasured, fmt::format("declines the bouncing mass: {}", declined)});
    return;
  }
  const BounceObservation obs = observe_bounces(entry, *problem, dt, impacts);
  out.push_back(verdict("impulse sign", obs.min_impulse >= 0.0 && !obs.impact_times.empty(),
                        fmt::format("min Lambda {:.3g} (>= 0){}, {}", obs.min_impulse,
                                    obs.impact_times.empty() ? "; no positive impulse at all" : "", where)));
  out.push_back(verdict("open contacts", obs.impulses_on_open_gap == 0,
                        fmt::format("{} steps with an impulse on an open gap (0)", obs.impulses_on_open_gap)));
  const BounceRatios r = bounce_ratios(obs, *problem, dt, impacts);
  out.push_back(verdict("impact times", r.impact_time <= 1.0,
                        fmt::format("{} of {} impacts seen; worst |t_i - t_i,exact| / (lag_steps i dt) = {:.3g} (<= 1, "
                                    "lag_steps {:g})", std::min<std::size_t>(obs.impact_times.size(), impacts), impacts,
                                    r.impact_time, obs.accuracy.lag_steps)));
  if (e == 0.0) {
    out.push_back({"flight energies", Outcome::NotMeasured, fmt::format("no flight after a plastic impact ({})", declined)});
  } else if (!compliant) {
    out.push_back(flight_energies(obs, *problem, dt, impacts));
  } else {
    const auto lossy = bouncing_mass(e);  // its restitution measured at e = 0.9 all the same
    out.push_back(flight_energies(observe_bounces(entry, *lossy, dt, impacts), *lossy, dt, impacts));
  }
}

void step_counters(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  if (entry.reference) {
    out.push_back({"step counters", Outcome::NotMeasured, "a reference counts its ODE solver's own steps and right-hand sides"});
    return;
  }
  const auto problem = bouncing_mass(0.0);
  auto integ = init_or_decline(entry, *problem);
  if (!integ) {
    out.push_back({"step counters", Outcome::NotMeasured, "declines bouncing-mass"});
    return;
  }
  const int steps = 1000;
  long bad_steps = 0, bad_forces = 0;
  double worst_t = 0.0;
  for (int k = 0; k < steps; ++k) {
    const double t0 = integ->state().t;
    const WorkCounters before = integ->work();
    const StepInfo info = integ->step(1e-3);
    worst_t = std::max(worst_t, std::abs(integ->state().t - (t0 + info.dt)));
    bad_steps += integ->work().steps != before.steps + 1;
    bad_forces += integ->work().force_evaluations < before.force_evaluations + 1;
  }
  out.push_back(verdict("step counters", bad_steps == 0 && bad_forces == 0 && worst_t <= 1e-12,
                        fmt::format("over {} steps: {} without work().steps + 1, {} without a force evaluation, "
                                    "worst |t - (t0 + dt)| {:.3g}", steps, bad_steps, bad_forces, worst_t)));
}

void momentum(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  const auto drift = free_flight_momentum_drift(entry, 1000);
  if (!drift)
    out.push_back({"momentum", Outcome::NotMeasured, "declines block-2d"});
  else
    out.push_back(verdict("momentum", *drift <= 1e-10,
                          fmt::format("block-2d free flight, 1000 steps: |P - P0| / sum m|v| = {:.3g} (<= 1e-10)", *drift)));
}

void order(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  if (entry.reference) {
    out.push_back({"order", Outcome::NotMeasured, "a reference: its error is set by its tolerance, not by dt"});
    return;
  }
  const auto s = smooth_order(entry);
  if (!s) {
    out.push_back({"order", Outcome::NotMeasured, "declines the wall-free spring chain"});
    return;
  }
  out.push_back(verdict("order", s->order >= 1.0 - 0.1,
                        fmt::format("wall-free spring chain: {:.3f} (errors {:.3g}, {:.3g}; >= 0.9)", s->order,
                                    s->error_half, s->error_quarter)));
}

void deformable(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  const char* where = "signorini-bar N = 20, e = 0, dt = stable_step / 2";
  const auto d = deformable_energy(entry);
  if (!d) {
    std::string declined;
    try {
      const SignoriniBar bar(Params(SignoriniBar::parameters_spec(), {{"N", "20"}}));
      entry.make(Params(entry.parameters()))->init(bar, bar.initial_state());
    } catch (const InputError& err) {
      declined = err.what();
    }
    out.push_back({"deformable", Outcome::NotMeasured, fmt::format("declines {}: {}", where, declined)});
    return;
  }
  const double bound = deformable_rise_bound();
  const bool finite = d->finished && std::isfinite(d->worst_rise) && std::isfinite(d->final_change);
  out.push_back(verdict("deformable", finite && d->worst_rise <= bound,
                        fmt::format("{}, to t = {:g}: worst (E - E0) / E0 = {:+.3g} (<= {:.3g}: no energy gain in the exact "
                                    "solution, and a flight's oscillation at this step is at most that), final {:+.3g}{}",
                                    where, d->t_final, d->worst_rise, bound, d->final_change,
                                    d->finished ? "" : fmt::format("; the run stopped: {}", d->message))));
}

// A value outside the range of `s`, or "" when its range is the whole real line.
std::string outside(const ParamSpec& s) {
  if (s.kind == ParamSpec::Kind::Choice) return "no-such-choice";
  if (s.lower > -1e308) return fmt::format("{}", s.lower_open ? s.lower : s.lower - 1.0);
  if (s.upper < 1e308) return fmt::format("{}", s.upper_open ? s.upper : s.upper + 1.0);
  return "";
}

// Every value outside a declared range, and a non-finite value for every real parameter,
// must be refused (InputError) by `make`.
template <class Make>
CheckVerdict refuses_bad_parameters(const ParamSpecs& specs, Make make) {
  int tried = 0, accepted = 0;
  std::string first;
  auto attempt = [&](const ParamSpec& s, const std::string& value) {
    ++tried;
    try {
      make(Params(specs, {{s.name, value}}));
      if (!accepted++) first = fmt::format("; {} = {} accepted", s.name, value);
    } catch (const InputError&) {
    }
  };
  for (const auto& s : specs) {
    if (const std::string value = outside(s); !value.empty()) attempt(s, value);
    if (s.kind == ParamSpec::Kind::Real) attempt(s, "nan");
  }
  return verdict("bad parameters", accepted == 0, fmt::format("{} of {} out-of-range values rejected{}", tried - accepted, tried, first));
}

void bad_parameters(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  out.push_back(refuses_bad_parameters(entry.parameters(), [&](const Params& p) { entry.make(p); }));
}

void determinism(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  const auto b = block({{"height", "0.01"}, {"nx", "6"}, {"ny", "3"}, {"vx", "0.5"}, {"spin", "1"}});
  std::vector<State> finals;
  std::vector<Vec> impulses;
  for (int threads : {1, 2}) {
    ThreadScope scope(threads);
    auto integ = init_or_decline(entry, b);
    if (!integ) {
      out.push_back({"determinism", Outcome::NotMeasured, "declines block-2d"});
      return;
    }
    RunOptions options{1e-4, 0.03, 1, false};
    options.max_steps = 3000;  // an adaptive step may collapse on the stiff block
    run(b, *integ, options);
    finals.push_back(integ->state());
    impulses.push_back(integ->impulses());
  }
  const bool same = finals[0].t == finals[1].t && finals[0].u == finals[1].u && finals[0].v == finals[1].v &&
                    impulses[0] == impulses[1];
  out.push_back(verdict("determinism", same,
                        fmt::format("block-2d on its floor to t = {:.3g}, 1 vs 2 threads: {}", finals[0].t,
                                    same ? "bitwise equal" : fmt::format("max |du| {:.3g}", (finals[0].u - finals[1].u)
                                                                                            .lpNorm<Eigen::Infinity>()))));
}

void friction(const IntegratorEntry& entry, std::vector<CheckVerdict>& out) {
  const SlidingMass p(Params(SlidingMass::parameters_spec(), {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "2"}}));
  auto integ = entry.make(Params(entry.parameters()));
  if (!integ->treats_friction()) {
    std::string message;
    try {
      integ->init(p, p.initial_state());
    } catch (const InputError& err) {
      message = err.what();
    }
    out.push_back(verdict("friction", message.find("mu = ") != std::string::npos,
                          message.empty() ? "treats_friction() is false but the sliding mass (mu = 0.8) was accepted"
                                          : fmt::format("declines the sliding mass (mu = 0.8): {}", message)));
    return;
  }
  integ->init(p, p.initial_state());
  double worst_cone = 0.0, worst_gain = 0.0, previous = integ->energy().total();
  RunOptions options{1e-3, 2.0 * p.stop_time(), 1, false};
  run(p, *integ, options, [&](const Integrator& it, const StepInfo&) {
    const double n = it.impulses()[0], t = std::abs(it.tangential_impulses()[0]);
    worst_cone = std::max(worst_cone, t - 0.8 * n);
    const double e = it.energy().total();
    worst_gain = std::max(worst_gain, e - previous);
    previous = e;
  });
  // Scales: the weight's impulse per step m g dt ~ 1e-2; the energy m g d ~ 10 J.
  out.push_back(verdict("friction", worst_cone <= 1e-12 && worst_gain <= 1e-11,
                        fmt::format("sliding mass (mu = 0.8): worst |T| - mu N = {:.3g} (<= 0), worst energy gain "
                                    "{:.3g} J (<= 0)", worst_cone, worst_gain)));
}

// What `nsbench run --fields` needs: a mesh the writer accepts, and finite stresses and body
// arrays at the initial state.
void field_mesh(const Problem& p, const State& s0, std::vector<CheckVerdict>& out) {
  const auto mesh = p.field_mesh();
  if (!mesh) {
    out.push_back({"field mesh", Outcome::NotMeasured, "none: nsbench run --fields refuses this problem"});
    return;
  }
  try {
    check_field_mesh(*mesh, p, "field mesh");
  } catch (const InputError& err) {
    out.push_back({"field mesh", Outcome::Fail, err.what()});
    return;
  }
  Eigen::MatrixXd stress(mesh->nelements(), static_cast<Index>(mesh->stress_components.size()));
  Eigen::MatrixXd bodies(mesh->nbodies(), mesh->body_columns());
  stress.setConstant(std::numeric_limits<double>::quiet_NaN());  // a row left unwritten shows
  bodies.setConstant(std::numeric_limits<double>::quiet_NaN());
  if (mesh->nelements() > 0) p.cell_stress(s0.u, stress);
  if (!mesh->body_arrays.empty()) p.body_data(s0, bodies);
  out.push_back(verdict("field mesh", stress.allFinite() && bodies.allFinite(),
                        fmt::format("{} points, {} elements, {} bodies; stresses and body arrays finite at the "
                                    "initial state", mesh->npoints(), mesh->nelements(), mesh->nbodies())));
}

}  // namespace

namespace {

constexpr double kRowTolerance = 1e-5;

// The configurations the rows are tested at: u0 and up to five random admissible ones (every
// gap >= 0) within 0.05 scale of it.
std::vector<Vec> row_configurations(const Problem& p, const Vec& u0, double scale, const std::function<Vec()>& random_vector) {
  ContactGeometry at = p.contact_geometry();
  std::vector<Vec> configurations = {u0};
  for (int tries = 0; tries < 400 && configurations.size() < 6; ++tries) {
    const Vec u = u0 + 0.05 * scale * random_vector();
    p.evaluate_contacts(u, at);
    if (at.gap.minCoeff() >= 0.0) configurations.push_back(u);
  }
  return configurations;
}

// Worst |FD - row . d| / (|row| |d|) of one coordinate of the contacts (g, s or s2: `coordinate`
// writes it at a configuration) along d at u, against `rows` at u.
double row_error(const RowSpMat& rows, const std::function<void(const Vec&, Vec&)>& coordinate, const Vec& u, const Vec& d,
                 double eps) {
  Vec plus(rows.rows()), minus(rows.rows());
  coordinate(u + eps * d, plus);
  coordinate(u - eps * d, minus);
  double worst = 0.0;
  for (Index i = 0; i < rows.rows(); ++i) {
    const double along = rows.row(i).dot(d), size = rows.row(i).norm() * d.norm();
    worst = std::max(worst, std::abs((plus[i] - minus[i]) / (2.0 * eps) - along) / std::max(size, 1e-300));
  }
  return worst;
}

// How far the rows at u are from what the laws read (contact_points given): `fit`, the worst
// |row . d - a . x'(d)| / (|row| |d|) of the vector a that best maps the contact point's
// velocity x'(d) (by central differences of contact_points along d) to row . d, so that a row
// sees nothing but the point's motion; `frame`, the worst departure of a_T, a_T2 from unit
// length, from orthogonality to the normal direction a_L / |a_L| and to each other.
struct FrameErrors {
  double fit = 0.0, frame = 0.0;
};

FrameErrors frame_errors(const Problem& p, const ContactGeometry& at, const Vec& u, const std::vector<Vec>& directions,
                         double eps) {
  const Index nc = at.gap.size(), k = static_cast<Index>(directions.size());
  const bool three_d = at.tangent2.rows() > 0;
  std::vector<Eigen::MatrixXd> velocity(directions.size());  // x'(d_k), nc x 3
  Eigen::MatrixXd plus(nc, 3), minus(nc, 3);
  for (std::size_t j = 0; j < directions.size(); ++j) {
    p.contact_points(u, u + eps * directions[j], plus);
    p.contact_points(u, u - eps * directions[j], minus);
    velocity[j] = (plus - minus) / (2.0 * eps);
  }
  FrameErrors e;
  for (Index i = 0; i < nc; ++i) {
    Eigen::MatrixXd A(k, 3);
    for (Index j = 0; j < k; ++j) A.row(j) = velocity[static_cast<std::size_t>(j)].row(i);
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> solver(A);
    const auto fitted = [&](const RowSpMat& rows) {
      Vec b(k);
      for (Index j = 0; j < k; ++j) b[j] = rows.row(i).dot(directions[static_cast<std::size_t>(j)]);
      const Eigen::Vector3d a = solver.solve(b);
      for (Index j = 0; j < k; ++j)
        e.fit = std::max(e.fit, std::abs(A.row(j).dot(a) - b[j]) / std::max(rows.row(i).norm() * directions[static_cast<std::size_t>(j)].norm(), 1e-300));
      return a;
    };
    const Eigen::Vector3d n = fitted(at.normal).normalized(), t = fitted(at.tangent);
    e.frame = std::max({e.frame, std::abs(t.norm() - 1.0), std::abs(t.dot(n))});
    if (!three_d) continue;
    const Eigen::Vector3d t2 = fitted(at.tangent2);
    e.frame = std::max({e.frame, std::abs(t2.norm() - 1.0), std::abs(t2.dot(n)), std::abs(t.dot(t2))});
  }
  return e;
}

// The verdict of the contact rows, its figure saying what failed and what to do about it.
CheckVerdict contact_rows_verdict(const Problem& p, std::size_t configurations, double normal, bool located, const FrameErrors& frame,
                                  double tangent, double tangent2) {
  const bool friction = p.contacts().tangent.rows() > 0, three_d = p.contacts().tangent2.rows() > 0;
  std::string figure = fmt::format("{} contacts {}, {} configurations: L against d g, worst {:.3g}", p.ncontacts(),
                                   p.contacts_move() ? "moving" : "constant", configurations, normal);
  std::vector<std::string> fixes;
  if (normal > kRowTolerance) fixes.push_back("L(U) = dg/dU, the gradient of the gaps evaluate_contacts gives");
  if (!friction) {
    figure += "; frictionless";
  } else if (located) {
    figure += fmt::format("; {} against the contact points' velocity, worst {:.3g}; tangents orthonormal and orthogonal to "
                          "the normal, worst {:.3g}", three_d ? "T, T2" : "T", frame.fit, frame.frame);
    if (frame.fit > kRowTolerance)
      fixes.push_back("L, T, T2 U' the components of the contact point's velocity dx/dU U' (contact_points: the point of the "
                      "body that touches)");
    if (frame.frame > kRowTolerance)
      fixes.push_back("T, T2 along two orthonormal tangents orthogonal to the normal: unit, at right angles to each other and "
                      "to L (anisotropic friction otherwise)");
  } else {
    figure += fmt::format("; T against d s, worst {:.3g}{}", tangent, three_d ? fmt::format("; T2 against d s2, worst {:.3g}", tangent2) : "");
    if (std::max(tangent, tangent2) > kRowTolerance)
      fixes.push_back("T = ds/dU of contact_slide (T2 of contact_slide2), only the check reads them; or give contact_points, "
                      "and the check tests T and T2 against the points' motion instead, as a curved 3D obstacle needs "
                      "(docs/contacts.md)");
  }
  figure += fmt::format(" (<= {:g})", kRowTolerance);
  if (!fixes.empty()) figure += fmt::format("; fix: {}", fmt::join(fixes, "; "));
  return verdict("contact rows", fixes.empty(), figure);
}

}  // namespace

CheckVerdict check_contact_rows(const Problem& p, const Vec& u0) {
  const Index n = p.ndof(), nc = p.ncontacts();
  if (nc == 0) return {"contact rows", Outcome::Pass, "0 contacts: no rows to test"};
  ContactGeometry at = p.contact_geometry(), plus = p.contact_geometry();
  const bool friction = at.tangent.rows() > 0, three_d = at.tangent2.rows() > 0;
  Eigen::MatrixXd points(nc, 3);
  const bool located = friction && p.contact_points(u0, u0, points);  // the frame test, else T = ds/dU
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const auto random_vector = [&] { return Vec(Vec::NullaryExpr(n, [&] { return uniform(rng); })); };
  const double scale = 1.0 + u0.cwiseAbs().maxCoeff(), eps = 1e-6 * scale;
  const std::vector<Vec> configurations = row_configurations(p, u0, scale, random_vector);
  double worst_normal = 0.0, worst_tangent = 0.0, worst_tangent2 = 0.0;
  FrameErrors frame;
  for (const Vec& u : configurations) {
    p.evaluate_contacts(u, at);
    std::vector<Vec> directions;
    for (int k = 0; k < (located ? 6 : 3); ++k) directions.push_back(random_vector());
    for (const Vec& d : directions) {
      worst_normal = std::max(worst_normal, row_error(at.normal, [&](const Vec& x, Vec& g) { p.evaluate_contacts(x, plus); g = plus.gap; }, u, d, eps));
      if (friction && !located)
        worst_tangent = std::max(worst_tangent, row_error(at.tangent, [&](const Vec& x, Vec& s) { p.contact_slide(x, s); }, u, d, eps));
      if (three_d && !located)
        worst_tangent2 = std::max(worst_tangent2, row_error(at.tangent2, [&](const Vec& x, Vec& s) { p.contact_slide2(x, s); }, u, d, eps));
    }
    if (located) {
      const FrameErrors e = frame_errors(p, at, u, directions, eps);
      frame.fit = std::max(frame.fit, e.fit);
      frame.frame = std::max(frame.frame, e.frame);
    }
  }
  return contact_rows_verdict(p, configurations.size(), worst_normal, located, frame, worst_tangent, worst_tangent2);
}

std::vector<CheckVerdict> check_integrator(const IntegratorEntry& entry) {
  std::vector<CheckVerdict> out;
  using Property = void (*)(const IntegratorEntry&, std::vector<CheckVerdict>&);
  const std::vector<std::pair<const char*, Property>> properties = {
      {"contact law", contact_law}, {"step counters", step_counters}, {"momentum", momentum}, {"order", order},
      {"deformable", deformable}, {"bad parameters", bad_parameters}, {"determinism", determinism}, {"friction", friction}};
  for (const auto& [name, property] : properties) {
    try {
      property(entry, out);
    } catch (const std::exception& err) {
      out.push_back({name, Outcome::Fail, fmt::format("threw: {}", err.what())});
    }
  }
  out.push_back({"allocation", Outcome::NotMeasured,
                 "the allocation counter lives in the test binary (nsbench_tests \"[allocation]\")"});
  return out;
}

std::vector<CheckVerdict> check_problem(const ProblemEntry& entry, const std::map<std::string, std::string>& overrides) {
  std::vector<CheckVerdict> out;
  std::unique_ptr<Problem> p;
  const Params params(entry.parameters(), overrides);  // a bad --set: InputError, bad input rather than a failed property
  try {
    p = entry.make(params);
  } catch (const std::exception& err) {
    out.push_back({"defaults", Outcome::Fail, fmt::format("built with {} it threw: {}", overrides.empty() ? "its defaults" : "the parameters given", err.what())});
    return out;
  }
  const Index n = p->ndof();
  const State s0 = p->initial_state();
  try {
    check_contacts(p->contacts(), n, p->name());
    const Contacts& c = p->contacts();
    const double g_min = c.size() ? (c.gap_offset + c.normal * s0.u).minCoeff() : 0.0;
    out.push_back(verdict("contacts", g_min >= -1e-12 && s0.u.size() == n && s0.v.size() == n,
                          fmt::format("{} contacts, shapes consistent; initial min gap {:.3g} (>= 0)", c.size(), g_min)));
  } catch (const InputError& err) {
    out.push_back({"contacts", Outcome::Fail, err.what()});
  }
  const SpMat m = p->mass_matrix();
  const double asym = (m - SpMat(m.transpose())).norm(), min_diag = m.diagonal().minCoeff();
  out.push_back(verdict("mass", m.rows() == n && m.cols() == n && asym <= 1e-12 * m.norm() && min_diag >= 0.0,
                        fmt::format("{} x {}, asymmetry {:.3g}, smallest diagonal {:.3g} (>= 0)", m.rows(), m.cols(), asym, min_diag)));
  // F_int = dV/du: a central difference of the strain energy along a direction d against F_int . d.
  Vec d = Vec::LinSpaced(n, 1.0, 2.0).cwiseProduct(Vec::LinSpaced(n, -1.0, 1.0).array().sin().matrix());
  if (d.norm() == 0.0) d.setOnes();
  const Vec u = s0.u + 1e-3 * d;
  const double eps = 1e-6;
  Vec f(n);
  p->internal_force(u, f);
  const double dv = (p->strain_energy(u + eps * d) - p->strain_energy(u - eps * d)) / (2.0 * eps), fd = f.dot(d);
  const double rel = std::abs(dv - fd) / std::max({std::abs(fd), std::abs(dv), 1e-300});
  out.push_back(verdict("force = dV/du", rel <= 1e-5 || std::abs(dv - fd) <= 1e-12,
                        fmt::format("d V_int / du . d = {:.6g}, F_int . d = {:.6g}, relative difference {:.3g} (<= 1e-5)", dv, fd, rel)));
  const double dt = p->stable_step();
  out.push_back(verdict("stable step", dt > 0.0, fmt::format("{:.4g} (> 0; inf: no stiffness, 2 / omega_max)", dt)));
  try {
    out.push_back(check_contact_rows(*p, s0.u));
  } catch (const std::exception& err) {
    out.push_back({"contact rows", Outcome::Fail, fmt::format("threw: {}", err.what())});
  }
  field_mesh(*p, s0, out);
  out.push_back(refuses_bad_parameters(entry.parameters(), [&](const Params& q) { entry.make(q); }));
  return out;
}

}  // namespace nsb
