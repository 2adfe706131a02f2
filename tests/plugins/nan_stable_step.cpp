// A problem plugin whose stable_step() is NaN (tests/studies/study_file_test.cpp): a point
// mass dropped on a floor, sound otherwise, as a plugin breaking the contract's stable step
// would be. A study runs the schemes that do not read the stable step and records the one
// that caps its steps by it (cd-lagrange-adaptive) as declined, with the reason.
#include <limits>

#include "problems/registry.hpp"
#include "problems/rigid_problem.hpp"

namespace {

class NanStableMass final : public nsb::RigidProblem {
 public:
  explicit NanStableMass(const nsb::Params& params) : params_(params) {
    mass_ = nsb::Vec::Ones(1);
    load_ = nsb::Vec::Constant(1, -9.81);
    contacts_.normal.resize(1, 1);
    contacts_.normal.insert(0, 0) = 1.0;
    contacts_.normal.makeCompressed();
    contacts_.gap_offset = nsb::Vec::Zero(1);
    contacts_.restitution = 0.5;
  }
  static nsb::ParamSpecs parameters_spec() { return {}; }
  std::string name() const override { return "nan-stable-mass"; }
  const nsb::Params& parameters() const override { return params_; }
  nsb::State initial_state() const override { return {0.0, nsb::Vec::Ones(1), nsb::Vec::Zero(1)}; }
  double stable_step() const override { return std::numeric_limits<double>::quiet_NaN(); }

 private:
  nsb::Params params_;
};

}  // namespace

NSBENCH_PROBLEM({"nan-stable-mass", "test plugin: a point mass on a floor whose stable_step() is NaN",
                 &NanStableMass::parameters_spec, &nsb::make_from_params<nsb::Problem, NanStableMass>});
