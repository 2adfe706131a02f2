#include "problems/block_2d.hpp"
#include "core/deterministic_math.hpp"
#include "problems/registry.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "core/threads.hpp"
#include "problems/lumped_gravity.hpp"
#include "problems/sparsity_pattern.hpp"

namespace nsb {

namespace {
// Q4 node coordinates in the parent square and the 2x2 Gauss abscissae.
constexpr double kXi[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr double kEta[4] = {-1.0, -1.0, 1.0, 1.0};
const double kGp = 1.0 / std::sqrt(3.0);
// Elements per thread below which one thread is faster (a step of the parallel loops costs
// a few microseconds; 2048 elements take about 50).
constexpr Index kMinElementsPerThread = 2048;
// Voigt index pairs (11, 22, 12).
constexpr int kI[3] = {0, 1, 0};
constexpr int kJ[3] = {0, 1, 1};
}  // namespace

ParamSpecs Block2d::parameters_spec() {
  return {
      ParamSpec::real("W", 1.0, 0.0, 1e308, "block width [m]", true),
      ParamSpec::real("H", 0.5, 0.0, 1e308, "block height [m]", true),
      ParamSpec::integer("nx", 8, 1, 1024, "elements along the width"),
      ParamSpec::integer("ny", 4, 1, 1024, "elements along the height"),
      ParamSpec::real("E", 1e6, 0.0, 1e308, "Young's modulus [Pa]", true),
      ParamSpec::real("nu", 0.3, 0.0, 0.5, "Poisson's ratio", false, true),
      ParamSpec::real("rho", 1000.0, 0.0, 1e308, "density [kg/m^3]", true),
      ParamSpec::choice("material", "svk", {"svk", "neo-hookean"}, "hyperelastic law"),
      ParamSpec::real("height", 0.1, 0.0, 1e308, "initial height of the lowest corner [m]"),
      ParamSpec::real("tilt", 15.0, -90.0, 90.0, "initial tilt, counter-clockwise [deg]"),
      ParamSpec::real("vx", 0.0, -1e308, 1e308, "initial horizontal velocity [m/s]"),
      ParamSpec::real("vy", -1.0, -1e308, 1e308, "initial vertical velocity, positive upwards [m/s]"),
      ParamSpec::real("spin", 0.0, -1e308, 1e308, "initial angular velocity about the centre [rad/s]"),
      ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2] (0: off)"),
      ParamSpec::real("e", 0.0, 0.0, 1.0, "Newton restitution coefficient"),
      ParamSpec::real("mu", 0.0, 0.0, 1e308, "Coulomb friction coefficient of the floor (0: frictionless)"),
      ParamSpec::real("floor_velocity", 0.0, -1e308, 1e308, "the floor's own velocity along +x (a belt) [m/s]"),
  };
}

Block2d::Block2d(const Params& p)
    : params_(p),
      nx_(p.integer("nx")),
      ny_(p.integer("ny")),
      rho_(p.real("rho")),
      g_(p.real("g")),
      e_(p.real("e")),
      neo_hookean_(p.choice("material") == "neo-hookean"),
      v0_(p.real("vx"), p.real("vy")),
      spin_(p.real("spin")) {
  const double E = p.real("E"), nu = p.real("nu"), W = p.real("W"), H = p.real("H");
  lambda_ = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));  // plane strain uses the 3D Lame constants
  mu_ = E / (2.0 * (1.0 + nu));

  // Reference configuration: the rectangle rotated by the tilt about its centre, centred
  // on x = 0, lowest corner at `height`.
  const double a = p.real("tilt") * std::numbers::pi / 180.0;
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(a).toRotationMatrix();
  X_.resize(2, nodes());
  for (Index j = 0; j <= ny_; ++j)
    for (Index i = 0; i <= nx_; ++i)
      X_.col(i + (nx_ + 1) * j) = R * Eigen::Vector2d(W * (double(i) / nx_ - 0.5), H * (double(j) / ny_ - 0.5));
  const double lift = p.real("height") - X_.row(1).minCoeff();
  X_.row(1).array() += lift;
  centre_ = Eigen::Vector2d(0.0, lift);

  // Gauss data of the one element shape: the rectangle hx x hy rotated by R, so
  // dX/dxi = R diag(hx, hy) / 2 everywhere.
  const Eigen::Matrix2d Jac = R * Eigen::Vector2d(W / nx_, H / ny_).asDiagonal() * 0.5;
  std::array<double, 4> me{};  // lumped mass of each element node
  for (int q = 0; q < 4; ++q) {
    const double xi = kXi[q] * kGp, eta = kEta[q] * kGp;
    Mat42 dxi;
    for (int k = 0; k < 4; ++k) {
      dxi(k, 0) = 0.25 * kXi[k] * (1 + kEta[k] * eta);
      dxi(k, 1) = 0.25 * kEta[k] * (1 + kXi[k] * xi);
    }
    Gauss& G = gauss_[q];
    G.dN = dxi * Jac.inverse();
    G.wj = Jac.determinant();
    for (int k = 0; k < 4; ++k) {
      me[k] += rho_ * G.wj * 0.25 * (1 + kXi[k] * xi) * (1 + kEta[k] * eta);
      wgrad_.x[k][q] = G.wj * G.dN(k, 0);
      wgrad_.y[k][q] = G.wj * G.dN(k, 1);
    }
  }
  const Index ne = nx_ * ny_;
  m_ = Vec::Zero(ndof());
  for (Index e = 0; e < ne; ++e) {
    const auto nodes = element_nodes(e);
    for (int k = 0; k < 4; ++k) m_.segment<2>(2 * nodes[k]).array() += me[k];
  }

  // Contacts: every boundary node, on its y dof.
  for (Index j = 0; j <= ny_; ++j)
    for (Index i = 0; i <= nx_; ++i)
      if (i == 0 || i == nx_ || j == 0 || j == ny_) boundary_.push_back(i + (nx_ + 1) * j);
  contacts_.normal.resize(static_cast<Index>(boundary_.size()), ndof());
  contacts_.gap_offset.resize(contacts_.normal.rows());
  for (Index r = 0; r < contacts_.normal.rows(); ++r) {
    contacts_.normal.insert(r, 2 * boundary_[r] + 1) = 1.0;
    contacts_.gap_offset[r] = X_(1, boundary_[r]);
  }
  contacts_.normal.makeCompressed();
  contacts_.restitution = e_;
  // Friction (tangent row on the x dof, slip u_T = v_a,x - w) only when mu > 0, so that the
  // frictionless block is described exactly as before.
  if (p.real("mu") > 0.0) {
    SpMat T(contacts_.normal.rows(), ndof());
    for (Index r = 0; r < T.rows(); ++r) T.insert(r, 2 * boundary_[r]) = 1.0;
    contacts_.set_friction(std::move(T), p.real("mu"), p.real("floor_velocity"));
  }

  // Element eigenvalue bound at U = 0: omega_max^2 <= lambda_max(M_e^{-1/2} K_e M_e^{-1/2}),
  // the same for every element.
  Mat8 Ke;
  element_tangent(0, Vec::Zero(ndof()), Ke);
  Eigen::Matrix<double, 8, 1> s;
  for (int r = 0; r < 8; ++r) s[r] = 1.0 / std::sqrt(me[r / 2]);
  const Mat8 A = s.asDiagonal() * Ke * s.asDiagonal();
  stable_step_ = 2.0 / std::sqrt(Eigen::SelfAdjointEigenSolver<Mat8>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff());
}

