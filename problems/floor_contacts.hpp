#pragma once
// Moving contacts of planar rigid-body points on the floor y = 0, U = (x, y, angle): the rows
// of problems/point_contact.hpp as a problem's contacts (rocking-block, painleve-rod).
//
//     g(U) = the point's height,  L(U) = (0, 1, dg/dangle),  T(U) = (1, 0, dX/dangle)
//
// Every entry is stored (L on y and the angle, T on x and the angle), so one pattern serves
// every configuration and evaluate_contacts refills values only.
#include <vector>

#include "problems/point_contact.hpp"
#include "problems/problem.hpp"

namespace nsb {

// The contacts from the points at U0 (`at_u0`, one per contact): the rows at U0,
// g0 = g(U0) - L(U0) U0, restitution e, friction mu on each (tangent rows only when mu > 0, so
// that mu = 0 is described exactly like a frictionless problem).
Contacts floor_contacts(const std::vector<PointContact>& at_u0, ConstVecRef u0, double e, double mu);

// Contact i's gap and rows, written into `out` (storage from contact_geometry() of contacts
// made by floor_contacts), values only, without allocating.
void write_floor_contact(Index i, const PointContact& c, ContactGeometry& out);

}  // namespace nsb
