#pragma once
// Field output for ParaView (`nsbench run --fields DIR`): a time series of a problem's bodies
// (problems/problem.hpp, FieldMesh) as VTK XML files,
//
//     DIR/fields.pvd           a Collection: for each written state (timestep = t) one
//                              DataSet per part: part 0 the element cells (fields_), then
//                              the vertex cells (bodies_); a problem with one kind has one
//     DIR/fields_NNNNNN.vtu    the element cells (bar and plane elements, springs) and the
//                              points they use, in the mesh's order
//     DIR/bodies_NNNNNN.vtu    the vertex cells (point masses, rigid bodies' centres), one
//                              point each, in their order
//
// UnstructuredGrid, ASCII, numbers in shortest round-trip form (a reader gets the run's
// doubles exactly). Each .vtu holds its cells in the reference configuration (Points, 3
// components, z = 0 below 3D; Cells VTK_VERTEX = 1, VTK_LINE = 3, VTK_QUAD = 9,
// VTK_HEXAHEDRON = 12 in FieldMesh's hex8 order, which is VTK's) and
//     PointData  displacement, velocity   3 components, from point_dofs (0 where a
//                                         component has no dof: a clamp, y and z of bars,
//                                         the held sides of bar-3d)
//                contact_impulse          3 components: the impulses the contacts applied
//                                         in the step that ended at t, L^T Lambda_N +
//                                         T^T Lambda_T, on the points whose dofs carry the
//                                         contact rows (a node-to-segment row splits its
//                                         impulse over the segment's nodes by its weights;
//                                         0 in the first file). The part of an impulse on a
//                                         dof that is no point component (a rotation) is not
//                                         shown.
//                bodies_ only: the body arrays (FieldMesh::body_arrays, Problem::body_data);
//                                         bodies that turn in 3D (FieldMesh::body_rotation_dofs)
//                                         also orientation_x and orientation_z, the body's
//                                         x and z axes in world axes: its orientation as the
//                                         product of every followed step's rotation
//                                         q <- exp(dtheta / 2) q (dtheta the step's increment of
//                                         the rotation dofs), from the first state written
//                                         (identity: the reference axes)
//     CellData   fields_ only: one Float64 array per stress component
//                (FieldMesh::stress_components; each problem's cell_stress() says which
//                stress, or a spring's force)
//                both: body (Int32, FieldMesh::cell_body)
// Two datasets, not one: a VTK array has a value on every cell or point of its dataset, and a
// stress on a point mass, or an angle on a bar node, would be a made-up number (0 reads as a
// physical zero); ParaView shows a part without the array coloured with its NaN colour.
// In ParaView: open fields.pvd (a multiblock of the parts), apply Warp By Vector
// (displacement) to see the bodies move, colour by a stress component; Glyph the bodies_
// points (e.g. a sphere scaled by radius, an arrow along orientation).
//
// The directory is written whole (core/output.hpp, ReportDirectory): into a staging sibling,
// swapped in by commit() when the run ends; a killed run leaves the old one. Earlier
// fields_*.vtu and bodies_*.vtu files of the directory are not kept. state() allocates
// nothing (the buffers are sized once, the files written with POSIX calls).
#include <Eigen/Geometry>

#include <filesystem>
#include <string>
#include <vector>

#include "core/output.hpp"
#include "run/run.hpp"
#include "problems/problem.hpp"

namespace nsb {

// Throws InputError, "CONTEXT: problem NAME: field_mesh(): what is wrong", when `mesh` is not
// one the writer can write for `problem` (shapes, dofs within ndof, cells of 1, 2, 4 or 8 points
// padded with -1, stress components for element cells, body arrays of 1 or 3 components): a
// plugin's mesh gets one clear line, not a crash or a file ParaView cannot read.
void check_field_mesh(const FieldMesh& mesh, const Problem& problem, const std::string& context);

class FieldWriter final : public StateSink {
 public:
  // Throws InputError naming `option` when the problem has no field mesh, its mesh is
  // malformed (check_field_mesh) or DIR cannot be staged. `expected_writes`: how many states
  // will be written (a size hint).
  FieldWriter(const Problem& problem, const std::filesystem::path& dir, const std::string& option, long expected_writes);
  FieldWriter(const FieldWriter&) = delete;
  FieldWriter& operator=(const FieldWriter&) = delete;

  // One .vtu of state s, with the normal and tangential impulses (size p each; the
  // tangential ones may be empty) of the step that ended at s.t.
  void state(const State& s, const Vec& normal_impulses, const Vec& tangential_impulses,
             const Vec& tangential_impulses2) override;
  // Follows the orientation of the bodies that turn (FieldMesh::body_rotation_dofs) to state s:
  // call it after every step (nsbench run passes it as the run's observer when
  // follows_rotations()), since the orientation depends on the path; state() follows the
  // state it writes too (with states further apart, the orientation is the product of their
  // rotations instead). Allocates nothing.
  void follow(const State& s);
  bool follows_rotations() const { return !orientation_.empty(); }
  // Writes fields.pvd and swaps the directory into place.
  void commit();
  long files() const { return static_cast<long>(times_.size()); }

 private:
  // One .vtu of each written state: the element cells (fields_) or the vertex cells (bodies_).
  struct Part {
    std::string name;  // file name prefix
    bool elements = true;
    std::vector<Index> points, cells;  // of the mesh, in the order written
    std::string head, tail;            // the parts of every .vtu that do not change (mesh, body ids)
  };
  Part make_part(bool elements) const;
  void append_point_vector(const char* name, const Part& part, const Vec& dof_values);
  void append_orientations();
  void flush(const std::string& path);

  const Problem& problem_;
  FieldMesh mesh_;
  ReportDirectory dir_;
  std::vector<Part> parts_;
  std::string buffer_, prefix_, path_;
  Eigen::MatrixXd stress_, body_;  // cell_stress() and body_data() of the state written
  Vec impulse_;  // L^T Lambda_N + T^T Lambda_T, per dof
  ContactGeometry moving_;  // moving contacts: the rows at the written state
  std::vector<Eigen::Quaterniond> orientation_;  // per body cell, of the bodies that turn
  Vec rotation_seen_;       // their rotation dofs at the last followed state
  bool followed_ = false;   // a state was followed: the next one's increments are rotations
  std::vector<double> times_;
};

}  // namespace nsb
