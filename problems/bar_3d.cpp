#include "problems/bar_3d.hpp"
#include "problems/linear_problem.hpp"
#include "problems/registry.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <map>

#include <fmt/format.h>

#include "core/threads.hpp"
#include "problems/bar3d_exact.hpp"
#include "problems/bar_memory.hpp"
#include "problems/hex8_elements.hpp"
#include "problems/signorini_bar.hpp"

namespace nsb {

namespace {

// Elements per thread below which one thread is faster (as block-2d's).
constexpr Index kMinLayerElementsPerThread = 2048;

// The parameters bar-3d shares with signorini-bar, which its exact 1D bar is built from.
constexpr const char* kSignoriniNames[] = {"L", "E", "rho", "A", "v0", "g0", "g", "N", "mass", "e"};

// Corner c of the hex8 element in the unit cube (hex8 order: (-,-,-), (+,-,-), (+,+,-), (-,+,-),
// then the same at zeta = +1), 0 or 1 along each axis.
constexpr int kBoxCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

}  // namespace

ParamSpecs Bar3d::parameters_spec() {
  constexpr double inf = 1e308;
  ParamSpecs specs{ParamSpec::real("L", 1.0, 0.0, inf, "bar length [m]", true)};
  const ParamSpecs material = bar_material_specs(1.0, 1.0, 1.0);
  specs.insert(specs.end(), material.begin(), material.end());
  specs.insert(specs.end(), {
      ParamSpec::real("v0", 1.0, 0.0, inf, "initial speed towards the wall [m/s]"),
      ParamSpec::real("g0", 0.0, 0.0, inf, "initial gap to the wall [m]"),
      ParamSpec::real("g", 0.0, 0.0, inf, "gravity towards the wall [m/s^2] (exact solution: problems/bouncing_bar.hpp)"),
      ParamSpec::integer("N", 100, 1, 100'000'000, "number of hex8 elements along the bar"),
      bar_mass_spec(),
      ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient of the wall-face nodes"),
      ParamSpec::real("nu", 0.3, 0.0, 0.5, "Poisson's ratio", false, true),
      ParamSpec::choice("lateral", "held", {"held", "free"},
                        "lateral displacements held (oedometric, exact solution) or the sides free (no exact solution)"),
      ParamSpec::integer("N_side", 1, 1, 1024, "hex8 elements along each side of the square cross-section"),
  });
  return specs;
}

template <class Visit>
void Bar3d::for_each_element(Visit&& visit) const {
  Index nodes_e[8], e = 0;
  for (Index k = 0; k < side_; ++k)
    for (Index j = 0; j < side_; ++j)
      for (Index i = 0; i < n_; ++i, ++e) {
        element_nodes(i, j, k, nodes_e);
        visit(e, nodes_e);
      }
}

Bar3d::Bar3d(const Params& p)
    : params_(p),
      n_(p.integer("N")),
      side_(p.integer("N_side")),
      dofs_per_node_(p.choice("lateral") == "held" ? 1 : 3),
      gravity_(p.real("g")),
      v0_(p.real("v0")) {
  // Refused before anything of the mesh's size is allocated.
  const double elements = static_cast<double>(n_) * static_cast<double>(side_ * side_);
  require_element_memory(elements, lateral_held() ? kBar3dBytesPerElementHeld : kBar3dBytesPerElementFree,
                         fmt::format("bar-3d: N = {}, N_side = {} ({} elements, lateral {})", n_, side_, elements, p.choice("lateral")),
                         "N * N_side^2");
  std::map<std::string, std::string> bar_values;
  for (const char* name : kSignoriniNames) bar_values[name] = p.values().at(name);
  exact_ = oedometric_bar(Params(SignoriniBar::parameters_spec(), bar_values), p.real("nu"));
  c_p_ = exact_->wave_speed();

  const double L = p.real("L");
  h_ = L / static_cast<double>(n_);
  a_ = std::sqrt(p.real("A")) / static_cast<double>(side_);
  const Hex8Material material = Hex8Material::from_young(Hex8Law::svk, p.real("E"), p.real("nu"));
  lambda_ = material.lambda;
  mu_ = material.mu;
  Hex8Nodes X;
  for (int c = 0; c < 8; ++c) X.col(c) << kBoxCorner[c][0] * h_, kBoxCorner[c][1] * a_, kBoxCorner[c][2] * a_;
  const Hex8Element element(X);
  element.tangent(X, material, Ke_);  // at F = I: the linear elastic stiffness
  for (int r = 0; r < 8; ++r)
    for (int c = 0; c < 8; ++c) Kx_(r, c) = Ke_(3 * r, 3 * c);
  Eigen::Matrix<double, 8, 8> Me;
  Eigen::Matrix<double, 8, 1> me;
  const double rho = p.real("rho");
  element.consistent_mass(rho, Me);
  element.lumped_mass(rho, me);
  const BarMassModel model = parse_bar_mass_model(p.choice("mass"));
  build_mass(Me, me, model);
  set_stable_step(Me, me, model);

  // One contact per wall-face node, on its x dof.
  const Index faces = (side_ + 1) * (side_ + 1);
  contacts_.normal.resize(faces, ndof());
  contacts_.normal.reserve(Eigen::VectorXi::Ones(ndof()));
  for (Index k = 0, r = 0; k <= side_; ++k)
    for (Index j = 0; j <= side_; ++j, ++r) contacts_.normal.insert(r, x_dof(0, j, k)) = 1.0;
  contacts_.normal.makeCompressed();
  contacts_.gap_offset = Vec::Constant(faces, p.real("g0"));
  contacts_.restitution = p.real("e");
}

Bar3d::~Bar3d() = default;

void Bar3d::build_mass(const Eigen::Matrix<double, 8, 8>& Me, const Eigen::Matrix<double, 8, 1>& me, BarMassModel model) {
  const Index n = ndof();
  const int D = dofs_per_node_;
  std::vector<Eigen::Triplet<double>> mt;
  mt.reserve(static_cast<std::size_t>(model == BarMassModel::Consistent ? 64 * D * elements() : 8 * D * elements()));
  for_each_element([&](Index, const Index* nodes_e) {
    for (int a = 0; a < 8; ++a)
      for (int d = 0; d < D; ++d) {
        if (model != BarMassModel::Consistent) {
          mt.emplace_back(D * nodes_e[a] + d, D * nodes_e[a] + d, me[a]);
          continue;
        }
        for (int b = 0; b < 8; ++b) mt.emplace_back(D * nodes_e[a] + d, D * nodes_e[b] + d, Me(a, b));
      }
  });
  M_.resize(n, n);
  M_.setFromTriplets(mt.begin(), mt.end());
  if (model == BarMassModel::Singular)
    for (Index k = 0; k <= side_; ++k)
      for (Index j = 0; j <= side_; ++j) make_node_massless(M_, x_dof(0, j, k), x_dof(1, j, k));
  M_.makeCompressed();
  x_mass_ = M_ * Vec::Ones(n);
  if (!lateral_held())
    for (Index q = 0; q < n; ++q)
      if (q % 3 != 0) x_mass_[q] = 0.0;
}

void Bar3d::set_stable_step(const Eigen::Matrix<double, 8, 8>& Me, const Eigen::Matrix<double, 8, 1>& me, BarMassModel model) {
  const int n = 8 * dofs_per_node_;
  Eigen::MatrixXd K = lateral_held() ? Eigen::MatrixXd(Kx_) : Eigen::MatrixXd(Ke_);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n, n);
  for (int a = 0; a < 8; ++a)
    for (int b = 0; b < 8; ++b)
      for (int d = 0; d < dofs_per_node_; ++d)
        M(dofs_per_node_ * a + d, dofs_per_node_ * b + d) = model == BarMassModel::Consistent ? Me(a, b) : (a == b ? me[a] : 0.0);
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M, Eigen::EigenvaluesOnly);
  stable_step_ = 2.0 / std::sqrt(eig.eigenvalues().maxCoeff());
}

