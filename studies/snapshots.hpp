#pragma once
// Snapshots of a body's deformed mesh for the pictures of the motion (figures of kind
// "deformed", scripts/figures.py): at chosen instants of a run, each cell's corners at their
// deformed positions, the cell's stress component, and the contact impulses as vectors at
// the mesh points,
//
//     f = L^T Lambda_N + T^T Lambda_T     (the step's generalised contact impulse),
//
// whose (x, y) dofs at a point are the impulse the contacts gave that point over the step (a
// node-to-segment contact spreads it over its segment's points, with opposite signs on the two
// bodies). Instants: the initial state, the first step with a contact impulse, the step of
// largest strain energy (the greatest compression), and the end of the run.
#include <optional>
#include <string>
#include <vector>

#include "problems/problem.hpp"
#include "studies/study.hpp"

namespace nsb {

// The runs pictured deformed in the block and bodies studies: the scheme under study and the
// reference, side by side.
inline const std::vector<std::string> kSnapshotSchemes = {"cd-lagrange", "penalty-bdf"};

class MeshSnapshots {
 public:
  // `component`: the name of the stress component coloured (one of field_mesh()'s); throws
  // std::logic_error when the problem has no quadrilateral mesh or no such component.
  MeshSnapshots(const Problem& problem, const std::string& component);
  // Fed with the initial state (impulses empty) and after every step, in order.
  void add(const State& s, const Vec& normal, const Vec& tangential);
  // Closes the run: the last state fed is the end snapshot. The snapshots, in time order,
  // as JSON (case results travel as JSON).
  Json finish();

 private:
  const Problem& problem_;
  FieldMesh mesh_;
  Index component_;
  Eigen::MatrixXd stress_;
  Vec impulse_;
  Json initial_, first_contact_, largest_, last_;
  double largest_energy_ = -1.0;
  Json take(const std::string& instant, const State& s, const Vec& normal, const Vec& tangential);
};

// The tables of the figure: cells (instant, integrator, at, x1, y1, ..., x4, y4, stress) and
// arrows (instant, integrator, at, x, y, Lambda_x, Lambda_y), the figure registered on the cells'.
struct SnapshotTables {
  Table cells, arrows;
};
SnapshotTables snapshot_tables(const std::string& id, const std::string& title, const std::string& caption,
                               const std::string& stress_label);
// Appends the snapshots of one run (MeshSnapshots::finish()) of `integrator`.
void add_snapshot_rows(SnapshotTables& tables, const std::string& integrator, const Json& snapshots);

}  // namespace nsb
