#pragma once
// A point mass on a slope of angle alpha with Coulomb friction mu, for the friction tests of
// the penalty schemes: x along the slope (downhill), y along its normal, one contact with
// normal row [0 1] (gap y), tangent row [1 0] (slip x'), a fixed slope (w = 0), e = 0.
// Gravity g: F_ext = m g (sin alpha, -cos alpha). Started on the slope (y = 0) at x' = v0.
// Exact (Coulomb): x'' = a = g (sin alpha - mu cos alpha) while x' > 0; for a < 0 it stops
// at t_s = v0 / (-a) and sticks.
#include <cmath>
#include <limits>
#include <numbers>

#include "problems/problem.hpp"

namespace nsb::testing {

class SlidingMass final : public Problem {
 public:
  SlidingMass(double alpha_deg, double mu, double v0, double m = 1.0, double g = 9.81)
      : alpha_(alpha_deg * std::numbers::pi / 180.0), mu_(mu), v0_(v0), m_(m), g_(g) {
    contacts_.normal.resize(1, 2);
    contacts_.normal.insert(0, 1) = 1.0;
    contacts_.normal.makeCompressed();
    contacts_.gap_offset = Vec::Zero(1);
    SpMat t(1, 2);
    t.insert(0, 0) = 1.0;
    contacts_.set_friction(t, mu, 0.0);
  }

  double acceleration() const { return g_ * (std::sin(alpha_) - mu_ * std::cos(alpha_)); }
  double stop_time() const { return v0_ / -acceleration(); }
  double normal_force() const { return m_ * g_ * std::cos(alpha_); }
  double tangential_load() const { return m_ * g_ * std::sin(alpha_); }

  std::string name() const override { return "sliding-mass-test"; }
  const Params& parameters() const override { return params_; }
  Index ndof() const override { return 2; }
  SpMat mass_matrix() const override {
    SpMat M(2, 2);
    M.insert(0, 0) = m_;
    M.insert(1, 1) = m_;
    return M;
  }
  void internal_force(ConstVecRef, VecRef f) const override { f.setZero(); }
  void tangent_stiffness(ConstVecRef, SpMat& K) const override { K.resize(2, 2); }
  bool is_linear() const override { return true; }
  void external_force(double, VecRef f) const override {
    f[0] = tangential_load();
    f[1] = -normal_force();
  }
  double strain_energy(ConstVecRef) const override { return 0.0; }
  double load_potential(ConstVecRef u) const override { return -tangential_load() * u[0] + normal_force() * u[1]; }
  const Contacts& contacts() const override { return contacts_; }
  State initial_state() const override { return {0.0, Vec::Zero(2), Vec{{v0_, 0.0}}}; }
  double stable_step() const override { return std::numeric_limits<double>::infinity(); }

 private:
  double alpha_, mu_, v0_, m_, g_;
  Contacts contacts_;
  Params params_;
};

}  // namespace nsb::testing
