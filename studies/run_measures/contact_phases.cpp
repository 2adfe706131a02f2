// Run measure "contact-phases": the contact phases of a run, counted at every step however long
// the run (ContactPhases, studies/measures.hpp: a phase starts at a step with a contact impulse
// after a flight longer than `min_flight`, so that a chattering contact is one phase), and the
// largest penetration max(0, -min_i g_i) over each tenth of the run's steps so far, to tell a
// bounded penetration from a growing one. Result: phases, starts (every phase's start time),
// max_penetration and penetration_by_tenth (of the run's time span [t_0, t_end]: the index
// tenth = floor(10 (t - t_0) / (t_end - t_0)), the last step included in the tenth tenth).
#include <algorithm>
#include <array>
#include <cmath>

#include "problems/contact_gaps.hpp"
#include "studies/measures.hpp"
#include "studies/run_measure.hpp"

namespace nsb {

namespace {

class ContactPhasesMeasure final : public RunMeasure {
 public:
  ContactPhasesMeasure(const Params& params, const Problem& problem, const Integrator& integrator)
      : gaps_(problem), phases_(params.real("min_flight")), t0_(integrator.state().t),
        span_(params.real("t_end") - t0_) {}
  void add(const Integrator& integrator, const StepInfo&) override {
    const State& s = integrator.state();
    phases_.add(s.t, integrator.impulses().size() > 0 && integrator.impulses().sum() > 0.0);
    const double penetration = std::max(0.0, -gaps_.min_at(s.u));
    const auto tenth = static_cast<std::size_t>(std::clamp(10.0 * (s.t - t0_) / span_, 0.0, 9.0));
    by_tenth_[tenth] = std::max(by_tenth_[tenth], penetration);
  }
  Json result() const override {
    return {{"phases", phases_.starts().size()}, {"starts", reals(phases_.starts())},
            {"max_penetration", real(*std::max_element(by_tenth_.begin(), by_tenth_.end()))},
            {"penetration_by_tenth", reals({by_tenth_.begin(), by_tenth_.end()})}};
  }

 private:
  ContactGaps gaps_;
  ContactPhases phases_;
  double t0_, span_;
  std::array<double, 10> by_tenth_{};
};

ParamSpecs contact_phases_parameters() {
  return {ParamSpec::real("min_flight", 0.0, 0.0, 1e12, "a flight shorter than this [s] does not end a phase (chatter)"),
          ParamSpec::real("t_end", 1.0, 0.0, 1e12, "the run's end [s], for the tenths of the penetration", true)};
}

std::unique_ptr<RunMeasure> make_contact_phases(const Params& params, const Problem& problem, const Integrator& integrator) {
  if (problem.contacts().size() == 0) throw InputError("contact-phases: problem " + problem.name() + " has no contact");
  if (!(params.real("t_end") > integrator.state().t))
    throw InputError("contact-phases t_end: must be after the run's start (give the case's t_end)");
  return std::make_unique<ContactPhasesMeasure>(params, problem, integrator);
}

}  // namespace

extern const RunMeasureEntry contact_phases_measure;
const RunMeasureEntry contact_phases_measure{"contact-phases",
                                             "contact phases counted every step, and the largest penetration per tenth of the run",
                                             &contact_phases_parameters, &make_contact_phases};

}  // namespace nsb