double Block2d::material(const Eigen::Matrix2d& F, Eigen::Vector3d& S, Eigen::Matrix3d* D) const {
  const Eigen::Matrix2d C = F.transpose() * F;
  Eigen::Matrix2d A, Sm;
  double m, W;
  if (neo_hookean_) {
    const double J = F.determinant();
    if (!(J > 0.0)) throw std::runtime_error("block-2d: inverted element (det F <= 0) in the neo-Hookean law");
    const double lnJ = nsb::dmath::log(J);
    A = C.inverse();
    Sm = mu_ * (Eigen::Matrix2d::Identity() - A) + lambda_ * lnJ * A;
    m = mu_ - lambda_ * lnJ;
    W = 0.5 * mu_ * (C.trace() - 2.0) - mu_ * lnJ + 0.5 * lambda_ * lnJ * lnJ;
  } else {
    const Eigen::Matrix2d E = 0.5 * (C - Eigen::Matrix2d::Identity());
    const double trE = E.trace();
    A.setIdentity();
    Sm = lambda_ * trE * A + 2.0 * mu_ * E;
    m = mu_;
    W = 0.5 * lambda_ * trE * trE + mu_ * E.squaredNorm();
  }
  S << Sm(0, 0), Sm(1, 1), Sm(0, 1);
  if (D)
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        (*D)(p, q) = lambda_ * A(kI[p], kJ[p]) * A(kI[q], kJ[q]) +
                     m * (A(kI[p], kI[q]) * A(kJ[p], kJ[q]) + A(kI[p], kJ[q]) * A(kJ[p], kI[q]));
  return W;
}

