// A deliberately broken integrator for `nsbench check` (tests/app/check_test.cpp): CD-Lagrange
// underneath, so its motion is right, but it reports its impulses with the sign convention
// inverted (a push apart as Lambda < 0) and never counts its force evaluations
// (work().force_evaluations stays 0, so budgets and work-precision tables would read nothing;
// its steps are counted by Integrator::step, as every integrator's are). And a problem whose field mesh names a dof it does
// not have (`nsbench run --fields` would refuse it): one free mass, otherwise sound.
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "problems/rigid_problem.hpp"

namespace {

class Broken final : public nsb::Integrator {
 public:
  explicit Broken(const nsb::Params& params) : Integrator(params), inner_(nsb::make_integrator("cd-lagrange")) {}
  static nsb::ParamSpecs parameters_spec() { return {}; }

  void init(const nsb::Problem& problem, const nsb::State& initial) override {
    bind(problem, initial);
    inner_->init(problem, initial);
  }

  nsb::StepInfo advance(double dt) override {
    const nsb::StepInfo info = inner_->step(dt);
    state_ = inner_->state();
    impulses_ = -inner_->impulses();
    tangential_impulses_ = inner_->tangential_impulses();
    return info;
  }

 private:
  std::unique_ptr<nsb::Integrator> inner_;
};

class BrokenMesh final : public nsb::RigidProblem {
 public:
  explicit BrokenMesh(const nsb::Params& params) : params_(params) {
    mass_ = nsb::Vec::Ones(1);
    load_ = nsb::Vec::Zero(1);
    contacts_.normal.resize(0, 1);
    contacts_.gap_offset.resize(0);
  }
  static nsb::ParamSpecs parameters_spec() { return {}; }
  std::string name() const override { return "broken-mesh"; }
  const nsb::Params& parameters() const override { return params_; }
  nsb::State initial_state() const override { return {0.0, nsb::Vec::Zero(1), nsb::Vec::Zero(1)}; }
  std::optional<nsb::FieldMesh> field_mesh() const override {
    nsb::FieldMesh mesh;
    mesh.add_vertex(0.0, 0.0, {1}, 0);  // dof 1 of a problem with one dof
    return mesh;
  }

 private:
  nsb::Params params_;
};

}  // namespace

NSBENCH_PROBLEM({"broken-mesh", "test plugin: a field mesh naming a dof the problem does not have",
                 &BrokenMesh::parameters_spec, &nsb::make_from_params<nsb::Problem, BrokenMesh>});
NSBENCH_INTEGRATOR({"broken", "test plugin: inverted impulse sign, no force evaluation count", &Broken::parameters_spec,
                    &nsb::make_from_params<nsb::Integrator, Broken>, false, false, {.explicit_step = true}});
