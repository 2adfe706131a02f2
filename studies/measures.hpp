#pragma once
// One library of the measures the studies take of a run, each a small observer fed after every
// step or a function of a run's numbers, each tested on a case with a known answer
// (tests/studies/measures_test.cpp):
//   - least-squares fits: a line with its 95% confidence interval (fit_line), the same fed one
//     point at a time (RunningSlope, an energy drift), and the convergence order in log-log
//     (fit_order, fitted_order, observed_order);
//   - momentum balance of a 1D problem (MomentumBalance): P - P0 - sum of the impulses of the
//     external forces and the contacts;
//   - the discrete energy balance (EnergyBalance, run/energy_balance.hpp, included here: `nsbench
//     run` reports it too): the change of the scheme's own energy minus the work of the loads
//     and of the contact impulses, per step and summed; its envelope per window (Envelope) and
//     the drift rule on it (drift_rule);
//   - contact phases and impact times (ContactPhases), the impacts compared with the exact ones
//     (compared_impacts) and the energies of the flights between them (FlightEnergies); the
//     start of a run's final rest (FinalRest: the bouncing mass's detected Zeno time);
//   - impacts seen per contact, with an observable before and after each and its amplitude
//     between them (ContactImpacts), and the closed forms they are held against on the
//     moving-contact problems (rocking_law_ratio, rocking_amplitude_after, rocking_rest_time,
//     painleve_jam_time);
//   - the cost of a run: the thread CPU time of its stepping, observer excluded (cost_column,
//     RunResult::step_cpu_seconds; median_cpu_seconds in studies/study.hpp for timed runs);
//   - stop and onset times of a slip (studies/slip_stop.hpp) and the Hausdorff distance between
//     graphs (studies/hausdorff.hpp) are the measures of those headers.
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "integrators/integrator.hpp"
#include "problems/problem.hpp"
#include "run/energy_balance.hpp"  // EnergyBalance: run/ reports it too (nsbench run)
#include "studies/table.hpp"

namespace nsb {


// A measure with no value (n/a): not measured, not defined, or the run diverged.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// True for a value a log-log fit or a ranking can use: positive and finite.
inline bool usable(double x) { return x > 0.0 && std::isfinite(x); }

// ---- Least-squares fits ----------------------------------------------------------------

// Least squares y = a + b x over the points (x_i, y_i) as given (the caller leaves out what
// is not a point), with the 95% confidence interval of b: b +- t_{0.975, n-2} SE, residual
// variance s^2 = SSR / (n - 2), SE = s / sqrt(Sxx), Sxx = sum (x_i - mean x)^2. The slope is
// NaN with fewer than two points or all x equal; the interval with fewer than three points
// (no residual degree of freedom).
struct LineFit {
  double slope = std::numeric_limits<double>::quiet_NaN();
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
  int points = 0;
};
LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y);

// The least-squares slope of y against x fed one point at a time, by Welford's updates
// (means and co-moments, no cancellation over millions of steps); NaN before two distinct x.
class RunningSlope {
 public:
  void add(double x, double y);
  double slope() const;

 private:
  double n_ = 0.0, mean_x_ = 0.0, mean_y_ = 0.0, cxy_ = 0.0, cxx_ = 0.0;
};

// Errors at or below this are round-off (a scheme exact for the case: Moreau-Jean's velocity
// under a constant force, a plugin at e = 1 on the bouncing mass): they carry no order and stay
// out of every study's order fits. The studies' errors are relative, or absolute on motions of
// size one (s, m, m/s), so one absolute threshold serves them all.
constexpr double kRoundOffError = 1e-11;
// The error, or NaN when it is at round-off (<= kRoundOffError) or not a number.
double above_round_off(double error);

// Observed order between two refinements: log(e1/e2) / log(h1/h2); NaN when an error is
// not positive and finite.
double observed_order(double h1, double e1, double h2, double e2);

