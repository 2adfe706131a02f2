#include "problems/floor_contacts.hpp"

namespace nsb {

Contacts floor_contacts(const std::vector<PointContact>& at_u0, ConstVecRef u0, double e, double mu) {
  const Index p = static_cast<Index>(at_u0.size());
  Contacts contacts;
  SpMat L(p, 3), T(p, 3);
  contacts.gap_offset = Vec(p);
  for (Index i = 0; i < p; ++i) {
    const PointContact& c = at_u0[static_cast<std::size_t>(i)];
    L.insert(i, 1) = c.normal_row[1];
    L.insert(i, 2) = c.normal_row[2];
    T.insert(i, 0) = c.tangent_row[0];
    T.insert(i, 2) = c.tangent_row[2];
    contacts.gap_offset[i] = c.gap - (c.normal_row[1] * u0[1] + c.normal_row[2] * u0[2]);
  }
  L.makeCompressed();
  contacts.normal = std::move(L);
  contacts.restitution = e;
  if (mu > 0.0) contacts.set_friction(std::move(T), mu, 0.0);
  return contacts;
}

void write_floor_contact(Index i, const PointContact& c, ContactGeometry& out) {
  out.gap[i] = c.gap;
  double* normal = out.normal.valuePtr() + out.normal.outerIndexPtr()[i];  // stored columns (y, angle)
  normal[0] = c.normal_row[1];
  normal[1] = c.normal_row[2];
  if (out.tangent.rows() == 0) return;
  double* tangent = out.tangent.valuePtr() + out.tangent.outerIndexPtr()[i];  // stored columns (x, angle)
  tangent[0] = c.tangent_row[0];
  tangent[1] = c.tangent_row[2];
}

}  // namespace nsb
