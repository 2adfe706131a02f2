#include "integrators/capabilities.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vector>

namespace nsb {

const Capabilities& DeclaredCapabilities::resolved(const Params& params) const {
  return !when.parameter.empty() && params.real(when.parameter) == when.value ? when.when_equal : always;
}

std::string DeclaredCapabilities::condition(const Params& params) const {
  if (when.parameter.empty()) return {};
  return fmt::format(" with {} {} {}", when.parameter, params.real(when.parameter) == when.value ? "=" : "!=", when.value);
}

namespace {

std::string needs_text(const Capabilities& c) {
  std::vector<std::string> parts;
  if (c.explicit_step) parts.push_back("explicit");
  if (c.mass != MassNeed::Any) parts.push_back(mass_need_name(c.mass));
  if (c.linear_only) parts.push_back("linear F_int");
  if (c.constant_force_only) parts.push_back("constant F_ext");
  if (c.inelastic_only) parts.push_back("e = 0 on contacts with mass");
  if (c.node_to_rigid_only) parts.push_back("node-to-rigid contacts");
  if (!c.max_dofs_parameter.empty()) parts.push_back(fmt::format("ndof <= {}", c.max_dofs_parameter));
  return parts.empty() ? "none" : fmt::format("{}", fmt::join(parts, "; "));
}

}  // namespace

std::string DeclaredCapabilities::text() const {
  if (when.parameter.empty()) return needs_text(always);
  return fmt::format("with {} != {}: {}; with {} = {}: {}", when.parameter, when.value, needs_text(always), when.parameter,
                     when.value, needs_text(when.when_equal));
}

const char* mass_need_name(MassNeed need) {
  switch (need) {
    case MassNeed::Any: return "any mass";
    case MassNeed::Diagonal: return "diagonal mass >= 0";
    case MassNeed::DiagonalPositive: return "diagonal mass > 0";
    case MassNeed::NoMasslessDofs: return "no massless dof";
  }
  return "?";
}

namespace {

// The one wording of every refusal: each requirement the problem misses, collected so that
// the one line names them all.
struct Refusal {
  std::string integrator;  // its name, and the parameter switch that applies (" with theta = 0")
  const Problem& problem;
  std::vector<std::string> shortfalls = {};

