#pragma once
// The 3D bar with its lateral displacements held (oedometric), exact solution (derivation in
// docs/three_d.md; Code_Aster's SDNV100 benchmark uses this bar).
//
// A linear elastic bar of length L (Young's modulus E, Poisson's ratio nu, density rho) whose
// lateral displacements are held has u = (u(x, t), 0, 0): the strain is uniaxial, eps_xx = u_x,
// and the stress sigma_xx = (lambda + 2 mu) u_x, so it obeys the 1D wave equation with the
// oedometric (P-wave) modulus
//     M = lambda + 2 mu = E (1 - nu) / ((1 + nu) (1 - 2 nu)),   c_p = sqrt(M / rho),
// and its impact on a rigid wall is the Signorini bar's d'Alembert solution
// (problems/signorini_bar.hpp) with E replaced by M: contact force A rho c_p v0 for 2 L / c_p.
// oedometric_bar builds that 1D bar, so the exact fields are SignoriniBar's own.
//
// Bad input (InputError, one line): E or rho not > 0, nu outside [0, 0.5) (at 0.5 the modulus
// is infinite: an incompressible bar held laterally cannot deform), L not > 0.
#include <memory>

#include "core/parameters.hpp"
#include "problems/signorini_bar.hpp"

namespace nsb {

double oedometric_modulus(double E, double nu);
double p_wave_speed(double E, double nu, double rho);
double bar3d_contact_duration(double L, double E, double nu, double rho);  // 2 L / c_p

// The Signorini bar of `signorini_params` (signorini-bar's parameters, E the Young's modulus)
// with E replaced by oedometric_modulus(E, nu): the 3D bar's exact solution.
std::unique_ptr<SignoriniBar> oedometric_bar(const Params& signorini_params, double nu);

}  // namespace nsb
