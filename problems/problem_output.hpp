#pragma once
// A problem's output, apart from its model (problems/problem.hpp) and its exact solution
// (problems/exact_solution.hpp): the problem-specific columns of a run's series, the figures
// of its summary and its bodies as a mesh for field output. The run driver (run/run.cpp),
// field output (run/field_output.hpp), studies and the Python bindings read a problem
// through it; integrators never do.
//
// Problem inherits this interface rather than handing out a separate object: every output
// reads the model's own data (its elements for stresses, its dofs for the observables, its
// exact solution for the *_exact columns), so a separate object would hold a reference back
// to the model and forward to it; inheriting keeps the parts apart as interfaces, with no
// adapter per problem and no change for the callers.
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "problems/state.hpp"

namespace nsb {

// A problem's bodies as a mesh, for field output (ParaView) and pictures of the fields.
// Displacement and velocity are point values taken from the dofs; element cells carry one
// value per cell and stress component, vertex cells the body arrays.
//
//     point a          reference position points.row(a) (z = 0, y = 0 for bars; 3D: x, y, z)
//     its component k  displacement u[point_dofs(a, k)], 0 where point_dofs(a, k) = -1 (a
//                      clamped node, a direction the body does not move in)
//     cell c           points cells(c, 0 ..), padded with -1 past its last point (cells has
//                      as many columns as the widest cell); its number of points is its type:
//                      1  a vertex: a point mass or the centre of a rigid body ("body cell")
//                      2  a line along +x of the reference: a bar element or a spring
//                      4  a bilinear quad, counter-clockwise: a plane element
//                      8  a hexahedron in VTK_HEXAHEDRON's (hex8_elements.hpp's) order: a solid
//                      cell_body[c] is its body id (0 when there is one body)
//     element cells    cells of 2, 4 or 8 points, in order: cell_stress() rows, a column per stress component
//     body cells       the vertex cells, in their order: body_data() writes one row each,
//                      the components of the body_arrays in order (e.g. a rigid body's angle)
//
// What the stress is (which measure, where in the cell) is stated by each problem's
// cell_stress(); what a body array is, by its body_data(). Vertex cells have no stress and
// element cells no body arrays: a field is written only where it means something
// (run/field_output.hpp writes the two kinds as two datasets of one series).
// A degree of freedom that is no translation of a point (a rigid body's rotation) reaches
// the picture through a body array, not through point_dofs (which maps components linearly
// to dofs).
struct FieldArray {
  std::string name;
  int components = 1;  // 1 (scalar) or 3 (a vector, x y z)
};

struct FieldMesh {
  int dimension = 1;                           // 1: along x (bars, chains); 2: in (x, y); 3: solids
  Eigen::MatrixXd points;                      // npoints x 2 (x 3 in 3D), reference coordinates
  Eigen::MatrixXi point_dofs;                  // npoints x dimension, dof of each component or -1
  Eigen::MatrixXi cells;                       // ncells x (widest cell), point indices, -1 padded
  std::vector<int> cell_body;                  // ncells, body id
  std::vector<std::string> stress_components;  // the columns of cell_stress()
  std::vector<FieldArray> body_arrays;         // the column groups of body_data()
  // 3D bodies that turn (optional; empty: none): per body cell, the first of its three dofs
  // whose increments over a step are that step's rotation vector in world axes (theta' = omega,
  // as the sphere's), or -1. The orientation is not a function of the state (it depends on the
  // path of omega), so the field writer follows it step by step (run/field_output.hpp).
  std::vector<int> body_rotation_dofs;

  Index npoints() const { return points.rows(); }
  Index ncells() const { return cells.rows(); }
  // Number of points of cell c (1 vertex, 2 line, 4 quad, 8 hexahedron).
  int cell_size(Index c) const;
  // Number of element cells (cells of 2 or more points): the rows of cell_stress().
  Index nelements() const;
  // Number of vertex cells: the rows of body_data().
  Index nbodies() const { return ncells() - nelements(); }
  // Total components of the body arrays: the columns of body_data().
  int body_columns() const;
  // Appends `part` (a mesh of the same dimension, stress components and body arrays) with
  // its dofs shifted by dof_offset and its cells given body id `body`.
  void append(const FieldMesh& part, Index dof_offset, int body);
  // Appends a vertex cell (a point mass, a rigid body's centre) at reference position (x, y),
  // its components on `dofs` (dimension entries, -1 where fixed), of body `body`.
  void add_vertex(double x, double y, std::initializer_list<int> dofs, int body);
};

class ProblemOutput {
 public:
  virtual ~ProblemOutput() = default;

  // Problem-specific columns of series.csv (e.g. q, v, q_exact for the bouncing mass).
  virtual std::vector<std::string> observable_names() const { return {}; }
  // Those columns in state s after a step of length dt whose contact impulses were
  // `impulses` (size p), written into out (observable_names().size()): the one observation
  // function, for the initial sample too (dt = 0; impulses then carry no step, and a column
  // that needs one, e.g. a contact force impulse / dt, is 0 there).
  // The default forwards to the 0.1.0 pair below, for a plugin that overrides those.
  virtual void observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const {
    observe_step(s, impulses, dt, out);
  }
  // 0.1.0's two observation functions, kept one minor version for plugins that override them
  // (deprecated, problems/plugin_compat.hpp: override the observe above). The built-ins never do.
  virtual void observe_step(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
    observe(s, out);
  }
  virtual void observe(const State& /*s*/, std::span<double> /*out*/) const {}

  // Problem-specific figures of a run's summary.json (its "problem_summary" object, written
  // only when this is not empty), e.g. an exact event time; a non-finite value is written null.
  virtual std::vector<std::pair<std::string, double>> summary_values() const { return {}; }

  // The bodies' mesh (FieldMesh), for problems that describe one; nullopt otherwise.
  virtual std::optional<FieldMesh> field_mesh() const { return std::nullopt; }
  // The stress of each element cell of field_mesh() at u, written into out (nelements() x
  // stress_components.size()) without allocating. Only called when field_mesh() has a value.
  virtual void cell_stress(ConstVecRef /*u*/, Eigen::Ref<Eigen::MatrixXd> /*out*/) const {}
  // The body arrays of each vertex cell of field_mesh() in state s, written into out
  // (nbodies() x body_columns()) without allocating. Only called when body_arrays is not empty.
  virtual void body_data(const State& /*s*/, Eigen::Ref<Eigen::MatrixXd> /*out*/) const {}
};

}  // namespace nsb