std::array<Index, 4> Block2d::element_nodes(Index e) const {
  const Index n0 = e % nx_ + (nx_ + 1) * (e / nx_);
  return {n0, n0 + 1, n0 + nx_ + 2, n0 + nx_ + 1};
}

Eigen::Matrix<double, 8, 1> Block2d::element_dofs(Index e, ConstVecRef u) const {
  const auto nodes = element_nodes(e);
  Eigen::Matrix<double, 8, 1> ue;
  for (int k = 0; k < 4; ++k) ue.segment<2>(2 * k) = u.segment<2>(2 * nodes[k]);
  return ue;
}

namespace {
// F = I + U_e grad N, and B with delta E (Voigt, engineering shear) = B delta u_e.
template <class Mat42>
void kinematics(const Eigen::Matrix<double, 8, 1>& ue, const Mat42& dN, Eigen::Matrix2d& F,
                Eigen::Matrix<double, 3, 8>& B) {
  F = Eigen::Matrix2d::Identity() + Eigen::Map<const Eigen::Matrix<double, 2, 4>>(ue.data()) * dN;
  for (int a = 0; a < 4; ++a)
    for (int k = 0; k < 2; ++k) {
      B(0, 2 * a + k) = F(k, 0) * dN(a, 0);
      B(1, 2 * a + k) = F(k, 1) * dN(a, 1);
      B(2, 2 * a + k) = F(k, 0) * dN(a, 1) + F(k, 1) * dN(a, 0);
    }
}
}  // namespace

template <bool kNeoHookean>
bool Block2d::add_row_forces(Index j, const double* u, double* f) const {
  // Local copies: the compiler then knows f does not alias them and keeps them in registers.
  const KernelGradients g = wgrad_;
  double G[2][4][4];  // unweighted gradients, for H = grad U
  for (int a = 0; a < 4; ++a)
    for (int q = 0; q < 4; ++q) {
      G[0][a][q] = gauss_[q].dN(a, 0);
      G[1][a][q] = gauss_[q].dN(a, 1);
    }
  const double lambda = lambda_, mu = mu_;
  bool ok = true;
  for (Index i = 0; i < nx_; ++i) {
    const Index n0 = i + (nx_ + 1) * j, n3 = n0 + nx_ + 1;
    const double* corner[4] = {u + 2 * n0, u + 2 * n0 + 2, u + 2 * n3 + 2, u + 2 * n3};
    double ux[4], uy[4];
    for (int a = 0; a < 4; ++a) {
      ux[a] = corner[a][0];
      uy[a] = corner[a][1];
    }
    double P00[4], P01[4], P10[4], P11[4];  // first Piola-Kirchhoff stress F S per Gauss point
    for (int q = 0; q < 4; ++q) {
      double H00 = 0.0, H01 = 0.0, H10 = 0.0, H11 = 0.0;
      for (int a = 0; a < 4; ++a) {
        H00 += ux[a] * G[0][a][q];
        H01 += ux[a] * G[1][a][q];
        H10 += uy[a] * G[0][a][q];
        H11 += uy[a] * G[1][a][q];
      }
      const double E00 = H00 + 0.5 * (H00 * H00 + H10 * H10);
      const double E11 = H11 + 0.5 * (H01 * H01 + H11 * H11);
      const double E01 = 0.5 * (H01 + H10 + H00 * H01 + H10 * H11);
      double S00, S11, S01;
      if constexpr (kNeoHookean) {
        const double J = (1.0 + H00) * (1.0 + H11) - H01 * H10;
        ok = ok && J > 0.0;
        const double lnJ = nsb::dmath::log(J), r = 1.0 / (J * J);
        // C^{-1} = adj(C) / J^2 with C = I + 2E.
        const double Ci00 = (1.0 + 2.0 * E11) * r, Ci11 = (1.0 + 2.0 * E00) * r, Ci01 = -2.0 * E01 * r;
        const double c = lambda * lnJ - mu;
        S00 = mu + c * Ci00;
        S11 = mu + c * Ci11;
        S01 = c * Ci01;
      } else {
        const double lt = lambda * (E00 + E11);
        S00 = lt + 2.0 * mu * E00;
        S11 = lt + 2.0 * mu * E11;
        S01 = 2.0 * mu * E01;
      }
      P00[q] = S00 + H00 * S00 + H01 * S01;
      P01[q] = S01 + H00 * S01 + H01 * S11;
      P10[q] = S01 + H10 * S00 + H11 * S01;
      P11[q] = S11 + H10 * S01 + H11 * S11;
    }
    for (int a = 0; a < 4; ++a) {
      double fx = 0.0, fy = 0.0;
      for (int q = 0; q < 4; ++q) {
        fx += P00[q] * g.x[a][q] + P01[q] * g.y[a][q];
        fy += P10[q] * g.x[a][q] + P11[q] * g.y[a][q];
      }
      double* fa = f + (corner[a] - u);
      fa[0] += fx;
      fa[1] += fy;
    }
  }
  return ok;
}

