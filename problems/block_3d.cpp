#include "problems/block_3d.hpp"
#include "problems/registry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "core/threads.hpp"
#include "problems/bar_memory.hpp"
#include "problems/lumped_gravity.hpp"
#include "problems/sparsity_pattern.hpp"

namespace nsb {

namespace {

// Elements per thread below which one thread is faster (a hex8 element's force takes about a
// microsecond; starting a parallel loop a few).
constexpr Index kMinBlockElementsPerThread = 512;

// Corner c of the hex8 element in the unit cube (hex8 order), 0 or 1 along each axis.
constexpr int kBlockCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};

Eigen::Matrix3d tilt_rotation(double degrees) {
  // About -y, so that x turns towards +z: x -> x cos a + z sin a.
  return Eigen::AngleAxisd(-degrees * std::numbers::pi / 180.0, Eigen::Vector3d::UnitY()).toRotationMatrix();
}

// The element's reference corners: the box of size h rotated by R (its position is irrelevant).
Hex8Nodes element_corners(const Eigen::Matrix3d& R, const Eigen::Vector3d& h) {
  Hex8Nodes X;
  for (int c = 0; c < 8; ++c) X.col(c) = R * Eigen::Vector3d(kBlockCorner[c][0] * h.x(), kBlockCorner[c][1] * h.y(), kBlockCorner[c][2] * h.z());
  return X;
}

}  // namespace

ParamSpecs Block3d::parameters_spec() {
  constexpr double inf = 1e308;
  return {
      ParamSpec::real("W", 1.0, 0.0, inf, "block width along x [m]", true),
      ParamSpec::real("D", 0.5, 0.0, inf, "block depth along y [m]", true),
      ParamSpec::real("H", 0.5, 0.0, inf, "block height along z [m]", true),
      ParamSpec::integer("nx", 8, 1, 1024, "elements along the width"),
      ParamSpec::integer("ny", 4, 1, 1024, "elements along the depth"),
      ParamSpec::integer("nz", 4, 1, 1024, "elements along the height"),
      ParamSpec::real("E", 1e6, 0.0, inf, "Young's modulus [Pa]", true),
      ParamSpec::real("nu", 0.3, 0.0, 0.5, "Poisson's ratio", false, true),
      ParamSpec::real("rho", 1000.0, 0.0, inf, "density [kg/m^3]", true),
      ParamSpec::choice("material", "svk", {"svk", "neo-hookean"}, "hyperelastic law"),
      ParamSpec::real("height", 0.1, 0.0, inf, "initial height of the lowest corner above the floor [m]"),
      ParamSpec::real("tilt", 15.0, -90.0, 90.0, "initial tilt about the y axis, the +x end up [deg]"),
      ParamSpec::real("vx", 0.0, -inf, inf, "initial velocity along x [m/s]"),
      ParamSpec::real("vy", 0.0, -inf, inf, "initial velocity along y [m/s]"),
      ParamSpec::real("vz", -1.0, -inf, inf, "initial vertical velocity, positive upwards [m/s]"),
      ParamSpec::real("spin", 0.0, -inf, inf, "initial angular velocity about the vertical through the centre [rad/s]"),
      ParamSpec::real("g", 9.81, 0.0, inf, "gravity [m/s^2] (0: off)"),
      ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient"),
      ParamSpec::real("mu", 0.0, 0.0, inf, "Coulomb friction coefficient of the floor (0: frictionless)"),
  };
}

