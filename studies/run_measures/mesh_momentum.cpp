// Run measure "mesh-momentum": one momentum identity of a mesh problem per step (MeshMomentum,
// studies/measures.hpp: the linear momentum px, py, pz, or the angular momentum jx, jy, jz about
// the origin, against every contact impulse and the external force). Result: largest, the
// largest residual; scale, the residual's scale; relative = largest / scale.
#include <fmt/format.h>

#include <algorithm>

#include "studies/measures.hpp"
#include "studies/run_measure.hpp"

namespace nsb {

namespace {

class MeshMomentumMeasure final : public RunMeasure {
 public:
  MeshMomentumMeasure(const Params& params, const Problem& problem, const Integrator& integrator)
      : momentum_(problem, integrator.state(), params.choice("component")) {}
  void add(const Integrator& integrator, const StepInfo& step) override { momentum_.add(integrator, step.dt); }
  Json result() const override {
    return {{"largest", real(momentum_.largest())}, {"scale", real(momentum_.scale())},
            {"relative", real(momentum_.largest() / momentum_.scale())}};
  }

 private:
  MeshMomentum momentum_;
};

ParamSpecs mesh_momentum_parameters() {
  return {ParamSpec::choice("component", "px", {"px", "py", "pz", "jx", "jy", "jz"},
                            "linear (p) or angular (j) momentum, its component")};
}

std::unique_ptr<RunMeasure> make_mesh_momentum(const Params& params, const Problem& problem, const Integrator& integrator) {
  const std::string& component = params.choice("component");
  const std::vector<std::string> valid = problem.field_mesh() ? MeshMomentum::components(problem) : std::vector<std::string>{};
  if (std::find(valid.begin(), valid.end(), component) == valid.end())
    throw InputError(fmt::format("mesh-momentum component {}: not a momentum of problem {} (valid: {})", component, problem.name(),
                                 valid.empty() ? "none: it has no field mesh" : fmt::format("{}", fmt::join(valid, ", "))));
  return std::make_unique<MeshMomentumMeasure>(params, problem, integrator);
}

}  // namespace

extern const RunMeasureEntry mesh_momentum_measure;
const RunMeasureEntry mesh_momentum_measure{"mesh-momentum", "a momentum identity of a mesh problem per step: its largest residual",
                     &mesh_momentum_parameters, &make_mesh_momentum};

}  // namespace nsb
