// A point mass in a paraboloid bowl z = (x^2 + y^2) / (2 R) under gravity, with Coulomb's
// cone and restitution (issue 57, item 1; tests/app/check_test.cpp): U = (x, y, z), M = m I,
// the gap g(U) = z - (x^2 + y^2) / (2 R) and L = dg/dU = (-x/R, -y/R, 1). Its tangents, as
// the laws need them: t1 = (1, 0, x/R) / |.| (orthogonal to L) and t2 = n x t1 (n = L / |L|),
// an orthonormal pair that is no pair of gradients (on a curved surface none is), so
// `nsbench check --problem bowl` passes only by testing the rows against the point's motion
// (contact_points: the mass itself). "bowl-skewed" keeps L and T but takes T2 = (0, 1, y/R),
// a gradient (of y + y^2 / (2 R)) that is neither unit nor orthogonal to T away from the
// bottom: an anisotropic friction law, which the check must fail.
#include <Eigen/Geometry>
#include <cmath>

#include "problems/registry.hpp"
#include "problems/rigid_problem.hpp"

namespace {

class Bowl final : public nsb::RigidProblem {
 public:
  Bowl(const nsb::Params& params, bool skewed) : params_(params), skewed_(skewed), R_(params.real("R")) {
    mass_ = nsb::Vec::Ones(3);
    load_ = nsb::Vec(3);
    load_ << 0.0, 0.0, -9.81;
    const nsb::Vec u0 = initial_state().u;
    nsb::SpMat L(1, 3), T(1, 3), T2(1, 3);
    for (int j = 0; j < 3; ++j) L.insert(0, j) = 1.0, T.insert(0, j) = 1.0, T2.insert(0, j) = 1.0;
    contacts_.normal = L;
    contacts_.restitution = 0.5;
    contacts_.set_cone(T, T2, 0.3);
    nsb::ContactGeometry at{nsb::Vec::Zero(1), L, T, T2};
    evaluate_contacts(u0, at);
    contacts_.normal = nsb::SpMat(at.normal);
    contacts_.tangent = nsb::SpMat(at.tangent);
    contacts_.tangent2 = nsb::SpMat(at.tangent2);
    contacts_.gap_offset = at.gap - contacts_.normal * u0;  // g0 = g(U0) - L(U0) U0
  }
  static nsb::ParamSpecs parameters_spec() {
    return {nsb::ParamSpec::real("R", 1.0, 0.0, 1e308, "radius of curvature at the bottom [m]", true),
            nsb::ParamSpec::real("x0", 0.3, -1e308, 1e308, "initial x [m]"),
            nsb::ParamSpec::real("y0", 0.2, -1e308, 1e308, "initial y [m]"),
            nsb::ParamSpec::real("h0", 0.05, 0.0, 1e308, "initial height above the bowl [m]")};
  }
  std::string name() const override { return skewed_ ? "bowl-skewed" : "bowl"; }
  const nsb::Params& parameters() const override { return params_; }
  bool contacts_move() const override { return true; }
  nsb::State initial_state() const override {
    const double x = params_.real("x0"), y = params_.real("y0");
    nsb::Vec u(3);
    u << x, y, (x * x + y * y) / (2.0 * R_) + params_.real("h0");
    return {0.0, u, nsb::Vec::Zero(3)};
  }
  void evaluate_contacts(nsb::ConstVecRef u, nsb::ContactGeometry& out) const override {
    const Eigen::Vector3d grad(-u[0] / R_, -u[1] / R_, 1.0), t1 = Eigen::Vector3d(1.0, 0.0, u[0] / R_).normalized();
    const Eigen::Vector3d t2 = skewed_ ? Eigen::Vector3d(0.0, 1.0, u[1] / R_) : Eigen::Vector3d(grad.normalized().cross(t1));
    out.gap[0] = u[2] - (u[0] * u[0] + u[1] * u[1]) / (2.0 * R_);
    for (int j = 0; j < 3; ++j) {
      out.normal.coeffRef(0, j) = grad[j];
      out.tangent.coeffRef(0, j) = t1[j];
      out.tangent2.coeffRef(0, j) = t2[j];
    }
  }
  // The contact point is the mass: its position is U, whatever configuration it touched at.
  bool contact_points(nsb::ConstVecRef, nsb::ConstVecRef u, Eigen::Ref<Eigen::MatrixXd> x) const override {
    x.row(0) = u.transpose();
    return true;
  }

 private:
  nsb::Params params_;
  bool skewed_;
  double R_;
};

std::unique_ptr<nsb::Problem> make_bowl(const nsb::Params& p) { return std::make_unique<Bowl>(p, false); }
std::unique_ptr<nsb::Problem> make_skewed(const nsb::Params& p) { return std::make_unique<Bowl>(p, true); }

}  // namespace

NSBENCH_PROBLEM({"bowl", "test plugin: a point mass in a paraboloid bowl, orthonormal tangents", &Bowl::parameters_spec, &make_bowl});
NSBENCH_PROBLEM({"bowl-skewed", "test plugin: the bowl with a second tangent neither unit nor orthogonal", &Bowl::parameters_spec,
                 &make_skewed});
