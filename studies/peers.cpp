// Study "peers": our schemes against a peer's implementation of the same scheme (docs/method.md
// section 2, "Peers run side by side"), e.g. moreau-jean against siconos-moreau-jean.
//
// Pairs (kPairs, data; a pair whose integrator is not registered is skipped, e.g. without the
// Siconos peers) x problems (kProblems): the bouncing mass (e = 0.9, dt = 1e-3, to t = 3: four
// impacts), the Signorini bar (N = 100, lumped, g0 = 0.4937, dt = 2e-3 = 0.2 h/c, to t = 3.5:
// one contact phase), a 10-mass spring chain hitting a wall (e = 1, dt = 1e-3, to t = 1:
// six impacts), and with Coulomb friction the sliding mass (30 degrees, mu = 0.8, v0 = 2,
// dt = 1e-3, to t = 2: slides, stops at t = 1.06, sticks) and the rolling disk dropped
// spinning (h0 = 0.05, omega0 = 20, e = 0.5, mu = 0.3, dt = 1e-3, to t = 1: slipping impacts,
// then at rest). Same theta, e and dt on both sides (each pair states its parameters).
// The 3D problems, run by the FrictionContact(3) pair only (named_only): the sphere on the
// incline (the defaults, mu = 0.3: the slip turns, then it rolls; dt = 1e-3, to t = 0.5) and
// bar-3d (N = 10, lumped, sides held, dt = 1e-2, to t = 2.5: one contact phase, 4 contacts).
// The rows at a given gamma run on the problems with impacts only (kImpacts), to keep the
// study short (11 s CPU in all, 7 s without them).
// Both integrators step in lockstep in one run; per step: largest difference of the
// displacements and of the velocities (max norm over the dofs, over the largest |u| and |v|
// of ours along the run), of the energies (over |E_0|) and of the contact impulses, normal
// and tangential (over the largest impulse of ours). Cost per step: CPU of each integrator alone, median of 3
// unobserved runs after a warm-up, over its steps; same process, same machine (BLAS serial:
// scripts/run.sh sets OPENBLAS_NUM_THREADS=1; Debian's libopenblas0-serial).
//
// What it shows (Siconos kernel 4.4.0, Debian):
//   - moreau-jean and MoreauJeanOSI, theta = 1/2: the same numbers to round-off (<= 1e-12):
//     same W = M + h^2 theta^2 K, same free velocity, same Newton law on the LCP.
//   - theta = 1 (second row set): they differ at impacts, by the active-set forecast alone.
//     Both activate a contact when g_k + gamma h g'_k <= 0, but with gamma unset ours takes
//     1 - theta (the known part of the theta-method's own position update) and
//     MoreauJeanOSI::addInteractionInIndexSet 1/2 whatever theta. At theta = 1 ours is
//     g_k <= 0: a contact acts only once penetrated (bouncing mass, dt = 1e-3: max
//     penetration 4.3e-3 against Siconos' 1.0e-3, impacts one step later).
//   - The same gamma on both sides (rows "gamma = 0", "gamma = 1/2", on the problems with
//     impacts): the same numbers to round-off at theta = 1/2 and 1 alike (<= 4.4e-13; the
//     bar's contact activates at the same step whatever gamma here, so its rows repeat the
//     unset ones). The unset rows are the bits of the scheme before gamma was a parameter.
//   - With friction (siconos-moreau-jean: FrictionContact(2), 2D NSGS to 1e-12): the same
//     numbers to round-off at theta = 1/2, normal and tangential impulses included (<= 5e-13);
//     at theta = 1 on the sliding mass too (the contact never opens, both forecasts keep it
//     active), on the dropped disk only at the same gamma (its impacts, as above). The Schatzman-Paoli and
//     D1MinusLinear pairs are n/a there: our schatzman-paoli and Siconos' D1MinusLinearOSI
//     decline friction.
//   - FrictionContact(3) with Siconos' 3D NSGS (one_step_problem = fc3d, to 1e-12), theta = 1/2:
//     the same numbers to round-off on the sphere's cone (du, dv <= 6e-16, dLambda <= 6e-14;
//     our cone solve is exact, coulomb_cone.hpp) and on bar-3d, where each wall contact is a
//     3D contact with mu = 0 and zero tangent rows (dLambda <= 1e-12).
//   - Siconos' cost per step is 15-80x ours: it hands the problem to dense uBLAS matrices
//     (perf: ~65% of its time in uBLAS' generic dense matrix-vector product, K q and M v,
//     not BLAS), O(n^2) per step where ours is sparse O(n).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "integrators/registry.hpp"
#include "run/run.hpp"
#include "problems/registry.hpp"
#include "studies/study.hpp"

