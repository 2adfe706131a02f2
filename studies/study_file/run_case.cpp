// The run of one case of a study file: its measures and its outcome.
//
//
// Measures (each a column; a run's error against the reference, sampled every sample_every
// steps and at the last step):
//   error        u: ||u - u_ref||_inf (v: ||v - v_ref||_inf, the velocities), an observable:
//                |o - o_ref|, divided by the largest |u_ref| (|v_ref|, |o_ref|) over the run
//                (absolute when that is 0); with `against` = o_exact, o_ref is the problem's
//                own observable o_exact at the run's state instead of the reference's; norm final (last
//                step), max (over the samples) or l2 (sqrt of the time-weighted mean square);
//                over every step (at its own dt): rms (sqrt(sum_k dt_k e_k^2 / (t_last - t0)), in
//                time up to the last step measured) or step rms (sqrt of the mean of e_k^2 over the
//                steps). With `scale`: each step's error divided by that value instead; with
//                `inside` = o: only the steps whose t - dt, t and t + dt lie where the problem's
//                exact observable o is > 0 (the exact contact phases: contact_force_exact).
//                A reference integrator's samples are interpolated linearly in time.
//   impact-time  max over the first `count` impacts of |t_i (scheme) - t_i (exact)|, t_i the
//                end of the first step with an impulse after a step without one [s]; with
//                min_flight_steps n: those up to the first whose exact flight is shorter than n
//                steps (compared_impacts, studies/measures.hpp); norm = "count": how many.
//   flight-energy  max over the first `count` flights of |E / E_i - 1| (FlightEnergies,
//                studies/measures.hpp), E at the exact mid-flight time or at the mid-flight
//                step between the run's own impacts (at = "mid-flight step"); an error that
//                converges with dt (fitted and pairwise orders); norm = "count": how many.
//   rest-start   the start of the run's final rest (FinalRest, studies/measures.hpp): the end of
//                the first step after which every step to the end has each `rest` bound's
//                observable at most at_most dt^dt_power, if that lasts longer than min_rest;
//                with exact = true its distance to the problem's summary value `summary` [s].
//   energy       (E - E0)/|E0| (E0 = 0: the problem's energy_scale(), run/run.hpp), E the scheme's own energy: max |.|, final, or drift (its
//                least-squares slope in time, 1/s); with `every` T, at the first step past each
//                from + k T (k = 1, 2, ... up to t_end, to half a step): count, first, final, or
//                drift (the slope against k, per T).
//   momentum     max over the samples of |P - P0 - sum_k (1^T F_ext(t_k) dt_k + 1^T L^T Lambda_k)|
//                / max |P| (P = 1^T M v, the momentum of a 1D problem): 0 for a scheme that
//                balances momentum exactly when the internal forces sum to zero.
//                With `component` (px, py, pz, jx, jy, jz) the identity of a 3D mesh problem
//                instead (MeshMomentum, studies/measures.hpp: every impulse counted, angular
//                per step), max over the steps, relative to its scale there.
//   penetration  max over the steps of max(0, -g).
//   chatter      RMS of the period-2 component (o_{k+1} - 2 o_k + o_{k-1}) / (4 scale) of an
//                observable over consecutive steps (those `inside` a phase, or every step);
//   zero-steps   how many of those steps have o = 0 (studies/measures.hpp, Chatter): the contact
//                force inside the exact contact, its chatter and the steps it was lost.
//   contact-duration  t_last - t_first + dt over the steps with a contact impulse (dt the nominal
//                step; ContactPhases::span), with exact = true its difference from the problem's
//                exact contact duration (ExactValue::contact_duration, the Signorini bar's 2L/c).
// An error with semi_discrete = true: |u_dof - u_dof,semi| against the same semi-discrete problem
// solved exactly (modal-exact, advanced to each sample), the time error alone; an error with
// per_nominal_step = true is sampled at most once per nominal step dt.
// An error, energy or momentum measure with a `window` [t0, t1] is sampled there only (its l2
// norm the mean over t1 - t0), e.g. a smooth window before the first impact.
//   hausdorff    H(run, ref) between the graphs {(t, o)} of an observable (the run's samples;
//                the exact solution with its jumps as vertical segments, or the reference run's
//                samples), in scaled coordinates (t / time_scale, o / value_scale), by default
//                time_scale = t_end and value_scale = the reference's largest |o|
//                (studies/hausdorff.hpp); norm "to reference" / "from reference": one directed
//                distance, "max error": max over the run's samples of |o - o_ref(t)| / value_scale,
//                "value scale": that scale (GraphErrors).
//   stop-time    |t_stop - t_stop exact| of a sliding mass, onset-time the same for a rolling
//   onset-time   disk's rolling onset: the slip's stop as the friction study measures it
//                (studies/slip_stop.hpp, one code for both) [s].
// A measure naming `problems` is measured on those only (n/a on the others). The ranking and
// the work-precision figures use the measure study.rank_by names (default: the first error).
// Status: ok, diverged, over budget, n/a (declined), or energy blow-up: at some step the
// scheme's energy rose above E0 by more than study.energy_blow_up (default 2) E scale (|E0|, or the problem's
// energy_scale() when E0 = 0) plus the work W the surroundings can have done on the system by
// then:
//     max_k (E_k - E0 - W_k) / E scale > energy_blow_up,
//     W_k = sum_{j<=k} ( sum_i |w_i| |Lambda_T,i,j|  +  max(0, F_ext(t_j) . (U_{j+1} - U_j)) ),
// the first term the work a moving obstacle (tangential velocity w, a belt) can do through
// friction, the second that of a time-dependent load (only then: a constant load's work is in
// the potential, part of E). Energy lost is never a blow-up: friction, inelastic impacts and
// numerical damping only lower E (a mass sliding down a slope against friction goes from
// E0 = 2 J to -5 J). The row keeps its values; the ranking leaves it out and says so. Status
// penetration: max(0, -g) over the steps above study.max_penetration (the same). A per-problem override of an integrator's parameters shows in its rows' integrator cell,
// "label [key=value]".
#include "studies/study_file/run_recorders.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "core/output.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "reference/cache.hpp"
#include "reference/modal_exact.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"
#include "studies/parallel.hpp"
#include "studies/ranking.hpp"
#include "studies/report_index.hpp"
#include "studies/slip_stop.hpp"

