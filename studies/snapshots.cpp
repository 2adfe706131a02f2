#include "studies/snapshots.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace nsb {

MeshSnapshots::MeshSnapshots(const Problem& problem, const std::string& component)
    : problem_(problem), mesh_(problem.field_mesh().value_or(FieldMesh{})) {
  if (mesh_.ncells() == 0 || mesh_.cells.cols() != 4)
    throw std::logic_error(fmt::format("snapshots: {} has no quadrilateral mesh", problem.name()));
  const auto& names = mesh_.stress_components;
  const auto it = std::find(names.begin(), names.end(), component);
  if (it == names.end())
    throw std::logic_error(fmt::format("snapshots: {} has no stress component {}", problem.name(), component));
  component_ = it - names.begin();
  stress_.resize(mesh_.ncells(), static_cast<Index>(names.size()));
  impulse_.resize(problem.ndof());
}

Json MeshSnapshots::take(const std::string& instant, const State& s, const Vec& normal, const Vec& tangential) {
  problem_.cell_stress(s.u, stress_);
  const Contacts& c = problem_.contacts();
  impulse_.setZero();
  if (normal.size()) impulse_.noalias() += c.normal.transpose() * normal;
  if (tangential.size() && c.tangent.rows()) impulse_.noalias() += c.tangent.transpose() * tangential;
  const auto component = [&](ConstVecRef v, Index a, Index k) {
    const int dof = mesh_.point_dofs(a, k);
    return dof < 0 ? 0.0 : v[dof];
  };
  std::vector<double> corners, stress, arrows;
  for (Index e = 0; e < mesh_.ncells(); ++e) {
    for (Index j = 0; j < 4; ++j) {
      const Index a = mesh_.cells(e, j);
      for (Index k = 0; k < 2; ++k) corners.push_back(mesh_.points(a, k) + component(s.u, a, k));
    }
    stress.push_back(stress_(e, component_));
  }
  for (Index a = 0; a < mesh_.npoints(); ++a) {
    const double fx = component(impulse_, a, 0), fy = component(impulse_, a, 1);
    if (fx == 0.0 && fy == 0.0) continue;
    arrows.insert(arrows.end(), {mesh_.points(a, 0) + component(s.u, a, 0), mesh_.points(a, 1) + component(s.u, a, 1), fx, fy});
  }
  return {{"instant", instant}, {"t", s.t}, {"corners", reals(corners)}, {"stress", reals(stress)}, {"arrows", reals(arrows)}};
}

void MeshSnapshots::add(const State& s, const Vec& normal, const Vec& tangential) {
  if (initial_.is_null()) {
    initial_ = take("initial", s, normal, tangential);
    return;
  }
  if (first_contact_.is_null() && normal.size() && normal.maxCoeff() > 0.0)
    first_contact_ = take("first contact", s, normal, tangential);
  const double energy = problem_.strain_energy(s.u);
  if (energy > largest_energy_) {
    largest_energy_ = energy;
    largest_ = take("largest compression", s, normal, tangential);
  }
  last_ = take("end", s, normal, tangential);
}

Json MeshSnapshots::finish() {
  std::vector<Json> all;
  for (const Json* j : {&initial_, &first_contact_, &largest_, &last_})
    if (!j->is_null()) all.push_back(*j);
  std::stable_sort(all.begin(), all.end(), [](const Json& a, const Json& b) { return a["t"].get<double>() < b["t"].get<double>(); });
  return all;
}

SnapshotTables snapshot_tables(const std::string& id, const std::string& title, const std::string& caption,
                               const std::string& stress_label) {
  SnapshotTables t;
  const std::vector<Column> keys = {{"instant", "", "", ""}, {"integrator", "", "", ""}, {"at", "", "", "time of the step"}};
  t.cells.id = id;
  t.cells.title = title;
  t.cells.caption = caption;
  t.cells.columns = keys;
  std::vector<std::string> corners;
  for (int j = 1; j <= 4; ++j)
    for (const char* axis : {"x", "y"}) {
      corners.push_back(fmt::format("{}{}", axis, j));
      t.cells.columns.push_back({corners.back(), "m", "{:.4e}", "deformed corner (counter-clockwise)"});
    }
  t.cells.columns.push_back({stress_label, "Pa", "{:.4e}", "cell stress"});
  t.cells.csv_only = true;
  t.arrows.id = id + "_impulses";
  t.arrows.title = title + ": contact impulses";
  t.arrows.caption = caption;
  t.arrows.columns = keys;
  t.arrows.columns.insert(t.arrows.columns.end(), {{"x", "m", "{:.4e}", "deformed point"}, {"y", "m", "{:.4e}", ""},
                                                   {"Lambda_x", "N s", "{:.4e}", "(L^T Lambda_N + T^T Lambda_T) at the point"},
                                                   {"Lambda_y", "N s", "{:.4e}", ""}});
  t.arrows.csv_only = true;
  t.cells.figures = {{id, title, "", stress_label, {}, {"instant", "integrator", "at"}, false, false, {}, false, false,
                      "", caption, "deformed", corners, {}, stress_label + " [Pa]", t.arrows.id}};
  return t;
}

void add_snapshot_rows(SnapshotTables& tables, const std::string& integrator, const Json& snapshots) {
  for (const Json& snap : snapshots) {
    const std::string instant = snap["instant"], at = fmt::format("t = {:.4f} s", snap["t"].get<double>());
    const Json &corners = snap["corners"], &stress = snap["stress"], &arrows = snap["arrows"];
    for (std::size_t e = 0; e < stress.size(); ++e) {
      std::vector<Cell> row = {instant, integrator, at};
      for (std::size_t j = 0; j < 8; ++j) row.push_back(number_cell(corners[8 * e + j]));
      row.push_back(number_cell(stress[e]));
      tables.cells.add_row(std::move(row));
    }
    for (std::size_t a = 0; a + 3 < arrows.size(); a += 4)
      tables.arrows.add_row({instant, integrator, at, number_cell(arrows[a]), number_cell(arrows[a + 1]),
                             number_cell(arrows[a + 2]), number_cell(arrows[a + 3])});
  }
}

}  // namespace nsb