Block3d::Block3d(const Params& p)
    : params_(p),
      nx_(p.integer("nx")),
      ny_(p.integer("ny")),
      nz_(p.integer("nz")),
      material_(Hex8Material::from_young(p.choice("material") == "neo-hookean" ? Hex8Law::neo_hookean : Hex8Law::svk,
                                         p.real("E"), p.real("nu"))),
      g_(p.real("g")),
      rotation_(tilt_rotation(p.real("tilt"))),
      element_size_(p.real("W") / static_cast<double>(nx_), p.real("D") / static_cast<double>(ny_),
                    p.real("H") / static_cast<double>(nz_)),
      element_(element_corners(rotation_, element_size_)),
      v0_(p.real("vx"), p.real("vy"), p.real("vz")),
      spin_(p.real("spin")) {
  // Refused before anything of the mesh's size is allocated.
  const double elements = static_cast<double>(nx_) * static_cast<double>(ny_) * static_cast<double>(nz_);
  require_element_memory(elements, kBlock3dBytesPerElement,
                         fmt::format("block-3d: nx = {}, ny = {}, nz = {} ({} elements)", nx_, ny_, nz_, elements),
                         "nx * ny * nz");
  // Reference configuration: the box rotated about its centre, centred on x = y = 0, its
  // lowest point at `height`.
  const Eigen::Vector3d size(p.real("W"), p.real("D"), p.real("H"));
  X_.resize(3, nodes());
  for (Index k = 0; k <= nz_; ++k)
    for (Index j = 0; j <= ny_; ++j)
      for (Index i = 0; i <= nx_; ++i) {
        const Eigen::Vector3d fraction(double(i) / nx_ - 0.5, double(j) / ny_ - 0.5, double(k) / nz_ - 0.5);
        X_.col(node(i, j, k)) = rotation_ * size.cwiseProduct(fraction);
      }
  const double lift = p.real("height") - X_.row(2).minCoeff();
  X_.row(2).array() += lift;
  centre_ = Eigen::Vector3d(0.0, 0.0, lift);

  Eigen::Matrix<double, 8, 1> me;
  element_.lumped_mass(p.real("rho"), me);
  m_ = Vec::Zero(ndof());
  for (Index k = 0; k < nz_; ++k)
    for_each_in_layer(k, [&](const Index* nodes_e) {
      for (int c = 0; c < 8; ++c) m_.segment<3>(3 * nodes_e[c]).array() += me[c];
    });

  // Contacts: every surface node, normal on its z dof; tangents on x and y when mu > 0.
  for (Index k = 0; k <= nz_; ++k)
    for (Index j = 0; j <= ny_; ++j)
      for (Index i = 0; i <= nx_; ++i)
        if (i == 0 || i == nx_ || j == 0 || j == ny_ || k == 0 || k == nz_) surface_.push_back(node(i, j, k));
  const Index nc = static_cast<Index>(surface_.size());
  SpMat L(nc, ndof()), T1(nc, ndof()), T2(nc, ndof());
  contacts_.gap_offset.resize(nc);
  for (Index r = 0; r < nc; ++r) {
    T1.insert(r, 3 * surface_[r]) = 1.0;
    T2.insert(r, 3 * surface_[r] + 1) = 1.0;
    L.insert(r, 3 * surface_[r] + 2) = 1.0;
    contacts_.gap_offset[r] = X_(2, surface_[r]);
  }
  L.makeCompressed();
  contacts_.normal = std::move(L);
  contacts_.restitution = p.real("e");
  if (p.real("mu") > 0.0) {
    T1.makeCompressed();
    T2.makeCompressed();
    contacts_.set_cone(std::move(T1), std::move(T2), p.real("mu"));
  }

  // Element eigenvalue bound at U = 0, the same for every element.
  Hex8Matrix Ke;
  element_.tangent(element_corners(rotation_, element_size_), material_, Ke);
  Hex8Vector s;
  for (int r = 0; r < 24; ++r) s[r] = 1.0 / std::sqrt(me[r / 3]);
  const Hex8Matrix A = s.asDiagonal() * Ke * s.asDiagonal();
  stable_step_ = 2.0 / std::sqrt(Eigen::SelfAdjointEigenSolver<Hex8Matrix>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff());
}

void Block3d::element_nodes(Index i, Index j, Index k, Index out[8]) const {
  for (int c = 0; c < 8; ++c) out[c] = node(i + kBlockCorner[c][0], j + kBlockCorner[c][1], k + kBlockCorner[c][2]);
}

Hex8Nodes Block3d::positions(const Index nodes_e[8], ConstVecRef u) const {
  Hex8Nodes x;
  for (int c = 0; c < 8; ++c) x.col(c) = X_.col(nodes_e[c]) + u.segment<3>(3 * nodes_e[c]);
  return x;
}

template <class Visit>
void Block3d::for_each_in_layer(Index k, Visit&& visit) const {
  Index nodes_e[8];
  for (Index j = 0; j < ny_; ++j)
    for (Index i = 0; i < nx_; ++i) {
      element_nodes(i, j, k, nodes_e);
      visit(nodes_e);
    }
}