void Block2d::internal_force(ConstVecRef u, VecRef f) const {
  f.setZero();
  const double* pu = u.data();
  double* pf = f.data();
  const int threads = threads_for(nx_ * ny_, kMinElementsPerThread);
  std::atomic<bool> ok{true};  // any row with an inverted element clears it
  // Even element rows, then odd ones: rows of one parity share no node.
  for (Index parity = 0; parity < 2; ++parity)
    strided_for(parity, ny_, 2, threads, [&](Index j) {
      if (!(neo_hookean_ ? add_row_forces<true>(j, pu, pf) : add_row_forces<false>(j, pu, pf)))
        ok.store(false, std::memory_order_relaxed);
    });
  if (!ok.load()) throw std::runtime_error("block-2d: inverted element (det F <= 0) in the neo-Hookean law");
}

void Block2d::element_tangent(Index e, ConstVecRef u, Mat8& Ke) const {
  const auto ue = element_dofs(e, u);
  Eigen::Matrix2d F;
  Eigen::Matrix<double, 3, 8> B;
  Eigen::Vector3d S;
  Eigen::Matrix3d D;
  Ke.setZero();
  for (int q = 0; q < 4; ++q) {
    const Gauss& G = gauss_[q];
    kinematics(ue, G.dN, F, B);
    material(F, S, &D);
    Ke.noalias() += G.wj * B.transpose() * D * B;
    Eigen::Matrix2d Sm;
    Sm << S[0], S[2], S[2], S[1];
    const Eigen::Matrix4d geo = G.wj * G.dN * Sm * G.dN.transpose();  // grad N_a . S grad N_b
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b) {
        Ke(2 * a, 2 * b) += geo(a, b);
        Ke(2 * a + 1, 2 * b + 1) += geo(a, b);
      }
  }
}

template <class Visit>
void Block2d::for_each_pattern_entry(Visit&& visit) const {
  // Dofs couple when their nodes share an element: the 3 x 3 node neighbourhood.
  for (Index jb = 0; jb <= ny_; ++jb)
    for (Index ib = 0; ib <= nx_; ++ib)
      for (int k = 0; k < 2; ++k)
        for (Index jn = std::max<Index>(jb - 1, 0); jn <= std::min(jb + 1, ny_); ++jn)
          for (Index in = std::max<Index>(ib - 1, 0); in <= std::min(ib + 1, nx_); ++in)
            for (int l = 0; l < 2; ++l) visit(2 * (ib + (nx_ + 1) * jb) + k, 2 * (in + (nx_ + 1) * jn) + l);
}

void Block2d::tangent_stiffness(ConstVecRef u, SpMat& K) const {
  prepare_sparsity_pattern(K, ndof(), [this](auto&& visit) { for_each_pattern_entry(visit); });
  double* values = K.valuePtr();
  const auto* inner = K.innerIndexPtr();
  const auto* outer = K.outerIndexPtr();
  const int threads = threads_for(nx_ * ny_, kMinElementsPerThread);
  // Element rows of one parity share no node, hence no entry of K.
  for (Index parity = 0; parity < 2; ++parity)
    strided_for(parity, ny_, 2, threads, [&](Index j) {
      Mat8 Ke;
      for (Index e = j * nx_; e < (j + 1) * nx_; ++e) {
        element_tangent(e, u, Ke);
        const auto nodes = element_nodes(e);
        for (int c = 0; c < 8; ++c) {
          // A column's rows are sorted: nodes 0, 1 of the element are adjacent there, so are 3, 2.
          const Index col = 2 * nodes[c / 2] + c % 2;
          const auto* begin = inner + outer[col];
          const auto* end = inner + outer[col + 1];
          const Index lower = std::lower_bound(begin, end, 2 * nodes[0]) - inner;
          const Index upper = std::lower_bound(begin, end, 2 * nodes[3]) - inner;
          const Index slot[8] = {lower, lower + 1, lower + 2, lower + 3, upper + 2, upper + 3, upper, upper + 1};
          for (int r = 0; r < 8; ++r) values[slot[r]] += Ke(r, c);
        }
      }
    });
}