namespace nsb {

namespace {

using Strings = std::map<std::string, std::string>;

struct PeerPair {
  std::string ours, peer;
  Strings ours_params, peer_params;
  std::string note;  // what is compared
  std::vector<std::string> only = {};  // the problems (registered names) it runs on; empty: all
};

const std::vector<std::string> kPeerImpactProblems = {"bouncing-mass", "signorini-bar", "spring-chain", "rolling-disk"};

// moreau-jean: gamma unset is 1 - theta in ours, 1/2 in Siconos' (the "theta = 1" rows).
// Schatzman-Paoli: theta = 0 on both sides (the explicit central difference: Siconos' theta
// is not ours, schatzman_paoli.hpp's; they coincide at 0 only).
const std::vector<PeerPair> kPairs = {
    {"moreau-jean", "siconos-moreau-jean", {{"theta", "0.5"}}, {{"theta", "0.5"}}, "theta = 1/2"},
    {"moreau-jean", "siconos-moreau-jean", {{"theta", "1"}}, {{"theta", "1"}}, "theta = 1"},
    // The same gamma on both sides: on the problems with impacts, where the forecast matters
    // (the sliding mass' contact never opens).
    {"moreau-jean", "siconos-moreau-jean", {{"theta", "0.5"}, {"gamma", "0"}}, {{"theta", "0.5"}, {"gamma", "0"}},
     "theta = 1/2, gamma = 0", kPeerImpactProblems},
    {"moreau-jean", "siconos-moreau-jean", {{"theta", "1"}, {"gamma", "0"}}, {{"theta", "1"}, {"gamma", "0"}},
     "theta = 1, gamma = 0", kPeerImpactProblems},
    {"moreau-jean", "siconos-moreau-jean", {{"theta", "1"}, {"gamma", "0.5"}}, {{"theta", "1"}, {"gamma", "0.5"}},
     "theta = 1, gamma = 1/2", kPeerImpactProblems},
    {"schatzman-paoli", "siconos-schatzman-paoli", {{"theta", "0"}}, {{"theta", "0"}}, "theta = 0"},
    {"d1-minus-linear", "siconos-d1-minus-linear", {}, {}, "defaults"},
    // FrictionContact(3) on every contact: on the 3D problems (the sphere's cone takes it anyway).
    {"moreau-jean", "siconos-moreau-jean", {{"theta", "0.5"}}, {{"theta", "0.5"}, {"one_step_problem", "fc3d"}},
     "theta = 1/2, FrictionContact(3) on every contact", {"sphere", "bar-3d"}},
};

struct PeerProblem {
  std::string label, problem;
  Strings params;
  double dt, t_end;
  bool named_only = false;  // run only by the pairs whose `only` names it
};

const std::vector<PeerProblem> kProblems = {
    {"bouncing mass, e = 0.9", "bouncing-mass", {{"e", "0.9"}}, 1e-3, 3.0},
    {"Signorini bar, N = 100, lumped", "signorini-bar", {{"N", "100"}, {"mass", "lumped"}, {"g0", "0.4937"}}, 2e-3, 3.5},
    {"spring chain, 10 masses, wall", "spring-chain", {{"n", "10"}, {"wall", "left"}}, 1e-3, 1.0},
    {"sliding mass, 30 deg, mu = 0.8, v0 = 2", "sliding-mass", {{"alpha", "30"}, {"mu", "0.8"}, {"v0", "2"}}, 1e-3, 2.0},
    {"rolling disk dropped, h0 = 0.05, omega0 = 20, e = 0.5, mu = 0.3", "rolling-disk",
     {{"h0", "0.05"}, {"omega0", "20"}, {"e", "0.5"}, {"mu", "0.3"}}, 1e-3, 1.0},
    {"sphere on the 20 deg incline, mu = 0.3: slips, turning, then rolls", "sphere", {}, 1e-3, 0.5, true},
    {"bar-3d, N = 10, lumped, sides held", "bar-3d", {{"N", "10"}}, 1e-2, 2.5, true},
};

bool registered(const std::string& name) {
  const auto& r = integrator_registry();
  return std::any_of(r.begin(), r.end(), [&](const IntegratorEntry& e) { return e.name == name; });
}

std::vector<Json> peers_cases(const StudyOptions&) {
  std::vector<Json> cases;
  for (std::size_t k = 0; k < kPairs.size(); ++k)
    if (registered(kPairs[k].ours) && registered(kPairs[k].peer))
      for (std::size_t p = 0; p < kProblems.size(); ++p) {
        const auto& only = kPairs[k].only;
        if (only.empty() ? !kProblems[p].named_only : std::find(only.begin(), only.end(), kProblems[p].problem) != only.end())
          cases.push_back({{"pair", k}, {"problem", p}});
      }
  return cases;
}

std::vector<std::string> peers_case_integrators(const Json& c) {
  const PeerPair& pair = kPairs[c["pair"].get<std::size_t>()];
  return {pair.ours, pair.peer};
}

Json peers_case(const Json& c) {
  const PeerPair& pair = kPairs[c["pair"].get<std::size_t>()];
  const PeerProblem& pp = kProblems[c["problem"].get<std::size_t>()];
  auto problem = make_problem(pp.problem, pp.params);
  std::unique_ptr<Integrator> ours, peer;
  try {  // a pair's parameters not taken, or a problem declined: n/a, with the reason
    ours = make_integrator(pair.ours, pair.ours_params);
    peer = make_integrator(pair.peer, pair.peer_params);
    ours->init(*problem, problem->initial_state());
    peer->init(*problem, problem->initial_state());
  } catch (const InputError& e) {
    return {{"status", kDeclinedStatus}, {"message", e.what()}};
  }
  RunOptions options;
  options.dt = pp.dt;
  options.t_end = pp.t_end;
  options.record_series = false;

  double du = 0.0, dv = 0.0, dE = 0.0, dE_end = 0.0, dimp = 0.0, u_scale = 0.0, v_scale = 0.0, imp_scale = 0.0;
  const double E0 = std::abs(ours->energy().total());
  long steps = 0;
  std::string status = status_name(RunStatus::Ok);
  try {
    while (ours->state().t < pp.t_end * (1.0 - 1e-12)) {
      ours->step(pp.dt);
      peer->step(pp.dt);
      ++steps;
      const State &a = ours->state(), &b = peer->state();
      if (!a.u.allFinite() || !b.u.allFinite()) {
        status = status_name(RunStatus::Diverged);
        break;
      }
      du = std::max(du, (a.u - b.u).lpNorm<Eigen::Infinity>());
      dv = std::max(dv, (a.v - b.v).lpNorm<Eigen::Infinity>());
      u_scale = std::max(u_scale, a.u.lpNorm<Eigen::Infinity>());
      v_scale = std::max(v_scale, a.v.lpNorm<Eigen::Infinity>());
      // Normal and tangential impulses alike (the tangential ones are 0 on both sides without friction).
      dimp = std::max({dimp, (ours->impulses() - peer->impulses()).lpNorm<Eigen::Infinity>(),
                       (ours->tangential_impulses() - peer->tangential_impulses()).lpNorm<Eigen::Infinity>()});
      imp_scale = std::max({imp_scale, ours->impulses().lpNorm<Eigen::Infinity>(), ours->tangential_impulses().lpNorm<Eigen::Infinity>()});
      dE_end = std::abs(ours->energy().total() - peer->energy().total()) / E0;
      dE = std::max(dE, dE_end);
    }
  } catch (const std::exception& e) {
    return {{"status", status_name(RunStatus::Diverged)}, {"message", e.what()}};
  }
  const double ours_cpu = median_cpu_seconds(*problem, pair.ours, pair.ours_params, options);
  const double peer_cpu = median_cpu_seconds(*problem, pair.peer, pair.peer_params, options);
  return {{"status", status}, {"steps", steps}, {"du", real(du / u_scale)}, {"dv", real(dv / v_scale)},
          {"dE", real(dE)}, {"dE_end", real(dE_end)}, {"dimp", real(imp_scale > 0.0 ? dimp / imp_scale : dimp)},
          {"ours_step", ours_cpu / steps}, {"peer_step", peer_cpu / steps}};
}

std::vector<Table> peers_tables(const std::vector<Json>& cases, const std::vector<Json>& results, const StudyOptions&) {
  Table t;
  t.id = "peers";
  t.title = "Peers: our schemes against another code's implementation of the same scheme";
  t.caption =
      "Both integrators step in lockstep, same problem, theta, e and dt. du, dv: max over steps of the max-norm "
      "difference of displacements and velocities, over the largest |u|, |v| of ours; dE: max |E_ours - E_peer| / |E0|; "
      "dLambda: max difference of the step impulses (normal and tangential) over our largest impulse. Cost: CPU per step of each alone ("
      + median_cpu_text() + "), BLAS single-threaded. A pair runs when both integrators are registered (peers: see the metadata).";
  t.columns = {{"ours", "", "", ""}, {"peer", "", "", ""}, {"parameters", "", "", ""}, {"problem", "", "", ""},
               {"dt", "", "{:.1e}", "step"}, {"steps", "", "", ""}, {"status", "", "", ""},
               {"du", "", "{:.2e}", "max |u_ours - u_peer| / max |u_ours|"},
               {"dv", "", "{:.2e}", "max |v_ours - v_peer| / max |v_ours|"},
               {"dE", "", "{:.2e}", "max |E_ours - E_peer| / |E0|"},
               {"dE end", "", "{:.2e}", "|E_ours - E_peer| / |E0| at t_end"},
               {"dLambda", "", "{:.2e}", "max |Lambda_ours - Lambda_peer| / max |Lambda_ours|, normal and tangential"},
               {"ours/step", "us", "{:.3g}", "CPU per step of ours", true},
               {"peer/step", "us", "{:.3g}", "CPU per step of the peer", true},
               {"peer/ours", "", "{:.3g}", "cost ratio", true}};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const PeerPair& pair = kPairs[cases[i]["pair"].get<std::size_t>()];
    const PeerProblem& pp = kProblems[cases[i]["problem"].get<std::size_t>()];
    const Json& r = results[i];
    std::vector<Cell> row = {pair.ours, pair.peer, pair.note, pp.label, pp.dt};
    if (r["status"] != status_name(RunStatus::Ok)) {
      row.push_back(Cell{});
      row.push_back(fmt::format("{}: {}", r["status"].get<std::string>(), r.value("message", "")));
      row.resize(t.columns.size());
    } else {
      const double ours = r["ours_step"].get<double>() * 1e6, peer = r["peer_step"].get<double>() * 1e6;
      row.insert(row.end(), {r["steps"].get<long>(), status_name(RunStatus::Ok), number_cell(r["du"]), number_cell(r["dv"]), number_cell(r["dE"]),
                             number_cell(r["dE_end"]), number_cell(r["dimp"]), ours, peer, peer / ours});
    }
    t.add_row(std::move(row));
  }
  const char* blas = std::getenv("OPENBLAS_NUM_THREADS");
  t.metadata = {{"study", "peers"}, {"OPENBLAS_NUM_THREADS", blas ? blas : "unset"}};
  return {t};
}

}  // namespace

extern const StudyEntry peers_study;
const StudyEntry peers_study{
    "peers", "our schemes against a peer code's (Siconos) on the bouncing mass, the lumped bar, the spring chain, the sliding mass, the rolling disk, the sphere and bar-3d",
    nullptr, &peers_cases, &peers_case, &peers_tables, &peers_case_integrators};

}  // namespace nsb
