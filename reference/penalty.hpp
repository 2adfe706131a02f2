#pragma once
// Penalty-regularised stiff reference: CVODE BDF with KLU and an analytic sparse Jacobian.
//
// Signorini's law is replaced by a compliant contact (spring-dashpot, Kelvin-Voigt) on each
// contact i, with gap g_i = g0_i + L_i u and the force clamped at zero (no adhesion):
//     f_i = -k g_i - c_i g'_i   while contact i is on;  on  <=>  g_i < 0 and f_i > 0
//     M u'' = F_ext(t) - F_int(u) + sum_on L_i^T f_i
// k = `stiffness` [N/m]; the penalty solution tends to the Signorini/Newton one as k -> inf
// (contact duration, penetration and phase errors of order 1/omega_i = sqrt(m_i / k),
// m_i = 1 / (L M^{-1} L^T)_ii, i.e. rate 1/2 in k).
// Damping: with `damping = restitution`, c_i = 2 zeta sqrt(k m_i) with zeta chosen so that
// (integrators/spring_dashpot.hpp; cd-penalty uses its own discrete map, cd_penalty.hpp)
// an isolated clamped contact rebounds with exactly the problem's restitution e:
//     e(zeta) = |x'(t*)|,  x'' + 2 zeta x' + x = 0,  x(0) = 0, x'(0) = 1,
//     t* = first t > 0 where x + 2 zeta x' = 0 (the clamped force vanishes)
// (closed form under- and over-damped; e -> 0 needs zeta -> inf, so zeta is capped at 16,
// a rebound of 1e-3 of the impact speed: stiffer dashpots switch faster than the root
// finding resolves, see penalty.cpp). `damping = none`: c = 0, the plain penalty
// k max(0, -g) (elastic: e = 1 at the contact itself).
// The on/off switches are located by root finding (on g_i and f_i, one direction each for
// the current mode) and CVODE restarts there, so each smooth phase has a smooth right-hand
// side and an exact Jacobian. At every CVODE return (root or output time) each contact's
// mode is set from the state, on <=> g_i < 0 and f_i > 0, a value exactly at zero decided
// by the motion (a gap at zero is on while closing): a root says where to look, not what
// to switch.
//     y = (u, v, Lambda),  u' = v,  v' = M^{-1} (F + sum_on L_i^T f_i),  Lambda_i' = f_i [on]
//     J = [ 0                          I               0 ]
//         [ -M^{-1} (K + k L_on^T L_on)  -M^{-1} L_on^T C L_on   0 ]
//         [ -k L_on                     -C L_on          0 ]
// Lambda (the time integral of the contact force) gives impulses(): its increase over a
// step, comparable with the impulses of the impulse-based schemes. It is a quadrature, left
// out of CVODE's error test (see penalty.cpp): M v' carries the same forces.
// Friction (docs/method.md section 6; a problem with mu > 0 somewhere): cd-penalty's regularised
// Coulomb law (integrators/spring_dashpot.hpp), here as a force of the ODE,
//     f_T,i = -mu_i f_i [on] phi(u_T,i / v_reg),  u_T,i = T_i v - w_i,  phi = clamp(., -1, 1)
//     v' += M^{-1} T^T f_T,   Lambda_T,i' = f_T,i   (y gains Lambda_T after Lambda)
// v_reg = `friction_velocity`. Jacobian rows of f_T (added to v' through M^{-1} T^T and to
// Lambda_T'): df_T/du = -mu phi (-k L_i) [on], df_T/dv = -mu phi (-c_i L_i) [on] - mu f_i / v_reg
// T_i [|u_T| < v_reg]: exact on each branch, piecewise at |u_T| = v_reg, where the force is
// continuous and its slope jumps. No root there: BDF's error test resolves the one kink of a
// stop or a start of slip, and a root would restart CVODE at every entry into the band.
// The viscous branch, c_T = mu f_i / v_reg, is stiff (relaxation time v_reg / (mu g) ~ 0.2 ms
// for a body resting under its weight at v_reg = 1 mm/s, mu = 0.5): BDF takes it in stride.
// As a reference its friction error is the regularisation's: a sliding body that stops
// reaches the band |u_T| = v_reg at t_s - v_reg / |a| (a its Coulomb deceleration) and then
// creeps at v_reg tan(alpha) / mu on a slope of angle alpha, O(v_reg) both
// (tests/reference/penalty_test.cpp measures it against the exact stop and the creep rate).
// Lambda_T gives tangential_impulses(), as Lambda gives impulses(). mu = 0 on every contact:
// y, the Jacobian and the roots are those of the frictionless scheme, bit for bit.
// 3D contacts (Contacts::has_cone, capability "3D friction cone"; docs/three_d.md): the
// regularised cone of spring_dashpot.hpp, the interval become the disk,
//     f_T,i = -mu_i f_i [on] phi(u_T,i / v_reg),  phi(x) = x / max(1, |x|),
//     u_T,i = (T_i v - w_i, T2_i v - w2_i) in R^2,
//     v' += M^{-1} (T^T f_T1 + T2^T f_T2),  Lambda_T2,i' = f_T2,i  (y gains Lambda_T2 last)
// with the Jacobian of that law (its 2x2 slope -mu f_i / v_reg I inside the band, -mu f_i
// (I - n n^T) / |u_T| outside, n = u_T / |u_T|, and -mu phi along f_i): exact on each branch.
// Its error as a reference is the 2D one: the slip reaches the band |u_T| = v_reg at
// t_s - v_reg / |a_slip| and then creeps (a sphere rolling down a slope of angle alpha at
// |u_T| = v_reg (2/7) tan(alpha) / mu, the static friction (2/7) m g sin(alpha) over mu F_N).
// Lambda_T2 gives tangential_impulses2().
// energy(): kinetic + potential + penalty springs k g_i^2 / 2 of the contacts that are on.
// Work counters as for event-driven (reference/cvode.hpp); extra: switches (on/off events),
// missed_switches (switches without a root of their own, found at a CVODE return: a function
// crossing zero twice within one CVODE step), unconfirmed_roots (roots after which the state
// kept the contact's mode, e.g. one reported again after its restart), restitution_floor.
// A missed switch-on is an energy source: the spring starts at k g^2 / 2, never stored (see
// mode(); what one cost on the hard study's block: docs/measurements.md).
// Cost of a bouncing contact with e = 1 (inherent, not a defect): the spring is undamped,
// so every bounce is resolved, its flight (2 v / g) and its contact (pi sqrt(m_i / k) long)
// alike, with a restart at each switch: 1 / (2 v / g + pi sqrt(m / k)) bounces per second,
// each with its own F_int evaluations. The switches measure it; the hard study tabulates them (its grazing drop:
// docs/measurements.md).
// Refused (InputError): a non-diagonal or singular mass (M^{-1} in the right-hand side).
//
// References: P. Wriggers, Computational Contact Mechanics, 2nd ed., Springer 2006, ch. 2
// and 6 (penalty method); J. T. Oden, J. A. C. Martins, Models and computational methods
// for dynamic friction phenomena, CMAME 52 (1985) (velocity-threshold regularisation); K. H. Hunt, F. R. E. Crossley, J. Appl. Mech. 42 (1975) 440-445
// and T. Schwager, T. Poeschel, Phys. Rev. E 75 (2007) (restitution of a clamped linear
// spring-dashpot); SUNDIALS CVODE user guide v6.4.1 (BDF, SUNLinSol_KLU, root finding).
// Moving contacts (Problem::contacts_move): declined through the capability "moving contacts"
// (integrators/capabilities.hpp, one refusal wording): its penalty forces and switching
// functions use the linear gap g0 + L U.
#include <memory>
#include <vector>