namespace nsb::study_files {

Json run_file_case(const StudySpec& spec, const Json& c) {
  const FileProblem& fp = spec.problems[c["problem"].get<std::size_t>()];
  const FileIntegrator& fi = spec.integrators[c["integrator"].get<std::size_t>()];
  auto problem = make_problem(fp.name, fp.parameters);
  const Overrides params = file_case_parameters(spec, c);
  RunOptions options;
  options.dt = c["dt"];
  const double t_end = case_t_end(spec, fp, c);
  options.t_end = t_end;
  options.record_series = false;
  options.max_force_evaluations = spec.budget_of(fp, options.dt, t_end);
  options.sample_every = spec.check_every;  // the driver checks the state for NaN at its samples
  if (const FileReference* ref = spec.reference_of(fp); ref && ref->lockstep && fi.name == ref->integrator)  // its error is 0 by construction
    return not_run("the reference of this problem");
  auto integrator = make_integrator(fi.name, params);
  if (const auto declined = init_or_decline(*integrator, *problem)) return not_run(*declined);
  const SpMat M = problem->mass_matrix();
  Reference reference(spec, *problem, M, fp);
  std::string semi_note;
  const std::unique_ptr<ModalExact> semi = semi_discrete_reference(spec, fp, fi.name, *problem, semi_note);
  const std::size_t nobs = problem->observable_names().size();
  std::vector<double> obs(nobs), obs_ref(nobs);
  std::vector<Accumulator> acc(spec.measures.size());
  std::vector<std::pair<double, double>> windows;  // each measure's window on this problem
  for (std::size_t m = 0; m < acc.size(); ++m) {
    windows.push_back(spec.measures[m].window_for(fp.label));
    acc[m].t_prev = windows[m].first;
  }
  std::vector<bool> on(spec.measures.size());  // measured on this problem
  bool stops = false;                          // a stop-time or onset-time measure is
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    const FileMeasure& fm = spec.measures[m];
    on[m] = fm.applies_to(fp.label);
    stops = stops || (on[m] && (fm.kind == MeasureKind::StopTime || fm.kind == MeasureKind::OnsetTime));
  }
  // P0 and the speed scale from the problem's initial velocity, not the scheme's state after init
  // (modal-exact's passes through its modal basis: round-off in P0).
  MomentumBalance momentum(*problem, problem->initial_state().v);
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && !spec.measures[m].component.empty()) acc[m].mesh_momentum.emplace(*problem, problem->initial_state(), spec.measures[m].component);
  const Energy energy0 = integrator->energy();
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind == MeasureKind::Hausdorff) {
      const State& s = integrator->state();
      acc[m].graph.add(s.t, state_observable(*problem, M, s, Vec::Zero(problem->ncontacts()), 0.0,
                                             spec.measures[m].observable_for(fp.label), obs, &energy0));
    }
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind >= MeasureKind::ImpactRatio)
      acc[m].events.emplace(spec.measures[m], *problem,
                            event_observable(*problem, M, *integrator, 0.0, spec.measures[m], obs, energy0));
  const double e0 = energy0.total();
  const double e_scale = fp.energy_scale > 0.0 ? fp.energy_scale : energy_error_scale(*problem, e0);
  double t_prev = 0.0;
  EnergyGrowth growth(*problem, integrator->state(), e0);
  std::optional<SlipStop> stop;
  if (stops) stop.emplace(*problem, integrator->state());
  IntervalMax history(t_end, kHistoryIntervals, 1);
  const auto history_measure = std::find_if(spec.measures.begin(), spec.measures.end(), [](const FileMeasure& m) {
    return m.kind == MeasureKind::Energy && m.history;
  });
  RunFigures figures(*problem, spec, fp, t_end, e0, e_scale);
  RunSeries series(spec, fp, t_end, *problem, M, *integrator, obs, energy0);
  RunImpulsesAndFields impulses_and_fields(spec, fp, fi, *problem, *integrator, options.dt);
  double e1 = kNaN;  // the energy after the first step
  // An energy measure's error of E: relative to E_1 (relative_to = "first step") or E0 (its scale).
  const auto energy_error = [&](const FileMeasure& fm, double e) { return fm.from_first_step ? (e - e1) / std::abs(e1) : (e - e0) / e_scale; };
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind == MeasureKind::FlightEnergy) {
      const FileMeasure& fm = spec.measures[m];
      std::vector<double> impacts = problem->exact()->impact_times(t_end);
      const std::size_t flights = compared_impacts(impacts, fm.count, fm.min_flight_steps * options.dt);
      acc[m].flights = FlightEnergies(std::move(impacts), problem->exact()->energies_after_impacts(t_end), flights,
                                      fm.at_mid_flight_step ? FlightEnergies::At::mid_flight_step : FlightEnergies::At::exact_mid_flight);
    }
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (on[m] && spec.measures[m].kind == MeasureKind::RestStart) acc[m].rest = FinalRest(spec.measures[m].min_rest);
  // Whether the state after a step is at rest by the bounds of a rest-start measure (each checked
  // only while the others before it hold).
  const auto at_rest = [&](const FileMeasure& fm, const Integrator& it, double dt, const Energy& energy) {
    return std::all_of(fm.rest.begin(), fm.rest.end(), [&](const FileMeasure::RestBound& b) {
      const double o = state_observable(*problem, M, it.state(), it.impulses(), dt, b.observable, obs, &energy);
      return (b.abs ? std::abs(o) : o) <= rest_bound(b.at_most, b.dt_power, options.dt);
    });
  };

  // An error of "v": the velocities, unless the problem has an observable of that name (its own).
  const auto& names = problem->observable_names();
  const bool own_v = std::find(names.begin(), names.end(), "v") != names.end();
  // Whether the problem's exact observable `name` is > 0 at t - dt, t and t + dt (FileMeasure::inside).
  const auto inside_phase = [&](const std::string& name, double t, double dt) {
    const double times[] = {t - dt, t, t + dt};
    return std::all_of(std::begin(times), std::end(times), [&](double at) {
      const std::optional<State> exact = problem->exact()->state(at);
      return exact && state_observable(*problem, M, *exact, Vec::Zero(problem->ncontacts()), 0.0, name, obs_ref, nullptr) > 0.0;
    });
  };
  // The measures at a step of length dt: every_step() measures at each step (each_step), the
  // others every sample_every steps and at the last step (sampled; `energy`: the state's).
  // (every_step() compares strings: asked once per run, not at every step of every measure.)
  std::vector<bool> every_step(spec.measures.size());
  for (std::size_t m = 0; m < spec.measures.size(); ++m) every_step[m] = spec.measures[m].every_step();
  const auto sample = [&](const Integrator& it, const Energy& energy, double dt, bool sampled, bool each_step) {
    const State& s = it.state();
    for (std::size_t m = 0; m < spec.measures.size(); ++m) {
      const FileMeasure& fm = spec.measures[m];
      if (every_step[m] ? !each_step : !sampled) continue;
      const bool inside = s.t >= windows[m].first && s.t <= windows[m].second;
      if (!on[m] || !(inside || fm.scale_over_run)) continue;  // an error relative to the run: its scale
      if (!fm.inside.empty() && !(inside && inside_phase(fm.inside, s.t, dt))) continue;
      Accumulator& a = acc[m];
      if (fm.per_nominal_step) {
        if (s.t < a.next_sample) continue;
        a.next_sample = s.t + (1.0 - 1e-9) * options.dt;
      }
      const double step_dt = every_step[m] ? dt : s.t - t_prev;  // the impulses' step (impulse / dt observables)
      double e = kNaN;
      if (fm.semi_discrete) {
        if (!semi) continue;  // n/a
        semi->advance_to(s.t);
        e = std::abs(s.u[fm.dof] - semi->displacement(fm.dof));
        if (fm.scale > 0.0) e /= fm.scale;
      } else if (fm.kind == MeasureKind::Error) {
        if (fm.observable == "u" || (fm.observable == "v" && !own_v)) {
          const bool u = fm.observable == "u";
          const Vec ref = u ? reference.u(s.t) : reference.v(s.t);
          e = ((u ? s.u : s.v) - ref).lpNorm<Eigen::Infinity>();
          a.scale = std::max(a.scale, ref.lpNorm<Eigen::Infinity>());
        } else {
          const double value = state_observable(*problem, M, s, it.impulses(), step_dt, fm.observable, obs, &energy);
          const double ref = fm.against.empty() ? reference.observable(s.t, fm.observable, obs_ref)
                                                : state_observable(*problem, M, s, it.impulses(), step_dt, fm.against, obs, &energy);
          e = std::abs(value - ref);
          a.scale = std::max(a.scale, std::abs(ref));
        }
        if (fm.scale > 0.0) e /= fm.scale;
      } else if (fm.kind == MeasureKind::Chatter || fm.kind == MeasureKind::ZeroSteps) {
        const double value = state_observable(*problem, M, s, it.impulses(), step_dt, fm.observable, obs, &energy);
        if (inside) a.chatter.add(fm.scale > 0.0 ? value / fm.scale : value);
        continue;
      } else if (fm.kind == MeasureKind::Estimate) {
        if (inside) a.samples.push_back(state_observable(*problem, M, s, it.impulses(), step_dt, fm.observable, obs, &energy));
        continue;
      } else if (fm.kind == MeasureKind::Hausdorff) {
        a.graph.add(s.t, state_observable(*problem, M, s, it.impulses(), s.t - t_prev, fm.observable_for(fp.label), obs, &energy));
      } else if (fm.kind == MeasureKind::Energy) {
        e = energy_error(fm, energy.total());
        a.drift.add(s.t, e);
        e = fm.norm == "final" ? e : std::abs(e);
      } else if (fm.kind == MeasureKind::Momentum && fm.component.empty()) {
        e = momentum.residual(s.v);
        a.scale = fm.initial_speeds_scale ? momentum.speed_scale()
                                          : std::max({a.scale, std::abs(momentum.momentum(s.v)), std::abs(momentum.initial())});
      }
      if (!inside) continue;
      a.largest = std::max(a.largest, std::abs(e));
      a.square += e * e * (s.t - a.t_prev);
      a.t_prev = s.t;
      a.last = e;
      a.timed_square += dt * e * e;
      a.step_square += e * e;
      ++a.steps;
    }
  };
  long step = 0;
  const RunResult r = run(*problem, *integrator, options, [&](const Integrator& it, const StepInfo& info) {
    const State& s = it.state();
    const Energy energy = it.energy();  // once per step: every figure below reads it
    reference.advance(info.dt);
    momentum.add(it, info.dt);
    if (step == 0) e1 = energy.total();
    const bool contact = it.impulses().sum() > 0.0;
    for (std::size_t m = 0; m < spec.measures.size(); ++m) {
      if (on[m] && (spec.measures[m].kind == MeasureKind::ImpactTime || spec.measures[m].kind == MeasureKind::ContactDuration))
        acc[m].impacts.add(s.t, contact);
      else if (acc[m].events) acc[m].events->add(s.t, it.impulses(), s.u, event_observable(*problem, M, it, info.dt, spec.measures[m], obs, energy));
      if (on[m] && spec.measures[m].kind == MeasureKind::FlightEnergy) acc[m].flights.add(s.t, contact, energy.total());
      if (on[m] && spec.measures[m].kind == MeasureKind::RestStart) acc[m].rest.add(s.t, at_rest(spec.measures[m], it, info.dt, energy));
      if (acc[m].mesh_momentum) acc[m].mesh_momentum->add(it, info.dt);
      if (on[m] && spec.measures[m].kind == MeasureKind::Energy && spec.measures[m].every > 0.0)
        sample_periodic(spec.measures[m], acc[m], s.t, options.dt, t_end, energy_error(spec.measures[m], energy.total()));
    }
    growth.add(it, info.dt, energy.total());
    if (stop) stop->add(s);
    if (history_measure != spec.measures.end()) history.add(s.t, {std::abs(energy.total() - e0) / e_scale});
    figures.add(it, info.dt, momentum, energy.total());
    series.add(*problem, M, it, info.dt, obs, energy);
    impulses_and_fields.add(*problem, it);
    sample(it, energy, info.dt, ++step % spec.sample_every == 0, true);
    t_prev = s.t;
  });
  Json out = {{"status", status_name(r.status)}, {"message", r.message}, {"steps", r.steps},
              {"force_evaluations", r.work.force_evaluations}, {"factorizations", r.work.factorizations},
              {"lcp_iterations", r.work.lcp_iterations}, {"solver_steps", r.work.steps},
              {"tangent_evaluations", r.work.tangent_evaluations}};
  out.update(figures.result(r, growth.largest() / e_scale));
  if (r.message.empty() && !semi_note.empty()) out["run"]["note"] = semi_note;  // why its semi-discrete errors are n/a
  std::vector<const std::vector<double>*> periodic;
  for (std::size_t m = 0; m < acc.size(); ++m) periodic.push_back(on[m] && spec.measures[m].every > 0.0 ? &acc[m].periodic : nullptr);
  series.write(periodic, out["run"]);
  impulses_and_fields.write(out["run"]);
  if (spec.cpu_repeats == 0) out["cpu"] = r.step_cpu_seconds;  // the observed run's, whatever its end
  // A blow-up or penetration seen before the budget ran out is reported as such.
  if (r.status != RunStatus::Ok && r.status != RunStatus::OverBudget) return out;
  if (const double g = growth.largest() / e_scale; g > spec.energy_blow_up_of(fp)) {
    out["status"] = "energy blow-up";
    out["message"] = fmt::format("max (E - E0 - W) / E scale = {:.3g} > {}", g, spec.energy_blow_up_of(fp));
  } else if (r.max_penetration > spec.max_penetration_of(fp)) {
    out["status"] = "penetration";
    out["message"] = fmt::format("max penetration {:.3g} > {}", r.max_penetration, spec.max_penetration_of(fp));
  }
  if (r.status != RunStatus::Ok && !(r.status == RunStatus::OverBudget && spec.measure_over_budget)) return out;
  if (step % spec.sample_every != 0) sample(*integrator, integrator->energy(), 0.0, true, false);
  history.finish();
  Json values = Json::array();
  for (std::size_t m = 0; m < spec.measures.size(); ++m) {
    const FileMeasure& fm = spec.measures[m];
    const Accumulator& a = acc[m];
    const double scale = fm.scale > 0.0 || !(a.scale > 0.0) ? 1.0 : a.scale;  // a fixed scale: divided at each step
    double v = kNaN;
    if (!on[m] || (fm.semi_discrete && !semi)) {
      values.push_back(real(v));
      continue;
    }
    switch (fm.kind) {
      case MeasureKind::Error:
        v = (fm.norm == "final"      ? a.last
             : fm.norm == "max"      ? a.largest
             : fm.norm == "rms"      ? std::sqrt(a.timed_square / (a.t_prev - windows[m].first))
             : fm.norm == "step rms" ? std::sqrt(a.step_square / static_cast<double>(a.steps))
             : fm.norm == "l2 in time" ? std::sqrt(a.timed_square)
                                     : std::sqrt(a.square / (std::min(t_end, windows[m].second) - windows[m].first))) / scale;
        break;
      case MeasureKind::ImpactTime: {
        if (fm.located) {
          v = located_impact_error(*integrator, *problem, t_end, fm.count);
          break;
        }
        const auto exact = problem->exact() ? problem->exact()->impact_times(t_end) : std::vector<double>{};
        const std::size_t n = compared_impacts(exact, fm.count, fm.min_flight_steps * options.dt);
        const std::vector<double>& impacts = a.impacts.starts();
        if (fm.norm == "count") {
          v = static_cast<double>(std::min(n, impacts.size()));
          break;
        }
        v = impacts.size() < n ? kNaN : 0.0;  // an impact missed: no error to report
        for (std::size_t i = 0; i < n && i < impacts.size(); ++i) v = std::max(v, std::abs(impacts[i] - exact[i]));
        break;
      }
      case MeasureKind::Energy:
        if (fm.every > 0.0) {
          v = periodic_value(fm.norm, a.periodic);
          break;
        }
        v = fm.norm == "max"      ? a.largest
            : fm.norm == "final"  ? a.last
            : fm.norm == "final abs" ? std::abs(a.last)
            : fm.norm == "offset" ? (e1 - e0) / e_scale
                                  : a.drift.slope();
        break;
      case MeasureKind::FlightEnergy:
        v = fm.norm == "count" ? static_cast<double>(a.flights.compared()) : a.flights.largest();
        break;
      case MeasureKind::RestStart:
        v = fm.exact ? std::abs(a.rest.start() - summary_value(*problem, fm.summary)) : a.rest.start();
        break;
      case MeasureKind::Momentum:
        v = a.mesh_momentum ? a.mesh_momentum->largest() / a.mesh_momentum->scale() : a.largest / scale;
        break;
      case MeasureKind::Penetration: v = r.max_penetration; break;
      case MeasureKind::Estimate: break;  // compared with the next run by the tables
      case MeasureKind::Chatter: v = a.chatter.rms(); break;
      case MeasureKind::ZeroSteps: v = static_cast<double>(a.chatter.zeros()); break;
      case MeasureKind::ContactDuration: {
        const double span = a.impacts.span(options.dt);
        v = fm.exact ? std::abs(span - problem->exact()->value(ExactValue::contact_duration).value()) : span;
        break;
      }
      default: v = a.events->result(*problem); break;
      case MeasureKind::StopTime:
      case MeasureKind::OnsetTime: {
        const ExactStop exact = exact_stop(*problem);
        v = std::abs(stop->time(exact.stays) - exact.stop_time);
        break;
      }
      case MeasureKind::Hausdorff: {
        const std::string& observable = fm.observable_for(fp.label);
        const Polyline ref = reference.graph(observable, t_end, obs_ref);
        const GraphErrors e = graph_errors(a.graph, ref, [&](double t) { return reference.observable(t, observable, obs_ref); },
                                           fm.time_scale > 0.0 ? fm.time_scale : t_end, fm.value_scale);
        v = fm.norm == "to reference"     ? e.to_reference
            : fm.norm == "from reference" ? e.from_reference
            : fm.norm == "max error"      ? e.max_error
            : fm.norm == "value scale"    ? e.value_scale
                                          : e.hausdorff;
        break;
      }
    }
    values.push_back(real(v));
  }
  out["values"] = values;  // an estimate's: NaN until the tables compare it with the next run (with_next_run_estimates)
  for (const FileTable& d : spec.tables)  // a flights table's flights: E_i / E0, exact E_i / E0, E_i / E_i exact - 1
    for (std::size_t m = 0; m < spec.measures.size(); ++m)
      if (d.rows == "flights" && on[m] && spec.measures[m].label == d.measure) {
        const FlightEnergies& f = acc[m].flights;
        std::vector<double> ratio, exact;
        for (std::size_t i = 0; i < f.compared(); ++i) {
          ratio.push_back(f.energies()[i] / e0);
          exact.push_back(f.exact()[i] / e0);
        }
        out["run"]["flights"][d.measure] = {{"ratio", reals(ratio)}, {"exact", reals(exact)}, {"error", reals(f.errors())}};
      }
  for (std::size_t m = 0; m < spec.measures.size(); ++m)
    if (spec.measures[m].kind == MeasureKind::Estimate) out["samples"][std::to_string(m)] = reals(acc[m].samples);
  if (spec.cpu_repeats > 0) out["cpu"] = median_cpu_seconds(*problem, fi.name, params, options, spec.cpu_repeats);
  if (history_measure != spec.measures.end())
    out["history"] = {{"t", reals(history.times())}, {"e", reals(history.largest(0))}};
  return out;
}

}  // namespace nsb::study_files

