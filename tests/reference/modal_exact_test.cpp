// modal-exact (reference/modal_exact.hpp) against the bouncing mass's exact solution, the
// CVODE event-driven reference on the lumped bar, the continuum contact duration 2L/c, and
// the identities it must keep exactly: energy (but for impact losses), momentum with the
// impulses, no penetration.
#include "reference/modal_exact.hpp"

#include <Eigen/LU>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "integrators/registry.hpp"
#include "problems/block_2d.hpp"
#include "problems/bouncing_mass.hpp"
#include "problems/registry.hpp"
#include "problems/signorini_bar.hpp"
#include "problems/spring_chain.hpp"
#include "reference/event_driven.hpp"
#include "studies/study.hpp"

using nsb::ModalExact;
using nsb::Params;

namespace {

constexpr double kEpsilon = std::numeric_limits<double>::epsilon();

ModalExact make_me() { return ModalExact(Params(ModalExact::parameters_spec())); }

void advance_to(nsb::Integrator& integ, double t_end, double dt) {
  while (integ.state().t < t_end - 1e-12) integ.step(std::min(dt, t_end - integ.state().t));
}

nsb::SignoriniBar modal_bar(const std::string& mass, int N, const std::map<std::string, std::string>& more = {}) {
  std::map<std::string, std::string> p = {{"mass", mass}, {"N", std::to_string(N)}};
  p.insert(more.begin(), more.end());
  return nsb::SignoriniBar(Params(nsb::SignoriniBar::parameters_spec(), p));
}

// The first contact of modal-exact: its first impact or arrival to the next release.
double contact_duration(const ModalExact& me) {
  double start = NAN;
  for (const auto& e : me.events()) {
    if (e.kind != ModalExact::EventKind::Release && std::isnan(start)) start = e.t;
    if (e.kind == ModalExact::EventKind::Release && !std::isnan(start)) return e.t - start;
  }
  return NAN;
}

// The same for event-driven.
double contact_duration(const nsb::EventDriven& ed) {
  const auto impacts = nsb::events_of_kind(ed.events(), {nsb::ContactEventKind::Impact});
  if (impacts.empty()) return NAN;
  const double start = impacts.front().t;
  for (const auto& r : nsb::events_of_kind(ed.events(), {nsb::ContactEventKind::Release}))
    if (r.t > start) return r.t - start;
  return NAN;
}

// Lumped bar, defaults (L = c = v0 = 1, g0 = 0): T_N from modal-exact, stepping to just past
// the continuum release 2L/c with steps that are no divisor of it.
double modal_contact_duration(int N) {
  const auto p = modal_bar("lumped", N);
  auto me = make_me();
  me.init(p, p.initial_state());
  advance_to(me, 1.2 * p.contact_duration(), 0.0437);
  return contact_duration(me);
}

// Round-off scale of modal-exact on the bar, relative: the eigendecompositions' backward
// error is eps max w^2 (of M^{-1} K), carried by a state of size v0 L / c over a time L / c,
// so eps (w_max L / c)^2 of the energy and of the momentum M v0. w_max = 2 c / h (lumped,
// singular), 2 sqrt(3) c / h (consistent).
// The stable step is 2 / w_max for each mass model.
double bar_roundoff(const nsb::SignoriniBar& p) {
  const double w_max = 2.0 / p.stable_step(), L_over_c = 0.5 * p.contact_duration();
  return kEpsilon * (w_max * L_over_c) * (w_max * L_over_c);
}

}  // namespace

