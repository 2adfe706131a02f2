#include "problems/bar_elements.hpp"

#include <algorithm>

namespace nsb {

ParamSpecs bar_material_specs(double E, double rho, double A) {
  constexpr double inf = 1e308;
  return {
      ParamSpec::real("E", E, 0.0, inf, "Young's modulus [Pa]", true),
      ParamSpec::real("rho", rho, 0.0, inf, "density [kg/m^3]", true),
      ParamSpec::real("A", A, 0.0, inf, "cross-section area [m^2]", true),
  };
}

ParamSpec bar_mass_spec() {
  return ParamSpec::choice("mass", "lumped", {"lumped", "consistent", "singular"},
                           "mass model (singular: massless contact node, Khenous-Laborde-Renard 2008)");
}

BarMassModel parse_bar_mass_model(const std::string& name) {
  if (name == "consistent") return BarMassModel::Consistent;
  if (name == "singular") return BarMassModel::Singular;
  return BarMassModel::Lumped;
}

void add_bar_triplets(Index first_dof, std::span<const double> ke, double me, BarMassModel model,
                      std::vector<Eigen::Triplet<double>>& kt, std::vector<Eigen::Triplet<double>>& mt) {
  const Index n = static_cast<Index>(ke.size());
  for (Index e = 0; e < n; ++e) {
    const Index i = first_dof + e;
    for (Index a = 0; a < 2; ++a)
      for (Index b = 0; b < 2; ++b) kt.emplace_back(i + a, i + b, a == b ? ke[e] : -ke[e]);
    if (model == BarMassModel::Consistent) {
      for (Index a = 0; a < 2; ++a)
        for (Index b = 0; b < 2; ++b) mt.emplace_back(i + a, i + b, me * (a == b ? 2.0 : 1.0) / 6.0);
    } else {
      mt.emplace_back(i, i, 0.5 * me);
      mt.emplace_back(i + 1, i + 1, 0.5 * me);
    }
  }
}

void make_node_massless(SpMat& M, Index node, Index neighbour) {
  M.coeffRef(neighbour, neighbour) += M.coeffRef(node, node);
  M.coeffRef(node, node) = 0.0;
}

double bar_strain_energy(ConstVecRef u, Index first_dof, std::span<const double> ke) {
  double s = 0.0;
  for (std::size_t e = 0; e < ke.size(); ++e) {
    const Index i = first_dof + static_cast<Index>(e);
    const double d = u[i + 1] - u[i];
    s += ke[e] * d * d;
  }
  return 0.5 * s;
}

void add_bar_field_mesh(FieldMesh& mesh, double x0, double h, Index elements, Index first_dof, bool clamped_end,
                        int body) {
  FieldMesh bar;
  bar.dimension = 1;
  bar.points = Eigen::MatrixXd::Zero(elements + 1, 2);
  bar.point_dofs.resize(elements + 1, 1);
  bar.cells.resize(elements, 2);
  for (Index i = 0; i <= elements; ++i) {
    bar.points(i, 0) = x0 + static_cast<double>(i) * h;
    bar.point_dofs(i, 0) = clamped_end && i == elements ? -1 : static_cast<int>(i);
  }
  for (Index e = 0; e < elements; ++e) bar.cells.row(e) << static_cast<int>(e), static_cast<int>(e + 1);
  mesh.dimension = 1;
  mesh.stress_components = {"sigma"};
  mesh.append(bar, first_dof, body);
}

void bar_stress(ConstVecRef u, Index first_dof, std::span<const double> ke, double area, bool clamped_end,
                Eigen::Ref<Vec> out) {
  const Index n = static_cast<Index>(ke.size());
  for (Index e = 0; e < n; ++e) {
    const Index i = first_dof + e;
    const double right = clamped_end && e == n - 1 ? 0.0 : u[i + 1];
    out[e] = ke[static_cast<std::size_t>(e)] * (right - u[i]) / area;
  }
}

}  // namespace nsb
