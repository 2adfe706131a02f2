#pragma once
// Exact semi-discrete reference for linear problems ("modal-exact"): piecewise modal
// superposition between contact-mode changes, events located on closed-form signals.
//
//     M u'' + K u = F + L^T lambda        (K, F constant; node-to-rigid contacts)
//     contact i on dof d:  g_i = a_i (u_d - p_i),   p_i = -g0_i / a_i
//
// Contact mode C = the set of closed contacts. In mode C:
//   held     dofs of closed contacts:  u_d = p_i, u_d' = 0
//   free massless dofs Z (zero mass row, e.g. the singular bar's contact node), condensed:
//            K_ZZ u_Z = F_Z - K_ZA u_A - K_ZH u_H      (K_ZZ must be invertible)
//   active   massive dofs A, not held:   M_AA u_A'' + K~ u_A = F~,
//            K~ = K_AA - K_AZ K_ZZ^{-1} K_ZA,   F~ = F_A - K_AH u_H - K_AZ K_ZZ^{-1} (F_Z - K_ZH u_H)
// Once per mode (cached by C): K~ phi = w^2 M_AA phi, Phi^T M_AA Phi = I (dense symmetric
// eigensolver on M_AA^{-1/2} K~ M_AA^{-1/2} when M_AA is diagonal, else the generalised one).
// u_A = Phi q, f = Phi^T F~, and each modal coordinate is exact:
//     w_j > 0:   q_j(tau) = qs_j + (q0_j - qs_j) cos(w_j tau) + q0'_j / w_j sin(w_j tau),  qs_j = f_j / w_j^2
//     w_j ~ 0:   q_j(tau) = q0_j + q0'_j tau + f_j tau^2 / 2       (rigid: w_j^2 <= 1e-12 max w^2)
// Event signals, one per contact, all linear in q (so c0 + c1 tau + c2 tau^2 + sum_j (A_j cos
// w_j tau + B_j sin w_j tau), evaluated in O(#modes) as s_i = k_i + l_i . q(tau)):
//     open contact     its gap g_i (of a free massless dof: of its condensed value)
//     closed contact   its reaction lambda_i = (M u'' + K u - F)_d / a_i   (what the obstacle
//                      pushes; u_A'' = Phi (f - W^2 q), so M_dA u_A'' is linear in q too)
// An event is the first tau in (0, tau_max] where some s_i < 0: gap closing through zero
// (impact or arrival) or reaction turning tensile (release). Search: samples every
// 2 pi / (w_max samples_per_period) (default 16 per shortest period) and at the vertex of
// each signal's polynomial (rigid-mode) part, a sign change bracketed between samples, then
// refined by the Illinois method to round-off (the event is the bracket's negative end).
// A signal an event left at zero that its derivatives send up, yet negative at the next
// sample (a short excursion: a node released from rest that its element pushes back at
// once) is searched at halving distances from the start; an excursion below round-off at
// all of them is no excursion: the contact is closed (or released) against its derivatives
// (counted in forced_events) rather than flipped back and forth at one instant.
// LIMITATION: a sign change is seen only when a sample lands on the negative side, so a dip
// below zero shorter than the sample spacing (two close roots, or a tangency: a double root)
// can be missed; at 16 samples per period of the fastest mode that takes a dip shorter than
// 1/16 of the shortest period. samples_per_period trades search cost for that margin.
//
// At an event (as event_driven.hpp, Acary & Brogliato 2008, ch. 7):
//   impacts   open contacts touching (gap <= round-off or the root found) and closing: the
//             massive ones solve Newton's impulse LCP with the closed massive contacts (e = 0)
//                 0 <= Lambda _|_ g'+ + e_i g'- >= 0,  g'+ = g'- + H Lambda,  H = L_I M_SS^{-1} L_I^T
//             (M_SS: the mass of the massive dofs, factorised once; solve_lcp, closed form for
//             one contact), v += M_SS^{-1} L^T Lambda; a massless dof has no impulse: it arrives
//             and its gap is continuous (no energy lost);
//   closing   a plastic impact (e = 0) or an arrival makes the contact a closed candidate;
//   reactions closed contacts and candidates stay closed while their reaction in the new mode
//             is compressive; a reaction zero to round-off is decided by its first derivative
//             that is not zero (rate, then acceleration, jerk; all zero: closed), as
//             event_driven.cpp does (the bar arriving unstressed at t = 0 closes); tensile
//             contacts are released together and the rest re-checked (exact for one contact
//             or uncoupled contacts, a heuristic for the acceleration-level LCP otherwise);
//   Zeno      a rebound slower than zeno_velocity is made plastic (counted as zeno_stops).
// Then the state is projected on the new mode: q0 = Phi^T M_AA u_A, q0' = Phi^T M_AA v_A.
// Round-off: a signal is zero when |s| <= 1e-12 (|k_i| + sum_j |l_ij q_j|) (its evaluation
// error is eps times that sum); an open contact within it while closing hits together.
// Exact up to the eigendecomposition's backward error eps max w^2 (of M^{-1} K), which the
// slow modes carrying the energy and momentum feel relatively as eps (w_max / w_low)^2: on
// the bar (L = c = 1) energy and momentum errors of 1e-12 at N = 100, 1e-10 at N = 800.
//
// step(dt) advances to t + dt exactly, handling every event inside. state(): all dofs;
// held dofs on the obstacle at rest, a free massless dof at its condensed value and rate.
// impulses(): the impacts' impulses plus the closed contacts' reactions integrated in closed
// form (integral of k_i + l_i . q over the segment), so 1^T M (v_end - v_start) =
// 1^T (L^T Lambda + F dt) to round-off. energy(): v^T M v / 2 + strain energy + load potential
// (conserved exactly except at massive impacts, which lose (1 - e^2) (g'-)^2 / (2 H_ii)).
// An impact at the initial time happens in init(): its impulse belongs to no step (as in
// event-driven); the momentum balance holds from state() after init().
// Work: force_evaluations stays 0 (no F_int is evaluated); extra force_equivalents counts a
// reconstruction of the state from the modes (O(n m), the cost of an F_int evaluation or
// more) as one, one per step and one per event inside it: a run's work budget
// (RunOptions::max_force_evaluations) counts them, so that it stops the reference as it stops
// the schemes; factorizations counts the eigen-
// decompositions and the Cholesky factorisations of M_SS and K_ZZ; extra: events (instants
// handled by step()), impacts, arrivals, releases, eigen_decompositions, root_evaluations
// (signal evaluations), zeno_stops, forced_events, force_equivalents.
// Cost: O(n^3) per mode (dense), O(n m) per step (state reconstruction: two dense
// matrix-vector products), O(m) per signal evaluation. step() allocates nothing once its
// modes are cached, but for the event log's amortised growth and a multi-contact impact LCP
// (solve_lcp).
//
// Declared (the registry entry; refused when the problem binds): a linear problem, a
// constant F_ext, node-to-rigid contacts, at most max_dofs dofs (dense eigendecomposition).
// Refused by init() (InputError): a massless dof with off-diagonal mass, M_SS not positive
// definite, K_ZZ singular, K not positive semidefinite, an initial penetration beyond round-off. The massless dofs'
// initial values are replaced by their condensed (quasi-static) ones.
//
// References: V. Acary, B. Brogliato, Numerical Methods for Nonsmooth Dynamical Systems,
// Springer 2008, ch. 7; M. Geradin, D. Rixen, Mechanical Vibrations, 3rd ed., Wiley 2015,
// ch. 2 (modal superposition, static condensation); Khenous, Laborde, Renard, Eur. J. Mech.
// A/Solids 27 (2008) (massless contact node); M. Dowell, P. Jarratt, BIT 11 (1971) 168-174
// (Illinois method).
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): its modal solution holds for
// linear kinematics only.
#include <list>
#include <map>
#include <mutex>
#include <optional>
#include <vector>

