#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <stdexcept>

#include "studies/hausdorff.hpp"

using namespace nsb;

namespace {

// A unit step at t_jump on [0, 1], the jump a vertical segment.
Polyline step_polyline(double t_jump, double height) {
  Polyline p;
  p.add(0.0, 0.0);
  p.add(t_jump, 0.0);
  p.add(t_jump, height);
  p.add(1.0, height);
  return p;
}

// Dense sampling of a's edges: a lower bound on h(a, b) within spacing / 2 of it (d is 1-Lipschitz).
double sampled_directed(const Polyline& a, const Polyline& b, double spacing) {
  double h = 0.0;
  for (std::size_t k = 0; k + 1 < a.size(); ++k) {
    const double len = std::hypot(a.t[k + 1] - a.t[k], a.x[k + 1] - a.x[k]);
    const int m = std::max(1, static_cast<int>(std::ceil(len / spacing)));
    for (int i = 0; i <= m; ++i) {
      const double s = static_cast<double>(i) / m;
      h = std::max(h, distance_to_polyline(a.t[k] + s * (a.t[k + 1] - a.t[k]), a.x[k] + s * (a.x[k + 1] - a.x[k]), b));
    }
  }
  return h;
}

}  // namespace

TEST_CASE("Hausdorff: two steps offset by d in time are d apart when the jump exceeds d", "[hausdorff]") {
  for (double d : {1e-1, 1e-3, 1e-6}) {
    const Polyline a = step_polyline(0.5, 1.0), b = step_polyline(0.5 + d, 1.0);
    CHECK(directed_hausdorff(a, b) == Approx(d).epsilon(1e-9));
    CHECK(directed_hausdorff(b, a) == Approx(d).epsilon(1e-9));
    CHECK(hausdorff(a, b) == Approx(d).epsilon(1e-9));
  }
}

TEST_CASE("Hausdorff: a jump smaller than the shift gives the jump's height, as the max norm would", "[hausdorff]") {
  const double d = 0.2, jump = 0.05;
  CHECK(hausdorff(step_polyline(0.4, jump), step_polyline(0.4 + d, jump)) == Approx(jump).epsilon(1e-9));
}

TEST_CASE("Hausdorff: a graph is at distance 0 from itself", "[hausdorff]") {
  Polyline a;
  for (int k = 0; k <= 1000; ++k) a.add(k * 1e-3, std::sin(7.0 * k * 1e-3) + (k > 400 ? 1.0 : 0.0));
  CHECK(hausdorff(a, a) == 0.0);
}

TEST_CASE("Hausdorff: directed distances are asymmetric", "[hausdorff]") {
  Polyline point, line;
  point.add(0.5, 1.0);
  line.add(0.0, 0.0);
  line.add(1.0, 0.0);
  CHECK(directed_hausdorff(point, line) == Approx(1.0));
  CHECK(directed_hausdorff(line, point) == Approx(std::hypot(0.5, 1.0)));
  // A step's graph contains a shifted copy's flat parts only: the step is d from the
  // ramp, the ramp farther from the step.
  Polyline ramp;
  ramp.add(0.0, 0.0);
  ramp.add(0.4, 0.0);
  ramp.add(0.6, 1.0);
  ramp.add(1.0, 1.0);
  const double there = directed_hausdorff(step_polyline(0.5, 1.0), ramp), back = directed_hausdorff(ramp, step_polyline(0.5, 1.0));
  CHECK(there != Approx(back));
}

TEST_CASE("Hausdorff: the maximum inside an edge (equidistant to two segments) is found", "[hausdorff]") {
  // d(a(s), B) = min(s, 1, 1 - s) on A = [0, 1] x {0}: the sup 1/2 is at no vertex of A.
  Polyline a, b;
  a.add(0.0, 0.0);
  a.add(1.0, 0.0);
  b.add(0.0, 0.0);
  b.add(0.0, 1.0);
  b.add(1.0, 1.0);
  b.add(1.0, 0.0);
  CHECK(directed_hausdorff(a, b) == Approx(0.5).epsilon(1e-9));
}

TEST_CASE("Hausdorff: certified against dense sampling on random monotone polylines", "[hausdorff]") {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Polyline a, b;
    double ta = 0.0, tb = 0.0;
    for (int k = 0; k < 40; ++k) {
      a.add(ta, u(gen));
      b.add(tb, u(gen));
      ta += u(gen) < 0.2 ? 0.0 : 0.05 * u(gen);  // some vertical segments
      tb += u(gen) < 0.2 ? 0.0 : 0.05 * u(gen);
    }
    const double spacing = 1e-3;
    const double exact = directed_hausdorff(a, b), dense = sampled_directed(a, b, spacing);
    CHECK(exact >= dense - 1e-12);
    CHECK(exact <= dense + spacing / 2 + 1e-12);
  }
}

