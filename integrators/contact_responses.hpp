#pragma once
// The contact responses r_i = S^{-1} L_i^T of an implicit scheme's iteration matrix S (and
// W^{-1} L_i^T, M^{-1} L_i^T alike): computed on a contact's first use after S changed and
// kept until the next change. Storage stays across changes, so a step allocates nothing once
// every contact has been active once.
#include <vector>

#include "integrators/integrator.hpp"

namespace nsb {

class ContactResponses {
 public:
  void bind(Index contacts) {
    responses_.assign(static_cast<std::size_t>(contacts), Vec());
    valid_.assign(static_cast<std::size_t>(contacts), 0);
  }
  // S changed: every response is recomputed on its next use.
  void invalidate() { std::fill(valid_.begin(), valid_.end(), 0); }

  // r_i, with solve_in_place(x): x <- S^{-1} x (and the scheme's solve count).
  template <class Rows, class SolveInPlace>
  const Vec& get(const Rows& L, Index i, SolveInPlace&& solve_in_place) {
    Vec& r = responses_[static_cast<std::size_t>(i)];
    if (!valid_[static_cast<std::size_t>(i)]) {
      r.setZero(L.cols());
      for (typename Rows::InnerIterator it(L, i); it; ++it) r[it.col()] = it.value();
      solve_in_place(r);
      valid_[static_cast<std::size_t>(i)] = 1;
    }
    return r;
  }

 private:
  std::vector<Vec> responses_;
  std::vector<char> valid_;  // computed for the current S
};

}  // namespace nsb
