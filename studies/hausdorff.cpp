#include "studies/hausdorff.hpp"
#include "core/deterministic_math.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <variant>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/parameters.hpp"
#include "run/run.hpp"
#include "studies/registry.hpp"
#include "studies/study_file.hpp"

namespace nsb {

namespace {

void check(const Polyline& p) {
  if (p.t.empty() || p.t.size() != p.x.size())
    throw std::invalid_argument("Hausdorff distance: a polyline needs one or more points and as many values as times");
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (!std::isfinite(p.t[k]) || !std::isfinite(p.x[k]))
      throw std::invalid_argument("Hausdorff distance: non-finite point " + std::to_string(k));
    if (k > 0 && p.t[k] < p.t[k - 1])
      throw std::invalid_argument("Hausdorff distance: times decrease at point " + std::to_string(k));
  }
}

std::size_t segments(const Polyline& b) { return std::max<std::size_t>(1, b.size() - 1); }

// The offset from (t, x) to the nearest point of segment j of b (its points j and j + 1; a
// single point when b has one).
struct Offset {
  double dt, dx;
};
Offset segment_offset(double t, double x, const Polyline& b, std::size_t j) {
  const std::size_t k = std::min(j + 1, b.size() - 1);
  const double dt = b.t[k] - b.t[j], dx = b.x[k] - b.x[j];
  const double len2 = dt * dt + dx * dx;
  double s = len2 > 0.0 ? ((t - b.t[j]) * dt + (x - b.x[j]) * dx) / len2 : 0.0;
  s = std::clamp(s, 0.0, 1.0);
  return {t - (b.t[j] + s * dt), x - (b.x[j] + s * dx)};
}

double segment_distance(double t, double x, const Polyline& b, std::size_t j) {
  const Offset o = segment_offset(t, x, b, j);
  return nsb::dmath::hypot(o.dt, o.dx);
}

// Whether hypot(o) < d, deciding from the squares where they leave no doubt: hypot (glibc:
// under 1 ulp) and the rounded sqrt(dt^2 + dx^2) differ by a few ulp, far inside the 1e-12
// margin, so the answer is hypot's own, bit for bit, and hypot is called only near the edge.
// Squares that overflow or underflow fall through to hypot.
bool shorter_than(Offset o, double d) {
  const double o2 = o.dt * o.dt + o.dx * o.dx, d2 = d * d;
  if (std::isfinite(d2) && d2 > 1e-280 && o2 > 1e-280) {
    if (o2 > d2 * (1.0 + 1e-12)) return false;
    if (o2 < d2 * (1.0 - 1e-12)) return true;
  }
  return nsb::dmath::hypot(o.dt, o.dx) < d;
}

struct Nearest {
  double d;
  std::size_t j;  // the nearest segment
};

// Bounding boxes of blocks of consecutive segments: a block whose box is farther than the
// nearest segment found so far is skipped whole.
constexpr std::size_t kBlock = 32;
struct Boxes {
  std::vector<double> t0, t1, x0, x1;
  explicit Boxes(const Polyline& b) {
    const std::size_t n = segments(b);
    for (std::size_t first = 0; first < n; first += kBlock) {
      const std::size_t last = std::min(first + kBlock, n);  // segments [first, last): points [first, last]
      const std::size_t end = std::min(last, b.size() - 1);
      t0.push_back(b.t[first]);
      t1.push_back(b.t[end]);
      x0.push_back(*std::min_element(b.x.begin() + first, b.x.begin() + end + 1));
      x1.push_back(*std::max_element(b.x.begin() + first, b.x.begin() + end + 1));
    }
  }
  // The offset from (t, x) to block k's box (zero inside it).
  Offset offset(std::size_t k, double t, double x) const {
    return {std::max({0.0, t0[k] - t, t - t1[k]}), std::max({0.0, x0[k] - x, x - x1[k]})};
  }
};

// Blocks are in time order (b is monotone in t): scanning outwards from the block holding t
// stops at the first block whose time range is farther than the nearest distance so far
// (|p - q| >= |t_p - t_q|).
Nearest nearest(double t, double x, const Polyline& b, const Boxes& boxes) {
  const std::size_t n = segments(b);
  const std::size_t k = static_cast<std::size_t>(std::upper_bound(b.t.begin(), b.t.end(), t) - b.t.begin());
  const std::size_t j0 = std::min(k > 0 ? k - 1 : 0, n - 1);
  Nearest best{segment_distance(t, x, b, j0), j0};
  const auto scan = [&](std::size_t block) {
    if (!shorter_than(boxes.offset(block, t, x), best.d)) return;
    for (std::size_t j = block * kBlock; j < std::min(n, (block + 1) * kBlock); ++j)
      if (const Offset o = segment_offset(t, x, b, j); shorter_than(o, best.d)) best = {nsb::dmath::hypot(o.dt, o.dx), j};
  };
  const std::size_t home = j0 / kBlock;
  scan(home);
  for (std::size_t block = home; block-- > 0;) {
    if (boxes.t1[block] < t - best.d) break;
    scan(block);
  }
  for (std::size_t block = home + 1; block < boxes.t0.size(); ++block) {
    if (boxes.t0[block] > t + best.d) break;
    scan(block);
  }
  return best;
}

}  // namespace

