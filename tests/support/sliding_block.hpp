#pragma once
// The 2D block sliding on the floor with Coulomb friction (vx = 2, tilt 0, height 0.01,
// 6 x 3), and the per-step checks of docs/method.md section 6 that every friction scheme must
// pass on it (tests/integrators/block_friction_test.cpp for all of them; the penalty
// schemes' own tests at their mu):
//   identity  |P_x,k+1 - P_x,k - sum_i Lambda_T,i|   (T rows +1 on the x dofs, sum F_int = 0)
//   sliding   |P_x,k+1 - P_x,k + mu sum_i Lambda_N,i| on the steps where every loaded contact
//             slides forwards (Lambda_T,i = -mu Lambda_N,i, to round-off: a scheme that
//             integrates forces, penalty-bdf, sums -mu f_N and f_N in two quadratures)
//   cone      |Lambda_T,i| - mu Lambda_N,i
//   work      Lambda_T,i u_T,i(+)  (the slip after the step never runs along the impulse)
// each the worst over the run; scale: the largest |P_x|.
#include <algorithm>
#include <cmath>
#include <string>

#include "run/run.hpp"
#include "problems/block_2d.hpp"

namespace nsb::testing {

inline Block2d sliding_block(const std::string& mu) {
  return Block2d(Params(Block2d::parameters_spec(), {{"mu", mu}, {"vx", "2"}, {"tilt", "0"},
                                                      {"height", "0.01"}, {"nx", "6"}, {"ny", "3"}}));
}

struct BlockFrictionChecks {
  RunResult run;
  double worst_identity = 0.0, worst_sliding = 0.0, worst_cone = 0.0, worst_work = 0.0;
  double total_tangential = 0.0, scale = 0.0;
  long sliding_steps = 0;
};

inline BlockFrictionChecks check_block_friction(const Block2d& b, Integrator& integ, double mu, double dt, double t_end) {
  BlockFrictionChecks c;
  const SpMat& T = b.contacts().tangent;
  double px_prev = b.linear_momentum(b.initial_state().v).x();
  Vec slip(T.rows());
  const RunOptions options{dt, t_end, 1, false};
  c.run = run(b, integ, options, [&](const Integrator& it, const StepInfo&) {
    const Vec& n = it.impulses();
    const Vec& t = it.tangential_impulses();
    const double px = b.linear_momentum(it.state().v).x();
    c.scale = std::max(c.scale, std::abs(px));
    c.worst_identity = std::max(c.worst_identity, std::abs(px - px_prev - t.sum()));
    bool all_forward = n.sum() > 0.0;
    for (Index i = 0; i < n.size(); ++i)
      if (n[i] > 0.0) all_forward = all_forward && std::abs(t[i] + mu * n[i]) <= 1e-12 * mu * n[i];
    if (all_forward) {
      ++c.sliding_steps;
      c.worst_sliding = std::max(c.worst_sliding, std::abs(px - px_prev + mu * n.sum()));
    }
    slip.noalias() = T * it.state().v;
    for (Index i = 0; i < n.size(); ++i) {
      c.worst_cone = std::max(c.worst_cone, std::abs(t[i]) - mu * n[i]);
      c.worst_work = std::max(c.worst_work, t[i] * slip[i]);
    }
    c.total_tangential += std::abs(t.sum());
    px_prev = px;
  });
  return c;
}

}  // namespace nsb::testing
