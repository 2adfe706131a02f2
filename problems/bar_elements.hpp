#pragma once
// Linear two-node elements of a 1D elastic bar and its three mass models, shared by the
// problems built from bars (signorini_bar.hpp, two_bars.hpp, mass_on_bar.hpp):
//
//     stiffness   element (E_e A / h) [1 -1; -1 1]
//     lumped      element (rho A h / 2) diag(1, 1)
//     consistent  element (rho A h / 6) [2 1; 1 2]
//     singular    lumped, then a contact end node's mass moved to its neighbour
//                 (make_node_massless; Khenous, Laborde, Renard, Eur. J. Mech. A/Solids 27, 2008)
//
// Each problem places its bars' nodes among its own dofs (first_dof) and chooses which end
// node loses its mass; the properties of the models (what the singular model keeps, the
// stable steps) are stated in signorini_bar.hpp.
#include <Eigen/SparseCore>
#include <span>
#include <string>
#include <vector>

#include "problems/problem.hpp"

namespace nsb {

enum class BarMassModel { Lumped, Consistent, Singular };

// The parameters E, rho, A (in this order, defaults given) and `mass`, as every bar problem
// spells them.
ParamSpecs bar_material_specs(double E, double rho, double A);
ParamSpec bar_mass_spec();

// "lumped" | "consistent" | "singular" (the `mass` parameter's choices).
BarMassModel parse_bar_mass_model(const std::string& name);

// Appends the triplets of a bar of ke.size() elements on the dofs first_dof .. first_dof +
// ke.size() (node i of the bar is dof first_dof + i): stiffness ke[e] per element into kt,
// element mass me into mt (the singular model's triplets are the lumped ones).
void add_bar_triplets(Index first_dof, std::span<const double> ke, double me, BarMassModel model,
                      std::vector<Eigen::Triplet<double>>& kt, std::vector<Eigen::Triplet<double>>& mt);

// The singular model's step on an assembled diagonal mass: node's mass goes to neighbour
// (the total mass is kept) and node keeps an explicit zero entry.
void make_node_massless(SpMat& M, Index node, Index neighbour);

// sum over the bar's elements of ke[e] (u_{e+1} - u_e)^2 / 2, nodes from first_dof.
double bar_strain_energy(ConstVecRef u, Index first_dof, std::span<const double> ke);

// Field output (FieldMesh in problem.hpp): appends a bar of `elements` elements of length h
// from x0 along +x, node i at (x0 + i h, 0) on dof first_dof + i, except that a clamped
// last node has none (-1), and its line cells with body id `body`.
void add_bar_field_mesh(FieldMesh& mesh, double x0, double h, Index elements, Index first_dof, bool clamped_end,
                        int body);

// The stress sigma_e = E_e (u_{e+1} - u_e) / h = ke[e] (u_{e+1} - u_e) / A of each element,
// constant over it, nodes from first_dof (clamped_end: the last node is fixed, u = 0),
// written into out (ke.size() entries).
void bar_stress(ConstVecRef u, Index first_dof, std::span<const double> ke, double area, bool clamped_end,
                Eigen::Ref<Vec> out);

}  // namespace nsb
