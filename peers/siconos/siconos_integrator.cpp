#include "peers/siconos/siconos_integrator.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <mutex>
#include <stdexcept>

#ifndef NSBENCH_SICONOS_VERSION
#define NSBENCH_SICONOS_VERSION "unknown"
#endif

namespace nsb {

std::string siconos_version() { return NSBENCH_SICONOS_VERSION; }

namespace {

// Siconos calls BLAS (dgemm, dgemv: uBLAS products routed to it, Lemke), and Debian's serial
// OpenBLAS is not safe to call from two threads at once (moreau_jean.hpp: its buffer table is
// taken without a lock). A study runs cases in parallel, so every use of a Siconos model
// (building, stepping, destroying) holds this one lock. ThreadSanitizer on the peers study
// with 2 jobs found the race in dgemm_oncopy under SiconosIntegrator::step before it.
// The registry entries name it (shared_lock) so that studies do not run two Siconos cases at once.
constexpr const char* kSiconosLock = "Siconos (BLAS)";
std::mutex& siconos_mutex() {
  static std::mutex m;
  return m;
}

std::vector<double> dense(const SpMat& A) {
  std::vector<double> out(static_cast<std::size_t>(A.rows() * A.cols()), 0.0);
  for (Index k = 0; k < A.outerSize(); ++k)
    for (SpMat::InnerIterator it(A, k); it; ++it) out[static_cast<std::size_t>(it.row() * A.cols() + it.col())] = it.value();
  return out;
}

std::vector<double> to_std(const Vec& x) { return {x.data(), x.data() + x.size()}; }

}  // namespace

ParamSpecs SiconosIntegrator::parameters_spec(siconos::Scheme scheme) {
  ParamSpecs specs;
  if (scheme == siconos::Scheme::MoreauJean) {
    specs.push_back(ParamSpec::real("theta", 0.5, 0.5, 1.0, "theta of MoreauJeanOSI"));
    specs.push_back(ParamSpec::real("gamma", 0.5, 0.0, 1.0, "MoreauJeanOSI's activation forecast: contacts with y_k + gamma h y'_k <= 0 are active (Siconos' default 1/2)"));
  }
  if (scheme == siconos::Scheme::SchatzmanPaoli)
    specs.push_back(ParamSpec::real("theta", 0.0, 0.0, 1.0, "theta of SchatzmanPaoliOSI (W = M + h^2 theta^2 K; 0: explicit)"));
  specs.push_back(ParamSpec::real("lcp_tol", 1e-12, 0.0, 1e-2, "tolerance of Siconos' Lemke LCP solver", true));
  if (scheme == siconos::Scheme::MoreauJean) {
    specs.push_back(ParamSpec::choice("one_step_problem", "auto", {"auto", "fc3d"},
                                      "Siconos' one-step problem: auto (Lemke LCP without friction, FrictionContact(2) with 2D friction, "
                                      "FrictionContact(3) with the 3D cone), fc3d (FrictionContact(3) on every contact, mu = 0 and zero "
                                      "tangent rows where the problem has none)"));
    specs.push_back(ParamSpec::real("friction_tol", 1e-12, 0.0, 1e-2, "tolerance of Siconos' friction solver (SICONOS_FRICTION_2D_NSGS or _3D_NSGS)", true));
    specs.push_back(ParamSpec::integer("friction_max_iter", 1000, 1, 1000000, "cap on the friction solver's Gauss-Seidel sweeps per step"));
  }
  specs.push_back(ParamSpec::integer("max_dofs", 128, 1, 100000, "largest problem accepted (Siconos gets dense M, K and W: O(n^2) per step)"));
  return specs;
}

SiconosIntegrator::SiconosIntegrator(const Params& params, siconos::Scheme scheme)
    : Integrator(params), scheme_(scheme) {}

SiconosIntegrator::~SiconosIntegrator() {
  const std::lock_guard lock(siconos_mutex());
  model_.reset();
}

void SiconosIntegrator::init(const Problem& problem, const State& initial) {
  const std::string who = fmt::format("--integrator {}", name());
  bind(problem, initial);
  const Contacts& contacts = problem.contacts();
  if (contacts.has_friction())
    for (Index i = 0; i < contacts.size(); ++i) {
      const double w = contacts.tangent_velocity[i], w2 = contacts.has_cone() ? contacts.tangent2_velocity[i] : 0.0;
      if (w != 0.0 || w2 != 0.0)
        throw InputError(fmt::format("{}: problem '{}' has an obstacle moving along contact {} (tangent_velocity w = {}, tangent2_velocity w2 = {}, e.g. "
                                     "block-2d's floor_velocity); Siconos' LagrangianLinearTIR has no velocity offset (y' = C v), so its slip "
                                     "would be T v instead of T v - w (valid: floor_velocity = 0, or mu = 0)",
                                     who, problem.name(), i, w, w2));
    }
  {
    const std::lock_guard lock(siconos_mutex());
    model_.reset();
  }
  h_ = 0.0;
}

void SiconosIntegrator::build(double h) {
  const Problem& problem = *problem_;
  siconos::ModelSpec spec;
  spec.scheme = scheme_;
  if (scheme_ != siconos::Scheme::D1MinusLinear) spec.theta = params_.real("theta");
  if (scheme_ == siconos::Scheme::MoreauJean) spec.gamma = params_.real("gamma");
  spec.lcp_tol = params_.real("lcp_tol");
  const Contacts& contacts = problem.contacts();
  if (scheme_ == siconos::Scheme::MoreauJean) {
    spec.fc3d = contacts.has_cone() || params_.choice("one_step_problem") == "fc3d";
    spec.friction_tol = params_.real("friction_tol");
    spec.friction_max_iter = static_cast<int>(params_.integer("friction_max_iter"));
  }
  if (contacts.has_friction()) {
    for (Index i = 0; i < contacts.size(); ++i) spec.tangent_rows.push_back(dense(SpMat(contacts.tangent.row(i))));
    if (contacts.has_cone())
      for (Index i = 0; i < contacts.size(); ++i) spec.tangent2_rows.push_back(dense(SpMat(contacts.tangent2.row(i))));
    spec.mu = to_std(contacts.mu);
  }
  spec.h = h;
  spec.t0 = state_.t;
  spec.restitution = problem.restitution();
  spec.ndof = static_cast<int>(problem.ndof());
  spec.mass = dense(mass_);
  SpMat K;
  problem.tangent_stiffness(state_.u, K);
  ++work_.tangent_evaluations;
  spec.stiffness = dense(K);
  Vec f_ext = Vec::Zero(problem.ndof());
  problem.external_force(state_.t, f_ext);
  if (f_ext.squaredNorm() > 0.0) spec.f_ext = to_std(f_ext);
  spec.q0 = to_std(state_.u);
  spec.v0 = to_std(state_.v);
  const SpMat& L = problem.gap_operator();
  for (Index i = 0; i < L.rows(); ++i) spec.gap_rows.push_back(dense(SpMat(L.row(i))));
  spec.gap_offset = to_std(problem.gap_offset());
  const std::lock_guard lock(siconos_mutex());
  model_ = std::make_unique<siconos::Model>(spec);
  h_ = h;
}

StepInfo SiconosIntegrator::advance(double h) {
  if (!model_) build(h);
  if (h != h_)
    throw InputError(fmt::format("--dt: {} takes one fixed step (Siconos' TimeDiscretisation, built with {}); got {}", name(), h_, h));
  siconos::StepStats stats;
  {
    const std::lock_guard lock(siconos_mutex());
    stats = model_->step(state_.u.data(), state_.v.data(), {impulses_.data(), tangential_impulses_.data(), tangential_impulses2_.data()});
  }
  ++work_.force_evaluations;  // one K q product per step, inside Siconos
  StepInfo info;
  info.dt = h;
  info.iterations = stats.iterations;
  info.converged = stats.converged;
  work_.lcp_iterations += stats.iterations;
  if (!stats.converged) ++work_.lcp_unconverged;
  return info;
}

NSBENCH_INTEGRATOR({"siconos-moreau-jean", "peer: Siconos MoreauJeanOSI(theta, gamma), TimeStepping, Lemke LCP, or 2D / 3D NSGS FrictionContact with friction (linear problems)", &SiconosPeer<siconos::Scheme::MoreauJean>::parameters_spec, &make_from_params<Integrator, SiconosPeer<siconos::Scheme::MoreauJean>>, false, true,
                    {.friction = true, .friction_cone = true, .mass = MassNeed::NoMasslessDofs, .linear_only = true, .constant_force_only = true, .max_dofs_parameter = "max_dofs"}, {}, kSiconosLock});
NSBENCH_INTEGRATOR({"siconos-schatzman-paoli", "peer: Siconos SchatzmanPaoliOSI(theta), TimeStepping, position-level Lemke LCP (linear problems)", &SiconosPeer<siconos::Scheme::SchatzmanPaoli>::parameters_spec, &make_from_params<Integrator, SiconosPeer<siconos::Scheme::SchatzmanPaoli>>, false, true,
                    {.mass = MassNeed::NoMasslessDofs, .linear_only = true, .constant_force_only = true, .max_dofs_parameter = "max_dofs"}, {}, kSiconosLock});
NSBENCH_INTEGRATOR({"siconos-d1-minus-linear", "peer: Siconos D1MinusLinearOSI, TimeSteppingD1Minus, impact and contact-force Lemke LCPs (linear problems)", &SiconosPeer<siconos::Scheme::D1MinusLinear>::parameters_spec, &make_from_params<Integrator, SiconosPeer<siconos::Scheme::D1MinusLinear>>, false, true,
                    {.mass = MassNeed::NoMasslessDofs, .linear_only = true, .constant_force_only = true, .max_dofs_parameter = "max_dofs"}, {}, kSiconosLock});

}  // namespace nsb
