#pragma once
// The gaps of a problem's contacts at a configuration, as the output reads them (the run's
// min_gap column, the penetration of run measures, a study's min_gap observable):
//     g(U) = g0 + L U                  constant kinematics
//     g(U) from evaluate_contacts      contacts that move (the gaps themselves, not g0 + L U,
//                                      their linearisation at U0)
// Storage is sized once; evaluating allocates nothing.
#include "problems/problem.hpp"

namespace nsb {

class ContactGaps {
 public:
  explicit ContactGaps(const Problem& problem);
  // g(u), one entry per contact (valid until the next call).
  const Vec& at(ConstVecRef u);
  // The smallest gap at u; +inf without contacts.
  double min_at(ConstVecRef u);
  // The gaps of the last evaluation, and the rows evaluated with them where contacts move
  // (nullptr for constant kinematics): what a run checks for non-finite geometry.
  const Vec& last() const { return problem_.contacts_move() ? moving_.gap : gap_; }
  const ContactGeometry* moving_rows() const { return problem_.contacts_move() ? &moving_ : nullptr; }

 private:
  const Problem& problem_;
  Vec gap_;
  ContactGeometry moving_;
};

}  // namespace nsb
