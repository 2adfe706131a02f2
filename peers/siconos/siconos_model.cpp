// Compiled as C++17 (see siconos_model.hpp).
#include "peers/siconos/siconos_model.hpp"

// The kernel's headers one by one: SiconosKernel.hpp (everything) doubles the compile time.
#include <siconos/kernel/D1MinusLinearOSI.hpp>
#include <siconos/kernel/FrictionContact.hpp>
#include <siconos/kernel/Interaction.hpp>
#include <siconos/kernel/LCP.hpp>
#include <siconos/kernel/LagrangianLinearTIDS.hpp>
#include <siconos/kernel/LagrangianLinearTIR.hpp>
#include <siconos/kernel/MoreauJeanOSI.hpp>
#include <siconos/kernel/NewtonImpactFrictionNSL.hpp>
#include <siconos/kernel/NewtonImpactNSL.hpp>
#include <siconos/kernel/NonSmoothDynamicalSystem.hpp>
#include <siconos/kernel/SchatzmanPaoliOSI.hpp>
#include <siconos/kernel/SiconosVector.hpp>
#include <siconos/kernel/SimpleMatrix.hpp>
#include <siconos/kernel/TimeDiscretisation.hpp>
#include <siconos/kernel/TimeStepping.hpp>
#include <siconos/kernel/TimeSteppingD1Minus.hpp>
#include <siconos/numerics/Friction_cst.h>
#include <siconos/numerics/lcp_cst.h>
#include <siconos/numerics/SolverOptions.h>

#include <stdexcept>
#include <string>

namespace nsb::siconos {

namespace {

SP::SiconosVector vector(const std::vector<double>& x) {
  auto out = std::make_shared<SiconosVector>(static_cast<unsigned>(x.size()));
  for (std::size_t i = 0; i < x.size(); ++i) out->setValue(static_cast<unsigned>(i), x[i]);
  return out;
}

SP::SimpleMatrix matrix(const std::vector<double>& a, std::size_t rows, std::size_t cols) {
  auto out = std::make_shared<SimpleMatrix>(static_cast<unsigned>(rows), static_cast<unsigned>(cols));
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t j = 0; j < cols; ++j) out->setValue(static_cast<unsigned>(i), static_cast<unsigned>(j), a[i * cols + j]);
  return out;
}

SP::LCP lemke(double tol) {
  auto p = std::make_shared<LCP>(SICONOS_LCP_LEMKE);
  p->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = tol;
  return p;
}

// Siconos' 2D nonsmooth Gauss-Seidel: per contact, the exact solution of the local law
// (separate, stick, slip either way), as our coulomb.hpp; dense Delassus matrix (LinearOSNS'
// default storage). Residual: |q + W r - u| / |q|.
//
// Siconos' 3D nonsmooth Gauss-Seidel (SICONOS_FRICTION_3D_NSGS) with the local solver Siconos
// 4.4 sets itself (SICONOS_FRICTION_3D_ONECONTACT_NSN_GP_HYBRID: nonsmooth Newton on the
// Alart-Curnier function alternating with a projection on the cone, local tolerance 1e-14, 10
// iterations); residual of the sweep: fc3d_compute_error, the natural-map residual of the cone
// complementarity over |q| (siconos_integrator.hpp).
SP::FrictionContact nsgs(int dimension, double tol, int max_iter) {
  auto p = std::make_shared<FrictionContact>(dimension, dimension == 2 ? SICONOS_FRICTION_2D_NSGS : SICONOS_FRICTION_3D_NSGS);
  p->numericsSolverOptions()->dparam[SICONOS_DPARAM_TOL] = tol;
  p->numericsSolverOptions()->iparam[SICONOS_IPARAM_MAX_ITER] = max_iter;
  return p;
}

// Contact i's rows for FrictionContact(dimension): L_i, then T_i (2, 3) and T2_i (3), a tangent
// row zero where the problem has none.
std::vector<double> contact_rows(const ModelSpec& spec, std::size_t i, int dimension) {
  const std::size_t n = static_cast<std::size_t>(spec.ndof);
  std::vector<double> rows = spec.gap_rows[i];
  const auto append = [&](const std::vector<std::vector<double>>& tangent) {
    if (tangent.empty()) rows.resize(rows.size() + n, 0.0);
    else rows.insert(rows.end(), tangent[i].begin(), tangent[i].end());
  };
  append(spec.tangent_rows);
  if (dimension == 3) append(spec.tangent2_rows);
  return rows;
}

}  // namespace

