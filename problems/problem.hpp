#pragma once
// Semi-discrete non-smooth mechanical system (DESIGN.md section 1):
//
//     M U'' + F_int(U) = F_ext(t) + L^T lambda
//     g(U) = g0 + L U                       (one row of L per contact; g >= 0 is open)
//     Signorini:  0 <= g  _|_  lambda >= 0
//     Newton impact law on closing contacts:  0 <= Lambda  _|_  g'(+) + e g'(-) >= 0
//
// Sign convention of this suite: g >= 0 open, g' = L M^{-1} P, a positive impulse pushes
// the bodies apart (the talk uses the opposite sign of L).
//
// A Problem is pure data and physics: it knows nothing of time integration. Integrators
// see only this interface, so any integrator runs any problem.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/parameters.hpp"

namespace nsb {

using Vec = Eigen::VectorXd;
using SpMat = Eigen::SparseMatrix<double>;
using Index = Eigen::Index;
using VecRef = Eigen::Ref<Vec>;
using ConstVecRef = Eigen::Ref<const Vec>;

// Displacement and velocity at time t. Staggered schemes document what their `v` means.
struct State {
  double t = 0.0;
  Vec u;
  Vec v;
};

class Problem {
 public:
  virtual ~Problem() = default;

  virtual std::string name() const = 0;
  // The validated parameters this instance was built with (written to every summary).
  virtual const Params& parameters() const = 0;
  virtual Index ndof() const = 0;

  // Mass matrix (n x n). Lumped and singular models are diagonal; a diagonal entry may be
  // zero for a massless dof (singular mass), which integrators must treat quasi-statically.
  virtual SpMat mass_matrix() const = 0;

  // Internal force F_int(u), written into f (size n) without allocating.
  virtual void internal_force(ConstVecRef u, VecRef f) const = 0;
  // Tangent stiffness dF_int/du at u. When K already holds this problem's sparsity pattern
  // (from an earlier call) only the values are refilled.
  virtual void tangent_stiffness(ConstVecRef u, SpMat& K) const = 0;
  // True when F_int(u) = K u with K independent of u (then K can be factorised once).
  virtual bool is_linear() const = 0;
  // Total external force at time t, written into f (size n).
  virtual void external_force(double t, VecRef f) const = 0;
  // True when F_ext does not depend on t (integrators may then evaluate it once).
  virtual bool external_force_is_constant() const { return true; }

  virtual double strain_energy(ConstVecRef u) const = 0;
  // Potential of the conservative part of F_ext (gravity); F_ext = -dV_load/du for it.
  virtual double load_potential(ConstVecRef u) const = 0;
  double potential(ConstVecRef u) const { return strain_energy(u) + load_potential(u); }

  // Contact: L (p x n), g0 (size p), Newton restitution coefficient e in [0, 1].
  virtual const SpMat& gap_operator() const = 0;
  virtual const Vec& gap_offset() const = 0;
  virtual double restitution() const = 0;
  Index ncontacts() const { return gap_operator().rows(); }

  virtual State initial_state() const = 0;
  // Largest stable step of the explicit central-difference scheme, 2 / omega_max (an
  // estimate, from the largest eigenvalue of M^{-1} K).
  virtual double stable_step() const = 0;
  // The same at configuration u, for schemes that follow a changing tangent (nonlinear
  // problems override it; a linear problem's stable step does not depend on u).
  virtual double stable_step_at(ConstVecRef /*u*/) const { return stable_step(); }

  // Problem-specific columns of series.csv (e.g. q, v, q_exact for the bouncing mass).
  virtual std::vector<std::string> observable_names() const { return {}; }
  virtual void observe(const State& /*s*/, std::span<double> /*out*/) const {}
  // The same columns after a step, for those that need the step's contact impulses (size p)
  // and its length dt (0 for the initial sample), e.g. a contact force impulse / dt. The
  // run driver calls this one; the default forwards to observe().
  virtual void observe_step(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
    observe(s, out);
  }

  // Exact solution where one is known.
  virtual std::optional<State> exact_state(double /*t*/) const { return std::nullopt; }
  // Exact times of the impacts in [0, t_end], in order, where the problem knows them
  // (impact-time errors of study files); empty otherwise.
  virtual std::vector<double> impact_times(double /*t_end*/) const { return {}; }
};

// The diagonal of M when M is diagonal; nullopt otherwise.
std::optional<Vec> diagonal_mass(const SpMat& M);

}  // namespace nsb
