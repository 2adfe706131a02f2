#pragma once
// The generic properties every integrator is held to, whoever wrote it: the built-ins in the
// Catch2 tests (tests/integrators/*_test.cpp call the measurements below) and any plugin by
// `nsbench check --integrator NAME` (check_integrator). One implementation for both.
//
//   impulse sign        every impulse Lambda_i >= 0 (a positive impulse pushes apart)
//   open contacts       no impulse on a contact open at both ends of a step by more than it
//                       can close in that step (dt max|v| + g dt^2)
//   impact times        on the bouncing mass (e = 0.9, dt = 1e-4, 5 impacts; e = 1 for a
//                       scheme whose restitution is not exact; e = 0 and the first impact for
//                       one without a velocity-level impact law, which declines e > 0):
//                       |t_i - t_i,exact| <= lag_steps i dt (the scheme's impact_accuracy())
//   flight energies     E in flight i within 2 lag_steps g dt i / (e^i w1) of E0 e^(2i); for
//                       a compliant contact (restitution_exact false, whose impact times
//                       are taken at e = 1) measured at e = 0.9 all the same, within
//                       2 i 0.02 (its restitution within 2 %): the declaration sets the
//                       bound, not whether the restitution is tested
//   step counters       step() advances state().t by the StepInfo's dt and adds 1 to
//                       work().steps and >= 1 to work().force_evaluations (not for a
//                       reference, which counts its ODE solver's steps)
//   momentum            block-2d in free flight (no gravity): sum_a m_a v_a kept to 1e-10 of
//                       sum_a m_a |v_a| over 1000 steps (sum_a F_int,a = 0)
//   order               wall-free spring chain against its modal-exact solution: the measured
//                       order log2(e(dt/2) / e(dt/4)) is at least 0.9 (a consistent scheme;
//                       not for a reference, whose error is its tolerance)
//   deformable          signorini-bar (N = 20, lumped, e = 0, no gravity) at half its stable
//                       step to t = 4, through its contact (t = 0 to 2) and the flight after:
//                       the run ends, its states finite, and the energy never rises above E0
//                       by more than deformable_rise_bound() of E0 (below)
//   bad parameters      every declared parameter refuses a value outside its range
//   determinism         block-2d on its floor, 1 thread and 2 threads: bitwise equal states
//   friction            treats_friction(): |tangential impulse| <= mu x normal impulse on
//                       the sliding mass and no energy gain; otherwise init declines, naming mu
//   allocation          not measured here: the allocation counter replaces malloc and lives
//                       in the test binary (nsbench_tests "[allocation]" for the built-ins)
//
// Exact solutions: problems/bouncing_mass.hpp (impact times, flight energies),
// reference/modal_exact.hpp (the chain).
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "problems/problem.hpp"

