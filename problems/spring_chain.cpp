#include "problems/spring_chain.hpp"
#include "problems/registry.hpp"

#include <Eigen/Eigenvalues>
#include <vector>

namespace nsb {

ParamSpecs SpringChain::parameters_spec() {
  return {
      ParamSpec::integer("n", 3, 2, 200, "number of masses"),
      ParamSpec::real("m", 1.0, 0.0, 1e308, "mass of the even-numbered masses [kg]", true),
      ParamSpec::real("mass_ratio", 2.0, 0.0, 1e308, "odd-numbered masses are mass_ratio * m", true),
      ParamSpec::real("k", 100.0, 0.0, 1e308, "spring stiffness [N/m]", true),
      ParamSpec::choice("wall", "none", {"none", "left", "both"}, "rigid wall left of mass 0, also right of mass n-1 (both), or none"),
      ParamSpec::real("gap", 0.1, 0.0, 1e308, "initial gap between an end mass and its wall [m]"),
      ParamSpec::real("e", 1.0, 0.0, 1.0, "Newton restitution coefficient at the wall"),
      ParamSpec::real("v0", 1.0, -1e308, 1e308, "rigid initial velocity towards the wall (-x) [m/s]"),
      ParamSpec::real("a", 0.5, -1e308, 1e308, "vibration: mass i starts with an extra a (-1)^i [m/s]"),
  };
}

SpringChain::SpringChain(const Params& params)
    : params_(params),
      n_(params.integer("n")),
      k_(params.real("k")),
      e_(params.real("e")),
      v0_(params.real("v0")),
      a_(params.real("a")),
      m_(n_) {
  const double m = params.real("m"), ratio = params.real("mass_ratio");
  for (Index i = 0; i < n_; ++i) m_[i] = (i % 2 == 0) ? m : ratio * m;
  M_.resize(n_, n_);
  M_.reserve(Eigen::VectorXi::Constant(n_, 1));
  for (Index i = 0; i < n_; ++i) M_.insert(i, i) = m_[i];
  M_.makeCompressed();

  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i + 1 < n_; ++i) {
    t.emplace_back(i, i, k_);
    t.emplace_back(i + 1, i + 1, k_);
    t.emplace_back(i, i + 1, -k_);
    t.emplace_back(i + 1, i, -k_);
  }
  K_.resize(n_, n_);
  K_.setFromTriplets(t.begin(), t.end());

  const std::string& wall = params.choice("wall");
  const Index walls = wall == "none" ? 0 : wall == "left" ? 1 : 2;
  contacts_.normal.resize(walls, n_);
  contacts_.gap_offset = Vec::Constant(walls, params.real("gap"));
  if (walls >= 1) contacts_.normal.insert(0, 0) = 1.0;
  if (walls == 2) contacts_.normal.insert(1, n_ - 1) = -1.0;
  contacts_.normal.makeCompressed();
  contacts_.restitution = e_;

  // omega_max^2 = largest eigenvalue of M^{-1/2} K M^{-1/2} (symmetric, same spectrum).
  const Vec s = m_.cwiseSqrt().cwiseInverse();
  const Eigen::MatrixXd A = s.asDiagonal() * Eigen::MatrixXd(K_) * s.asDiagonal();
  const double lambda_max = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(A, Eigen::EigenvaluesOnly).eigenvalues().maxCoeff();
  stable_step_ = 2.0 / std::sqrt(lambda_max);
}


double SpringChain::strain_energy(ConstVecRef u) const {
  double w = 0.0;
  for (Index i = 0; i + 1 < n_; ++i) w += 0.5 * k_ * (u[i + 1] - u[i]) * (u[i + 1] - u[i]);
  return w;
}

State SpringChain::initial_state() const {
  State s;
  s.u = Vec::Zero(n_);
  s.v.resize(n_);
  for (Index i = 0; i < n_; ++i) s.v[i] = -v0_ + ((i % 2 == 0) ? a_ : -a_);
  return s;
}

void SpringChain::observe(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
  out[0] = momentum(s.v);
  out[1] = s.v[0];
}

std::optional<FieldMesh> SpringChain::field_mesh() const {
  // Mass i is point i; the springs (element cells) first, then a vertex cell on each mass.
  FieldMesh mesh;
  mesh.dimension = 1;
  mesh.points = Eigen::MatrixXd::Zero(n_, 2);
  mesh.points.col(0) = Vec::LinSpaced(n_, 0.0, static_cast<double>(n_ - 1));
  mesh.point_dofs = Eigen::VectorXi::LinSpaced(n_, 0, static_cast<int>(n_ - 1));
  mesh.cells = Eigen::MatrixXi::Constant(2 * n_ - 1, 2, -1);
  for (Index i = 0; i + 1 < n_; ++i) mesh.cells.row(i) << static_cast<int>(i), static_cast<int>(i + 1);
  mesh.cells.col(0).tail(n_) = Eigen::VectorXi::LinSpaced(n_, 0, static_cast<int>(n_ - 1));
  mesh.cell_body.assign(static_cast<std::size_t>(2 * n_ - 1), 0);
  mesh.stress_components = {"spring_force"};
  return mesh;
}

void SpringChain::cell_stress(ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> out) const {
  for (Index i = 0; i + 1 < n_; ++i) out(i, 0) = k_ * (u[i + 1] - u[i]);
}

NSBENCH_PROBLEM({"spring-chain", "masses joined by linear springs, no external force, optional rigid wall (momentum and energy test bed)", &SpringChain::parameters_spec, &make_from_params<Problem, SpringChain>});

}  // namespace nsb
