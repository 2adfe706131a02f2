// An integrator whose init returns only once `parties` runs of it are in init at the same time
// (or declines after `wait` seconds, saying how many were): CD-Lagrange underneath. A study of
// `parties` cases of it ends ok only when the case pool ran them side by side, which is what
// tests/python/test_study_api.py asks of nsbench.study.run (a pool that serialised them, or held
// the GIL, would decline them all). The wait is a guard against a hang, not a measurement.
#include <chrono>
#include <condition_variable>
#include <mutex>

#include "integrators/registry.hpp"

namespace {

std::mutex arrivals_mutex;
std::condition_variable arrived;
long arrivals = 0;

class Rendezvous final : public nsb::Integrator {
 public:
  explicit Rendezvous(const nsb::Params& params)
      : Integrator(params), inner_(nsb::make_integrator("cd-lagrange")), parties_(params.integer("parties")),
        wait_(params.real("wait")) {}
  static nsb::ParamSpecs parameters_spec() {
    return {nsb::ParamSpec::integer("parties", 2, 1, 64, "runs that must be in init at once"),
            nsb::ParamSpec::real("wait", 60.0, 0.0, 600.0, "seconds to wait for them before declining")};
  }

  void init(const nsb::Problem& problem, const nsb::State& initial) override {
    {
      std::unique_lock lock(arrivals_mutex);
      const long ticket = ++arrivals, target = (ticket + parties_ - 1) / parties_ * parties_;
      arrived.notify_all();
      if (!arrived.wait_for(lock, std::chrono::duration<double>(wait_), [&] { return arrivals >= target; })) {
        arrivals = target;  // the next group starts afresh
        throw nsb::InputError("rendezvous: the other runs of its group did not start while it waited");
      }
    }
    bind(problem, initial);
    inner_->init(problem, initial);
  }

  nsb::StepInfo advance(double dt) override {
    const nsb::StepInfo info = inner_->step(dt);
    state_ = inner_->state();
    impulses_ = inner_->impulses();
    work_ = inner_->work();
    return info;
  }

 private:
  std::unique_ptr<nsb::Integrator> inner_;
  long parties_;
  double wait_;
};

}  // namespace

NSBENCH_INTEGRATOR({"rendezvous", "test plugin: CD-Lagrange whose init waits for the other runs of its group",
                    &Rendezvous::parameters_spec, &nsb::make_from_params<nsb::Integrator, Rendezvous>, false, false,
                    {.explicit_step = true, .mass = nsb::MassNeed::DiagonalPositive}});
