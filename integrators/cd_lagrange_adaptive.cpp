#include "integrators/cd_lagrange_adaptive.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "integrators/cd_lagrange.hpp"
#include "integrators/registry.hpp"

namespace nsb {

ParamSpecs CdLagrangeAdaptive::parameters_spec() {
  ParamSpecs specs = {
      ParamSpec::choice("momentum", "variational", {"variational", "talk"},
                        "momentum update: KMOW variable-step (variational) or the talk's (tau_k+tau_k+1)/(2 tau_k+1) weighting"),
      ParamSpec::choice("energy_target", "impact-law", {"impact-law", "no-work"},
                        "work of the impulses in the energy balance: Newton impact law, or none (the talk)"),
      ParamSpec::choice("step_rule", "energy-balance", {"energy-balance", "talk"},
                        "tau_{k+2}: the root of the discrete energy balance, or the talk's update (its equation for tau_{k+2}, iterated)"),
      ParamSpec::real("energy_tol", 1e-12, 1e-15, 1e-2,
                      "energy residual tolerance, relative to the energy terms (step_rule talk: relative change of tau_{k+2})"),
      ParamSpec::integer("max_iter", 100, 2, 100000, "energy residual evaluations per step"),
      ParamSpec::real("tau_min_ratio", 1e-3, 0.0, 1.0, "smallest step, times the first requested step", true),
      ParamSpec::real("tau_max_ratio", 10.0, 1.0, 1e308, "largest step (user cap), times the first requested step"),
      ParamSpec::real("cfl_fraction", 0.9, 0.0, 1.0, "steps stay below cfl_fraction * the problem's stable step", true),
  };
  // The contact solve is the fixed scheme's: same LCP parameters.
  const ParamSpecs lcp = CdLagrange::parameters_spec();
  specs.insert(specs.end(), lcp.begin(), lcp.end());
  return specs;
}

CdLagrangeAdaptive::CdLagrangeAdaptive(const Params& params)
    : Integrator(params),
      talk_momentum_(params.choice("momentum") == "talk"),
      no_work_(params.choice("energy_target") == "no-work"),
      talk_step_(params.choice("step_rule") == "talk"),
      energy_tol_(params.real("energy_tol")),
      tau_min_ratio_(params.real("tau_min_ratio")),
      tau_max_ratio_(params.real("tau_max_ratio")),
      cfl_fraction_(params.real("cfl_fraction")),
      max_iter_(params.integer("max_iter")) {
  lcp_ = lcp_options(params);
}

void CdLagrangeAdaptive::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  m_ = mass_.diagonal();
  minv_ = m_.cwiseInverse();

  const Index n = problem.ndof();
  u_prev_ = state_.u;
  u_next_ = Vec::Zero(n);
  v_next_ = Vec::Zero(n);
  f_int_ = Vec::Zero(n);
  f_ext_ = Vec::Zero(n);
  acc_ = Vec::Zero(n);
  gdot_prev_ = Vec::Zero(problem.ncontacts());
  problem.external_force(state_.t, f_ext_);
  e_ = problem.restitution();
  // Its steps are capped by the stable step: a NaN one (a plugin breaking the contract) or one
  // <= 0 would lift or collapse the cap without a word (std::min drops a NaN), so it declines.
  const double stable = problem.stable_step();
  if (!(stable > 0.0))
    throw InputError(fmt::format("integrator cd-lagrange-adaptive: problem {} reports the stable step {}, which caps its steps; "
                                 "valid: stable_step() > 0 (inf without stiffness)", problem.name(), stable));
  cfl_ = cfl_fraction_ * stable;
  contact_ = ImpulseContact(problem, minv_, lcp_);
  friction_ = problem.contacts().has_friction();
  if (friction_) {
    T_ = problem.contacts().tangent;
    tdot_prev_ = Vec::Zero(problem.ncontacts());
    tdot_next_ = Vec::Zero(problem.ncontacts());
  }
  started_ = false;
  auto& extra = work_.extra;
  iterations_ = &extra["energy_iterations"];
  no_root_ = &extra["no_root_steps"];
  capped_ = &extra["cfl_capped_steps"];
  unconverged_ = &extra["unconverged_steps"];
  max_residual_ = &extra["max_rel_residual"];
}

