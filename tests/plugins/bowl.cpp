// The example problem plugin (examples/plugin/bowl.cpp, issue 57 items 1 and 6;
// tests/app/check_test.cpp), and beside it "bowl-skewed", which keeps its L and T but takes
// T2 = (0, 1, y/R), a gradient (of y + y^2 / (2 R)) that is neither unit nor orthogonal to T away
// from the bottom: an anisotropic friction law, which `nsbench check --problem` must fail.
#include "../../examples/plugin/bowl.cpp"

namespace {

class SkewedBowl final : public Bowl {
 public:
  using Bowl::Bowl;
  std::string name() const override { return "bowl-skewed"; }
  void evaluate_contacts(nsb::ConstVecRef u, nsb::ContactGeometry& out) const override {
    Bowl::evaluate_contacts(u, out);
    const double t2[3] = {0.0, 1.0, u[1] / radius()};
    for (int j = 0; j < 3; ++j) out.tangent2.coeffRef(0, j) = t2[j];
  }
};

std::unique_ptr<nsb::Problem> make_skewed(const nsb::Params& p) { return std::make_unique<SkewedBowl>(p); }

}  // namespace

NSBENCH_PROBLEM({"bowl-skewed", "test plugin: the bowl with a second tangent neither unit nor orthogonal", &Bowl::parameters_spec,
                 &make_skewed});