template <class Layer>
bool Block3d::for_layers_by_parity(Layer&& layer) const {
  const int threads = threads_for(elements(), kMinBlockElementsPerThread);
  std::atomic<bool> ok{true};  // a layer that threw (an inverted element) clears it
  // Even element layers, then odd ones: layers of one parity share no node.
  for (Index parity = 0; parity < 2; ++parity)
    strided_for(parity, nz_, 2, threads, [&](Index k) {
      try {
        layer(k);
      } catch (const std::runtime_error&) {
        ok.store(false, std::memory_order_relaxed);
      }
    });
  return ok.load();
}

void Block3d::internal_force(ConstVecRef u, VecRef f) const {
  f.setZero();
  const bool ok = for_layers_by_parity([&](Index k) {
    Hex8Vector fe;
    for_each_in_layer(k, [&](const Index* nodes_e) {
      element_.internal_force(positions(nodes_e, u), material_, fe);
      for (int c = 0; c < 8; ++c) f.segment<3>(3 * nodes_e[c]) += fe.segment<3>(3 * c);
    });
  });
  if (!ok) throw std::runtime_error("block-3d: inverted element (det F <= 0) in the neo-Hookean law");
}

template <class Visit>
void Block3d::for_each_pattern_entry(Visit&& visit) const {
  // Dofs couple when their nodes share an element: the 3 x 3 x 3 node neighbourhood, whose
  // node indices increase with (k, j, i).
  const auto range = [](Index c, Index n) { return std::pair{std::max<Index>(c - 1, 0), std::min(c + 1, n)}; };
  for (Index kb = 0; kb <= nz_; ++kb)
    for (Index jb = 0; jb <= ny_; ++jb)
      for (Index ib = 0; ib <= nx_; ++ib)
        for (int d = 0; d < 3; ++d) {
          const Index col = 3 * node(ib, jb, kb) + d;
          const auto [k0, k1] = range(kb, nz_);
          const auto [j0, j1] = range(jb, ny_);
          const auto [i0, i1] = range(ib, nx_);
          for (Index kn = k0; kn <= k1; ++kn)
            for (Index jn = j0; jn <= j1; ++jn)
              for (Index in = i0; in <= i1; ++in)
                for (int l = 0; l < 3; ++l) visit(col, 3 * node(in, jn, kn) + l);
        }
}

void Block3d::tangent_stiffness(ConstVecRef u, SpMat& K) const {
  prepare_sparsity_pattern(K, ndof(), [this](auto&& visit) { for_each_pattern_entry(visit); });
  double* values = K.valuePtr();
  const auto* inner = K.innerIndexPtr();
  const auto* outer = K.outerIndexPtr();
  // Element layers of one parity share no node, hence no entry of K.
  const bool ok = for_layers_by_parity([&](Index k) {
    Hex8Matrix Ke;
    for_each_in_layer(k, [&](const Index* nodes_e) {
      element_.tangent(positions(nodes_e, u), material_, Ke);
      for (int c = 0; c < 24; ++c) {
        const Index col = 3 * nodes_e[c / 3] + c % 3;
        const auto* begin = inner + outer[col];
        const auto* end = inner + outer[col + 1];
        for (int a = 0; a < 8; ++a) {
          // Node a's three rows are consecutive in the column.
          const Index slot = std::lower_bound(begin, end, 3 * nodes_e[a]) - inner;
          for (int d = 0; d < 3; ++d) values[slot + d] += Ke(3 * a + d, c);
        }
      }
    });
  });
  if (!ok) throw std::runtime_error("block-3d: inverted element (det F <= 0) in the neo-Hookean law");
}

double Block3d::strain_energy(ConstVecRef u) const {
  // Per element layer, then summed in layer order: the same sum for any thread count.
  std::vector<double> layer(static_cast<std::size_t>(nz_), 0.0);
  const bool ok = for_layers_by_parity([&](Index k) {
    double W = 0.0;
    for_each_in_layer(k, [&](const Index* nodes_e) { W += element_.energy(positions(nodes_e, u), material_); });
    layer[static_cast<std::size_t>(k)] = W;
  });
  if (!ok) throw std::runtime_error("block-3d: inverted element (det F <= 0) in the neo-Hookean law");
  double W = 0.0;
  for (const double w : layer) W += w;
  return W;
}

