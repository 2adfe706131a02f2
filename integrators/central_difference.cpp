#include "integrators/central_difference.hpp"

#include <utility>

#include "core/threads.hpp"

namespace nsb {

void CentralDifference::reset(const Problem& problem, const State& state, Vec mass) {
  m = std::move(mass);
  // Massless dofs get minv = 0: the kick leaves them to the scheme.
  minv = (m.array() > 0.0).select(m.cwiseInverse(), 0.0);
  u_prev = state.u;
  v_prev = state.v;
  f_int = Vec::Zero(problem.ndof());
  f_ext = Vec::Zero(problem.ndof());
  problem.external_force(state.t, f_ext);
  started = false;
}

void CentralDifference::drift(const Problem& problem, State& state, double h, WorkCounters& work) {
  if (!started) {
    problem.internal_force(state.u, f_int);
    ++work.force_evaluations;
    state.v += 0.5 * h * minv.cwiseProduct(f_ext - f_int);
    started = true;
  }
  std::swap(u_prev, state.u);
  parallel_ranges(state.u.size(), [&](Index b, Index e) {
    state.u.segment(b, e - b).noalias() = u_prev.segment(b, e - b) + h * state.v.segment(b, e - b);
  });
  problem.internal_force(state.u, f_int);
  ++work.force_evaluations;
  if (!problem.external_force_is_constant()) problem.external_force(state.t + h, f_ext);
}

void CentralDifference::kick(State& state, double h) {
  std::swap(v_prev, state.v);
  parallel_ranges(state.v.size(), [&](Index b, Index e) {
    const Index k = e - b;
    state.v.segment(b, k).noalias() =
        v_prev.segment(b, k) + h * minv.segment(b, k).cwiseProduct(f_ext.segment(b, k) - f_int.segment(b, k));
  });
}

Energy CentralDifference::energy(const Problem& problem, const State& state) const {
  return {0.5 * v_prev.dot(m.cwiseProduct(v_prev)), 0.5 * (problem.potential(u_prev) + problem.potential(state.u))};
}

}  // namespace nsb
