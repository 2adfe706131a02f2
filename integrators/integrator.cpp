#include "integrators/integrator.hpp"

namespace nsb {

void Integrator::bind(const Problem& problem, const State& initial) {
  problem_ = &problem;
  mass_ = problem.mass_matrix();
  state_ = initial;
  impulses_ = Vec::Zero(problem.ncontacts());
  work_ = WorkCounters{};
}

Energy Integrator::energy() const {
  const Vec& v = state_.v;
  return {0.5 * v.dot(mass_ * v), problem_->potential(state_.u)};
}

}  // namespace nsb