void Bar3d::element_nodes(Index i, Index j, Index k, Index out[8]) const {
  const Index n0 = node(i, j, k), sy = n_ + 1, sz = (n_ + 1) * (side_ + 1);
  const Index face[4] = {n0, n0 + 1, n0 + 1 + sy, n0 + sy};
  for (int c = 0; c < 4; ++c) {
    out[c] = face[c];
    out[c + 4] = face[c] + sz;
  }
}

// f_e = K_e u_e for every element of layer i (D dofs per node), added into f.
template <int D>
void Bar3d::add_layer_forces(Index i, const double* u, double* f) const {
  using ElementVector = Eigen::Matrix<double, 8 * D, 1>;
  const auto& K = [this]() -> const Eigen::Matrix<double, 8 * D, 8 * D>& {
    if constexpr (D == 1) return Kx_; else return Ke_;
  }();
  Index nodes_e[8];
  ElementVector ue, fe;
  for (Index k = 0; k < side_; ++k)
    for (Index j = 0; j < side_; ++j) {
      element_nodes(i, j, k, nodes_e);
      for (int a = 0; a < 8; ++a)
        for (int d = 0; d < D; ++d) ue[D * a + d] = u[D * nodes_e[a] + d];
      fe.noalias() = K * ue;
      for (int a = 0; a < 8; ++a)
        for (int d = 0; d < D; ++d) f[D * nodes_e[a] + d] += fe[D * a + d];
    }
}

