// The discrete energy balance of run/energy_balance.hpp.
#include "run/energy_balance.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace nsb {

EnergyBalance::EnergyBalance(const Problem& problem, const Integrator& integrator)
    : problem_(problem),
      f_(Vec::Zero(problem.ndof())),
      f_prev_(Vec::Zero(problem.ndof())),
      f_ext_(Vec::Zero(problem.ndof())),
      f_ext_prev_(Vec::Zero(problem.ndof())),
      u1_(integrator.state().u),
      u2_(integrator.state().u),
      v1_(integrator.state().v),
      v2_(integrator.state().v),
      e1_(integrator.energy()),
      t1_(integrator.state().t) {
  const std::string& name = integrator.name();
  staggered_ = name == "cd-lagrange" || name == "cd-lagrange-adaptive";
  if (name == "moreau-jean") {
    if (integrator.parameters().choice("projection") != "none")
      throw InputError("energy balance: moreau-jean with projection = position moves U with no impulse");
    theta_ = integrator.parameters().real("theta");
  } else if (!staggered_) {
    throw InputError(fmt::format("energy balance: not derived for integrator '{}' (cd-lagrange, cd-lagrange-adaptive, moreau-jean)", name));
  }
  massive_ = (problem.mass_matrix().diagonal().array() > 0.0).select(Vec::Ones(problem.ndof()), Vec::Zero(problem.ndof()));
  if (problem.contacts_move()) moving_rows_ = problem.contact_geometry();
  problem.external_force(t1_, f_ext_prev_);
  f_ext_ = f_ext_prev_;
}

void EnergyBalance::contact_force(const Integrator& integrator, const Vec& u) {
  f_.setZero();
  if (moving_rows_) {
    problem_.evaluate_contacts(u, *moving_rows_);
    add_contact_impulses(*moving_rows_, integrator, f_);
  } else {
    add_contact_impulses(problem_.contacts(), integrator, f_);
  }
}

void EnergyBalance::add(const Integrator& integrator) {
  if (staggered_) add_staggered(integrator);
  else add_step_end(integrator);
  const State& s = integrator.state();
  u2_.swap(u1_);
  u1_ = s.u;
  v2_.swap(v1_);
  v1_ = s.v;
  e1_ = integrator.energy();
  t1_ = s.t;
  ++reports_;
}

void EnergyBalance::close(double residual, double size, double energy_change, double load_work, double contact_work) {
  residual_ = residual;
  cumulative_ += residual;
  largest_ = std::max(largest_, std::abs(residual));
  size_sum_ += size;
  energy_change_ += energy_change;
  load_work_ += load_work;
  contact_work_ += contact_work;
  ++closed_;
}

// Report j closes the jump at t_j of report j - 1 (f_prev_, between v2_ and v1_ on the massive
// dofs, v1_ and v on the massless), from the second on: v2_ is not v_{1/2} before.
void EnergyBalance::add_staggered(const Integrator& integrator) {
  const State& s = integrator.state();
  const Energy e = integrator.energy();
  if (reports_ >= 2) {
    const double load = problem_.load_potential(s.u), load_before = problem_.load_potential(u2_);
    const double force_work = 0.5 * f_ext_prev_.dot(s.u - u2_);
    const double massless = 0.5 * (f_prev_ - f_prev_.cwiseProduct(massive_)).dot(v1_ + s.v);
    const double w_c = w_prev_massive_ + massless;
    const double r = e.total() - e1_.total() - force_work - 0.5 * (load - load_before) - w_c;
    close(r, e.kinetic + std::abs(e.potential) + e1_.kinetic + std::abs(e1_.potential) + std::abs(load) + std::abs(load_before) +
                 std::abs(force_work) + std::abs(w_c), e.total() - e1_.total(), force_work + 0.5 * (load - load_before), w_c);
  }
  contact_force(integrator, s.u);  // the rows at U_{k+1}, where the scheme applies them
  w_prev_massive_ = 0.5 * f_.cwiseProduct(massive_).dot(v1_ + s.v);
  f_prev_.swap(f_);
  if (!problem_.external_force_is_constant()) problem_.external_force(s.t, f_ext_prev_);
}

void EnergyBalance::add_step_end(const Integrator& integrator) {
  const State& s = integrator.state();
  const Energy e = integrator.energy();
  contact_force(integrator, u1_);  // the rows at U_k, where the scheme applies them
  if (!problem_.external_force_is_constant()) problem_.external_force(s.t, f_ext_);
  const double load = problem_.load_potential(s.u), load_before = problem_.load_potential(u1_);
  const double force_work = (theta_ * f_ext_ + (1.0 - theta_) * f_ext_prev_).dot(s.u - u1_);
  const double w_c = 0.5 * f_.dot(v1_ + s.v);
  const double r = e.total() - e1_.total() - force_work - (load - load_before) - w_c;
  close(r, e.kinetic + std::abs(e.potential) + e1_.kinetic + std::abs(e1_.potential) + std::abs(load) + std::abs(load_before) +
               std::abs(force_work) + std::abs(w_c), e.total() - e1_.total(), force_work + (load - load_before), w_c);
  f_ext_prev_.swap(f_ext_);
  if (problem_.external_force_is_constant()) f_ext_ = f_ext_prev_;
}

RunBalance::RunBalance(const Problem& problem, const Integrator& integrator) {
  try {
    balance_.emplace(problem, integrator);
  } catch (const InputError& err) {
    not_derived_ = err.what();
  }
}

RunEnergyBalance RunBalance::figures() const {
  if (!balance_) return {not_derived_};
  const EnergyBalance& b = *balance_;
  return {"", b.closed(), b.energy_change(), b.load_work(), b.contact_work(), b.cumulative(), b.round_off()};
}

std::string with_energy_balance(const std::string& summary_json, const RunEnergyBalance& balance) {
  using nlohmann::json;
  json j = json::parse(summary_json);
  const auto number = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };  // a diverged run: null
  if (!balance.not_derived.empty())
    j["energy_balance"] = {{"derived", false}, {"reason", balance.not_derived}};
  else
    j["energy_balance"] = {{"derived", true}, {"steps_closed", balance.steps_closed},
                           {"energy_change", number(balance.energy_change)}, {"load_work", number(balance.load_work)},
                           {"contact_work", number(balance.contact_work)}, {"residual", number(balance.residual)},
                           {"round_off", number(balance.round_off)}};
  return j.dump(2) + "\n";
}

}  // namespace nsb
