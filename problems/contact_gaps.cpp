#include "problems/contact_gaps.hpp"

#include <limits>

namespace nsb {

ContactGaps::ContactGaps(const Problem& problem) : problem_(problem), gap_(problem.ncontacts()) {
  if (problem.contacts_move()) moving_ = problem.contact_geometry();
}

const Vec& ContactGaps::at(ConstVecRef u) {
  if (problem_.contacts_move()) {
    problem_.evaluate_contacts(u, moving_);
    return moving_.gap;
  }
  gap_.noalias() = problem_.gap_operator() * u;
  gap_ += problem_.gap_offset();
  return gap_;
}

double ContactGaps::min_at(ConstVecRef u) {
  const Vec& g = at(u);
  return g.size() ? g.minCoeff() : std::numeric_limits<double>::infinity();
}

}  // namespace nsb