void Bar3d::internal_force(ConstVecRef u, VecRef f) const {
  f.setZero();
  const double* pu = u.data();
  double* pf = f.data();
  const int threads = threads_for(elements(), kMinLayerElementsPerThread);
  // Even element layers, then odd ones: layers of one parity share no node.
  for (Index parity = 0; parity < 2; ++parity)
    strided_for(parity, n_, 2, threads, [&](Index i) {
      if (lateral_held())
        add_layer_forces<1>(i, pu, pf);
      else
        add_layer_forces<3>(i, pu, pf);
    });
}

SpMat Bar3d::assemble_stiffness() const {
  const int D = dofs_per_node_, n = 8 * D;
  std::vector<Eigen::Triplet<double>> kt;
  kt.reserve(static_cast<std::size_t>(n * n * elements()));
  for_each_element([&](Index, const Index* nodes_e) {
    for (int r = 0; r < n; ++r)
      for (int c = 0; c < n; ++c)
        kt.emplace_back(D * nodes_e[r / D] + r % D, D * nodes_e[c / D] + c % D, D == 1 ? Kx_(r, c) : Ke_(r, c));
  });
  SpMat K(ndof(), ndof());
  K.setFromTriplets(kt.begin(), kt.end());
  K.makeCompressed();
  return K;
}

void Bar3d::tangent_stiffness(ConstVecRef, SpMat& K) const {
  std::call_once(k_once_, [this] { K_ = assemble_stiffness(); });
  copy_stiffness(K_, K);
}

double Bar3d::strain_energy(ConstVecRef u) const {
  // sum_e u_e^T K_e u_e / 2, element by element (no assembled K, no allocation).
  const int D = dofs_per_node_, n = 8 * D;
  Eigen::Matrix<double, 24, 1> ue;
  double W = 0.0;
  for_each_element([&](Index, const Index* nodes_e) {
    for (int r = 0; r < n; ++r) ue[r] = u[D * nodes_e[r / D] + r % D];
    W += D == 1 ? ue.head<8>().dot(Kx_ * ue.head<8>()) : ue.dot(Ke_ * ue);
  });
  return 0.5 * W;
}

double Bar3d::energy_scale() const {
  return 0.5 * exact_->total_mass() * (v0_ * v0_ + 2.0 * gravity_ * params_.real("g0"));
}

State Bar3d::initial_state() const {
  State s;
  s.u = Vec::Zero(ndof());
  s.v = Vec::Zero(ndof());
  for (Index q = 0; q < ndof(); q += dofs_per_node_) s.v[q] = -v0_;
  return s;
}

