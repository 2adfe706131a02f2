#pragma once
// The measurements behind the properties matrix (studies/properties.cpp): each
// claim of A. Gravouil's talk "CD-Lagrange" (2022) under the talk's own conditions (deformable
// body against a rigid obstacle, diagonal mass, the singular mass of its line of work: Di Stasio,
// Dureisseix, Gravouil et al., "An explicit time-integrator with singular mass for non-smooth
// dynamics", Comput. Mech. 2021) and beyond them (lumped and consistent masses, other
// observables). Each function takes the integrator's name, so the properties matrix
// (studies/properties.cpp) runs the same measurement for every scheme.
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.hpp"
#include "studies/study.hpp"

namespace nsb {

// (2) Hausdorff distance on the bars, space and time refined together: N = 25, 50, 100, 200
// linear elements, dt = 0.9 x the stable step; the graph of an observable of the run against
// the exact one (jumps as vertical segments), scaled by (T = t_end, V = the exact graph's
// largest |value|) as in the hausdorff study (studies/hausdorff.hpp, graph_errors). Problems and horizons:
//   signorini-bar  v0 1, g0 0 (nondimensional), to 1.5 contact durations 2 L / c
//   bouncing-bar   Doyen-Ern-Piperno's drop, to its first impact + one period 16 L / c
// Observables:
//   u_contact      displacement of the contact node (x = 0)
//   v_contact      velocity of the contact node (the massless node's: its rate)
//   v_mid          velocity at the fixed material point x = L / 2 (node N / 2)
//   contact_force  impulse / dt of the step
struct BarGraphFit {
  std::string problem, mass, observable;
  std::vector<double> dt, distance;  // per refinement (distance NaN when a run failed)
  OrderFit fit;                      // order of the distance in dt, 95% interval
  std::string note;                  // "declined: ...", a failed run's status, or empty
};
const std::vector<std::string>& bar_graph_observables();
std::vector<BarGraphFit> bar_hausdorff(const std::string& integrator, const std::vector<std::string>& masses);

// (4) Energy at impact: the bouncing bar (Doyen-Ern-Piperno's data, N = 100, dt = 0.9 x the
// stable step) with a mass model and restitution e of the contact node, run to its first
// impact + 3 periods 16 L / c. A contact phase: the steps with an impulse on the contact node,
// gaps shorter than the wave time L / c merged (the lumped node's chatter). Its jump: the
// scheme's own total energy (kinetic + strain + weight) after the phase's last impulse minus
// that before its first, relative to the kinetic energy at the first impact.
struct ImpactEnergy {
  long phases = 0;
  double worst_jump = 0.0;  // max |jump|, relative
  double worst_signed = 0.0;  // the jump of largest magnitude, with its sign
  std::string note;         // "declined: ..." or a failed run's status, else empty
  WorkCounters work;
  long contact_steps = 0;
  std::vector<std::pair<double, double>> history;  // (t, (E - E_0) / the impact's kinetic energy), every 10th step
  // What explains a large jump, measured: the step above the scheme's own stable step with its
  // contacts (work().extra["stable_step_with_contacts"], cd-penalty's springs), or the contact
  // node's speed above 100x the impact speed (the exact solution's is at most the impact speed;
  // a lumped node's chatter reaches a few times it: docs/measurements.md): a massless node's
  // spurious velocity mode, which the velocity-level impact law then acts on.
  std::string remark;
};
ImpactEnergy bar_impact_energy(const std::string& integrator, const std::string& mass, double restitution);

// (3) Angular momentum of a deformable body: block-2d (SVK, 8 x 4 Q4, frictionless floor,
// spin 3 rad/s, vx 0.3 m/s), dt = 0.5 x the stable step.
//   free flight  g 0, 10 m above the floor, `free_steps` steps: max |P - P_0| and |J - J_0|
//                over the steps, J = sum_a m_a x_a x v_a of the reported (u, v)
//   on the floor g 9.81, dropped from 0.1 m at 1 m/s, `floor_steps` steps: max over the steps
//                of |J_k - J_{k-1} - w sum_a x_a x F_ext,a - sum_i x_i Lambda_i| (the impulses'
//                moments at the step's new positions), from the state after the first step;
//                w = tau, or (tau_{k+1} + tau_{k+2})/2 for cd-lagrange-adaptive (its variational
//                kick; studies/measures.hpp variable_step_weight)
// All relative to sum_a m_a |x_a| |v_a| at the start (P: sum_a m_a |v_a|).
struct SpinningBlock {
  long free_steps = 0, floor_steps = 0, contact_steps = 0;
  double free_linear = 0.0, free_angular = 0.0, floor_angular = 0.0;
  double impulse_moment = 0.0;  // sum of |the impulses' moments| on the floor, relative
  std::vector<std::pair<double, double>> floor_history;  // (t, the step's relative J balance residual) on the floor
  std::string note;
  WorkCounters work;  // of the floor run
};
SpinningBlock spinning_block(const std::string& integrator, long free_steps, long floor_steps);

// (4), (5) The energy study's two long runs with e = 1 (studies/builtin/energy.toml): the bouncing mass,
// h0 1, dt 1e-3, 100 impacts; the spring chain between walls 0.5 m away, dt 0.02 s, 40 s. Errors
// |E - E_1| / E_1, E the scheme's own energy, E_1 after its first step; each figure the worst
// of the two runs. A fixed-step scheme fills first / second (max over each half of the run; NaN
// when a run failed or was declined); cd-lagrange-adaptive fills the adaptive figures.
struct EnergyFigures {
  double first = 0, second = 0;          // fixed step
  double adaptive = 0, cfl = 0, dt_min = 1e300, dt_max = 0;  // adaptive: max error, largest step / stable step, steps
  double no_root = 0;  // adaptive steps whose energy equation had no root
  long collapsed = 0;  // adaptive steps at the floor tau_min = tau_min_ratio x the requested dt
  bool adaptive_ok = true;
  std::string note;  // a declined or failed run
};
EnergyFigures energy_runs(const std::string& integrator);

// (7) Robustness: the bouncing mass, e = 1, h0 = 1 (period 0.903 s), dt = 0.02 s, stepped to
// its `target`-th impact (the scheme's own impacts, whatever its phase error), at most 2x the
// exact flights' steps, then to the end of that impact's contact phase: finite states, the
// final (E - E_1) / E_1 (E_1 after the first step),
// the largest penetration over one step of travel at the impact speed. history: (impacts,
// (E - E_1) / E_1) at every target / 100 impacts (the figure of the claim).
struct LongRun {
  bool ok = false;
  long impacts = 0, target = 0, steps = 0;
  double energy = std::numeric_limits<double>::quiet_NaN(), penetration = std::numeric_limits<double>::quiet_NaN(), t_end = 0;
  std::vector<std::pair<long, double>> history;
  std::string note;  // a declined run
};
LongRun long_run(const std::string& integrator, long target);

// A run's work: the scheme's work counters and its steps with a contact (an impulse > 0).
struct RunWork {
  long contact_steps = 0;
  WorkCounters work;
  std::string note;  // "declined: ..." or a failed run's status, else empty
};

// (1) The Signorini bar as the claims study runs it for claim (1): lumped mass, N 100,
// dt 0.9 h / c, to the contact's start + 1.5 contact durations 2 L / c (a linear bar against a
// rigid wall: a diagonal Delassus operator).
RunWork signorini_bar_work(const std::string& integrator);

// (6) Contact between two deformable bodies (H = L M^{-1} L^T not diagonal): two-blocks as the
// bodies study runs it (no gravity, the upper block at (0.5, -1) m/s, e = 0, mu = 0), dt 1e-4 s
// to t = 0.1 s (it lands at 0.05 s).
RunWork bodies_contact_cost(const std::string& integrator);
// (6) Contact between two bodies through one contact row (H 1 x 1, so diagonal: the closed
// form applies): two-bars with its defaults (L1 1, L2 2, N1 50, N2 100, lumped, v0 1, e = 0),
// dt 0.9 x its stable step, to t = 2 L2 / c (bar 2's pulse back at the contact).
RunWork two_bars_contact_cost(const std::string& integrator);

}  // namespace nsb
