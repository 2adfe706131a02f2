#include "reference/event_driven.hpp"
#include "integrators/registry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace nsb {

namespace {

// Events at one instant beyond this mean the event logic cycles (a bug, not physics: a
// Zeno sequence is cut by zeno_velocity long before).
constexpr long kMaxEventsPerStep = 100000;
// An open contact's gap is known to about atol + rtol |u| (CVODE's error control, the root
// located to round-off): a penetration this many times beyond it is an impact missed.
constexpr double kPenetrationTolerance = 1e3;

}  // namespace

ParamSpecs EventDriven::parameters_spec() {
  return {
      ParamSpec::choice("method", "bdf", {"bdf", "adams"}, "CVODE linear multistep method (bdf: Newton + KLU; adams: fixed point)"),
      ParamSpec::real("rtol", 1e-11, 0.0, 1e-2, "CVODE relative tolerance", true),
      ParamSpec::real("atol", 1e-13, 0.0, 1.0, "CVODE absolute tolerance (also the gap below which contacts hit together)", true),
      // 0 would let the impacts accumulate until a landing is too slow for the root finder
      // and the dof falls through the obstacle (issue 20): excluded.
      ParamSpec::real("zeno_velocity", 1e-4, 0.0, 1e308, "rebound speed below which an impact is made plastic and the contact closes", true),
  };
}

EventDriven::EventDriven(const Params& params)
    : Integrator(params), zeno_velocity_(params.real("zeno_velocity")) {
  counts_own_steps_ = true;  // CVODE's steps (Cvode::add_work)
  settings_.bdf = params.choice("method") == "bdf";
  settings_.rtol = params.real("rtol");
  settings_.atol = params.real("atol");
}

void EventDriven::init(const Problem& problem, const State& initial) {
  bind(problem, initial);
  const Index n = problem.ndof();
  minv_ = mass_.diagonal().cwiseInverse();

  contacts_ = node_contacts(problem);
  dof_closed_.assign(static_cast<std::size_t>(n), 0);
  closed_.assign(contacts_.size(), 0);
  e_ = problem.restitution();
  events_ = releases_ = zeno_stops_ = 0;
  event_log_.clear();

  // y = (u, v, Lambda): Lambda_i integrates contact i's reaction while it is closed.
  y_.resize(2 * n + static_cast<Index>(contacts_.size()));
  y_ << state_.u, state_.v, Vec::Zero(static_cast<Index>(contacts_.size()));
  f_ = Vec::Zero(n);
  fext_ = Vec::Zero(n);
  problem.external_force(state_.t, fext_);
  g_ = Vec::Zero(static_cast<Index>(contacts_.size()));
  problem.tangent_stiffness(state_.u, K_);
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    const double gap = c.a * (state_.u[c.dof] - c.position);
    if (gap < -settings_.atol)
      throw InputError(fmt::format("event-driven: the initial state penetrates contact {} (gap {}); valid: gap >= -atol", i, gap));
    // Within atol of the obstacle, a contact counts as touching (handle_events): a gap that
    // is open but that small would make the start an impact, not the problem's initial state.
    if (gap > 0.0 && gap <= settings_.atol)
      throw InputError(fmt::format("event-driven: contact {} starts at gap {:g}, within atol = {:g} of the obstacle, where it "
                                   "counts as touching; valid: atol < {:g} (the smallest open initial gap)",
                                   i, gap, settings_.atol, gap));
  }
  cvode_ = std::make_unique<Cvode>(static_cast<OdeSystem&>(*this), y_.size(), static_cast<int>(contacts_.size()), settings_);
  // Every root watches its function decreasing through zero (see the header).
  cvode_->set_root_directions(std::vector<int>(contacts_.size(), -1));
  // Contacts touching at t0 impact or close before the first step.
  handle_events(state_.t, std::vector<int>(contacts_.size(), 0));
  state_.u = y_.head(n);
  state_.v = y_.segment(n, n);
  impulses_.setZero();
  publish_work();
}

void EventDriven::net_force(double t, ConstVecRef u) {
  problem_->internal_force(u, f_);
  if (!problem_->external_force_is_constant()) problem_->external_force(t, fext_);
  f_ = fext_ - f_;
}

void EventDriven::rhs(double t, ConstVecRef y, VecRef ydot) {
  const Index n = problem_->ndof();
  net_force(t, y.head(n));
  ydot.head(n) = y.segment(n, n);
  ydot.segment(n, n) = minv_.cwiseProduct(f_);
  for (Index k = 0; k < n; ++k)
    if (dof_closed_[k]) ydot[k] = ydot[n + k] = 0.0;
  for (std::size_t i = 0; i < contacts_.size(); ++i)
    ydot[2 * n + static_cast<Index>(i)] = closed_[i] ? -f_[contacts_[i].dof] / contacts_[i].a : 0.0;
}

