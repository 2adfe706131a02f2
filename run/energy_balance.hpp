#pragma once
// The discrete energy balance of a run (EnergyBalance), in the run library so that `nsbench
// run` reports it (app/nsbench.cpp) as the studies measure it (studies/measures.hpp forwards it).
#include <limits>
#include <optional>
#include <string>

#include "integrators/integrator.hpp"
#include "problems/problem.hpp"

namespace nsb {

// f += L^T Lambda_N + T^T Lambda_T + T2^T Lambda_T2 (the rows a scheme has: tangents where it
// reports their impulses), of constant Contacts or of a ContactGeometry evaluated at a
// configuration: the contact impulses as generalised forces (EnergyBalance here, the momentum
// measures of studies/measures.hpp).
template <class Rows>
void add_contact_impulses(const Rows& rows, const Integrator& integrator, Vec& f) {
  f.noalias() += rows.normal.transpose() * integrator.impulses();
  if (rows.tangent.rows() && integrator.tangential_impulses().size()) f.noalias() += rows.tangent.transpose() * integrator.tangential_impulses();
  if (rows.tangent2.rows() && integrator.tangential_impulses2().size()) f.noalias() += rows.tangent2.transpose() * integrator.tangential_impulses2();
}

// Discrete energy balance: per step, the change of the scheme's own energy E
// (Integrator::energy(): what its balance is written for) minus the work of the loads and of
// the contact impulses, each impulse working along the scheme's velocities either side of it:
//     r = E_after - E_before - W_ext - W_c.
// An impulse P applied between the velocities v- and v+ (M (v+ - v-) = P + ...) changes the
// kinetic energy by exactly P^T (v- + v+) / 2, so
//     W_c   = 1/2 f^T (v- + v+),  f = L^T Lambda_N + T^T Lambda_T + T2^T Lambda_T2
//             (the rows at the configuration where the scheme applies them);
//     W_ext = F^T dU + V_load(U_after) - V_load(U_before): the scheme's quadrature of the work
//             of F_ext, less the part already in E (F_ext = -grad V_load for gravity: W_ext = 0
//             to round-off), dU the displacement that quadrature pairs with F.
// Per scheme (the derivation of each residual in its header's terms):
//   cd-lagrange, cd-lagrange-adaptive (staggered; report k: u = U_{k+1}, v = v_{k+3/2},
//     E = E_{k+1/2} = 1/2 P_{k+1/2}^T M^{-1} P_{k+1/2} + 1/2 (V(U_k) + V(U_{k+1}))): the step
//     ending at t_{k+1} applies P = tau_bar F_{k+1} + f_{k+1} at t_{k+1}, between v- = v_{k+1/2}
//     and v+ = v_{k+3/2} (tau_bar = tau: fixed step; (tau_{k+1} + tau_{k+2})/2: adaptive). The
//     energy reported after that step does not hold v_{k+3/2} yet: the balance of the jump at
//     t_{k+1} closes one report later, r_{k+1} = E_{k+3/2} - E_{k+1/2} - W_ext - W_c with
//         W_ext = 1/2 F_ext(t_{k+1})^T (U_{k+2} - U_k) + 1/2 (V_load(U_{k+2}) - V_load(U_k))
//         W_c   = 1/2 f_{k+1}^T (v_{k+1/2} + v_{k+3/2})  on the massive dofs;
//     a massless dof (singular mass) is quasi-static: its contact force Lambda / tau acts over
//     the dual cell [t_{k+1/2}, t_{k+3/2}], work 1/2 f_i (U_{k+2} - U_k)_i / tau = 1/2 f_i
//     (v_i + v_i'), its reported v the rate (U_{k+1} - U_k)_i / tau, here of reports k and k+1.
//     Then (fixed step; the momentum identity of the kick cancels every term but F_int's)
//         r_{k+1} = 1/2 (Psi(U_{k+2}) - Psi(U_k)) - 1/2 F_int(U_{k+1})^T (U_{k+2} - U_k),
//     the trapezoidal defect of the strain energy: 0 for a rigid body (Psi = 0), whatever the
//     impacts; for a linear elastic body (Psi = U^T K U / 2)
//         r_{k+1} = 1/4 (U_{k+2} - U_k)^T K (U_{k+2} - 2 U_{k+1} + U_k) = O(tau^2) per step,
//     oscillating with the motion and not zero. The adaptive variant chooses tau_{k+2} so that
//     this same residual, with its W_c = (1 - e)/2 Lambda^T g'_{k+1/2} (energy_target
//     impact-law, equal to W_c here when the contact law holds: g'_{k+3/2} = -e g'_{k+1/2}
//     where Lambda > 0) and friction's W_T, is <= energy_tol S on the steps with a root. The
//     start's half kick is no jump between two reported velocities (v_{1/2} is not reported):
//     the first residual is that of the jump at t_2, at the second report.
//   moreau-jean (report k: u = U_{k+1}, v = V_{k+1}; E = 1/2 V^T M V + V(U) at the report):
//     P = h F_bar + f between v- = V_k and v+ = V_{k+1}, F_bar = theta F_{k+1} + (1 - theta) F_k,
//     f with the rows at U_k; W_ext = F_ext_bar^T (U_{k+1} - U_k) + V_load(U_{k+1}) - V_load(U_k),
//     so that, F_int linear (the scheme's linearisation exact),
//         r = Psi(U_{k+1}) - Psi(U_k) - F_int_bar^T dU + h (1/2 - theta) F_bar^T (V_{k+1} - V_k):
//     0 to round-off for theta = 1/2 (the trapezoidal rule is exact on a quadratic Psi),
//     impacts included; for theta > 1/2 the numerical dissipation, -(theta - 1/2) h^2 F^T M^{-1}
//     F per step in free flight under a constant force F (-h^2 m g^2 / 2 for a mass at theta 1).
//     Not with projection = position (its correction moves U_{k+1} with no impulse).
// Other schemes are refused (InputError): their balance is not derived here.
// round_off(): a bound of the rounding in the summed residual, 8 eps sum_k S_k with S_k the size
// of the terms of step k (the kinetic and |potential| parts of both energies, |V_load| at
// both ends, |F^T dU| and |W_c|): one unit rounding per term of each step's eight, summed
// linearly over the steps (the worst case, not the random walk's sqrt(n)). A scheme whose
// balance is exact stays below it (tests/studies/measures_test.cpp).
class EnergyBalance {
 public:
  // After integrator.init(), before its first step.
  EnergyBalance(const Problem& problem, const Integrator& integrator);
  void add(const Integrator& integrator);  // after each step
  double residual() const { return residual_; }        // r of the last step closed (0 before)
  double cumulative() const { return cumulative_; }    // the sum of r so far
  double largest() const { return largest_; }          // max |r| so far
  double round_off() const { return 8.0 * std::numeric_limits<double>::epsilon() * size_sum_; }
  long closed() const { return closed_; }              // steps whose balance is closed
  // The sums over the closed steps of the residual's three terms, E_after - E_before, W_ext
  // and W_c: cumulative() is their difference to round-off. For the staggered schemes the
  // closed steps run from the second report to the one before the last (the last jump closes
  // a report later), so energy_change() is not E_end - E0 there.
  double energy_change() const { return energy_change_; }
  double load_work() const { return load_work_; }
  double contact_work() const { return contact_work_; }