double Block2d::strain_energy(ConstVecRef u) const {
  // Per element row, then summed in row order: the same sum for any thread count.
  std::vector<double> row(static_cast<std::size_t>(ny_), 0.0);
  const int threads = threads_for(nx_ * ny_, kMinElementsPerThread);
  strided_for(0, ny_, 1, threads, [&](Index j) {
    Eigen::Matrix2d F;
    Eigen::Matrix<double, 3, 8> B;
    Eigen::Vector3d S;
    double W = 0.0;
    for (Index e = j * nx_; e < (j + 1) * nx_; ++e) {
      const auto ue = element_dofs(e, u);
      for (int q = 0; q < 4; ++q) {
        kinematics(ue, gauss_[q].dN, F, B);
        W += gauss_[q].wj * material(F, S, nullptr);
      }
    }
    row[static_cast<std::size_t>(j)] = W;
  });
  double W = 0.0;
  for (const double w : row) W += w;
  return W;
}

std::optional<FieldMesh> Block2d::field_mesh() const {
  FieldMesh mesh;
  mesh.dimension = 2;
  mesh.points = X_.transpose();
  mesh.point_dofs.resize(nodes(), 2);
  for (Index a = 0; a < nodes(); ++a) mesh.point_dofs.row(a) << static_cast<int>(2 * a), static_cast<int>(2 * a + 1);
  mesh.cells.resize(nx_ * ny_, 4);
  for (Index e = 0; e < nx_ * ny_; ++e)
    for (int k = 0; k < 4; ++k) mesh.cells(e, k) = static_cast<int>(element_nodes(e)[k]);
  mesh.cell_body.assign(static_cast<std::size_t>(nx_ * ny_), 0);
  mesh.stress_components = {"sigma_xx", "sigma_yy", "sigma_xy"};
  return mesh;
}

void Block2d::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  Eigen::Matrix2d F;
  Eigen::Matrix<double, 3, 8> B;
  Eigen::Vector3d S;
  for (Index e = 0; e < nx_ * ny_; ++e) {
    const auto ue = element_dofs(e, u);
    Eigen::Matrix2d mean = Eigen::Matrix2d::Zero();
    for (int q = 0; q < 4; ++q) {
      kinematics(ue, gauss_[q].dN, F, B);
      material(F, S, nullptr);
      Eigen::Matrix2d Sm;
      Sm << S[0], S[2], S[2], S[1];
      mean += F * Sm * F.transpose() / F.determinant();
    }
    out.row(e) << 0.25 * mean(0, 0), 0.25 * mean(1, 1), 0.25 * mean(0, 1);
  }
}

SpMat Block2d::mass_matrix() const { return diagonal_mass_matrix(m_); }

void Block2d::external_force(double, VecRef f) const { lumped_gravity_force(m_, 2, g_, f); }

double Block2d::load_potential(ConstVecRef u) const { return lumped_gravity_potential(m_, X_, u, g_); }

State Block2d::initial_state() const {
  State s;
  s.u = Vec::Zero(ndof());
  s.v.resize(ndof());
  for (Index a = 0; a < nodes(); ++a) {
    const Eigen::Vector2d r = X_.col(a) - centre_;
    s.v.segment<2>(2 * a) = v0_ + spin_ * Eigen::Vector2d(-r.y(), r.x());
  }
  return s;
}

Eigen::Vector2d Block2d::linear_momentum(ConstVecRef v) const {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (Index a = 0; a < nodes(); ++a) p += m_[2 * a] * v.segment<2>(2 * a);
  return p;
}

double Block2d::angular_momentum(ConstVecRef u, ConstVecRef v) const {
  double J = 0.0;
  for (Index a = 0; a < nodes(); ++a) {
    const double x = X_(0, a) + u[2 * a], y = X_(1, a) + u[2 * a + 1];
    J += m_[2 * a] * (x * v[2 * a + 1] - y * v[2 * a]);
  }
  return J;
}

std::vector<std::string> Block2d::observable_names() const {
  return {"strain_energy", "gravity_energy", "px", "py", "angular_momentum", "closed_contacts"};
}

void Block2d::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  const Eigen::Vector2d p = linear_momentum(s.v);
  long closed = 0;
  for (Index r = 0; r < contacts_.normal.rows(); ++r) closed += (contacts_.gap_offset[r] + s.u[2 * boundary_[r] + 1] <= 0.0);
  out[0] = strain_energy(s.u);
  out[1] = load_potential(s.u);
  out[2] = p.x();
  out[3] = p.y();
  out[4] = angular_momentum(s.u, s.v);
  out[5] = static_cast<double>(closed);
}

NSBENCH_PROBLEM({"block-2d", "hyperelastic Q4 block (plane strain) dropped tilted on a rigid frictionless floor", &Block2d::parameters_spec, &make_from_params<Problem, Block2d>});

}  // namespace nsb