std::optional<FieldMesh> Block3d::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 3;
  mesh.points = X_.transpose();
  mesh.point_dofs.resize(nodes(), 3);
  for (Index a = 0; a < nodes(); ++a)
    for (int d = 0; d < 3; ++d) mesh.point_dofs(a, d) = static_cast<int>(3 * a + d);
  mesh.cells.resize(elements(), 8);
  Index e = 0;
  for (Index k = 0; k < nz_; ++k)
    for_each_in_layer(k, [&](const Index* nodes_e) {
      for (int c = 0; c < 8; ++c) mesh.cells(e, c) = static_cast<int>(nodes_e[c]);
      ++e;
    });
  mesh.cell_body.assign(static_cast<std::size_t>(elements()), 0);
  mesh.stress_components = {"sigma_xx", "sigma_yy", "sigma_zz", "sigma_yz", "sigma_xz", "sigma_xy"};
  return mesh;
}

void Block3d::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  // At the centre of the rotated box grad_X N_a = R (c_a / (4 h)), c_a = +-1 per axis.
  Eigen::Matrix<double, 8, 3> grad;
  for (int c = 0; c < 8; ++c)
    grad.row(c) = (rotation_ * Eigen::Vector3d((2 * kBlockCorner[c][0] - 1) / (4.0 * element_size_.x()),
                                               (2 * kBlockCorner[c][1] - 1) / (4.0 * element_size_.y()),
                                               (2 * kBlockCorner[c][2] - 1) / (4.0 * element_size_.z())))
                      .transpose();
  Index e = 0;
  Eigen::Matrix3d S;
  for (Index k = 0; k < nz_; ++k)
    for_each_in_layer(k, [&](const Index* nodes_e) {
      const Eigen::Matrix3d F = positions(nodes_e, u) * grad;
      hex8_material_response(F, material_, S, nullptr);
      const Eigen::Matrix3d sigma = F * S * F.transpose() / F.determinant();
      out.row(e++) << sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(1, 2), sigma(0, 2), sigma(0, 1);
    });
}

SpMat Block3d::mass_matrix() const { return diagonal_mass_matrix(m_); }

void Block3d::external_force(double, VecRef f) const { lumped_gravity_force(m_, 3, g_, f); }

double Block3d::load_potential(ConstVecRef u) const { return lumped_gravity_potential(m_, X_, u, g_); }

State Block3d::initial_state() const {
  State s;
  s.u = Vec::Zero(ndof());
  s.v.resize(ndof());
  const Eigen::Vector3d omega(0.0, 0.0, spin_);
  for (Index a = 0; a < nodes(); ++a) s.v.segment<3>(3 * a) = v0_ + omega.cross(X_.col(a) - centre_);
  return s;
}

Eigen::Vector3d Block3d::linear_momentum(ConstVecRef v) const {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (Index a = 0; a < nodes(); ++a) p += m_[3 * a] * v.segment<3>(3 * a);
  return p;
}

Eigen::Vector3d Block3d::centre_of_mass(ConstVecRef u) const {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (Index a = 0; a < nodes(); ++a) c += m_[3 * a] * (X_.col(a) + u.segment<3>(3 * a));
  return c / total_mass();
}

Eigen::Vector3d Block3d::angular_momentum(ConstVecRef u, ConstVecRef v) const {
  const Eigen::Vector3d c = centre_of_mass(u);
  Eigen::Vector3d J = Eigen::Vector3d::Zero();
  for (Index a = 0; a < nodes(); ++a)
    J += m_[3 * a] * (X_.col(a) + u.segment<3>(3 * a) - c).cross(Eigen::Vector3d(v.segment<3>(3 * a)));
  return J;
}

std::vector<std::string> Block3d::observable_names() const {
  return {"strain_energy", "gravity_energy", "px", "py", "pz", "xc", "yc", "zc", "jx", "jy", "jz", "closed_contacts"};
}

void Block3d::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const Eigen::Vector3d p = linear_momentum(s.v), c = centre_of_mass(s.u), J = angular_momentum(s.u, s.v);
  out[0] = strain_energy(s.u);
  out[1] = load_potential(s.u);
  for (int d = 0; d < 3; ++d) {
    out[2 + d] = p[d];
    out[5 + d] = c[d];
    out[8 + d] = J[d];
  }
  long closed = 0;
  for (const Index a : surface_) closed += X_(2, a) + s.u[3 * a + 2] <= 0.0;
  out[11] = static_cast<double>(closed);
}

NSBENCH_PROBLEM({"block-3d", "hyperelastic hex8 block dropped tilted (optionally spinning, sliding) on a rigid floor, Coulomb cone mu", &Block3d::parameters_spec, &make_from_params<Problem, Block3d>});

}  // namespace nsb