// acc_ = M^{-1} (F_ext(t) - F_int(u)) at the current u and the time t.
void CdLagrangeAdaptive::load_force(double t) {
  problem_->internal_force(state_.u, f_int_);
  ++work_.force_evaluations;
  if (!problem_->external_force_is_constant()) problem_->external_force(t, f_ext_);
  acc_.noalias() = minv_.cwiseProduct(f_ext_ - f_int_);
}

void CdLagrangeAdaptive::start(double dt) {
  tau_min_ = tau_min_ratio_ * dt;
  tau_max_ = tau_max_ratio_ * dt;
  const double up = step_bound();
  tau_ = std::min(dt, up);
  if (dt > up) ++*capped_;
  tau_prev_ = tau_;  // w_{1/2} = 1: the talk's weights start as after constant steps
  load_force(state_.t);
  state_.v += 0.5 * tau_ * acc_;  // P_{1/2}
  u_next_.noalias() = state_.u + tau_ * state_.v;
  load_cur_ = problem_->load_potential(state_.u);
  pot_cur_ = problem_->strain_energy(state_.u) + load_cur_;
  load_next_ = problem_->load_potential(u_next_);
  pot_next_ = problem_->strain_energy(u_next_) + load_next_;
}

StepInfo CdLagrangeAdaptive::advance(double dt_requested) {
  StepInfo info;
  if (!started_) {
    start(dt_requested);
    started_ = true;
  }
  // U_{k+1}: the trial position of the accepted step, computed when tau_{k+1} was chosen.
  std::swap(u_prev_, state_.u);
  std::swap(state_.u, u_next_);
  const double t_next = state_.t + tau_;
  pot_prev_ = pot_cur_;
  pot_cur_ = pot_next_;
  load_prev_ = load_cur_;
  load_cur_ = load_next_;
  load_force(t_next);

  kinetic_ = 0.5 * state_.v.dot(m_.cwiseProduct(state_.v));
  energy_ = kinetic_ + 0.5 * (pot_prev_ + pot_cur_);
  scale_ = kinetic_ + 0.5 * (std::abs(pot_prev_) + std::abs(pot_cur_));
  gdot_prev_.noalias() = problem_->gap_operator() * state_.v;
  if (friction_) tdot_prev_.noalias() = T_ * state_.v;
  fext_u_prev_ = f_ext_.dot(u_prev_);
  impulse_rate_prev_ = impulses_.dot(gdot_prev_);

  choose_next_step(info);
  std::swap(state_.v, v_next_);  // v = M^{-1} P_{k+3/2}
  info.dt = tau_;
  tau_prev_ = tau_;
  tau_ = tau_next_;
  return info;
}

// r(tau) = E_{k+3/2} - E_{k+1/2} - W_ext - W_Lambda for tau_{k+2} = tau; leaves the trial
// P_{k+3/2}, U_{k+2}, impulses and V(U_{k+2}) of that tau in the members.
double CdLagrangeAdaptive::residual(double tau, StepInfo& info) {
  if (talk_momentum_) {
    const double w_prev = (tau_prev_ + tau_) / (2.0 * tau_), w = (tau_ + tau) / (2.0 * tau);
    v_next_.noalias() = (w_prev / w) * state_.v + (tau_ / w) * acc_;
  } else {
    v_next_.noalias() = state_.v + (0.5 * (tau_ + tau)) * acc_;
  }
  // The free velocity depends on tau, so does the impulse: the contact is solved per trial.
  work_.lcp_iterations += contact_.apply(state_.u, state_.v, v_next_, impulses_, tangential_impulses_, info, work_);
  u_next_.noalias() = state_.u + tau * v_next_;
  load_next_ = problem_->load_potential(u_next_);
  pot_next_ = problem_->strain_energy(u_next_) + load_next_;
  const double kinetic = 0.5 * v_next_.dot(m_.cwiseProduct(v_next_));
  const double w_ext = 0.5 * (f_ext_.dot(u_next_) - fext_u_prev_) + 0.5 * (load_next_ - load_prev_);
  double w_impulse = no_work_ ? 0.0 : 0.5 * (1.0 - e_) * impulses_.dot(gdot_prev_);
  if (friction_) {
    tdot_next_.noalias() = T_ * v_next_;
    w_impulse += 0.5 * (tangential_impulses_.dot(tdot_next_) + tangential_impulses_.dot(tdot_prev_));
  }
  ++*iterations_;
  return kinetic + 0.5 * (pot_cur_ + pot_next_) - energy_ - w_ext - w_impulse;
}