// The convergence order: fit_line of log e against log h with its 95% interval over the
// points with positive finite error. The points are the distinct h: repeats of an h (a
// deterministic run repeated) are one point, at the mean of their log e, and `points` counts
// distinct h; otherwise each repeat would add a residual degree of freedom and narrow the
// interval without adding information.
struct OrderFit {
  double order = std::numeric_limits<double>::quiet_NaN();
  double low = std::numeric_limits<double>::quiet_NaN();
  double high = std::numeric_limits<double>::quiet_NaN();
  int points = 0;
};
OrderFit fit_order(const std::vector<double>& h, const std::vector<double>& e);
// Its order alone (NaN with fewer than two such points).
double fitted_order(const std::vector<double>& h, const std::vector<double>& e);
// Two-sided 97.5% quantile of Student's t with `dof` >= 1 degrees of freedom.
double student_t975(int dof);

// ---- Observers fed after every step ----------------------------------------------------

// Momentum balance of a 1D problem, P = 1^T M v: after each step of length dt ending at t,
//     P_k - P_0 - sum_j ( 1^T F_ext(t_j - dt_j) w_j + 1^T L^T Lambda_j ),
// w_j the weight of the step's force in the scheme's momentum update (variable_step_weight:
// (tau_{j} + tau_{j+1})/2 for cd-lagrange-adaptive, dt_j for the others),
// zero for a scheme that balances momentum exactly when the internal forces sum to zero.
class MomentumBalance {
 public:
  MomentumBalance(const Problem& problem, const Vec& v0);
  void add(const Integrator& integrator, double dt);  // after each step
  double momentum(const Vec& v) const { return mass_row_.dot(v); }
  double initial() const { return p0_; }
  double residual(const Vec& v) const;  // |P - P0 - impulses|, absolute
  double signed_residual(const Vec& v) const;  // P - P0 - impulses
  // sum_i M_ii |v0_i|: a scale of the residual that is not zero when P0 is (bodies moving apart).
  double speed_scale() const { return speed_scale_; }

 private:
  const Problem& problem_;
  Vec ones_, mass_row_, gap_row_, f_ext_;
  double p0_ = 0.0, impulse_sum_ = 0.0, speed_scale_ = 0.0;
  double constant_force_sum_ = std::numeric_limits<double>::quiet_NaN();  // 1^T F_ext of a constant load
};

// Momentum identities of a 3D mesh problem (its field_mesh(): points and their dofs), one
// component each: "px", "py", "pz" the linear momentum P_d = r_d^T M v (r_d: 1 on the dofs of
// component d of every point) and "jx", "jy", "jz" the angular momentum about the origin
// J = sum_a x_a x (M v)_a (x_a = X_a + u_a, (M v)_a the entries of M v on point a's dofs: the
// continuum's int rho x x v for any mass matrix of the mesh's shape functions). What changes them
// is every contact impulse (normal and both tangent rows) and the external force,
// f_k = L^T Lambda_N + T^T Lambda_T + T2^T Lambda_T2 + w F_ext(t_k - dt), w the weight of the
// step's force in the scheme's momentum update (variable_step_weight: (tau_{k+1} + tau_{k+2})/2
// for cd-lagrange-adaptive, dt for the others); the balance of each step k from the second (a
// scheme's first step may start from a velocity at another time: CD-Lagrange's half step):
//   linear    |P_k - P_{k-1} - r_d^T f_k|  (the internal forces sum to zero);
//   angular   |J_k - J_{k-1} - sum_a (x_a,k x f_a,k)_d|, the torques at the end-of-step
//             positions (CD-Lagrange's exact discrete balance, as the block study measures it),
//             the internal forces having no net torque at one configuration.
// largest(): the largest residual so far; scale(): sum_i M_ii |v0_i| (linear) or
// sum_a |x_a,0| |(M v0)_a| (angular), so that a residual relative to it is not 0 / 0 when the
// momentum is. Contacts that move with the configuration (Problem::contacts_move) carry the
// impulses through their rows evaluated at the end-of-step configuration U_k, where the
// torques are taken: CD-Lagrange's rows (L(U_{k+1}) of its step); a scheme that applies them
// through rows at another configuration (Moreau-Jean: L(U_k) of its step, the start) shows the
// difference in J, and in P only where the rows' weights do not sum to zero per direction
// (two-blocks' node-to-segment rows do, in every configuration).
// The weight of the step's force in the momentum update of a scheme that chooses its steps,
// given the step dt it just took: cd-lagrange-adaptive's variable-step variational kick
// P_{k+3/2} = P_{k+1/2} + (tau_{k+1} + tau_{k+2})/2 F_{k+1} + L^T Lambda (its header; KMOW 2000)
// gives (dt + next_step())/2. None for a scheme that steps at the requested dt: its weight is
// that dt (the caller's). A momentum balance that weights the force by the step taken instead
// charges the adaptive step's J and P with (tau_{k+2} - tau_{k+1})/2 F (its moment) per step:
// 2.9e-4 relative on the spinning block on the floor, where the scheme balances to 2e-16.
std::optional<double> variable_step_weight(const Integrator& integrator, double dt);

