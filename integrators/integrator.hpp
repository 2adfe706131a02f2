#pragma once
// Time integrator interface. An integrator is bound to one Problem by init() and then
// advanced by step(). As in MFEM's ODESolver::Step, step() may take another step than the
// one requested (an adaptive scheme chooses its own) and reports the step it took.
//
// The contract (what the studies, the tables and `nsbench check` rely on; a plugin's
// integrator follows it like every built-in; `nsbench check --integrator NAME` tests it):
//   registry entry  names the integrator and declares its Capabilities
//                 (integrators/capabilities.hpp: friction, explicit, mass, linear only,
//                 node-to-rigid only, largest size); the entry's make() gives both to the
//                 integrator it builds, so name() is the entry's name and no class repeats it.
//   constructor(const Params&)  reads its parameters (declared by a static parameters_spec(),
//                 range-checked before it runs: a value outside is refused with InputError).
//   init(problem, initial)  calls bind(problem, initial) first: bind() checks the contacts, the
//                 problem's contract where cheap (a symmetric mass, no negative diagonal, no
//                 gap closed at `initial`) and the declared capabilities (check_capabilities: one refusal wording per kind),
//                 stores problem_, state_ = initial, mass_ = problem.mass_matrix(), and sizes
//                 impulses_ and tangential_impulses_ to the contacts (zero). Then it builds its
//                 caches and throws InputError naming the problem for one it cannot run for a
//                 reason of its own (not a declared capability): the studies show that as n/a,
//                 never a wrong number.
//   advance(dt)   the scheme's step, called by the non-virtual step(dt): advances state_.u and
//                 state_.v by one step of dt (or of the step it chooses, returned in
//                 StepInfo::dt), adds the F_int evaluations made to work_.force_evaluations
//                 (budgets and the work-precision tables read them) and the other counters as
//                 they apply. step() then sets state_.t to the start time plus that step and
//                 counts it in work_.steps: advance() leaves both alone (a scheme that needs
//                 the end time computes it, state_.t + dt). impulses_ holds this step's normal
//                 impulses, one Lambda_i >= 0 per contact, 0 on a contact open through the
//                 step (zero it, then fill it: never left from an earlier step);
//                 tangential_impulses_ likewise (0 without friction), and
//                 tangential_impulses2_ for 3D contacts (the cone: capability "3D friction
//                 cone").
//   energy()      override when the scheme's own balance is another energy than
//                 v^T M v / 2 + V(u) at state_ (a staggered scheme: the half-step energy).
//   impact_accuracy()  override when one impact may lag more than 2 steps, or when the
//                 restitution is not exact (a compliant, penalty contact).
// Helpers for a new scheme: ImpulseContact (integrators/impulse_contact.hpp: Moreau's
// velocity-level impulse law with restitution, and Coulomb friction, given M^{-1} diagonal),
// lcp_parameter_specs() / lcp_options() (its LCP solver's parameters, solvers/lcp.hpp),
// CentralDifference (integrators/central_difference.hpp: the explicit staggered update), and
// solve_coulomb_local for one contact's 2D Coulomb law. A minimal correct example:
// examples/plugin/symplectic_euler.cpp; the method and conventions: docs/method.md.
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "integrators/capabilities.hpp"
#include "problems/problem.hpp"

namespace nsb {

struct StepInfo {
  double dt = 0.0;         // the step actually taken
  long iterations = 0;     // inner iterations of this step (LCP, energy equation, Newton)
  bool converged = true;   // inner solvers met their tolerance
};

// Work done so far, for work-precision studies.
struct WorkCounters {
  long steps = 0;
  long force_evaluations = 0;    // F_int evaluations
  long tangent_evaluations = 0;  // tangent stiffness assemblies
  long factorizations = 0;
  long linear_solves = 0;
  long lcp_iterations = 0;
  long lcp_unconverged = 0;      // steps whose LCP did not meet its tolerance
  std::map<std::string, double> extra;  // integrator-specific counters
};

// A contact event located by an integrator that tracks events (the references): an impact,
// a release (reaction through zero), the arrival of a massless dof (no impulse), a Zeno
// stop (a slow rebound replaced by a plastic impact: the contact closes), or a penalty
// spring switching on or off. rate_* = the normal velocity g' just before and after;
// impulse: the contact's impulse (impacts and Zeno stops, else 0).
enum class ContactEventKind { Impact, Release, Arrival, ZenoStop, Switch };
struct ContactEvent {
  double t;
  Index contact;
  ContactEventKind kind;
  double rate_before = 0.0, rate_after = 0.0;
  double impulse = 0.0;
};
// The events of the given kinds, in order.
std::vector<ContactEvent> events_of_kind(const std::vector<ContactEvent>& events,
                                         std::initializer_list<ContactEventKind> kinds);
// "impact", "release", "arrival", "zeno-stop", "switch".
const char* event_kind_name(ContactEventKind kind);
// The events as CSV: t, contact, kind, rate_before, rate_after, impulse.
std::string events_to_csv(const std::vector<ContactEvent>& events);

struct Energy {
  double kinetic = 0.0;
  double potential = 0.0;
  double total() const { return kinetic + potential; }
};

// What a scheme's own impact law lets one expect of its impacts, derived from the law (not
// measured): the generic contact-law test (tests/integrators/contact_law_test.cpp) holds
// every scheme to it.
struct ImpactAccuracy {
  // Bound on the phase lag one impact adds, in steps. 2 for a one-step impulse law: the
  // impact is seen at the end of the step that closes the gap (<= 1 step late) and rebounds
  // from a penetration of at most one step of travel (<= 1 more).
  double lag_steps = 2.0;
  // The rebound speed is e times the impact speed up to O(dt) (false for a compliant
  // contact resolved over a few steps, whose restitution depends on the impact's phase).
  bool restitution_exact = true;
};

struct IntegratorEntry;

class Integrator {
 public:
  virtual ~Integrator() = default;

