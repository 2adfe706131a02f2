// A problem that takes 3.5 s to build, as a 1e8-element bar takes a minute to assemble
// (tests/app/cli_test.cpp: `nsbench run` says it is preparing the run meanwhile). Otherwise
// a point mass at rest on nothing: one dof, no contact.
#include <chrono>
#include <thread>

#include "problems/registry.hpp"
#include "problems/rigid_problem.hpp"

namespace {

class SlowSetup final : public nsb::RigidProblem {
 public:
  explicit SlowSetup(const nsb::Params& params) : params_(params) {
    std::this_thread::sleep_for(std::chrono::milliseconds(3500));
    mass_ = nsb::Vec::Ones(1);
    load_ = nsb::Vec::Zero(1);
    contacts_.normal.resize(0, 1);
    contacts_.gap_offset.resize(0);
  }
  static nsb::ParamSpecs parameters_spec() { return {}; }
  std::string name() const override { return "slow-setup"; }
  const nsb::Params& parameters() const override { return params_; }
  nsb::State initial_state() const override { return {0.0, nsb::Vec::Zero(1), nsb::Vec::Zero(1)}; }

 private:
  nsb::Params params_;
};

}  // namespace

NSBENCH_PROBLEM({"slow-setup", "test plugin: a free mass that takes 3.5 s to build", &SlowSetup::parameters_spec,
                 &nsb::make_from_params<nsb::Problem, SlowSetup>});