class MeshMomentum {
 public:
  MeshMomentum(const Problem& problem, const State& initial, const std::string& component);
  void add(const Integrator& integrator, double dt);  // after each step
  double largest() const { return largest_; }
  double scale() const { return scale_; }
  // The components a problem's mesh allows: px, py, pz (as many as its dimension), jx, jy, jz in 3D.
  static std::vector<std::string> components(const Problem& problem);

 private:
  // M v into p_ (no allocation per step) and its moment about the origin.
  double angular_momentum(const State& s);
  double torque(const State& s, const Vec& f) const;
  const Problem& problem_;
  SpMat M_;
  Eigen::MatrixXd points_;
  Eigen::MatrixXi point_dofs_;
  int axis_ = 0;
  bool angular_ = false;
  Vec f_, f_ext_, p_;
  std::optional<ContactGeometry> moving_rows_;  // the rows at the step's end (moving contacts)
  double previous_ = 0.0;  // P or J at the last step
  double largest_ = 0.0, scale_ = 0.0;
  long steps_ = 0;
};

// The envelope of a series per window of time: max |value| over the values at t in
// [t0 + j w, t0 + (j + 1) w), one per completed window (a window is complete once a value
// at or past its end arrives; a partial last window is left out), at its midpoint time.
// `expected` windows are reserved up front, so that add() allocates nothing within them.
class Envelope {
 public:
  Envelope(double t0, double window, std::size_t expected = 0) : t0_(t0), window_(window) {
    times_.reserve(expected);
    maxima_.reserve(expected);
  }
  void add(double t, double value);
  const std::vector<double>& times() const { return times_; }
  const std::vector<double>& maxima() const { return maxima_; }

 private:
  double t0_, window_, current_ = 0.0;
  long index_ = 0;
  bool seen_ = false;
  std::vector<double> times_, maxima_;
};

// The drift rule on an envelope (Envelope: e.g. of EnergyBalance::cumulative() per period):
// drift = the least-squares slope of the envelope against its times with its 95% interval
// (fit_line), and over_run = drift x (last time - first time). No drift when the interval
// contains 0 (no slope the scatter of the windows can tell from none) or |over_run| <=
// round_off (a change rounding alone can make: EnergyBalance::round_off()); an exactly linear
// drift above round-off fails (its interval is the slope alone), and so does an envelope that
// falls steadily (a decaying transient: the interval lies below 0); the sign is the caller's to
// read. Fewer than kDriftMinWindows
// windows: not measured (NaN drift, no_drift false): with 8 windows the fit keeps 6 residual
// degrees of freedom, t_{0.975,6} = 2.45, so the interval is not carried by the quantile of
// too few points (t_{0.975,1} = 12.7).
inline constexpr int kDriftMinWindows = 8;
struct Drift {
  double drift = kNaN, low = kNaN, high = kNaN, over_run = kNaN;
  int windows = 0;
  bool no_drift = false;
};
Drift drift_rule(const std::vector<double>& times, const std::vector<double>& envelope, double round_off);

// Contact phases: a phase starts at a step with a contact impulse after a step without one,
// more than `min_flight` after the last step with an impulse (a chattering contact is one
// phase). Its start times are the impact times the studies compare with exact ones.
class ContactPhases {
 public:
  explicit ContactPhases(double min_flight = 0.0) : min_flight_(min_flight) {}
  // After each step ending at t: whether it had a contact impulse; true when a phase starts.
  bool add(double t, bool contact);
  const std::vector<double>& starts() const { return starts_; }
  // The contact's span over the run: from the first step with an impulse to the last, each
  // step carrying one nominal step dt of contact force, t_last - t_first + dt (a contact held
  // through [t0, t0 + T] gives T to O(dt)); NaN without an impulse.
  double span(double dt) const;