TEST_CASE("modal-exact: bouncing-mass impact times and rebound speeds within 1e-12 of the exact ones",
          "[reference][modal-exact]") {
  for (double e : {1.0, 0.9}) {
    DYNAMIC_SECTION("e=" << e) {
      const nsb::BouncingMass p(Params(nsb::BouncingMass::parameters_spec(), {{"e", std::to_string(e)}, {"v0", "0.7"}}));
      auto me = make_me();
      me.init(p, p.initial_state());
      // e = 1: 30 impacts. e = 0.9: through the Zeno accumulation (about 100 impacts).
      const double t_end = e < 1.0 ? p.zeno_time() + 0.5 : 0.5 * (p.impact_time(30) + p.impact_time(31));
      advance_to(me, t_end, 0.0137);  // no divisor of the flights: impacts fall inside steps
      int i = 0;
      for (const auto& ev : me.events()) {
        ++i;
        if (ev.rate_after == 0.0) {  // the Zeno stop (checked below)
          CHECK(ev.kind == ModalExact::EventKind::ZenoStop);
          break;
        }
        REQUIRE(ev.kind == ModalExact::EventKind::Impact);
        const double rebound = std::pow(e, i) * p.first_impact_speed();
        CAPTURE(i);
        CHECK(std::abs(ev.t - p.impact_time(i)) <= 1e-12 * p.impact_time(i));
        CHECK(std::abs(ev.rate_after - rebound) <= 1e-12 * rebound);
        CHECK(std::abs(ev.rate_before + rebound / e) <= 1e-12 * rebound / e);
      }
      if (e == 1.0) {
        CHECK(i == 30);
        CHECK(me.work().extra.at("zeno_stops") == 0);
      } else {
        // The plastic impact comes at the first landing whose rebound would be slower than
        // zeno_velocity = 1e-4; the flights it cuts last 2 e v / (g (1 - e)) < 2e-4 / (g (1 - e)).
        const double g = 9.81, v_zeno = 1e-4;
        REQUIRE(me.work().extra.at("zeno_stops") == 1);
        REQUIRE(me.events().back().rate_after == 0.0);
        CHECK(me.events().back().t <= p.zeno_time());
        CHECK(p.zeno_time() - me.events().back().t <= 2 * v_zeno / (g * (1 - e)));
        CHECK(std::abs(me.events().back().rate_before) < v_zeno / e);
        // At rest on the floor, held there exactly; the floor holds the weight m g dt.
        CHECK(me.state().u[0] == 0.0);
        CHECK(me.state().v[0] == 0.0);
        CHECK(me.work().extra.at("releases") == 0);
        me.step(0.1);
        CHECK(me.impulses()[0] == Approx(g * 0.1).epsilon(1e-14));
      }
    }
  }
}

TEST_CASE("modal-exact vs event-driven: lumped bar contact duration within 1e-6 relative",
          "[reference][modal-exact][event-driven][signorini-bar]") {
  // The check of the CVODE reference (rtol 1e-11) against an independent exact
  // solution of the same semi-discrete bar. The contact is one impact (the contact node
  // stops plastically at t = 0) and one release (its reaction back to zero near 2L/c).
  for (int N : {20, 100}) {
    DYNAMIC_SECTION("N=" << N) {
      const auto p = modal_bar("lumped", N);
      const double t_end = 1.2 * p.contact_duration();
      auto me = make_me();
      me.init(p, p.initial_state());
      advance_to(me, t_end, 0.0437);
      nsb::EventDriven ed(Params(nsb::EventDriven::parameters_spec()));
      ed.init(p, p.initial_state());
      advance_to(ed, t_end, 0.0437);
      REQUIRE(me.events().size() == 2);
      CHECK(me.events()[0].t == 0.0);
      REQUIRE(nsb::events_of_kind(ed.events(), {nsb::ContactEventKind::Impact}).size() == 1);
      REQUIRE(nsb::events_of_kind(ed.events(), {nsb::ContactEventKind::Release}).size() == 1);
      const double T_me = contact_duration(me), T_ed = contact_duration(ed);
      CAPTURE(T_me, T_ed);
      CHECK(std::abs(T_ed - T_me) <= 1e-6 * T_me);
      // The semi-discrete contact is longer than the continuum's 2L/c (next test).
      CHECK(T_me > p.contact_duration());
    }
  }
}

