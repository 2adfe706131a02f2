#pragma once
// Event-driven reference integrator (CVODE with root finding) for node-to-rigid contacts.
//
// Between events the smooth dynamics in first-order form, y = (u, v):
//     u' = v,    M v' = F_ext(t) - F_int(u) = F            (M diagonal, positive)
// with each contact i acting on a single dof d: g_i = g0_i + a_i u_d.  Contact modes:
//   open    g_i free;  root on g_i (decreasing through 0) = impact;
//   closed  dof held on the obstacle (u_d = -g0_i / a_i, v_d = 0, u_d' = v_d' = 0) with the
//           reaction  lambda_i = -F_d / a_i;  root on lambda_i (decreasing through 0) =
//           the reaction would become tensile: the contact reopens.
// At an impact (Newton's law, Acary & Brogliato 2008, sec. 6.1 and ch. 7): the contacts I
// hitting together (root found, or gap <= atol and closing) solve the impulse LCP
//     0 <= Lambda  _|_  g'+ + e_i g'-  >= 0,   g'+ = g'- + H Lambda,   H = L_I M^{-1} L_I^T
// (solve_lcp; H is diagonal here since the contacts sit on distinct dofs), v += M^{-1} L^T Lambda,
// the gaps are set to zero exactly, then CVODE restarts (CVodeReInit).
// Restart at a zero gap: every root watches one direction (decreasing), and a gap that is
// exactly zero at a restart is not a root for CVODE until it has moved away, so the rebound
// itself cannot fire the root again.
// Zeno (accumulation of impacts): a rebound slower than `zeno_velocity` is replaced by a
// plastic impact (e_i = 0) and the contact closes (counted in work().extra["zeno_stops"]).
// With the bouncing mass this ends the bounces within 2 zeno_velocity / (g (1 - e)) of the
// accumulation time. Choose zeno_velocity >> sqrt(g atol): the gap is only known to about
// atol, which shifts a landing at speed v by atol / v in time and g atol / v in speed (the
// default 1e-4 m/s keeps that below 1e-4 relative at the default atol = 1e-13).
// A closing contact stays closed when its acceleration-level LCP
//     0 <= lambda  _|_  g'' = L M^{-1} (F + L^T lambda)  >= 0
// gives lambda > 0, and opens otherwise.
//
// step(dt) advances to t + dt exactly (CVODE in CV_NORMAL mode: interpolated output, no
// restart unless an event happens); impulses() is what the contacts gave during the step:
// the impacts' impulses plus the closed contacts' reactions integrated over the step
// (p extra states Lambda_i' = lambda_i while contact i is closed, under CVODE's error
// control), so the momentum balance holds with them as with any time-stepping scheme.
// Work: CVODE steps, RHS (= F_int) evaluations, Jacobian evaluations, KLU factorisations,
// Newton iterations; extra: root_evaluations, events, impacts, releases, zeno_stops,
// restarts, error_test_failures.
//
// Declared (the registry entry; refused when the problem binds): a diagonal mass with
// entries > 0 (a massless dof is an algebraic equation: IDA or elimination, not done here),
// node-to-rigid contacts. Refused by init() (InputError): an initial penetration beyond atol, an open initial gap within atol (it would
// count as touching: the run would start on the obstacle, not at the problem's state).
// Checked after every step: an open contact penetrated beyond 1e3 (atol + rtol |u_d|) is an
// impact the root finder missed (zeno_velocity tiny, a grazing landing): the run stops as
// diverged with that reason, not a solution reported as ok.
//
// References: V. Acary, B. Brogliato, Numerical Methods for Nonsmooth Dynamical Systems,
// Springer 2008, ch. 7 (event-driven schemes); F. Pfeiffer, C. Glocker, Multibody Dynamics
// with Unilateral Contacts, Wiley 1996; SUNDIALS CVODE user guide v6.4.1 (root finding,
// CVodeReInit). See reference/cvode.hpp.
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): it locates impacts and releases by
// root finding on g0 + L U(t) and integrates the constrained phases with L constant; locating
// on g(U(t)) is cheap, but the constrained phases would need L(U) and the curvature term
// (dL/dU [V]) V in their index reduction, which are not implemented, so the reference declines
// rather than integrate frozen rows. It would run no case of the suite if it did: every
// problem with moving contacts has friction (the rocking block's pivot must stick to rock, the
// Painleve rod's jam is a friction effect, the blocks slide with mu), which this reference does
// not treat (the capability "friction": a closed contact here holds the normal direction only).
#include <memory>

#include "integrators/integrator.hpp"
#include "solvers/lcp.hpp"
#include "reference/cvode.hpp"
#include "reference/node_contacts.hpp"

namespace nsb {

class EventDriven final : public Integrator, private OdeSystem {
 public:
  explicit EventDriven(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;

  // Every event located so far: impacts (a Zeno stop for a rebound replaced by a plastic
  // impact) with g' before and after and the impulse, and releases: a closed contact's
  // reaction reaching zero, or a plastic impact's contact whose reaction would be tensile
  // (it leaves the obstacle from rest).
  const std::vector<ContactEvent>& events() const override { return event_log_; }

 private:
  StepInfo advance(double dt_requested) override;
  using Contact = NodeContact;

  void rhs(double t, ConstVecRef y, VecRef ydot) override;
  void jacobian(double t, ConstVecRef y, CsrMatrix& J) override;
  void roots(double t, ConstVecRef y, VecRef g) override;

  void net_force(double t, ConstVecRef u);  // f_ = F_ext(t) - F_int(u)
  // Impacts, closings and releases at (t, y_), given the roots CVODE reported; restarts.
  void handle_events(double t, const std::vector<int>& fired);
  void close(const Contact& c);  // holds the dof on the obstacle
  void publish_work();
  void check_no_penetration(double t) const;  // throws std::runtime_error (the run: diverged)

  CvodeSettings settings_;
  double zeno_velocity_;
  LcpOptions lcp_;
  std::unique_ptr<Cvode> cvode_;
  std::vector<Contact> contacts_;
  std::vector<char> closed_;      // per contact
  std::vector<char> dof_closed_;  // per dof
  Vec minv_, y_, f_, fext_, g_;
  SpMat K_;
  double e_ = 0.0;
  std::vector<ContactEvent> event_log_;
  long events_ = 0, releases_ = 0, zeno_stops_ = 0;
};

}  // namespace nsb
