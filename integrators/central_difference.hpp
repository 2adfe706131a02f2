#pragma once
// The explicit central difference (leapfrog) shared by cd-lagrange and cd-penalty, which
// differ only in their contact treatment, applied by the scheme after the kick:
//
//     V_{1/2}        = V_0 + h/2 M^{-1} (F_ext - F_int)(U_0)                (first step)
//     U_{k+1}        = U_k + h V_{k+1/2}                                     drift
//     V_{k+3/2}^free = V_{k+1/2} + h M^{-1} (F_ext - F_int)(U_{k+1})         kick
//
// M diagonal (minv; 0 on massless dofs, which the scheme handles between drift and kick).
// Both updates run on NSBENCH_THREADS threads, element-wise (core/threads.hpp): the same
// bits for any count. Energy at the half step (the scheme's discrete energy, docs/method.md):
//     T_{k+1/2} = 1/2 V_{k+1/2}^T M V_{k+1/2},  V_{k+1/2} = (after a step) v_prev
//     V_{k+1/2} = 1/2 (V(U_k) + V(U_{k+1}))
#include "integrators/integrator.hpp"

namespace nsb {

struct CentralDifference {
  Vec m, minv;
  Vec u_prev, v_prev;  // U_k and V_{k+1/2} after a step
  Vec f_int, f_ext;    // at U_{k+1}, t_{k+1}
  bool started = false;

  // Binds to `problem` at `state`; `mass` diagonal.
  void reset(const Problem& problem, const State& state, Vec mass);
  // The first step's half kick, then U_{k+1}, and F_int and F_ext there (at t_{k+1} =
  // state.t + h; state.t itself is left to Integrator::step).
  void drift(const Problem& problem, State& state, double h, WorkCounters& work);
  // V <- V + h M^{-1} (F_ext - F_int), the velocity before it kept in v_prev.
  void kick(State& state, double h);
  // The half-step energy above (after the first step; before it the state's own applies).
  Energy energy(const Problem& problem, const State& state) const;
};

}  // namespace nsb