#include "integrators/integrator.hpp"
#include "solvers/lcp.hpp"
#include "reference/node_contacts.hpp"

namespace nsb {

class ModalExact final : public Integrator {
 public:
  explicit ModalExact(const Params& params);
  // Not copyable: mode_ and the published counters point into its own containers.
  ModalExact(const ModalExact&) = delete;
  ModalExact& operator=(const ModalExact&) = delete;
  static ParamSpecs parameters_spec();

  static constexpr const char* kName = "modal-exact";
  void init(const Problem& problem, const State& initial) override;

  // Every event so far: impacts of massive dofs (with impulse; a Zeno stop for the plastic
  // impact that ends an accumulation), arrivals of massless dofs (no impulse) and releases
  // (reaction through zero, or a plastic candidate whose reaction would be tensile).
  // rate_* = g' just before and after (releases: 0, 0).
  using EventKind = ContactEventKind;
  using Event = ContactEvent;
  const std::vector<Event>& events() const override { return event_log_; }

  // Sampling one dof at many times (a study's reference at a scheme's step times) without
  // the O(n m) state reconstruction of step(): advance_to(t) moves the solution to t >= its
  // time, handling the events on the way; state().t is then t, but state().u and v are
  // those of the last event or step() until the next step(). displacement(dof) is u_dof at
  // the current time in O(m); impulses() holds what the contacts gave since that step().
  void advance_to(double t);
  double displacement(Index dof) const;

