#pragma once
// Restitution of a clamped linear spring-dashpot contact (Kelvin-Voigt, force
// f = max(0, -k g - c g') while g < 0), the map of penalty-bdf (reference/penalty.hpp),
// which integrates the contact ODE accurately, and the limit of cd-penalty's discrete map
// (cd_penalty.hpp) as its contact spans many steps:
//     e(zeta) = |x'(t*)|,  x'' + 2 zeta x' + x = 0,  x(0) = 0, x'(0) = 1,
//     t* = first t > 0 where x + 2 zeta x' = 0 (the clamped force vanishes),
//     c = 2 zeta sqrt(k m),  m the contact's effective mass 1 / (L M^{-1} L^T)_ii
// (closed form under-, critically and over-damped). e -> 0 needs zeta -> inf: callers cap
// zeta and say so. References: Hunt & Crossley, J. Appl. Mech. 42 (1975); Schwager &
// Poeschel, Phys. Rev. E 75 (2007).
//
// Regularised Coulomb friction, the penalty schemes' tangential law (one place for both):
//     F_T = -mu F_N phi(u_T / v_reg),  phi(x) = clamp(x, -1, 1),  u_T = T v - w,  F_N >= 0
// the velocity-threshold regularisation of J. T. Oden and J. A. C. Martins, "Models and
// computational methods for dynamic friction phenomena", CMAME 52 (1985): Coulomb's sliding
// force for |u_T| >= v_reg, a viscous law of coefficient mu F_N / v_reg below. Why the
// saturated ramp rather than tanh (Chrono's SMC contact, MuJoCo's soft constraints use smooth
// or impedance-based regularisations): (i) above v_reg it is Coulomb's law exactly, so a
// sliding contact carries exactly mu F_N (|F_T| = mu F_N bit for bit, which the block's
// momentum identity checks); (ii) its implicit form has a closed form (below); (iii) creep,
// the regularisation's own error, is linear and explicit: under a tangential load F below
// mu F_N the contact slides steadily at u_T = v_reg F / (mu F_N) (tan(alpha) / mu v_reg on a
// slope), where tanh gives v_reg atanh(F / (mu F_N)), 27% faster at tan(alpha) / mu = 0.73.
// The price: dF_T/du_T jumps at |u_T| = v_reg (an implicit integrator's Jacobian is
// piecewise constant there; the force itself is continuous).
// Implicit form (backward Euler in the slip): with the slip s before the tangential force
// and u_T(+) = s + h_T Lambda_T after a tangential impulse Lambda_T (h_T = T M^{-1} T^T of
// the contact), Lambda_T = -mu Lambda_N phi(u_T(+) / v_reg) is solved by
//     Lambda_T = -mu Lambda_N phi(s / (v_reg + h_T mu Lambda_N))
// (the same law with v_reg widened by the slip the full friction impulse makes): stable for
// any step, and u_T(+) keeps the sign of s (friction never reverses the slip).
//
// The regularised cone (3D contacts, Contacts::has_cone: slip u_T in R^2 along (T, T2)): the
// same law with the interval become the disk,
//     F_T = -mu F_N phi(u_T / v_reg),  phi(x) = x / max(1, |x|)     (the 1D clamp for |x| in R)
// i.e. the viscous law -mu F_N u_T / v_reg for |u_T| < v_reg and Coulomb's sliding force
// -mu F_N u_T / |u_T| (|F_T| = mu F_N, opposite to the slip) beyond. Its slope: dF_T/du_T =
// -mu F_N / v_reg I inside, -mu F_N (I - n n^T) / |u_T| (n = u_T / |u_T|) outside (the
// sliding force turns with the slip, unlike the 1D saturated branch); dF_T/dF_N = -mu phi.
// Implicit form, with H_T = [T; T2] M^{-1} [T; T2]^T (2x2 SPD) and u_T(+) = s + H_T Lambda_T:
// Lambda_T = -mu Lambda_N phi(u_T(+) / v_reg) has one solution (u + H_T dPsi(u) = s, Psi the
// convex potential of the law, is strongly monotone in the H_T^{-1} inner product). H_T = h I
// (a node of a lumped mesh, a rigid sphere): the 1D widening, in closed form,
//     Lambda_T = -mu Lambda_N phi(s / (v_reg + h mu Lambda_N)).
// Any other H_T: the viscous branch u = (I + a / v_reg H_T)^{-1} s (a = mu Lambda_N) if
// |u| <= v_reg, else the sliding branch u = (I + a / r H_T)^{-1} s with |u| = r, the scalar
// equation |(I + a / r H_T)^{-1} s| = r bracketed on [v_reg, |s|] (positive at v_reg, <= 0 at
// |s| since (I + c H_T)^{-1} shrinks) and bisected to 1e-15 relative; then Lambda_T =
// -a u / |u|, on the disk's boundary to round-off. Either way u_T(+) is a positive multiple
// of (I + c H_T)^{-1} s: friction never reverses the slip.
#include <Eigen/Core>
#include <functional>

namespace nsb {

// Restitution of a clamped spring-dashpot of damping ratio zeta >= 0.
double spring_dashpot_restitution(double zeta);
// The damping ratio giving restitution e in [0, 1], at most max_ratio (e below
// spring_dashpot_restitution(max_ratio) gets max_ratio).
double spring_dashpot_damping_ratio(double e, double max_ratio);
// The same for any restitution map zeta -> e(zeta) decreasing towards 0, with
// e(1e-12) > e: bisection in log zeta on [1e-12, max_ratio] (cd_penalty.hpp's discrete map).
double damping_ratio_for_restitution(double e, double max_ratio, const std::function<double(double)>& restitution);

// The law above at normal force (or impulse) `normal` >= 0 and slip rate `slip`, with its
// partial derivatives (d_slip = 0 on the saturated branches, |slip| >= v_reg).
struct RegularisedFriction {
  double force;
  double d_slip;
  double d_normal;
};
RegularisedFriction regularised_friction(double mu, double normal, double slip, double v_reg);
// The implicit form above: the tangential impulse for normal impulse `normal`, slip `slip`
// before it and tangential compliance h_T.
double implicit_regularised_friction(double mu, double normal, double slip, double h_tangent, double v_reg);

// The regularised cone above at normal force `normal` >= 0 and slip `slip` (R^2), with its
// partial derivatives.
struct RegularisedConeFriction {
  Eigen::Vector2d force;
  Eigen::Matrix2d d_slip;
  Eigen::Vector2d d_normal;
};
RegularisedConeFriction regularised_cone_friction(double mu, double normal, const Eigen::Vector2d& slip, double v_reg);
// The cone's implicit form above: the tangential impulse (R^2) for normal impulse `normal`,
// slip `slip` before it and tangential compliance H_T (2x2 SPD).
Eigen::Vector2d implicit_regularised_cone_friction(double mu, double normal, const Eigen::Vector2d& slip,
                                                   const Eigen::Matrix2d& h_tangent, double v_reg);

}  // namespace nsb