#include "integrators/integrator.hpp"
#include "reference/cvode.hpp"

namespace nsb {

class PenaltyBdf final : public Integrator, private OdeSystem {
 public:
  explicit PenaltyBdf(const Params& params);
  static ParamSpecs parameters_spec();

  void init(const Problem& problem, const State& initial) override;
  // Every switch of a contact's spring on or off (a root, or a switch found at a CVODE
  // return), with g' at the switch (continuous: before = after; no impulse).
  const std::vector<ContactEvent>& events() const override { return event_log_; }
  Energy energy() const override;

  // Damping ratio zeta giving restitution e to a clamped spring-dashpot (header formula).
  static double damping_ratio(double e);
  // Restitution of a clamped spring-dashpot of damping ratio zeta.
  static double restitution(double zeta);

 private:
  StepInfo advance(double dt_requested) override;
  void rhs(double t, ConstVecRef y, VecRef ydot) override;
  void jacobian(double t, ConstVecRef y, CsrMatrix& J) override;
  void roots(double t, ConstVecRef y, VecRef g) override;

  void gaps(ConstVecRef y);  // g_, gdot_, f_ (penalty forces as if on)
  void friction_forces(ConstVecRef v);  // ft_ from fc_ (zero on the contacts that are off)
  void friction_jacobian(ConstVecRef y, std::vector<Eigen::Triplet<double, sunindextype>>& entries);
  void set_directions();
  // Mode of contact i from the state gaps() left (force_root: its force root fired).
  bool mode(Index i, bool force_root) const;
  void publish_work();

  CvodeSettings settings_;
  double k_;
  double v_reg_;
  bool damped_;
  bool friction_ = false;
  bool restitution_floored_ = false;  // the problem's e was below e(max damping ratio)
  std::unique_ptr<Cvode> cvode_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> L_;
  Vec minv_, c_, y_, force_, fext_, g_, gdot_, fc_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> T_;
  Vec mu_, w_, ft_;
  bool cone_ = false;  // 3D contacts with friction: T2, w2, the forces along T2
  Eigen::SparseMatrix<double, Eigen::RowMajor> T2_;
  Vec w2_, ft2_;
  std::vector<char> on_;
  SpMat K_;
  long switches_ = 0;
  std::vector<ContactEvent> event_log_;
  long missed_switches_ = 0;  // mode switches found at a CVODE return, not by a root
  long unconfirmed_roots_ = 0;  // roots after which the state kept the contact's mode
};

}  // namespace nsb