 private:
  StepInfo advance(double dt_requested) override;
  using Contact = NodeContact;
  struct Mode {
    std::vector<char> closed;                  // per contact
    std::vector<Index> active, massless, held;  // dofs: A, free massless Z, held H
    std::vector<Index> slot;  // per dof: its index in active or massless, -1 when held
    Eigen::MatrixXd phi;      // |A| x m, M_AA-orthonormal
    Eigen::MatrixXd phi_t_m;  // Phi^T M_AA: projection of u_A on q
    Vec omega, force, q_static;  // w_j (0: rigid), f_j, f_j / w_j^2 (0: rigid)
    std::vector<Index> rigid;    // indices of the rigid modes
    Eigen::MatrixXd cond;     // u_Z = cond0 + cond q
    Vec cond0;
    Eigen::MatrixXd signal;   // s_i = signal0_i + signal.row(i) q
    Vec signal0;
    double sample_step;       // search spacing; +inf without oscillating modes
    Index size() const { return omega.size(); }
  };

  const Mode& mode_for(const std::vector<char>& closed);
  Mode build_mode(const std::vector<char>& closed);
  // The modes already built for the same system (K_, M_, F_, contacts_, samples_per_period_,
  // compared bit for bit) by any ModalExact of the process: a study sets up a reference per case
  // on a few meshes, and the O(n^3) eigendecompositions were most of a case's CPU time at
  // n = 800. A pure cache (the same inputs give the same bits), bounded (kSharedModeBytes,
  // least recently used out).
  std::optional<Mode> shared_mode(const std::vector<char>& closed) const;
  void share_mode(const Mode& md) const;
  struct SharedModes;
  static std::list<SharedModes>& shared_modes(std::mutex*& guard);
  // q_, qd_ at tau (positions only when qd is null) into qt, qdt.
  void modal_at(double tau, Vec& qt, Vec* qdt) const;
  double signal_value(Index i, const Vec& q) const;
  // Derivative r = 0..3 of signal i at the current q_, qd_, with its round-off scale.
  void signal_derivative(Index i, int r, double& value, double& scale) const;
  // +1 / -1: sign of the first derivative (from order r0) of signal i that is not zero to
  // round-off; 0 when all are.
  int leading_sign(Index i, int r0) const;
  // First event in (0, tau_max], or contact -1. forced: signal `contact` starts at zero and
  // its derivatives say it moves up, but it is below zero at every sample down to round-off
  // (an excursion too small to resolve): the handler overrules the derivatives.
  struct Found {
    double tau;
    Index contact;
    bool forced;
  };
  Found find_event(double tau_max);
  long advance_through_events(double target);  // returns the events handled
  // The first root of signal i in (lo, hi] given its values there (fhi < 0).
  Found locate(Index i, double lo, double flo, double hi, double fhi);
  double refine(Index i, double a, double fa, double b, double fb);
  void propagate(double tau);     // q_, qd_ to tau; closed contacts' reactions into impulses_
  void reconstruct();             // state_.u, state_.v from the mode and q_, qd_
  void project();                 // q_, qd_ from state_.u, state_.v (held, massless set)
  // Impacts, arrivals, closings and releases at the current state; `fired`: the contact
  // whose signal crossed zero (-1: none, at init), `forced` as in Found. Leaves the new mode
  // and q_, qd_ set.
  void handle_events(Index fired, bool forced);
  void publish_work();

  double zeno_velocity_;
  long samples_per_period_;
  LcpOptions lcp_;
  std::vector<Contact> contacts_;
  std::vector<char> massless_;        // per dof
  std::vector<Index> contact_of_;     // per dof, -1: none
  Eigen::MatrixXd K_, M_;             // dense
  Vec F_;
  Eigen::MatrixXd minv_lt_;           // M_SS^{-1} L^T on the massive dofs (n x p), 0 on massless rows
  double e_ = 0.0;
  std::map<std::vector<char>, Mode> modes_;
  const Mode* mode_ = nullptr;
  // Work space, sized at init: modal state at the anchor (q_, qd_) and at tau, the signals
  // at the last two samples, the vertices of their polynomial parts, the hits of an event.
  Vec q_, qd_, qt_, qdt_, qint_, work_a_, work_b_, signal_prev_, signal_now_, vertex_, lcp_x_;
  std::vector<char> closed_work_;
  std::vector<Index> hits_, lcp_set_;
  std::vector<double> restitution_, rate_before_;
  // Work counters inside work_.extra (map nodes are stable): updating them allocates nothing.
  std::vector<std::pair<double*, const long*>> published_;
  std::vector<Event> event_log_;
  long events_ = 0, impacts_ = 0, arrivals_ = 0, releases_ = 0, zeno_stops_ = 0, decompositions_ = 0, cholesky_ = 0;
  long root_evaluations_ = 0, forced_events_ = 0, force_equivalents_ = 0;
};

}  // namespace nsb
