// A problem plugin: a point mass in a paraboloid bowl z = (x^2 + y^2) / (2 R) under gravity,
// with Coulomb's cone and Newton's restitution, whose contact moves with the mass (the normal
// turns as it slides): U = (x, y, z), M = m I (m = 1 kg), F_ext = (0, 0, -m g),
//     g(U) = z - (x^2 + y^2) / (2 R),     L(U) = dg/dU = (-x/R, -y/R, 1),
//     t1 = (1, 0, x/R) / |(1, 0, x/R)|    (orthogonal to L),     t2 = n x t1,  n = L / |L|,
// an orthonormal tangent pair at every configuration. On a curved surface no orthonormal pair is
// a pair of gradients (the tangent directions are not integrable), so `nsbench check --problem
// bowl` tests the rows against the motion of the contact point (contact_points: the mass itself):
// L U' is the gap's rate, T U' and T2 U' the point's tangential velocity (docs/contacts.md).
// A scheme that reads the rows where the mass is (moving contacts: cd-lagrange, moreau-jean,
// nsga, ...) takes it; the others decline it.
#include <nsbench/problems/registry.hpp>
#include <nsbench/problems/rigid_problem.hpp>

#include <Eigen/Geometry>

namespace {

class Bowl : public nsb::RigidProblem {
 public:
  explicit Bowl(const nsb::Params& params) : params_(params), R_(params.real("R")) {
    mass_ = nsb::Vec::Ones(3);
    load_ = nsb::Vec(3);
    load_ << 0.0, 0.0, -9.81;
    const nsb::Vec u0 = initial_state().u;
    nsb::SpMat L(1, 3), T(1, 3), T2(1, 3);  // the rows' pattern: one contact on the three dofs
    for (int j = 0; j < 3; ++j) L.insert(0, j) = 1.0, T.insert(0, j) = 1.0, T2.insert(0, j) = 1.0;
    contacts_.normal = L;
    contacts_.restitution = 0.5;
    contacts_.set_cone(T, T2, 0.3);
    nsb::ContactGeometry at{nsb::Vec::Zero(1), L, T, T2};
    Bowl::evaluate_contacts(u0, at);
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
  std::string name() const override { return "bowl"; }
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
    const Eigen::Vector3d t2 = grad.normalized().cross(t1);
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

 protected:
  double radius() const { return R_; }

 private:
  nsb::Params params_;
  double R_;
};

std::unique_ptr<nsb::Problem> make_bowl(const nsb::Params& p) { return std::make_unique<Bowl>(p); }

}  // namespace

NSBENCH_PROBLEM({"bowl", "plugin example: a point mass in a paraboloid bowl (moving contact, Coulomb cone, e = 0.5)",
                 &Bowl::parameters_spec, &make_bowl});
