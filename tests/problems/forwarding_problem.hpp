#pragma once
// A test problem that is a registered problem with one thing changed: every member forwards to
// the problem it holds, and a test's subclass overrides the one it changes (an obstacle on a
// belt, a time-dependent load).
#include <memory>

#include "problems/problem.hpp"

class ForwardingProblem : public nsb::Problem {
 public:
  explicit ForwardingProblem(std::unique_ptr<nsb::Problem> problem) : p_(std::move(problem)) {}
  std::string name() const override { return p_->name(); }
  const nsb::Params& parameters() const override { return p_->parameters(); }
  nsb::Index ndof() const override { return p_->ndof(); }
  nsb::SpMat mass_matrix() const override { return p_->mass_matrix(); }
  void internal_force(nsb::ConstVecRef u, nsb::VecRef f) const override { p_->internal_force(u, f); }
  void tangent_stiffness(nsb::ConstVecRef u, nsb::SpMat& K) const override { p_->tangent_stiffness(u, K); }
  bool is_linear() const override { return p_->is_linear(); }
  void external_force(double t, nsb::VecRef f) const override { p_->external_force(t, f); }
  bool external_force_is_constant() const override { return p_->external_force_is_constant(); }
  double strain_energy(nsb::ConstVecRef u) const override { return p_->strain_energy(u); }
  double load_potential(nsb::ConstVecRef u) const override { return p_->load_potential(u); }
  const nsb::Contacts& contacts() const override { return p_->contacts(); }
  nsb::State initial_state() const override { return p_->initial_state(); }
  double stable_step() const override { return p_->stable_step(); }

 protected:
  const nsb::Problem& held() const { return *p_; }

 private:
  std::unique_ptr<nsb::Problem> p_;
};