TEST_CASE("modal-exact: lumped bar contact duration T_N -> 2L/c at the rate 2/3 of dispersive fronts",
          "[reference][modal-exact][signorini-bar]") {
  // Why 2/3: the lumped chain's dispersion w = (2c/h) sin(kh/2) = c k (1 - (kh)^2/24 + ...)
  // has its largest group velocity c at k = 0, and a front that has travelled a distance D
  // spreads over an Airy layer of width ~ (h^2 D)^(1/3) (D/h sites: (D/h)^(1/3) sites, the
  // Bessel-function front of the chain, E. Schroedinger, Ann. Phys. 44, 1914; Whitham, Linear
  // and Nonlinear Waves, 1974, ch. 11). The release waits for the unloading front back from
  // the free end (D = 2L), so T_N - 2L/c ~ C h^(2/3) L^(1/3) / c. Measured (L = c = 1):
  //     N       10      20      40      80      160     320
  //     T_N-2   0.04922 0.03230 0.02102 0.01347 0.00859 0.00545
  //     (T_N-2) N^(2/3)  0.228  0.238  0.246  0.250  0.253  0.255
  // local orders 0.608, 0.620, 0.642, 0.650, 0.656: pre-asymptotic, rising towards 2/3 (the
  // constant still grows by about 1 % per doubling at N = 320).
  const std::vector<int> meshes = {10, 20, 40, 80, 160, 320};
  std::vector<double> h, err;
  for (int N : meshes) {
    h.push_back(1.0 / N);
    err.push_back(modal_contact_duration(N) - 2.0);
  }
  for (std::size_t k = 0; k < meshes.size(); ++k) {
    CAPTURE(meshes[k], err[k]);
    CHECK(err[k] > 0.0);
    if (k == 0) continue;
    CHECK(err[k] < err[k - 1]);
    // Each local order in a band around 2/3 that holds the measured pre-asymptotic drift.
    const double order = nsb::observed_order(h[k - 1], err[k - 1], h[k], err[k]);
    CAPTURE(order);
    CHECK(order > 0.58);
    CHECK(order < 0.70);
  }
  // Fitted over N = 40..320: within 0.03 of 2/3 (measured 0.649).
  const double fitted = nsb::fitted_order({h.begin() + 2, h.end()}, {err.begin() + 2, err.end()});
  CAPTURE(fitted);
  CHECK(std::abs(fitted - 2.0 / 3.0) <= 0.03);
}

TEST_CASE("modal-exact: consistent and singular bars keep energy (but for the impact law's loss), momentum with "
          "the impulses, and the gap",
          "[reference][modal-exact][signorini-bar]") {
  for (std::string mass : {"consistent", "singular"}) {
    for (double g0 : {0.0, 0.1234}) {
      DYNAMIC_SECTION(mass << " g0=" << g0) {
        const int N = 50;
        const auto p = modal_bar(mass, N, {{"g0", std::to_string(g0)}});
        const double roundoff = bar_roundoff(p);
        auto me = make_me();
        me.init(p, p.initial_state());
        // Impact-law losses: one contact, on dof 0 with a = 1: (1 - e^2) (g'-)^2 / (2 H),
        // H = (M^{-1})_00, e = 0 for the bar. The massless node arrives: no loss.
        const double H = mass == "singular" ? NAN : Eigen::MatrixXd(p.mass_matrix()).inverse()(0, 0);
        const auto losses = [&]() {
          double sum = 0.0;
          for (const auto& ev : me.events())
            if (ev.kind == ModalExact::EventKind::Impact) sum += 0.5 * ev.rate_before * ev.rate_before / H;
          return sum;
        };
        const double E_start = p.exact_energy();  // before init: the rigid bar at -v0
        const double P_start = p.momentum(me.state().v);
        double impulses = 0.0, worst_energy = 0.0, min_gap = INFINITY;
        while (me.state().t < p.contact_start() + 1.5 * p.contact_duration()) {
          me.step(0.01);
          impulses += me.impulses()[0];
          worst_energy = std::max(worst_energy, std::abs(me.energy().total() - (E_start - losses())) / E_start);
          min_gap = std::min(min_gap, p.gap_offset()[0] + me.state().u[0]);
        }
        // The contact happened: the impulse is about 2 M v0, and it released.
        CHECK(impulses > 1.9 * p.total_mass() * p.rebound_velocity());
        CHECK(me.work().extra.at("releases") >= 1);
        if (mass == "singular") {
          CHECK(me.work().extra.at("impacts") == 0);
          CHECK(me.work().extra.at("arrivals") >= 1);
        } else {
          CHECK(me.work().extra.at("impacts") >= 1);
          CHECK(losses() > 0.0);
        }
        CAPTURE(roundoff, worst_energy);
        CHECK(worst_energy <= roundoff);
        CHECK(std::abs(p.momentum(me.state().v) - P_start - impulses) <= roundoff * p.total_mass() * p.rebound_velocity());
        CHECK(min_gap >= -1e-12);
      }
    }
  }
}