namespace nsb {

std::string file_result_damage(const StudySpec& spec, const Json& r) {
  const auto reals_or_null = [](const Json& a) {
    return a.is_array() && std::all_of(a.begin(), a.end(), [](const Json& x) { return x.is_number() || x.is_null(); });
  };
  for (const char* key : {"status", "message", "steps", "force_evaluations"})
    if (!r.contains(key)) return fmt::format("no key '{}'", key);
  if (r.contains("values") && !(reals_or_null(r["values"]) && r["values"].size() == spec.measures.size()))
    return fmt::format("values is not an array of {} numbers (or null)", spec.measures.size());
  if (r.contains("cpu") && !(r["cpu"].is_number() || r["cpu"].is_null())) return "cpu is not a number";
  for (const char* key : {"factorizations", "lcp_iterations"})
    if (r.contains(key) && !r[key].is_number_integer()) return fmt::format("{} is not an integer", key);
  if (r.contains("samples")) {  // an estimate's samples: an array of numbers per estimate measure, by its index
    const Json& samples = r["samples"];
    if (!samples.is_object()) return "samples is not a table";
    for (std::size_t m = 0; m < spec.measures.size(); ++m)
      if (spec.measures[m].kind == MeasureKind::Estimate &&
          !(samples.contains(std::to_string(m)) && samples[std::to_string(m)].is_array() &&
            std::all_of(samples[std::to_string(m)].begin(), samples[std::to_string(m)].end(), [](const Json& x) { return x.is_number(); })))
        return fmt::format("samples has no array of numbers for measure {}", m);
  }
  if (r.contains("history")) {
    const Json& h = r["history"];
    if (!h.is_object() || !h.contains("t") || !h.contains("e") || !reals_or_null(h["t"]) || !reals_or_null(h["e"]) ||
        h["t"].size() != h["e"].size())
      return "history is not two arrays t and e of numbers of the same length";
  }
  return {};
}

}  // namespace nsb
