#pragma once
// Restitution of a clamped linear spring-dashpot contact (Kelvin-Voigt, force
// f = max(0, -k g - c g') while g < 0), shared by the penalty schemes (cd_penalty.hpp,
// reference/penalty.hpp) so that both map a Newton restitution e to the same damping:
//     e(zeta) = |x'(t*)|,  x'' + 2 zeta x' + x = 0,  x(0) = 0, x'(0) = 1,
//     t* = first t > 0 where x + 2 zeta x' = 0 (the clamped force vanishes),
//     c = 2 zeta sqrt(k m),  m the contact's effective mass 1 / (L M^{-1} L^T)_ii
// (closed form under-, critically and over-damped). e -> 0 needs zeta -> inf: callers cap
// zeta and say so. References: Hunt & Crossley, J. Appl. Mech. 42 (1975); Schwager &
// Poeschel, Phys. Rev. E 75 (2007).
namespace nsb {

// Restitution of a clamped spring-dashpot of damping ratio zeta >= 0.
double spring_dashpot_restitution(double zeta);
// The damping ratio giving restitution e in [0, 1], at most max_ratio (e below
// spring_dashpot_restitution(max_ratio) gets max_ratio).
double spring_dashpot_damping_ratio(double e, double max_ratio);

}  // namespace nsb