void EventDriven::jacobian(double, ConstVecRef y, CsrMatrix& J) {
  // J = [0, I, 0; -M^{-1} K, 0, 0; K_d / a, 0, 0] with the rows of held dofs and of open
  // contacts zeroed (kept as explicit zeros, so that the pattern, and KLU's analysis,
  // survive mode changes). Row 2n + i: d(lambda_i)/du = d(-F_d / a_i)/du = K_{d,:} / a_i.
  const Index n = problem_->ndof();
  if (!problem_->is_linear()) problem_->tangent_stiffness(y.head(n), K_);
  std::vector<Eigen::Triplet<double, sunindextype>> entries;
  entries.reserve(static_cast<std::size_t>(n + 2 * K_.nonZeros()));
  for (Index k = 0; k < n; ++k) entries.emplace_back(k, n + k, dof_closed_[k] ? 0.0 : 1.0);
  std::vector<Index> contact_of(static_cast<std::size_t>(n), -1);
  for (std::size_t i = 0; i < contacts_.size(); ++i) contact_of[contacts_[i].dof] = static_cast<Index>(i);
  for (Index col = 0; col < K_.outerSize(); ++col)
    for (SpMat::InnerIterator it(K_, col); it; ++it) {
      entries.emplace_back(n + it.row(), it.col(), dof_closed_[it.row()] ? 0.0 : -minv_[it.row()] * it.value());
      if (const Index i = contact_of[it.row()]; i >= 0)
        entries.emplace_back(2 * n + i, it.col(), closed_[i] ? it.value() / contacts_[i].a : 0.0);
    }
  J.resize(y.size(), y.size());
  J.setFromTriplets(entries.begin(), entries.end());
  J.makeCompressed();
}

void EventDriven::roots(double t, ConstVecRef y, VecRef g) {
  const Index n = problem_->ndof();
  net_force(t, y.head(n));
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    g[static_cast<Index>(i)] = closed_[i] ? -f_[c.dof] / c.a : c.a * (y[c.dof] - c.position);
  }
}

void EventDriven::close(const Contact& c) {
  y_[c.dof] = c.position;
  y_[problem_->ndof() + c.dof] = 0.0;
}

void EventDriven::handle_events(double t, const std::vector<int>& fired) {
  const Index n = problem_->ndof();
  const std::size_t p = contacts_.size();
  // Releases: the reaction of a closed contact reached zero; the dof leaves the obstacle
  // from rest (and is no impact candidate now, or it would close again at once).
  std::vector<char> released(p, 0);
  for (std::size_t i = 0; i < p; ++i)
    if (closed_[i] && fired[i]) {
      closed_[i] = 0;
      dof_closed_[contacts_[i].dof] = 0;
      released[i] = 1;
      ++releases_;
      event_log_.push_back({t, static_cast<Index>(i), ContactEventKind::Release});
    }
  // Impacts: open contacts whose root fired or that touch (gap <= atol) while closing.
  std::vector<std::size_t> hit;
  std::vector<double> restitution;
  std::vector<char> zeno_stop;
  for (std::size_t i = 0; i < p; ++i) {
    if (closed_[i] || released[i]) continue;
    const Contact& c = contacts_[i];
    const double gap = c.a * (y_[c.dof] - c.position), rate = c.a * y_[n + c.dof];
    if ((fired[i] || gap <= settings_.atol) && rate <= 0.0) {
      hit.push_back(i);
      const bool zeno = e_ * -rate < zeno_velocity_;
      zeno_stop.push_back(zeno && e_ > 0.0 && rate < 0.0);
      if (zeno_stop.back()) ++zeno_stops_;
      restitution.push_back(zeno ? 0.0 : e_);
    }
  }
  if (!hit.empty()) {
    const Index h = static_cast<Index>(hit.size());
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(h, h);  // contacts on distinct dofs: diagonal
    Vec q(h), x = Vec::Zero(h);
    for (Index k = 0; k < h; ++k) {
      const Contact& c = contacts_[hit[k]];
      D(k, k) = c.a * c.a * minv_[c.dof];
      q[k] = (1.0 + restitution[k]) * c.a * y_[n + c.dof];
    }
    const LcpResult res = solve_lcp(D, q, x, lcp_);
    work_.lcp_iterations += res.iterations;
    if (!res.converged) ++work_.lcp_unconverged;
    for (Index k = 0; k < h; ++k) {
      const Contact& c = contacts_[hit[k]];
      const double before = c.a * y_[n + c.dof];
      y_[n + c.dof] += minv_[c.dof] * c.a * x[k];
      event_log_.push_back({t, static_cast<Index>(hit[k]), zeno_stop[k] ? ContactEventKind::ZenoStop : ContactEventKind::Impact,
                            before, c.a * y_[n + c.dof], x[k]});
      y_[c.dof] = c.position;  // the gap is zero at the impact, exactly
      impulses_[static_cast<Index>(hit[k])] += x[k];
      if (restitution[k] == 0.0) {
        closed_[hit[k]] = 1;  // candidate: kept below if its reaction is compressive
        dof_closed_[c.dof] = 1;
      }
    }
  }
  // Closed contacts: held while the acceleration-level LCP gives a compressive reaction
  // (diagonal here: lambda_i = -F_d / a_i > 0), released otherwise. A zero reaction (an
  // unstressed body arriving on the obstacle, as the bar at t = 0) is decided by its rate
  // lambda_i' = (K v)_d / a_i: released while the reaction is zero, the dof would sit at
  // zero gap with no root to catch it going through, since a root at its start is no root.
  net_force(t, y_.head(n));
  if (!problem_->is_linear()) problem_->tangent_stiffness(y_.head(n), K_);
  for (std::size_t i = 0; i < p; ++i) {
    if (!closed_[i]) continue;
    const Contact& c = contacts_[i];
    const double reaction = -f_[c.dof] / c.a;
    // Zero up to the round-off of F_int (a rigidly moving body: K u = 0 only to eps |K| |u|).
    const double roundoff = 1e-12 * (std::abs(fext_[c.dof]) + K_.col(c.dof).cwiseAbs().sum() * y_.head(n).cwiseAbs().maxCoeff());
    const bool zero = std::abs(f_[c.dof]) <= roundoff;
    if (reaction > 0.0 && !zero) {
      close(c);
    } else if (zero && K_.col(c.dof).dot(y_.segment(n, n)) / c.a >= 0.0) {  // K symmetric: row = column
      close(c);
    } else {
      closed_[i] = 0;
      dof_closed_[c.dof] = 0;
      y_[n + c.dof] = 0.0;  // a plastic impact left it at rest on the obstacle
      ++releases_;
      event_log_.push_back({t, static_cast<Index>(i), ContactEventKind::Release});
    }
  }
  cvode_->restart(t, y_);
}

