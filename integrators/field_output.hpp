#pragma once
// Field output for ParaView (`nsbench run --fields DIR`): a time series of a problem's body
// mesh (problems/problem.hpp, FieldMesh) as VTK XML files,
//
//     DIR/fields.pvd           a Collection: one DataSet per written state, timestep = t
//     DIR/fields_NNNNNN.vtu    UnstructuredGrid, ASCII, numbers in shortest round-trip form
//                              (a reader gets the run's doubles exactly)
//
// Each .vtu holds the mesh in its reference configuration (Points, 3 components, z = 0;
// Cells VTK_LINE = 3 for bars, VTK_QUAD = 9 for plane bodies) and
//     PointData  displacement, velocity   3 components, from point_dofs (0 where a
//                                         component has no dof: a clamp, y and z of bars)
//                contact_impulse          3 components: the impulses the contacts applied
//                                         in the step that ended at t, L^T Lambda_N +
//                                         T^T Lambda_T, on the points whose dofs carry the
//                                         contact rows (a node-to-segment row splits its
//                                         impulse over the segment's nodes by its weights;
//                                         0 in the first file). Impulses on dofs that are
//                                         no point (mass-on-bar's striker) are not shown.
//     CellData   one Float64 array per stress component (FieldMesh::stress_components, each
//                problem's cell_stress() says which stress), body (Int32, FieldMesh::cell_body)
// In ParaView: open fields.pvd, apply Warp By Vector (displacement) to see the deformed
// bodies, colour by a stress component.
//
// The directory is written whole (core/output.hpp, ReportDirectory): into a staging sibling,
// swapped in by commit() when the run ends; a killed run leaves the old one. Earlier
// fields_*.vtu files of the directory are not kept. state() allocates nothing (the buffers
// are sized once, the files written with POSIX calls).
#include <filesystem>
#include <string>
#include <vector>

#include "core/output.hpp"
#include "integrators/run.hpp"
#include "problems/problem.hpp"

namespace nsb {

class FieldWriter final : public StateSink {
 public:
  // Throws InputError naming `option` when the problem has no field mesh or DIR cannot be
  // staged. `expected_writes`: how many states will be written (a size hint).
  FieldWriter(const Problem& problem, const std::filesystem::path& dir, const std::string& option, long expected_writes);
  FieldWriter(const FieldWriter&) = delete;
  FieldWriter& operator=(const FieldWriter&) = delete;

  // One .vtu of state s, with the normal and tangential impulses (size p each; the
  // tangential ones may be empty) of the step that ended at s.t.
  void state(const State& s, const Vec& normal_impulses, const Vec& tangential_impulses) override;
  // Writes fields.pvd and swaps the directory into place.
  void commit();
  long files() const { return static_cast<long>(times_.size()); }

 private:
  void append_point_vector(const char* name, const Vec& dof_values);
  void flush(const std::string& path);

  const Problem& problem_;
  FieldMesh mesh_;
  ReportDirectory dir_;
  std::string head_, tail_;  // the parts of every .vtu that do not change (mesh, body ids)
  std::string buffer_, prefix_, path_;
  Eigen::MatrixXd stress_;
  Vec impulse_;  // L^T Lambda_N + T^T Lambda_T, per dof
  std::vector<double> times_;
};

}  // namespace nsb