// tau_up: the user cap or the CFL bound at U_{k+1}, whichever is smaller.
// A NaN or non-positive stable_step_at(u) ends the run (diverged, with the reason) instead of
// lifting the cap.
double CdLagrangeAdaptive::step_bound() const {
  if (problem_->is_linear()) return std::min(tau_max_, cfl_);
  const double stable = problem_->stable_step_at(state_.u);
  if (!(stable > 0.0))
    throw std::runtime_error(fmt::format("problem {} reports the stable step {} at t = {:.6g}; valid: stable_step_at(u) > 0",
                                         problem_->name(), stable, state_.t));
  return std::min(tau_max_, cfl_fraction_ * stable);
}

// The talk's update of tau_{k+2} (header) from the trial of the last residual() call.
double CdLagrangeAdaptive::talk_update() const {
  const Vec step = u_next_ - state_.u;
  const double numerator = 0.5 * v_next_.dot(m_.cwiseProduct(step));
  const double kinetic_next = 0.5 * v_next_.dot(m_.cwiseProduct(v_next_));
  const double impulse_rate = impulses_.dot(problem_->gap_operator() * v_next_);
  const double d = tau_prev_ / (2.0 * tau_ * tau_) * state_.v.dot(m_.cwiseProduct(state_.u - u_prev_)) + (pot_cur_ - load_cur_) +
                   0.5 * (kinetic_next + kinetic_) - f_ext_.dot(state_.u) - 0.5 * (impulse_rate + impulse_rate_prev_);
  return numerator / d;
}

void CdLagrangeAdaptive::choose_by_talk_update(StepInfo& info) {
  const double up = step_bound(), lo = std::min(tau_min_, up);
  double tau = std::clamp(tau_, lo, up);
  long updates = 0;
  bool settled = false;
  while (!settled && updates < max_iter_) {
    residual(tau, info);
    ++updates;
    const double next = talk_update();
    const double clamped = std::isfinite(next) && next > lo ? std::min(next, up) : lo;
    settled = std::abs(clamped - tau) <= energy_tol_ * tau;
    tau = clamped;
  }
  const double r = residual(tau, info);  // the trial of the step taken
  if (!settled) {
    ++*unconverged_;
    info.converged = false;
  }
  if (tau <= lo) ++*no_root_;
  if (tau >= up) ++*capped_;
  *max_residual_ = std::max(*max_residual_, std::abs(r) / (scale_ + std::numeric_limits<double>::min()));
  info.iterations = updates + 1;
  tau_next_ = tau;
}