struct Model::Impl {
  ModelSpec spec;
  SP::LagrangianLinearTIDS ds;
  std::vector<SP::Interaction> contacts;
  SP::NonSmoothDynamicalSystem nsds;
  SP::TimeStepping time_stepping;            // Moreau-Jean, Schatzman-Paoli
  SP::TimeSteppingD1Minus d1_time_stepping;  // D1MinusLinear
  SP::FrictionContact friction;              // MoreauJean with friction (or fc3d): its one-step problem
};

Model::Model(const ModelSpec& spec) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.spec = spec;
  const std::size_t n = static_cast<std::size_t>(spec.ndof);
  try {
    m.ds = std::make_shared<LagrangianLinearTIDS>(vector(spec.q0), vector(spec.v0), matrix(spec.mass, n, n));
    m.ds->setKPtr(matrix(spec.stiffness, n, n));
    if (!spec.f_ext.empty()) m.ds->setFExtPtr(vector(spec.f_ext));
    // The nsbench run driver decides when to stop: Siconos' horizon only has to lie beyond.
    m.nsds = std::make_shared<NonSmoothDynamicalSystem>(spec.t0, spec.t0 + 1e12 * spec.h);
    m.nsds->insertDynamicalSystem(m.ds);
    // FrictionContact(dimension) on every contact, or (dimension 1) the LCP.
    const int dimension = spec.fc3d ? 3 : spec.tangent_rows.empty() ? 1 : 2;
    if (dimension > 1 && spec.scheme != Scheme::MoreauJean)
      throw std::invalid_argument("friction is treated by the Moreau-Jean peer only");
    auto law = std::make_shared<NewtonImpactNSL>(spec.restitution);
    for (std::size_t i = 0; i < spec.gap_rows.size(); ++i) {
      SP::Interaction inter;
      if (dimension > 1) {
        // y = (g_i, T_i q[, T2_i q]): the normal row first, as MoreauJeanOSI's index set reads
        // y(0)(0), y(1)(0); Siconos' tangential reactions act along +T_i, +T2_i (p = C^T
        // lambda) and oppose the slip y'(1:), our Lambda_T and u_T. No tangential restitution
        // (e_t = 0).
        std::vector<double> offset(static_cast<std::size_t>(dimension), 0.0);
        offset[0] = spec.gap_offset[i];
        auto relation = std::make_shared<LagrangianLinearTIR>(matrix(contact_rows(spec, i, dimension), offset.size(), n), vector(offset));
        const double mu = spec.mu.empty() ? 0.0 : spec.mu[i];
        inter = std::make_shared<Interaction>(std::make_shared<NewtonImpactFrictionNSL>(spec.restitution, 0.0, mu, dimension), relation);
      } else {
        auto b = std::make_shared<SiconosVector>(1);
        b->setValue(0, spec.gap_offset[i]);
        auto relation = std::make_shared<LagrangianLinearTIR>(matrix(spec.gap_rows[i], 1, n), b);
        inter = std::make_shared<Interaction>(law, relation);
      }
      m.nsds->link(inter, m.ds);
      m.contacts.push_back(inter);
    }
    auto td = std::make_shared<TimeDiscretisation>(spec.t0, spec.h);
    switch (spec.scheme) {
      case Scheme::MoreauJean: {
        if (dimension > 1) m.friction = nsgs(dimension, spec.friction_tol, spec.friction_max_iter);
        SP::OneStepNSProblem osnsp = m.friction ? SP::OneStepNSProblem(m.friction) : lemke(spec.lcp_tol);
        m.time_stepping = std::make_shared<TimeStepping>(m.nsds, td, std::make_shared<MoreauJeanOSI>(spec.theta, spec.gamma), osnsp);
        m.time_stepping->initialize();
        break;
      }
      case Scheme::SchatzmanPaoli:
        m.time_stepping = std::make_shared<TimeStepping>(m.nsds, td, std::make_shared<SchatzmanPaoliOSI>(spec.theta), lemke(spec.lcp_tol));
        m.time_stepping->initialize();
        break;
      case Scheme::D1MinusLinear:
        m.d1_time_stepping = std::make_shared<TimeSteppingD1Minus>(m.nsds, td, 2);
        m.d1_time_stepping->insertIntegrator(std::make_shared<D1MinusLinearOSI>());
        m.d1_time_stepping->insertNonSmoothProblem(lemke(spec.lcp_tol), SICONOS_OSNSP_TS_VELOCITY);
        m.d1_time_stepping->insertNonSmoothProblem(lemke(spec.lcp_tol), SICONOS_OSNSP_TS_VELOCITY + 1);
        m.d1_time_stepping->initialize();
        break;
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("Siconos model: ") + e.what());
  }
}