TEST_CASE("modal-exact: singular bar bouncing under gravity keeps its energy over several contacts",
          "[reference][modal-exact][signorini-bar]") {
  // g = 0.25: contact about 2L/c = 2, flight about 2 v0 / g = 8; four contacts by t = 35. The
  // static parts of the modes (q_s = f / w^2) and the rigid mode's parabola are exercised.
  const auto p = modal_bar("singular", 30, {{"g", "0.25"}});
  auto me = make_me();
  me.init(p, p.initial_state());
  const double E0 = me.energy().total();
  double worst = 0.0, min_gap = INFINITY;
  while (me.state().t < 35.0) {
    me.step(0.05);
    worst = std::max(worst, std::abs(me.energy().total() - E0) / E0);
    min_gap = std::min(min_gap, me.state().u[0]);
  }
  CHECK(me.work().extra.at("arrivals") >= 4);
  CHECK(me.work().extra.at("impacts") == 0);
  CHECK(worst <= bar_roundoff(p));
  CHECK(min_gap >= -1e-12);
}

TEST_CASE("modal-exact: advance_to and displacement sample one dof as step() does, through events",
          "[reference][modal-exact][signorini-bar]") {
  // Singular (a massless dof) and lumped (a held massive dof) bars under gravity, sampled at
  // times that are not the stepping ones, across arrivals, impacts and releases.
  for (const std::string mass : {"singular", "lumped"}) {
    const auto p = modal_bar(mass, 20, {{"g", "0.25"}});
    auto stepped = make_me(), sampled = make_me();
    stepped.init(p, p.initial_state());
    sampled.init(p, p.initial_state());
    double worst = 0.0;
    while (stepped.state().t < 20.0) {
      stepped.step(0.0731);
      sampled.advance_to(stepped.state().t);
      for (nsb::Index dof : {nsb::Index(0), nsb::Index(1), nsb::Index(10), nsb::Index(20)})
        worst = std::max(worst, std::abs(sampled.displacement(dof) - stepped.state().u[dof]));
    }
    INFO(mass);
    CHECK(sampled.events().size() == stepped.events().size());
    CHECK(sampled.events().size() >= 4);
    CHECK(worst <= 1e-12);
    CHECK_THROWS_AS(sampled.advance_to(1.0), nsb::InputError);
  }
}

TEST_CASE("modal-exact: lumped bar bouncing under gravity: the contact node's chatter only loses energy",
          "[reference][modal-exact][signorini-bar]") {
  // The energy study's case (N = 50, g = 0.25) to t = 100: dozens of plastic impacts of the
  // contact node and releases, among them (t = 88.28) a release from rest that the element
  // pushes back after 2.3 ms, shorter than one search sample (3.9 ms): found by halving.
  const auto p = modal_bar("lumped", 50, {{"g", "0.25"}});
  auto me = make_me();
  me.init(p, p.initial_state());
  double E_prev = me.energy().total(), worst_gain = 0.0, min_gap = INFINITY, shortest_flight = INFINITY;
  while (me.state().t < 100.0) {
    me.step(0.01);
    worst_gain = std::max(worst_gain, me.energy().total() - E_prev);
    E_prev = me.energy().total();
    min_gap = std::min(min_gap, me.state().u[0]);
  }
  for (std::size_t k = 1; k < me.events().size(); ++k)
    if (me.events()[k - 1].kind == ModalExact::EventKind::Release && me.events()[k].kind == ModalExact::EventKind::Impact)
      shortest_flight = std::min(shortest_flight, me.events()[k].t - me.events()[k - 1].t);
  CHECK(me.work().extra.at("impacts") >= 20);
  CHECK(shortest_flight < 0.003);
  CHECK(me.work().extra.at("forced_events") == 0);
  CHECK(worst_gain <= bar_roundoff(p) * p.exact_energy());  // between impacts: conserved to round-off
  CHECK(min_gap >= -1e-12);
}