std::optional<State> Bar3d::state(double t) const {
  if (!lateral_held()) return std::nullopt;
  const auto line = exact_->state(t);
  if (!line) return std::nullopt;
  State s;
  s.t = t;
  s.u.resize(ndof());
  s.v.resize(ndof());
  for (Index k = 0; k <= side_; ++k)
    for (Index j = 0; j <= side_; ++j)
      for (Index i = 0; i <= n_; ++i) {
        s.u[x_dof(i, j, k)] = line->u[i];
        s.v[x_dof(i, j, k)] = line->v[i];
      }
  return s;
}

std::vector<std::pair<std::string, double>> Bar3d::summary_values() const {
  const bool dalembert = lateral_held() && gravity_ == 0.0 && v0_ > 0.0;
  return {{"contact_end_exact", dalembert ? exact_->contact_start() + exact_->contact_duration() : std::numeric_limits<double>::quiet_NaN()}};
}

std::vector<std::string> Bar3d::observable_names() const { return exact_->observable_names(); }

void Bar3d::observe(const State& s, const Vec& impulses, double dt, std::span<double> out) const {
  double u = 0.0, v = 0.0;
  for (Index k = 0; k <= side_; ++k)
    for (Index j = 0; j <= side_; ++j) {
      u += s.u[x_dof(0, j, k)];
      v += s.v[x_dof(0, j, k)];
    }
  const double faces = static_cast<double>((side_ + 1) * (side_ + 1));
  exact_->write_observables(s.t, u / faces, v / faces, momentum(s.v), lateral_held(), out);
  if (dt > 0.0) out[2] = impulses.sum() / dt;
}

std::optional<FieldMesh> Bar3d::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 3;
  mesh.points.resize(nodes(), 3);
  mesh.point_dofs.setConstant(nodes(), 3, -1);
  for (Index k = 0; k <= side_; ++k)
    for (Index j = 0; j <= side_; ++j)
      for (Index i = 0; i <= n_; ++i) {
        const Index a = node(i, j, k);
        mesh.points.row(a) << static_cast<double>(i) * h_, static_cast<double>(j) * a_, static_cast<double>(k) * a_;
        for (int d = 0; d < dofs_per_node_; ++d) mesh.point_dofs(a, d) = static_cast<int>(dofs_per_node_ * a + d);
      }
  mesh.cells.resize(elements(), 8);
  for_each_element([&](Index e, const Index* nodes_e) {
    for (int c = 0; c < 8; ++c) mesh.cells(e, c) = static_cast<int>(nodes_e[c]);
  });
  mesh.cell_body.assign(static_cast<std::size_t>(elements()), 0);
  mesh.stress_components = {"sigma_xx", "sigma_yy", "sigma_zz", "sigma_yz", "sigma_xz", "sigma_xy"};
  return mesh;
}

void Bar3d::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  // At the box's centre grad N_a = (xi_a / (4 h), eta_a / (4 a), zeta_a / (4 a)).
  const int D = dofs_per_node_;
  for_each_element([&](Index e, const Index* nodes_e) {
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();  // grad u, row: displacement component
    for (int c = 0; c < 8; ++c) {
      const Eigen::Vector3d grad((2 * kBoxCorner[c][0] - 1) / (4.0 * h_), (2 * kBoxCorner[c][1] - 1) / (4.0 * a_),
                                 (2 * kBoxCorner[c][2] - 1) / (4.0 * a_));
      for (int d = 0; d < D; ++d) H.row(d) += u[D * nodes_e[c] + d] * grad.transpose();
    }
    const Eigen::Matrix3d eps = 0.5 * (H + H.transpose());
    const Eigen::Matrix3d sigma = lambda_ * eps.trace() * Eigen::Matrix3d::Identity() + 2.0 * mu_ * eps;
    out.row(e) << sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(1, 2), sigma(0, 2), sigma(0, 1);
  });
}

NSBENCH_PROBLEM({"bar-3d", "hex8 elastic bar hitting a rigid wall, nondimensional; lateral held (exact 1D solution with c_p) or free; mass lumped|consistent|singular", &Bar3d::parameters_spec, &make_from_params<Problem, Bar3d>});

}  // namespace nsb