Model::~Model() = default;

StepStats Model::step(double* q, double* v, const Impulses& impulses) {
  Impl& m = *impl_;
  StepStats stats;
  try {
    // The solver is not called on a step without active contacts, and then leaves its last
    // counts in place: clear them first.
    SolverOptions* friction_options = m.friction ? m.friction->numericsSolverOptions().get() : nullptr;
    if (friction_options) {
      friction_options->iparam[SICONOS_IPARAM_ITER_DONE] = 0;
      friction_options->dparam[SICONOS_DPARAM_RESIDU] = 0.0;
    }
    // Read between the step and the switch to the next one: the latter resets the
    // multipliers of the contacts it drops from the active set.
    if (m.time_stepping) {
      m.time_stepping->computeOneStep();
      read(q, v, impulses);
      m.time_stepping->nextStep();
    } else {
      m.d1_time_stepping->advanceToEvent();
      read(q, v, impulses);
      m.d1_time_stepping->processEvents();
    }
    if (friction_options) {
      stats.iterations = friction_options->iparam[SICONOS_IPARAM_ITER_DONE];
      // TimeStepping only prints the solver's failure (DefaultCheckSolverOutput): test it here.
      stats.converged = !(friction_options->dparam[SICONOS_DPARAM_RESIDU] > m.spec.friction_tol);
    }
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("Siconos step: ") + e.what());
  }
  return stats;
}

void Model::read(double* q, double* v, const Impulses& impulses) const {
  const SiconosVector& sq = *impl_->ds->q();
  const SiconosVector& sv = *impl_->ds->velocity();
  for (unsigned i = 0; i < sq.size(); ++i) {
    q[i] = sq.getValue(i);
    v[i] = sv.getValue(i);
  }
  const Impl& m = *impl_;
  const double h = m.spec.h;
  for (std::size_t i = 0; i < m.contacts.size(); ++i) {
    const Interaction& inter = *m.contacts[i];
    switch (m.spec.scheme) {
      case Scheme::MoreauJean:  // lambda(1): the impulse of the step, (normal, tangential[, tangential 2]) with friction
        impulses.normal[i] = inter.lambda(1)->getValue(0);
        if (m.friction) impulses.tangential[i] = inter.lambda(1)->getValue(1);
        if (m.spec.fc3d) impulses.tangential2[i] = inter.lambda(1)->getValue(2);
        break;
      case Scheme::SchatzmanPaoli:  // lambda(0) = R, with W (q - q_free) = L^T R: R / h
        impulses.normal[i] = inter.lambda(0)->getValue(0) / h;
        break;
      case Scheme::D1MinusLinear:  // impact impulse, plus the contact force over the step
        impulses.normal[i] = inter.lambda(1)->getValue(0) + (inter.lambda(2) ? h * inter.lambda(2)->getValue(0) : 0.0);
        break;
    }
  }
}

}  // namespace nsb::siconos