Polyline scaled(const Polyline& p, double time_scale, double value_scale) {
  if (!(time_scale > 0.0) || !std::isfinite(time_scale) || !(value_scale > 0.0) || !std::isfinite(value_scale))
    throw std::invalid_argument("Hausdorff distance: the time and value scales must be positive and finite");
  Polyline s;
  s.t.reserve(p.size());
  s.x.reserve(p.size());
  for (std::size_t k = 0; k < p.size(); ++k) s.add(p.t[k] / time_scale, p.x[k] / value_scale);
  return s;
}

double distance_to_polyline(double t, double x, const Polyline& b) {
  check(b);
  return nearest(t, x, b, Boxes(b)).d;
}

double directed_hausdorff(const Polyline& a, const Polyline& b, HausdorffTolerance tol) {
  check(a);
  check(b);
  const Boxes boxes(b);
  std::vector<Nearest> at(a.size());
  double h = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    at[k] = nearest(a.t[k], a.x[k], b, boxes);
    h = std::max(h, at[k].d);
  }
  struct Piece {
    double s0, s1;
    Nearest n0, n1;
  };
  std::vector<Piece> stack;
  for (std::size_t k = 0; k + 1 < a.size(); ++k) {
    const double dt = a.t[k + 1] - a.t[k], dx = a.x[k + 1] - a.x[k], length = nsb::dmath::hypot(dt, dx);
    stack.push_back({0.0, 1.0, at[k], at[k + 1]});
    while (!stack.empty()) {
      const Piece p = stack.back();
      stack.pop_back();
      const double t0 = a.t[k] + p.s0 * dt, x0 = a.x[k] + p.s0 * dx, t1 = a.t[k] + p.s1 * dt, x1 = a.x[k] + p.s1 * dx;
      // Bounds on the piece: 1-Lipschitz, and the convexity of the distance to each end's nearest segment.
      // Each bound is computed only while the piece is not yet settled (they only lower it).
      const double settled = h + tol.rtol * h + tol.atol;
      if (0.5 * (p.n0.d + p.n1.d + (p.s1 - p.s0) * length) <= settled) continue;
      if (std::max(p.n0.d, segment_distance(t1, x1, b, p.n0.j)) <= settled) continue;
      if (std::max(p.n1.d, segment_distance(t0, x0, b, p.n1.j)) <= settled) continue;
      const double sm = 0.5 * (p.s0 + p.s1);
      const Nearest nm = nearest(a.t[k] + sm * dt, a.x[k] + sm * dx, b, boxes);
      h = std::max(h, nm.d);
      stack.push_back({p.s0, sm, p.n0, nm});
      stack.push_back({sm, p.s1, nm, p.n1});
    }
  }
  return h;
}