 private:
  void contact_force(const Integrator& integrator, const Vec& u);  // f into f_
  void add_staggered(const Integrator& integrator);
  void add_step_end(const Integrator& integrator);
  void close(double residual, double size, double energy_change, double load_work, double contact_work);
  const Problem& problem_;
  bool staggered_ = false;
  double theta_ = 0.5;
  Vec massive_;                  // 1 on the dofs with mass, 0 on the massless
  Vec f_, f_prev_, f_ext_, f_ext_prev_;
  Vec u1_, u2_, v1_, v2_;        // u and v at the last two reports (or the initial state)
  std::optional<ContactGeometry> moving_rows_;
  Energy e1_;                    // the energy at the last report
  double t1_ = 0.0;              // its time
  double w_prev_massive_ = 0.0;  // staggered: 1/2 f^T (v- + v+) of the last step, massive dofs
  double residual_ = 0.0, cumulative_ = 0.0, largest_ = 0.0, size_sum_ = 0.0;
  double energy_change_ = 0.0, load_work_ = 0.0, contact_work_ = 0.0;
  long reports_ = 0, closed_ = 0;
};

// What `nsbench run` reports of the balance of a whole run (its line, summary.json's
// "energy_balance"): EnergyBalance's sums, or why no balance is derived for the scheme.
struct RunEnergyBalance {
  std::string not_derived;  // EnergyBalance's refusal ("energy balance: not derived for ..."); empty when derived
  long steps_closed = 0;
  double energy_change = 0.0, load_work = 0.0, contact_work = 0.0, residual = 0.0, round_off = 0.0;
};
// An EnergyBalance over a run where one is derived for the scheme, else the reason: what
// `nsbench run` feeds after every step.
class RunBalance {
 public:
  RunBalance(const Problem& problem, const Integrator& integrator);  // after integrator.init()
  bool derived() const { return balance_.has_value(); }
  void add(const Integrator& integrator) {
    if (balance_) balance_->add(integrator);
  }
  RunEnergyBalance figures() const;

 private:
  std::optional<EnergyBalance> balance_;
  std::string not_derived_;
};
// summary.json (summary_to_json's text) with the key "energy_balance" added: {"derived": false,
// "reason"} or {"derived": true, "steps_closed", "energy_change", "load_work", "contact_work",
// "residual", "round_off"} (absolute, the problem's energy units); every other key unchanged.
std::string with_energy_balance(const std::string& summary_json, const RunEnergyBalance& balance);

}  // namespace nsb