namespace nsb {

class BouncingMass;

// The integrator of `entry` with its defaults, initialised on the problem's initial state;
// null when it declines the problem (InputError at init: a mass model, a nonlinearity,
// friction it does not treat).
std::unique_ptr<Integrator> init_or_decline(const IntegratorEntry& entry, const Problem& problem);

struct BounceObservation {
  std::vector<double> impact_times;   // the first step with an impulse after one without
  std::vector<double> flight_energy;  // energy at mid-flight of flight i (i = 1, 2, ...)
  double min_impulse = 0.0;
  long impulses_on_open_gap = 0;
  ImpactAccuracy accuracy;
};

// Runs `entry` (defaults) on `problem` with step dt to mid-flight after impact `impacts`.
BounceObservation observe_bounces(const IntegratorEntry& entry, const BouncingMass& problem, double dt, int impacts);

// Worst ratio of error to bound over the impacts (<= 1: within the scheme's declared
// impact_accuracy); +inf when fewer impacts or flights than `impacts` were seen.
struct BounceRatios {
  double impact_time = 0.0, flight_energy = 0.0;
};
BounceRatios bounce_ratios(const BounceObservation& obs, const BouncingMass& problem, double dt, int impacts);

// Largest |P(t) - P0| / sum_a m_a |v_a| over `steps` steps of block-2d in free flight
// (spinning, no gravity); nullopt when the integrator declines the block.
std::optional<double> free_flight_momentum_drift(const IntegratorEntry& entry, int steps);

struct SmoothOrder {
  double error_half = 0.0, error_quarter = 0.0, order = 0.0;  // at dt/2, dt/4 of stable_step / 8
};
// Displacement error at the final time on the wall-free 5-mass spring chain against its
// modal-exact solution, 64 steps of stable_step / 8 halved twice, from a state with both
// velocity and acceleration (the masses displaced by 0.05 sin(1 + i), so that a first-order
// scheme measures 1, not the 2 a start at rest in the springs hid it behind); nullopt when the
// integrator declines the chain.
std::optional<SmoothOrder> smooth_order(const IntegratorEntry& entry);

// The deformable case. Its exact solution gains no energy: the continuum bar conserves it, the
// lumped semi-discrete one loses some at each node impact (e = 0), and no load works (g = 0).
// What a scheme reports, E_n = K(v_n) + V(u_n), still oscillates in flight with no gain: a
// consistent scheme that conserves a modified energy H of each mode omega reports E_n within a
// factor 1 -+ p of it, p = omega dt / 2 for the least accurate such, symplectic Euler (H =
// E_n - omega^2 dt u_n v_n / 2, and |omega u v| <= E_n), (omega dt / 2)^2 for the central
// difference, 0 for the trapezoidal rule. From the rigid start (E0 = H: all kinetic, omega =
// 0), with a contact that loses H and omega <= omega_max = 2 / stable_step, E_n <= E0 / (1 -
// p), p = dt / stable_step: a rise of at most p / (1 - p) of E0. A larger rise is energy the
// scheme made; so is a non-finite state.
inline constexpr double kDeformableStepRatio = 0.5;  // dt / stable_step
inline constexpr double kDeformableEnd = 4.0;        // the contact lasts T = 2 L / c = 2 from t = 0
double deformable_rise_bound();                      // p / (1 - p)
struct DeformableEnergy {
  double worst_rise = 0.0;    // max over the steps of (E - E0) / E0
  double final_change = 0.0;  // (E_end - E0) / E0
  double t_final = 0.0;
  bool finished = false;      // the run reached t_end (not diverged, not over its step budget)
  std::string message;        // why it stopped otherwise
};
// The integrator of `entry` (defaults) on the deformable case; nullopt when it declines the bar.
std::optional<DeformableEnergy> deformable_energy(const IntegratorEntry& entry);

// One line of `nsbench check`.
struct CheckVerdict {
  enum class Outcome { Pass, Fail, NotMeasured };
  std::string property;
  Outcome outcome = Outcome::Pass;
  std::string figure;  // the measured figure against its bound, or why not measured
};
const char* outcome_name(CheckVerdict::Outcome o);

// Every property above for `entry`. An exception from the integrator (other than a declined
// problem, which some properties expect) is a failed property, not an abort.
std::vector<CheckVerdict> check_integrator(const IntegratorEntry& entry);

// A problem's contract (problems/problem.hpp): built with its defaults and `overrides`
// (`nsbench check --problem P --set key=value`; a bad one throws InputError); contacts whose
// shapes agree, initially open or touching; a symmetric mass with a non-negative diagonal;
// F_int = dV_int/du (central difference of strain_energy along a fixed direction);
// a positive stable_step() (inf without stiffness); the contact rows (check_contact_rows) at
// random admissible configurations (for constant kinematics too, where they hold to
// round-off); a field mesh `nsbench run --fields` can write (check_field_mesh), with finite
// stresses and body arrays at the initial state (not measured without one); bad parameters
// refused.
std::vector<CheckVerdict> check_problem(const ProblemEntry& entry, const std::map<std::string, std::string>& overrides = {});

// The contact rows' part of check_problem for one problem around configuration u0, at u0 and
// at up to five random admissible configurations (every gap >= 0) within 0.05 (1 + max|u0|)
// of it, along random directions d (three, six with contact points):
//   - L(U) against central differences of g(U): L = dg/dU;
//   - with friction and Problem::contact_points given, what the laws read: the vectors a_L,
//     a_T, a_T2 that best map the contact point's velocity x'(d) (central differences of
//     contact_points) to L d, T d, T2 d must reproduce every row . d (a row sees nothing but
//     the point's motion), a_T and a_T2 unit, orthogonal to a_L and to each other (isotropic
//     Coulomb friction; no integrability T = ds/dU, which curved 3D obstacles cannot meet);
//   - with friction and no contact points: T(U) against central differences of contact_slide
//     (T = ds/dU), T2 of contact_slide2.
// Error of a row: |FD - row . d| / (|row| |d|); every error <= 1e-5 to pass. The figure says how
// many configurations were admissible and, on a failure, what to change.
CheckVerdict check_contact_rows(const Problem& p, const Vec& u0);

}  // namespace nsb