double hausdorff(const Polyline& a, const Polyline& b, HausdorffTolerance tol) {
  return std::max(directed_hausdorff(a, b, tol), directed_hausdorff(b, a, tol));
}

Polyline sampled_graph(const std::function<double(double)>& value, double t_end, std::size_t n,
                       const std::vector<double>& jump_times, double jump_fraction) {
  const double delta = 1e-10 * t_end;
  std::vector<double> times;
  for (std::size_t k = 0; k <= n; ++k) times.push_back(t_end * static_cast<double>(k) / static_cast<double>(n));
  for (double t : jump_times)
    if (t - delta > 0.0 && t + delta < t_end) times.insert(times.end(), {t - delta, t + delta});
  std::sort(times.begin(), times.end());
  Polyline g;
  double largest = 0.0;
  for (double t : times) {
    g.add(t, value(t));
    largest = std::max(largest, std::abs(g.x.back()));
  }
  const double jump_threshold = jump_fraction * largest;
  Polyline out;
  for (std::size_t k = 0; k < g.size(); ++k) {
    if (k > 0 && std::abs(g.x[k] - g.x[k - 1]) > jump_threshold && g.t[k] - g.t[k - 1] > 2 * delta) {
      double lo = g.t[k - 1], hi = g.t[k], x_lo = g.x[k - 1], x_hi = g.x[k];
      while (hi - lo > delta) {  // keep the half across which the value changes most
        const double mid = 0.5 * (lo + hi), x_mid = value(mid);
        if (std::abs(x_mid - x_lo) >= std::abs(x_hi - x_mid)) {
          hi = mid;
          x_hi = x_mid;
        } else {
          lo = mid;
          x_lo = x_mid;
        }
      }
      if (lo > g.t[k - 1]) out.add(lo, x_lo);
      if (hi < g.t[k]) out.add(hi, x_hi);
    }
    out.add(g.t[k], g.x[k]);
  }
  return out;
}

Polyline run_graph(const Problem& problem, Integrator& integrator, double dt, double t_end,
                   const std::function<double(const State&, const Vec&, double)>& value, RunResult* result) {
  Polyline g;
  g.add(integrator.state().t, value(integrator.state(), Vec::Zero(problem.ncontacts()), 0.0));
  RunOptions options;
  options.dt = dt;
  options.t_end = t_end;
  options.record_series = false;
  const RunResult r = run(problem, integrator, options, [&](const Integrator& it, const StepInfo& info) {
    g.add(it.state().t, value(it.state(), it.impulses(), info.dt));
  });
  if (result) *result = r;
  return g;
}

Polyline exact_graph(const Problem& problem, const std::function<double(const State&)>& value, double t_end) {
  const ExactSolution& exact = *problem.exact();
  return sampled_graph([&](double t) { return value(*exact.state(t)); }, t_end, kHausdorffExactSamples, exact.impact_times(t_end),
                       kHausdorffJumpFraction);
}

GraphErrors graph_errors(const Polyline& run, const Polyline& reference, const std::function<double(double)>& reference_at,
                         double time_scale, double value_scale) {
  GraphErrors e;
  e.time_scale = time_scale;
  e.value_scale = value_scale;
  if (!(value_scale > 0.0))
    for (double x : reference.x) e.value_scale = std::max(e.value_scale, std::abs(x));
  if (!(e.value_scale > 0.0)) e.value_scale = 1.0;
  for (std::size_t k = 0; k < run.size(); ++k) e.max_error = std::max(e.max_error, std::abs(run.x[k] - reference_at(run.t[k])));
  e.max_error /= e.value_scale;
  const Polyline a = scaled(run, e.time_scale, e.value_scale), b = scaled(reference, e.time_scale, e.value_scale);
  e.to_reference = directed_hausdorff(a, b);
  e.from_reference = directed_hausdorff(b, a);
  e.hausdorff = std::max(e.to_reference, e.from_reference);
  return e;
}

}  // namespace nsb