 private:
  double min_flight_;
  bool in_contact_ = false;
  double last_contact_ = -1e300;
  std::vector<double> starts_;
};

// The impacts of a run compared with the exact ones (exact: the exact impact times in order):
// the first `count`, up to the first whose exact flight to the next exact impact lasts less
// than `min_flight` (flights below the step's resolution: the Zeno phase; min_flight = 10 dt
// keeps flights of 10 steps at least; an impact with no next exact impact then ends them too);
// min_flight = 0: the first `count` of them.
std::size_t compared_impacts(const std::vector<double>& exact, std::size_t count, double min_flight);

// Flight energies against the exact energies after the impacts (energies[i - 1]: E_i, after
// impact i of `impacts`, the exact impact times), fed the energy after every step: flight i
// (between impacts i and i + 1) for i = 1 .. flights gives E / E_i - 1, where E is the energy
//   at = exact_mid_flight: at the first step ending at or after the exact mid-flight time
//                          (t_i + t_{i+1}) / 2 (flights with a known next impact only);
//   at = mid_flight_step:  at the step midway by index (k_i + k_{i+1}) / 2, rounded down,
//                          between the steps k_i, k_{i+1} that start the run's contact phases
//                          i and i + 1 (ContactPhases): the numerical flight, whatever its
//                          timing error; a flight whose next phase never starts is not compared.
class FlightEnergies {
 public:
  enum class At { exact_mid_flight, mid_flight_step };
  FlightEnergies() = default;
  FlightEnergies(std::vector<double> impacts, std::vector<double> energies, std::size_t flights, At at)
      : impacts_(std::move(impacts)), energies_(std::move(energies)), flights_(flights), at_(at) {}
  // After each step ending at t: whether it had a contact impulse, and the energy.
  void add(double t, bool contact, double energy);
  // max |E / E_i - 1| over the flights compared (NaN: none).
  double largest() const;
  std::size_t compared() const { return errors_.size(); }
  const std::vector<double>& errors() const { return errors_; }
  // The energies E of the flights compared, and the exact E_i (the first compared() against them).
  const std::vector<double>& energies() const { return measured_; }
  const std::vector<double>& exact() const { return energies_; }

 private:
  std::vector<double> impacts_, energies_, errors_, measured_;
  std::size_t flights_ = 0;
  At at_ = At::exact_mid_flight;
  ContactPhases phases_;
  std::vector<double> since_start_;  // mid_flight_step: the energies from the last phase's first step on
};

// The start of a run's final rest, fed after each step ending at t whether the step is at rest
// (e.g. its speed and height below what a few steps of gravity give: the bouncing mass after its
// Zeno time): the end of the first step of the stretch of steps at rest that lasts to the run's
// last step, provided that stretch lasts longer than `min_rest` (from that first step's end to
// the last step's); NaN otherwise (the last step not at rest: no rest yet).
class FinalRest {
 public:
  explicit FinalRest(double min_rest = 0.0) : min_rest_(min_rest) {}
  void add(double t, bool at_rest) {
    if (!at_rest) start_ = kNaN;
    else if (std::isnan(start_)) start_ = t;
    last_ = t;
  }
  double start() const { return last_ - start_ > min_rest_ ? start_ : kNaN; }

 private:
  double min_rest_, start_ = kNaN, last_ = kNaN;
};
// A bound of a step at rest that scales with the step: at_most dt^power, multiplied factor by
// factor from the left ((at_most dt) dt: the rounding of a study's 2 g dt dt).
double rest_bound(double at_most, int power, double dt);

// An observable's values at consecutive steps (the contact force over its level inside the exact
// contact phase): its chatter, the RMS over the interior values of the period-2 component
// (o_{k+1} - 2 o_k + o_{k-1}) / 4 (an alternation of amplitude a, o_k = 1 +- a, gives a; a
// smooth variation O(dt^2)), and how many are zero (a contact lost and regained inside the
// exact contact).
class Chatter {
 public:
  void add(double value);
  double rms() const;  // NaN with fewer than three values
  long zeros() const { return zeros_; }

