// dropped-ball: a problem plugin as nsbench 0.1.0 documented them (problems/problem.hpp of
// release 0.1.0), kept as it was so that CI shows when a change breaks such a plugin
// (scripts/plugin-example.sh builds it against the installed nsbench, expects a deprecation
// warning naming the replacement of each 0.1.0 override, and runs it).
//
// A point mass dropped from rest at height h0 onto a rigid floor, e = 1: the first impact at
// t1 = sqrt(2 h0 / g), then one every T = 2 t1; s after leaving the floor (at speed w = g t1),
//     q = w s - g s^2 / 2,   v = w - g s   (before t1: s = t + t1, the flight's second half).
#include <cmath>

#include <nsbench/problems/registry.hpp>
#include <nsbench/problems/rigid_problem.hpp>

namespace {

using namespace nsb;

class DroppedBall final : public RigidProblem {
 public:
  explicit DroppedBall(const Params& params) : params_(params), g_(params.real("g")), h0_(params.real("h0")) {
    t1_ = std::sqrt(2.0 * h0_ / g_);
    contacts_.normal.resize(1, 1);
    contacts_.normal.insert(0, 0) = 1.0;
    contacts_.normal.makeCompressed();
    contacts_.gap_offset = Vec::Zero(1);
    contacts_.restitution = 1.0;
    mass_ = Vec::Constant(1, 1.0);
    load_ = Vec::Constant(1, -g_);
  }
  static ParamSpecs parameters_spec() {
    return {ParamSpec::real("g", 9.81, 0.0, 1e308, "gravity [m/s^2]", true),
            ParamSpec::real("h0", 1.0, 0.0, 1e308, "drop height [m]", true)};
  }

  std::string name() const override { return "dropped-ball"; }
  const Params& parameters() const override { return params_; }
  State initial_state() const override {
    State s;
    s.u = Vec::Constant(1, h0_);
    s.v = Vec::Zero(1);
    return s;
  }
  std::vector<std::string> observable_names() const override { return {"q", "q_exact"}; }
  void observe(const State& s, std::span<double> out) const override {
    out[0] = s.u[0];
    out[1] = exact_state(s.t)->u[0];
  }
  std::optional<State> exact_state(double t) const override {
    State s;
    s.t = t;
    s.u.resize(1);
    s.v.resize(1);
    const double w = g_ * t1_;
    const double since = t < t1_ ? t + t1_ : std::fmod(t - t1_, 2.0 * t1_);  // time since leaving the floor
    s.u[0] = w * since - 0.5 * g_ * since * since;
    s.v[0] = w - g_ * since;
    return s;
  }
  std::vector<double> impact_times(double t_end) const override {
    std::vector<double> times;
    for (double t = t1_; t <= t_end; t += 2.0 * t1_) times.push_back(t);
    return times;
  }

 private:
  Params params_;
  double g_, h0_, t1_;
};

}  // namespace

NSBENCH_PROBLEM({"dropped-ball", "0.1.0 plugin: a ball dropped on a rigid floor, e = 1 (exact solution)",
                 &DroppedBall::parameters_spec, &nsb::make_from_params<nsb::Problem, DroppedBall>});