  // The name of the registry entry that made this integrator ("" for one built directly,
  // outside the registry: a test's). Virtual only so that a 0.1.0 plugin's override still
  // compiles (deprecated, integrators/plugin_compat.hpp); nsbench names it after its entry.
  virtual std::string name() const { return name_; }
  // Binds the integrator to `problem` (which must outlive it) and sets the initial state.
  // Throws InputError when the problem is outside what the scheme handles.
  virtual void init(const Problem& problem, const State& initial) = 0;
  // Advances from state().t by (about) dt_requested; returns the step taken. The time and the
  // step count (unless the scheme counts its own) are kept here, around the scheme's
  // advance(). Virtual only for a 0.1.0 plugin that overrides it (deprecated: it then keeps
  // state_.t and work_.steps itself, as 0.1.0 asked; integrators/plugin_compat.hpp).
  virtual StepInfo step(double dt_requested) {
    const double t0 = state_.t;
    const StepInfo info = advance(dt_requested);
    state_.t = t0 + info.dt;
    if (!counts_own_steps_) ++work_.steps;
    return info;
  }
  // The energy the scheme's own balance is written for; the default is
  // v^T M v / 2 + V(u) at the current state.
  virtual Energy energy() const;
  // Every contact event located since init(), in time order; empty for the schemes that do
  // not locate events (time-stepping).
  virtual const std::vector<ContactEvent>& events() const;
  // See ImpactAccuracy; valid after init().
  virtual ImpactAccuracy impact_accuracy() const { return {}; }
  // The capabilities the registry entry declares, for this integrator's parameters
  // (Capabilities::resolved); none for an integrator built outside the registry.
  Capabilities capabilities() const;
  // True for a scheme that is only conditionally stable at a fixed step dt: dt must stay
  // below the problem's stable step (Problem::stable_step) or the run blows up. Virtual, like
  // treats_friction(), only for a 0.1.0 plugin's override (deprecated: declare the capability).
  virtual bool conditionally_stable() const { return capabilities().explicit_step; }
  // True for a scheme that treats Coulomb friction (Contacts::mu, docs/method.md section 6).
  virtual bool treats_friction() const { return capabilities().friction; }

  const State& state() const { return state_; }
  // Contact impulses Lambda (size p) applied during the last step; >= 0.
  const Vec& impulses() const { return impulses_; }
  // Tangential impulses Lambda_T (size p) of the last step, along +T; zero without friction.
  const Vec& tangential_impulses() const { return tangential_impulses_; }
  // 3D contacts (Contacts::tangent2): the impulses along +T2 (size p) of the last step; zero
  // for 2D contacts and without friction.
  const Vec& tangential_impulses2() const { return tangential_impulses2_; }
  const WorkCounters& work() const { return work_; }
  const Params& parameters() const { return params_; }

 protected:
  explicit Integrator(Params params) : params_(std::move(params)) {}
  // The scheme's own step (see the contract above): everything but state_.t and work_.steps.
  // A scheme must override it, or (deprecated, 0.1.0) step(). Nothing checks that when the
  // entry is built (advance is protected); the default throws std::logic_error naming the
  // integrator, and is reached only by a scheme that overrides neither.
  virtual StepInfo advance(double dt_requested);
  // Common part of init(): checks the problem's contacts (check_contacts), the contract's
  // mass and initial gaps (check_problem_contract) and the declared capabilities
  // (check_capabilities), stores the problem and state, sizes the impulses.
  void bind(const Problem& problem, const State& initial);

  const Problem* problem_ = nullptr;
  SpMat mass_;
  State state_;
  Vec impulses_;
  Vec tangential_impulses_;
  Vec tangential_impulses2_;
  WorkCounters work_;
  Params params_;
  // Set by a scheme whose work_.steps is another count than its calls of step(): the CVODE
  // references report CVODE's internal steps (reference/cvode.hpp).
  bool counts_own_steps_ = false;

 private:
  friend struct IntegratorEntry;
  template <class Base, class T>
  friend struct PluginCompat;
  std::string name_;
  std::optional<DeclaredCapabilities> declared_;  // the entry's; none outside the registry
  // What a 0.1.0 plugin's conditionally_stable() and treats_friction() overrides say, folded
  // into declared_ when the entry builds it (IntegratorEntry::make).
  bool legacy_explicit_ = false;
  bool legacy_friction_ = false;
};

}  // namespace nsb

#include "integrators/plugin_compat.hpp"