StepInfo EventDriven::advance(double dt) {
  StepInfo info;
  impulses_.setZero();
  const double target = state_.t + dt;
  double t = state_.t;
  const Index n = problem_->ndof();
  const Vec reaction_start = y_.tail(impulses_.size());
  long events = 0;
  // Stop once within round-off of the target: CVODE refuses a tout that close to t.
  while (target - t > 1e-14 * std::max(1.0, std::abs(target))) {
    if (!cvode_->advance(target, t, y_)) break;
    handle_events(t, cvode_->root_info());
    ++events_;
    if (++events > kMaxEventsPerStep)
      throw std::runtime_error(fmt::format("event-driven: more than {} events in one step at t = {}", kMaxEventsPerStep, t));
  }
  impulses_ += y_.tail(impulses_.size()) - reaction_start;  // closed contacts' reactions
  check_no_penetration(target);
  state_.u = y_.head(n);
  state_.v = y_.segment(n, n);
  info.dt = dt;
  info.iterations = events;
  publish_work();
  return info;
}

void EventDriven::check_no_penetration(double t) const {
  for (std::size_t i = 0; i < contacts_.size(); ++i) {
    const Contact& c = contacts_[i];
    const double gap = c.a * (y_[c.dof] - c.position);
    const double tolerance = kPenetrationTolerance * (settings_.atol + settings_.rtol * std::abs(y_[c.dof]));
    if (!closed_[i] && gap < -tolerance)
      throw std::runtime_error(fmt::format("event-driven: contact {} was passed through unseen (gap {:.3g} at t = {:g}, "
                                           "beyond {:.3g}): an impact the root finder missed; the run is not a solution",
                                           i, gap, t, -tolerance));
  }
}

void EventDriven::publish_work() {
  cvode_->add_work(work_);
  work_.extra["events"] = static_cast<double>(events_);
  work_.extra["impacts"] = static_cast<double>(std::count_if(
      event_log_.begin(), event_log_.end(), [](const ContactEvent& e) { return e.kind != ContactEventKind::Release; }));
  work_.extra["releases"] = static_cast<double>(releases_);
  work_.extra["zeno_stops"] = static_cast<double>(zeno_stops_);
}

NSBENCH_INTEGRATOR({"event-driven", "reference: CVODE with root finding, Newton impacts, closed-contact mode (node-to-rigid contacts)", &EventDriven::parameters_spec, &make_from_params<Integrator, EventDriven>, true, false,
                    {.mass = MassNeed::DiagonalPositive, .node_to_rigid_only = true}});

}  // namespace nsb