void CdLagrangeAdaptive::choose_next_step(StepInfo& info) {
  if (talk_step_) {
    choose_by_talk_update(info);
    return;
  }
  struct Probe {
    double tau, r;
    double below, above;  // the probes next to it in the scan (its search interval)
  };
  const double up = step_bound();
  const double lo = std::min(tau_min_, up);
  const double tol = energy_tol_ * scale_ + std::numeric_limits<double>::min();
  const double pred = std::clamp(tau_, lo, up);

  long evals = 0;
  Probe last{}, best{};
  const auto eval = [&](double tau, double below, double above) {
    const Probe p{tau, residual(tau, info), below, above};
    ++evals;
    last = p;
    if (evals == 1 || std::abs(p.r) < std::abs(best.r)) best = p;
    return p;
  };
  const auto differ = [](const Probe& a, const Probe& b) { return (a.r < 0.0) != (b.r < 0.0); };
  const auto next_out = [&](int side, double d) { return side == 0 ? std::min(up, pred * (1.0 + d)) : std::max(lo, pred / (1.0 + d)); };

  std::optional<double> chosen;
  std::optional<std::pair<Probe, Probe>> bracket;
  const Probe first = eval(pred, next_out(1, 1e-3), next_out(0, 1e-3));
  if (std::abs(first.r) <= tol) chosen = pred;
  // Bracketing: probes moving out from the predictor, geometrically in ratio, both sides.
  Probe outer[2] = {first, first};  // outermost probe above, below the predictor
  bool open[2] = {pred < up, pred > lo};
  for (double d = 1e-3; !chosen && !bracket && (open[0] || open[1]) && evals < max_iter_; d *= 4.0) {
    for (int side = 0; side < 2 && !chosen && !bracket && evals < max_iter_; ++side) {
      if (!open[side]) continue;
      const double tau = next_out(side, d);
      open[side] = side == 0 ? tau < up : tau > lo;
      const double beyond = next_out(side, 4.0 * d);
      const Probe p = side == 0 ? eval(tau, outer[0].tau, beyond) : eval(tau, beyond, outer[1].tau);
      if (std::abs(p.r) <= tol)
        chosen = tau;
      else if (differ(p, outer[side]))
        bracket = std::pair{outer[side], p};
      outer[side] = p;
    }
  }
  // No sign change among the probes: golden section on |r| between the neighbours of the
  // best probe (r keeps its sign there unless two roots hide between probes, which then
  // gives a bracket). What is left at the end is the least residual: no root.
  if (!chosen && !bracket) {
    const double sign = best.r < 0.0 ? -1.0 : 1.0, g = 0.5 * (std::sqrt(5.0) - 1.0);
    const Probe centre = best;
    double a = centre.below, b = centre.above;
    Probe x1 = eval(b - g * (b - a), a, b), x2 = eval(a + g * (b - a), a, b);
    while (evals < max_iter_ && b - a > 1e-9 * b) {
      if (sign * x1.r <= 0.0 || sign * x2.r <= 0.0) {
        bracket = std::pair{centre, sign * x1.r <= 0.0 ? x1 : x2};
        break;
      }
      if (sign * x1.r < sign * x2.r) {
        b = x2.tau;
        x2 = x1;
        x1 = eval(b - g * (b - a), a, b);
      } else {
        a = x1.tau;
        x1 = x2;
        x2 = eval(a + g * (b - a), a, b);
      }
    }
    if (std::abs(best.r) <= tol) chosen = best.tau;
  }
  bool no_root = false;
  if (!chosen && bracket) {
    // Illinois: secant on the bracket, halving the stale end's residual so that both ends
    // move (superlinear, never leaves the bracket).
    auto [a, b] = *bracket;
    while (evals < max_iter_) {
      const Probe c = eval(b.tau - b.r * (b.tau - a.tau) / (b.r - a.r), 0, 0);
      if (std::abs(c.r) <= tol) {
        chosen = c.tau;
        break;
      }
      if (std::abs(b.tau - a.tau) <= 4.0 * std::numeric_limits<double>::epsilon() * c.tau) break;
      if (differ(c, b))
        a = b;
      else
        a.r *= 0.5;
      b = c;
    }
    if (!chosen) {
      ++*unconverged_;
      info.converged = false;
    }
  } else if (!chosen) {
    no_root = true;
    ++*no_root_;
  }
  if (!chosen) chosen = best.tau;
  if (*chosen != last.tau) eval(*chosen, 0, 0);
  if (tau_ > up || (no_root && *chosen == up)) ++*capped_;
  *max_residual_ = std::max(*max_residual_, std::abs(last.r) / (scale_ + std::numeric_limits<double>::min()));
  info.iterations = evals;
  tau_next_ = *chosen;
}

Energy CdLagrangeAdaptive::energy() const {
  if (!started_) return Integrator::energy();
  return {kinetic_, 0.5 * (pot_prev_ + pot_cur_)};
}

NSBENCH_INTEGRATOR({"cd-lagrange-adaptive", "CD-Lagrange with the step chosen from the discrete energy balance (KMOW variable step), CFL-capped", &CdLagrangeAdaptive::parameters_spec, &make_from_params<Integrator, CdLagrangeAdaptive>, false, false,
                    {.friction = true, .mass = MassNeed::DiagonalPositive}});

}  // namespace nsb