TEST_CASE("modal-exact: spring chain between two walls, e = 1: energy conserved, momentum changes by the impulses",
          "[reference][modal-exact][spring-chain]") {
  const nsb::SpringChain p(Params(nsb::SpringChain::parameters_spec(), {{"n", "5"}, {"wall", "both"}, {"gap", "0.05"}}));
  auto me = make_me();
  me.init(p, p.initial_state());
  const double E0 = me.energy().total(), P0 = p.momentum(me.state().v);
  double wall_impulse = 0.0, worst = 0.0, min_gap = INFINITY;
  for (int k = 0; k < 2000; ++k) {
    me.step(0.01);
    // Momentum: L^T Lambda summed over the dofs, L = [e_0; -e_{n-1}].
    wall_impulse += me.impulses()[0] - me.impulses()[1];
    worst = std::max(worst, std::abs(me.energy().total() - E0) / E0);
    min_gap = std::min(min_gap, (p.gap_offset() + p.gap_operator() * me.state().u).minCoeff());
  }
  REQUIRE(me.work().extra.at("impacts") >= 10);
  CHECK(me.work().extra.at("zeno_stops") == 0);
  bool left = false, right = false;
  for (const auto& ev : me.events()) (ev.contact == 0 ? left : right) = true;
  CHECK((left && right));
  // Round-off: k / m = 100 (w_max ~ 20) and t = 20: the eigendecomposition error
  // eps w_max^2 over t and the impacts' eps per event; 1e-12 leaves a margin of 10 or more.
  CHECK(worst <= 1e-12);
  CHECK(std::abs(p.momentum(me.state().v) - P0 - wall_impulse) <= 1e-12 * p.momentum(p.initial_state().v.cwiseAbs()));
  CHECK(min_gap >= -1e-12);
}

TEST_CASE("modal-exact: two contacts hitting together go through the impulse LCP at one instant",
          "[reference][modal-exact][spring-chain][contact]") {
  // Two equal masses joined by a spring k, flying apart at -a and +a towards walls at the same
  // gap: each moves by x(t) = (a / w) sin(w t), w = sqrt(2 k / m), and both hit at
  // t1 = asin(gap w / a) / w, rebounding with e = 1.
  const double k = 100.0, a = 0.5, gap = 0.02, w = std::sqrt(2.0 * k);
  const nsb::SpringChain p(Params(nsb::SpringChain::parameters_spec(), {{"n", "2"}, {"mass_ratio", "1"}, {"wall", "both"},
                                                                        {"gap", "0.02"}, {"v0", "0"}, {"a", "-0.5"}}));
  auto me = make_me();
  me.init(p, p.initial_state());
  const double E0 = me.energy().total();
  advance_to(me, 0.1, 0.0137);
  REQUIRE(me.events().size() >= 2);
  const auto& left = me.events()[0];
  const auto& right = me.events()[1];
  CHECK(left.contact != right.contact);
  CHECK(left.t == right.t);
  CHECK(me.work().lcp_iterations >= 1);  // one LCP of size 2, not two single impacts
  const double t1 = std::asin(gap * w / a) / w;
  CHECK(std::abs(left.t - t1) <= 1e-14);
  for (const auto& ev : {left, right}) {
    CHECK(ev.kind == ModalExact::EventKind::Impact);
    CHECK(ev.rate_before == Approx(-a * std::cos(w * t1)).epsilon(1e-12));
    CHECK(ev.rate_after == Approx(-ev.rate_before).epsilon(1e-12));
  }
  CHECK(std::abs(me.energy().total() - E0) <= 1e-14 * E0);
}

TEST_CASE("modal-exact: refuses what it cannot integrate exactly, saying why", "[reference][modal-exact][bad-input]") {
  // Its declared capabilities, checked when it binds (the registry's entry gives them).
  const nsb::Block2d block(Params(nsb::Block2d::parameters_spec()));
  auto me = nsb::make_integrator(ModalExact::kName);
  CHECK_THROWS_WITH(me->init(block, block.initial_state()), Catch::Contains("nonlinear"));
  const auto big = modal_bar("lumped", 3000);
  CHECK_THROWS_WITH(me->init(big, big.initial_state()), Catch::Contains("max_dofs"));
  CHECK_THROWS_AS(ModalExact(Params(ModalExact::parameters_spec(), {{"samples_per_period", "1"}})), nsb::InputError);
}