 private:
  double before_ = 0.0, last_ = 0.0, square_ = 0.0;
  long values_ = 0, zeros_ = 0;
};

// Impacts seen per contact: a step at which a contact takes an impulse after steps in which it
// took none, during which its gap was open (> 0) and then fell (it approached the obstacle):
// the largest gap of those impulse-free steps (from t = 0, or from the step after its last
// impulse) is above zero and above the gap at the start of the impulse step. A contact closed
// at t = 0 (gap <= 0) carries its load from the first step on, and a pivot that loses its
// impulse for a step takes it up again with its gap at most where that step left it (drift of
// order g dt^2, either sign): neither is an impact (the rocking block's pivot; counting those
// gave ratios 1.001 and 17 impacts in 1.5 s where the exact solution has 2). A contact that
// leaves and strikes again within one step is not seen either. At each impact: its time, an
// observable before (at the end of the step before) and after (at the end of the impact step),
// and its amplitude after: the largest |value| at the ends of the steps after the impact step,
// up to the step before the next impact (or the run's last step). A time-stepping scheme may
// apply the impulse a step after the gap closed (Moreau-Jean forecasts it at U_k): before and
// after are taken around the impulse, so that step's smooth motion adds O(dt) to the ratio.
class ContactImpacts {
 public:
  struct Impact {
    double t = 0.0, before = 0.0, after = 0.0, amplitude = 0.0;
  };
  ContactImpacts(const Vec& initial_gaps, double initial_value);
  // After each step ending at t: the contacts' normal impulses, their gaps and the observable's value.
  void add(double t, const Vec& impulses, const Vec& gaps, double value);
  const std::vector<Impact>& impacts() const { return impacts_; }

 private:
  std::vector<bool> carrying_;      // took an impulse in the last step (or closed at t = 0)
  std::vector<double> open_peak_;   // largest gap since its last impulse (-inf while carrying)
  std::vector<double> last_gap_;    // gap at the end of the last step
  double previous_;
  std::vector<Impact> impacts_;
};

// The closed forms the rigid study holds the schemes against, asked of the problem's exact
// solution (problems/exact_solution.hpp), NaN where it does not give them:
// the rocking block's impact ratio omega+ / omega- under Housner's law, 1 - (3/2) sin^2(alpha),
// or Moreau's (its exact solution's: Newton and Coulomb on both corners; NaN below mu_H, where
// the corner would slip: rocking about a stuck pivot needs |F / N| = 3 sin(alpha) cos(alpha) /
// (1 + 3 cos^2(alpha)) = mu_H at theta = 0 even at rest, so with mu < mu_H the pivot slides before
// the impact and no rocking approach reaches the state the slip outcome starts from), its exact amplitude
// |theta_max| after impact k (1-based; NaN past the impacts its exact solution marches) and
// its exact time to rest (+inf when it never rests), the number of impacts its exact solution
// describes (rocking_exact_impacts, 0 elsewhere: 1 when the corner slips at the first, whose
// Moreau ratio then ends it); the Painleve rod's dynamic jam time
// (problems/painleve_rod_exact.hpp; NaN when its sliding phase ends otherwise).
enum class ImpactLaw { housner, moreau };
double rocking_law_ratio(const Problem& problem, ImpactLaw law);
double rocking_amplitude_after(const Problem& problem, std::size_t k);
double rocking_rest_time(const Problem& problem);
std::size_t rocking_exact_impacts(const Problem& problem);
double painleve_jam_time(const Problem& problem);
// A problem's summary value of that name (Problem::summary_values: a closed-form figure such as
// the sphere's exact roll-onset time t_roll_exact, +inf when it never rolls); NaN when it has none.
double summary_value(const Problem& problem, const std::string& name);

// ---- Cost --------------------------------------------------------------------------------

// The one definition of a run's cost in a table: the thread CPU time of the stepping of the
// observed run, the observer excluded (RunResult::step_cpu_seconds); a timing column.
Column cost_column();

}  // namespace nsb
