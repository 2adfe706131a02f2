// Moreau-Jean with an indefinite iteration matrix W = M + h^2 theta^2 K must still give the
// theta-method step: CHOLMOD's simplicial LL^T fails on it, then the sparse LU fallback acts
// (small and sparse or larger and dense alike).
#include <Eigen/LU>
#include <catch2/catch.hpp>

#include "integrators/moreau_jean.hpp"


namespace {

// n unit masses, no contact, K = k (3 11^T / n - I): eigenvalues -k (n - 1 times) and 2 k.
class Saddle final : public nsb::Problem {
 public:
  Saddle(double k, nsb::Index n) : k_(k), n_(n) {
    contacts_.normal.resize(0, n);
    K_ = (k * (Eigen::MatrixXd::Constant(n, n, 3.0 / n) - Eigen::MatrixXd::Identity(n, n))).sparseView();
  }
  Eigen::MatrixXd dense_stiffness() const { return Eigen::MatrixXd(K_); }
  std::string name() const override { return "saddle"; }
  const nsb::Params& parameters() const override { return params_; }
  nsb::Index ndof() const override { return n_; }
  nsb::SpMat mass_matrix() const override {
    nsb::SpMat M(n_, n_);
    M.setIdentity();
    return M;
  }
  void internal_force(nsb::ConstVecRef u, nsb::VecRef f) const override { f = K_ * u; }
  void tangent_stiffness(nsb::ConstVecRef, nsb::SpMat& K) const override { K = K_; }
  bool is_linear() const override { return true; }
  void external_force(double, nsb::VecRef f) const override { f.setZero(); }
  double strain_energy(nsb::ConstVecRef u) const override { return 0.5 * u.dot(K_ * u); }
  double load_potential(nsb::ConstVecRef) const override { return 0.0; }
  const nsb::Contacts& contacts() const override { return contacts_; }
  nsb::State initial_state() const override {
    return {0.0, nsb::Vec::LinSpaced(n_, 0.1, -0.3), nsb::Vec::LinSpaced(n_, -0.2, 0.4)};
  }
  double stable_step() const override { return 2.0 / std::sqrt(k_); }

 private:
  double k_;
  nsb::Index n_;
  nsb::Params params_;
  nsb::SpMat K_;
  nsb::Contacts contacts_;
};

}  // namespace

TEST_CASE("moreau-jean: an indefinite iteration matrix gives the theta step (LU fallback when Cholesky fails)",
          "[integrators][moreau-jean]") {
  const double k = 100.0, h = 0.5, theta = 0.5;  // eigenvalues of W: 1 - 6.25 and 1 + 12.5
  for (const nsb::Index n : {2, 200}) {
    const Saddle problem(k, n);
    nsb::MoreauJean integ(nsb::Params(nsb::MoreauJean::parameters_spec(), {{"theta", "0.5"}}));
    const nsb::State s0 = problem.initial_state();
    integ.init(problem, s0);
    integ.step(h);
    const auto fallbacks = integ.work().extra.count("lu_fallbacks") ? integ.work().extra.at("lu_fallbacks") : 0.0;
    CHECK(fallbacks == 1.0);
    const Eigen::MatrixXd K = problem.dense_stiffness();
    const Eigen::MatrixXd W = Eigen::MatrixXd::Identity(n, n) + h * h * theta * theta * K;
    const nsb::Vec v1 = s0.v + W.lu().solve(-h * K * s0.u - h * h * theta * K * s0.v);
    const nsb::Vec u1 = s0.u + h * 0.5 * (s0.v + v1);
    // W's condition number is 13.5 / 5.25: the solves agree to a few hundred eps_mach.
    CHECK((integ.state().v - v1).cwiseAbs().maxCoeff() <= 1e-12 * v1.cwiseAbs().maxCoeff());
    CHECK((integ.state().u - u1).cwiseAbs().maxCoeff() <= 1e-12 * u1.cwiseAbs().maxCoeff());
  }
}