// Issue 30, finding 10: modal-exact counted no work, so no budget stopped it (1e8 steps in
// 27 s, status ok). Each step and each event inside it is one F_int-evaluation equivalent.
TEST_CASE("modal-exact: its work counts against a run's budget", "[reference][modal-exact]") {
  const nsb::BouncingMass p(Params(nsb::BouncingMass::parameters_spec(), {{"e", "0.9"}}));
  auto me = make_me();
  me.init(p, p.initial_state());
  nsb::RunOptions options;
  options.dt = 1e-3;
  options.t_end = 10.0;
  options.record_series = false;
  options.max_force_evaluations = 1000;
  const nsb::RunResult r = nsb::run(p, me, options);
  CHECK(r.status == nsb::RunStatus::OverBudget);
  CHECK(r.steps <= 1001);
  CHECK(r.work.force_evaluations == 0);
  CHECK(r.work.extra.at("force_equivalents") >= static_cast<double>(r.steps));
  CHECK_THAT(r.message, Catch::StartsWith("budget of 1000 F_int evaluations (or their equivalents) exceeded"));
}

// The modes a ModalExact builds are shared by every ModalExact of the process set up on the same
// system (inputs compared bit for bit): a second reference on the same bar gives the same bits
// and counts the same work (its decompositions are counted as if made); a bar that differs in
// its load only (gravity: F) is not given the first bar's modes.
TEST_CASE("modal-exact: a second reference on the same system gives the same bits and counters, another load its own modes",
          "[reference][modal-exact][signorini-bar]") {
  const auto run = [](const nsb::SignoriniBar& p) {
    auto me = make_me();
    me.init(p, p.initial_state());
    advance_to(me, 6.0, 0.0731);
    return std::make_pair(me.state(), me.work());
  };
  const auto bar = modal_bar("lumped", 30, {{"g", "0.25"}});
  const auto [first, first_work] = run(bar);
  const auto [second, second_work] = run(bar);
  CHECK(first.u == second.u);
  CHECK(first.v == second.v);
  CHECK(first_work.factorizations == second_work.factorizations);
  CHECK(first_work.extra == second_work.extra);
  CHECK(first_work.extra.at("eigen_decompositions") >= 2);  // open and closed
  // Same mesh, another gravity: its own modes (a shared mode would keep the first bar's load).
  const auto [other, other_work] = run(modal_bar("lumped", 30, {{"g", "0.5"}}));
  REQUIRE(other.t == Approx(6.0));
  CHECK(other.u != first.u);
  CHECK(other_work.extra.at("eigen_decompositions") >= 2);
}

// Bit-identical on every machine, one setting of it: Eigen sizes its matrix-product blocks from
// the cache sizes it reads off the processor, and blocking the reduction dimension reorders the
// sums. Two machines' cache sizes are set in turn here and modal-exact's run on the consistent
// hex8 bar is the same. (What did differ between machines was glibc's sin and cos:
// core/deterministic_math.hpp, tests/scripts/machine_settings_test.py.)
TEST_CASE("modal-exact: the consistent hex8 bar's run is bit-identical whatever cache sizes Eigen reads off the machine",
          "[reference][modal-exact]") {
  const auto problem = nsb::make_problem("bar-3d", {{"N", "80"}, {"mass", "consistent"}});
  const std::ptrdiff_t l1 = Eigen::l1CacheSize(), l2 = Eigen::l2CacheSize(), l3 = Eigen::l3CacheSize();
  const auto final_state = [&](std::ptrdiff_t c1, std::ptrdiff_t c2, std::ptrdiff_t c3) {
    Eigen::setCpuCacheSizes(c1, c2, c3);
    auto me = nsb::make_integrator("modal-exact");
    me->init(*problem, problem->initial_state());
    advance_to(*me, 1.0, 0.01);
    Eigen::setCpuCacheSizes(l1, l2, l3);
    return me->state();
  };
  // Caches of 16 KiB, 256 KiB, 2 MiB and an Intel Xeon's 48 KiB, 2 MiB, 480 MiB.
  const nsb::State a = final_state(16 << 10, 256 << 10, 2 << 20), b = final_state(48 << 10, 2 << 20, 480 << 20);
  REQUIRE(a.u.size() > 100);
  for (Eigen::Index i = 0; i < a.u.size(); ++i) {
    INFO("dof " << i);
    CHECK(a.u[i] == b.u[i]);
    CHECK(a.v[i] == b.v[i]);
  }
}