TEST_CASE("Hausdorff: scales, and bad polylines are refused", "[hausdorff]") {
  const Polyline a = scaled(step_polyline(5.0, 2.0), 10.0, 2.0);
  CHECK(a.t[1] == 0.5);
  CHECK(a.x[3] == 1.0);
  CHECK_THROWS_AS(scaled(a, 0.0, 1.0), std::invalid_argument);
  Polyline back;
  back.add(1.0, 0.0);
  back.add(0.5, 0.0);
  CHECK_THROWS_AS(hausdorff(back, a), std::invalid_argument);
  CHECK_THROWS_AS(hausdorff(Polyline{}, a), std::invalid_argument);
}

TEST_CASE("Hausdorff: sampled_graph makes a jump vertical, at a known time or located by bisection", "[hausdorff]") {
  const auto value = [](double t) { return t < 0.3137 ? t : t - 1.0; };
  for (const std::vector<double>& known : {std::vector<double>{0.3137}, std::vector<double>{}}) {
    const Polyline g = sampled_graph(value, 1.0, 16, known, 0.5);
    Polyline exact;  // the true graph: the segments and the vertical jump
    exact.add(0.0, 0.0);
    exact.add(0.3137, 0.3137);
    exact.add(0.3137, 0.3137 - 1.0);
    exact.add(1.0, 0.0);
    CHECK(hausdorff(g, exact) < 1e-9);
  }
}

#include "integrators/registry.hpp"
#include "problems/registry.hpp"

TEST_CASE("Hausdorff: order about 1 on the bouncing mass for cd-lagrange and moreau-jean, where the max norm stalls", "[hausdorff]") {
  const auto problem = make_problem("bouncing-mass", {{"e", "0.9"}, {"h0", "1"}});
  const double t_end = problem->exact()->impact_times(1e3).at(2) + 0.2;
  const auto v = [](const State& s) { return s.v[0]; };
  const Polyline exact = exact_graph(*problem, v, t_end);
  const auto exact_at = [&](double t) { return problem->exact()->state(t)->v[0]; };
  for (const std::string name : {"cd-lagrange", "moreau-jean"}) {
    std::vector<double> h, emax, eh;
    for (double dt : {4e-3, 2e-3, 1e-3, 5e-4}) {
      auto it = make_integrator(name);
      it->init(*problem, problem->initial_state());
      const Polyline run = run_graph(*problem, *it, dt, t_end, [](const State& s, const Vec&, double) { return s.v[0]; }, nullptr);
      const GraphErrors e = graph_errors(run, exact, exact_at, t_end);
      h.push_back(dt);
      emax.push_back(e.max_error);
      eh.push_back(e.hausdorff);
    }
    INFO(name);
    const OrderFit fh = fit_order(h, eh), fm = fit_order(h, emax);
    CHECK(fh.order > 0.6);
    CHECK(fh.order < 1.4);
    CHECK(std::abs(fm.order) < 0.2);  // a jump a step late is an O(1) max-norm error at any step
    CHECK(emax.back() > 0.3);
  }
}

TEST_CASE("Hausdorff: graph errors of a step a shift late, their value scale the reference's largest |value| or the one given",
          "[hausdorff]") {
  // Steps of height 2 at 0.4 (the reference) and 0.5 (the run): in (t / 1, x / V) a shift of
  // 0.1 against a jump of 2 / V > 0.1, so both directed distances are 0.1; the run's vertex
  // (0.5, 0) is 2 below the reference there, a max-norm error of 2 / V.
  const Polyline ref = step_polyline(0.4, 2.0), late = step_polyline(0.5, 2.0);
  const auto ref_at = [](double t) { return t > 0.4 ? 2.0 : 0.0; };
  const GraphErrors own = graph_errors(late, ref, ref_at, 1.0);
  CHECK(own.value_scale == 2.0);
  CHECK(own.max_error == 1.0);
  CHECK(own.to_reference == Approx(0.1).epsilon(1e-9));
  CHECK(own.from_reference == Approx(0.1).epsilon(1e-9));
  CHECK(own.hausdorff == std::max(own.to_reference, own.from_reference));
  const GraphErrors given = graph_errors(late, ref, ref_at, 1.0, 4.0);
  CHECK(given.value_scale == 4.0);
  CHECK(given.max_error == 0.5);
  CHECK(given.hausdorff == Approx(0.1).epsilon(1e-9));  // jump 0.5 > shift 0.1: still the shift
}