  void operator()(const std::string& need, const std::string& has, const std::string& valid) {
    shortfalls.push_back(fmt::format("needs {}; problem {} has {} (valid: {})", need, problem.name(), has, valid));
  }
  void throw_if_any() const {
    if (!shortfalls.empty())
      throw InputError(fmt::format("integrator {} {}", integrator, fmt::join(shortfalls, "; it also ")));
  }
};

// What M lacks for `need`, "" when it meets it.
std::string mass_shortfall(MassNeed need, const SpMat& M) {
  if (need == MassNeed::Any) return {};
  if (need == MassNeed::NoMasslessDofs) {
    for (Index k = 0; k < M.rows(); ++k)
      if (!(M.coeff(k, k) > 0.0)) return fmt::format("a massless dof (dof {} has mass {})", k, M.coeff(k, k));
    return {};
  }
  const auto m = diagonal_mass(M);
  if (!m) return "a non-diagonal mass matrix";
  for (Index k = 0; k < m->size(); ++k) {
    const double mk = (*m)[k];
    if (need == MassNeed::DiagonalPositive ? !(mk > 0.0) : !(mk >= 0.0))
      return fmt::format("{} (dof {} has mass {})", mk == 0.0 ? "a massless dof" : "a negative mass", k, mk);
  }
  return {};
}

std::string mass_requirement(MassNeed need) {
  switch (need) {
    case MassNeed::Diagonal: return "a diagonal mass matrix with entries >= 0";
    case MassNeed::DiagonalPositive: return "a diagonal mass matrix with entries > 0 (M^{-1} in the update)";
    case MassNeed::NoMasslessDofs: return "an invertible mass matrix (every diagonal entry > 0)";
    case MassNeed::Any: break;
  }
  return "any mass matrix";
}

// What keeps the contacts from being node-to-rigid, "" when they are.
std::string node_to_rigid_shortfall(const Problem& problem) {
  using RowMajor = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  const RowMajor L = problem.gap_operator();
  std::vector<Index> contact_of(static_cast<std::size_t>(problem.ndof()), -1);
  for (Index i = 0; i < L.rows(); ++i) {
    Index dofs = 0, dof = -1;
    for (RowMajor::InnerIterator it(L, i); it; ++it)
      if (it.value() != 0.0) ++dofs, dof = it.col();
    if (dofs != 1) return fmt::format("contact {} acting on {} dofs", i, dofs);
    Index& other = contact_of[static_cast<std::size_t>(dof)];
    if (other >= 0) return fmt::format("contacts {} and {} on dof {}", other, i, dof);
    other = i;
  }
  return {};
}

// True when some contact row acts on a dof that has mass: where an impact law would act.
bool contact_on_massive_dof(const SpMat& M, const SpMat& L) {
  for (Index j = 0; j < L.outerSize(); ++j)
    for (SpMat::InnerIterator it(L, j); it; ++it)
      for (SpMat::InnerIterator m(M, j); m; ++m)
        if (m.value() != 0.0) return true;
  return false;
}

}  // namespace

void check_capabilities(const DeclaredCapabilities& declared, const std::string& integrator, const Params& params,
                        const Problem& problem, const SpMat& mass) {
  const Capabilities& can = declared.resolved(params);
  Refusal refuse{integrator + declared.condition(params), problem};
  const Contacts& c = problem.contacts();
  if (problem.contacts_move() && !can.moving_contacts)
    refuse("contacts with constant kinematics (g = g0 + L U, L and T fixed)",
           "contacts that move with the configuration (g(U), L(U), T(U))",
           "a problem whose contact rows are constant, or an integrator `nsbench list` marks as treating moving contacts");
  if (c.has_cone() && !can.friction_cone)
    refuse("2D contacts (one tangent row: the Coulomb interval) or mu = 0",
           fmt::format("3D contacts with friction (two tangent rows: the Coulomb cone, mu = {})", c.max_mu()),
           "a problem with 2D contacts or mu = 0, or an integrator `nsbench list` marks as treating the 3D friction cone");
  if (c.has_friction() && !can.friction)
    refuse("mu = 0 (it does not treat Coulomb friction)", fmt::format("mu = {}", c.max_mu()),
           "a problem with mu = 0, or an integrator `nsbench list` marks as treating friction");
  if (can.linear_only && !problem.is_linear())
    refuse("a linear F_int (F_int = K u, K constant)", "a nonlinear F_int", "a linear problem");
  if (can.constant_force_only && !problem.external_force_is_constant())
    refuse("a constant F_ext", "a time-dependent F_ext", "a problem with a constant load");
  if (can.inelastic_only && problem.restitution() > 0.0 && contact_on_massive_dof(mass, problem.gap_operator()))
    refuse("e = 0 on contacts with mass (it has no velocity-level impact law)",
           fmt::format("restitution e = {} on a contact with mass", problem.restitution()),
           "e = 0, or a problem whose contact dofs are massless, e.g. mass=singular");
  if (!can.max_dofs_parameter.empty()) {
    const long max_dofs = params.integer(can.max_dofs_parameter);
    if (problem.ndof() > max_dofs)
      refuse(fmt::format("at most {} = {} dofs", can.max_dofs_parameter, max_dofs), fmt::format("{} dofs", problem.ndof()),
             fmt::format("{} >= {}, or a smaller problem", can.max_dofs_parameter, problem.ndof()));
  }
  if (const std::string has = mass_shortfall(can.mass, mass); !has.empty())
    refuse(mass_requirement(can.mass), has, "a problem with a lumped mass, e.g. mass=lumped");
  if (can.node_to_rigid_only && !problem.contacts_move())
    if (const std::string has = node_to_rigid_shortfall(problem); !has.empty())
      refuse("node-to-rigid contacts (each contact on one dof, one contact per dof)", has,
             "a problem whose contacts each hold one dof against a fixed obstacle");
  refuse.throw_if_any();
}

}  // namespace nsb
