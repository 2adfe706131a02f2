#include "problems/bar3d_exact.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <string>

#include "problems/input_check.hpp"

namespace nsb {

double oedometric_modulus(double E, double nu) {
  require_input(E > 0.0 && std::isfinite(E), "bar-3d", "E", E, "(0, inf)");
  require_input(nu >= 0.0 && nu < 0.5, "bar-3d", "nu", nu, "[0, 0.5)");
  return E * (1.0 - nu) / ((1.0 + nu) * (1.0 - 2.0 * nu));
}

double p_wave_speed(double E, double nu, double rho) {
  require_input(rho > 0.0 && std::isfinite(rho), "bar-3d", "rho", rho, "(0, inf)");
  return std::sqrt(oedometric_modulus(E, nu) / rho);
}

double bar3d_contact_duration(double L, double E, double nu, double rho) {
  require_input(L > 0.0 && std::isfinite(L), "bar-3d", "L", L, "(0, inf)");
  return 2.0 * L / p_wave_speed(E, nu, rho);
}

std::unique_ptr<SignoriniBar> oedometric_bar(const Params& signorini_params, double nu) {
  std::map<std::string, std::string> values = signorini_params.values();
  values["E"] = fmt::format("{:.17g}", oedometric_modulus(signorini_params.real("E"), nu));
  return std::make_unique<SignoriniBar>(Params(SignoriniBar::parameters_spec(), values));
}

}  // namespace nsb
