#include "integrators/integrator.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace nsb {

void Integrator::bind(const Problem& problem, const State& initial) {
  const Contacts& c = problem.contacts();
  check_contacts(c, problem.ndof(), problem.name());
  mass_ = problem.mass_matrix();
  check_problem_contract(problem, mass_, initial);
  if (declared_) check_capabilities(*declared_, name_, params_, problem, mass_);
  problem_ = &problem;
  state_ = initial;
  impulses_ = Vec::Zero(problem.ncontacts());
  tangential_impulses_ = Vec::Zero(problem.ncontacts());
  tangential_impulses2_ = Vec::Zero(problem.ncontacts());
  work_ = WorkCounters{};
}

StepInfo Integrator::advance(double /*dt_requested*/) {
  throw std::logic_error("integrator " + name_ + " overrides neither advance(dt) nor step(dt)");
}

Capabilities Integrator::capabilities() const { return declared_ ? declared_->resolved(params_) : Capabilities{}; }

Energy Integrator::energy() const {
  const Vec& v = state_.v;
  return {0.5 * v.dot(mass_ * v), problem_->potential(state_.u)};
}

const std::vector<ContactEvent>& Integrator::events() const {
  static const std::vector<ContactEvent> none;
  return none;
}

std::vector<ContactEvent> events_of_kind(const std::vector<ContactEvent>& events,
                                         std::initializer_list<ContactEventKind> kinds) {
  std::vector<ContactEvent> out;
  for (const auto& e : events)
    if (std::find(kinds.begin(), kinds.end(), e.kind) != kinds.end()) out.push_back(e);
  return out;
}

const char* event_kind_name(ContactEventKind kind) {
  switch (kind) {
    case ContactEventKind::Impact: return "impact";
    case ContactEventKind::Release: return "release";
    case ContactEventKind::Arrival: return "arrival";
    case ContactEventKind::ZenoStop: return "zeno-stop";
    case ContactEventKind::Switch: return "switch";
  }
  return "?";
}

std::string events_to_csv(const std::vector<ContactEvent>& events) {
  std::string out = "t,contact,kind,rate_before,rate_after,impulse\n";
  for (const auto& e : events)
    out += fmt::format("{},{},{},{},{},{}\n", e.t, e.contact, event_kind_name(e.kind), e.rate_before, e.rate_after, e.impulse);
  return out;
}

}  // namespace nsb
