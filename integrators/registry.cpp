#include "integrators/registry.hpp"

#include "core/registry.hpp"
#include "integrators/cd_lagrange.hpp"
#include "integrators/cd_lagrange_adaptive.hpp"
#include "integrators/cd_penalty.hpp"
#include "integrators/d1_minus_linear.hpp"
#include "integrators/moreau_jean.hpp"
#include "integrators/schatzman_paoli.hpp"
#include "integrators/newmark_lm.hpp"
#include "integrators/nsga.hpp"
#include "reference/event_driven.hpp"
#include "reference/modal_exact.hpp"
#include "reference/penalty.hpp"

namespace nsb {

const std::vector<IntegratorEntry>& integrator_registry() {
  static const std::vector<IntegratorEntry> entries = [] {
    std::vector<IntegratorEntry> list = {
      {"cd-lagrange", "explicit variational CD-Lagrange, fixed step, impulse contact", &CdLagrange::parameters_spec, &make_from_params<Integrator, CdLagrange>, false},
      {"cd-lagrange-adaptive", "CD-Lagrange with the step chosen from the discrete energy balance (KMOW variable step), CFL-capped", &CdLagrangeAdaptive::parameters_spec, &make_from_params<Integrator, CdLagrangeAdaptive>, false},
      {"moreau-jean", "Moreau-Jean theta-method, velocity-level LCP with Newton restitution", &MoreauJean::parameters_spec, &make_from_params<Integrator, MoreauJean>, false},
      {"schatzman-paoli", "Schatzman-Paoli two-step scheme, position-level impact law (theta = 0: explicit, Carpenter-Taylor-Katona for e = 0)", &SchatzmanPaoli::parameters_spec, &make_from_params<Integrator, SchatzmanPaoli>, false},
      {"cd-penalty", "explicit central difference with penalty contact (spring-dashpot, kappa = penalty_factor m / dt^2)", &CdPenalty::parameters_spec, &make_from_params<Integrator, CdPenalty>, false},
      {"d1-minus-linear", "Schindler-Acary D1MinusLinear, half-explicit velocity level, impacts at the step's end", &D1MinusLinear::parameters_spec, &make_from_params<Integrator, D1MinusLinear>, false},
      {"nsga", "nonsmooth generalised-alpha (Bruls-Acary-Cardona 2014): position correction and velocity impact law, rho_inf", &Nsga::parameters_spec, &make_from_params<Integrator, Nsga>, false},
      {"newmark-lm", "Newmark (beta, gamma) with position-level Lagrange multipliers; mass redistribution with a singular mass", &NewmarkLm::parameters_spec, &make_from_params<Integrator, NewmarkLm>, false},
      {"event-driven", "reference: CVODE with root finding, Newton impacts, closed-contact mode (node-to-rigid contacts)", &EventDriven::parameters_spec, &make_from_params<Integrator, EventDriven>, true},
      {ModalExact::kName, "reference: exact modal solution of linear problems between contact events, closed-form event signals (node-to-rigid contacts)", &ModalExact::parameters_spec, &make_from_params<Integrator, ModalExact>, true},
      {"penalty-bdf", "reference: penalty-regularised contact (spring-dashpot), CVODE BDF + KLU, analytic sparse Jacobian", &PenaltyBdf::parameters_spec, &make_from_params<Integrator, PenaltyBdf>, true},
    };
    for (auto& peer : peer_integrators()) list.push_back(std::move(peer));
    return list;
  }();
  return entries;
}

const IntegratorEntry& find_integrator(const std::string& name) {
  return find_entry(integrator_registry(), name, "--integrator", "integrator");
}

std::unique_ptr<Integrator> make_integrator(const std::string& name,
                                            const std::map<std::string, std::string>& overrides) {
  return make_entry(find_integrator(name), overrides);
}

}  // namespace nsb
