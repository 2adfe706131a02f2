#pragma once
// Hausdorff distance between the graphs of two time histories ("convergence in the
// non-smooth sense": a velocity that jumps at an impact converges in this distance, not in the
// max norm, when the computed jump is a step late).
//
// A history is a polyline through its samples (t_k, x_k) in order, in scaled coordinates
// (t / T, x / X): a jump between two samples is a steep segment, and a jump of an exact
// solution is a vertical segment when the exact solution is sampled on both sides of it
// (exact_graph). Both polylines are monotone in t (t_k nondecreasing).
//
//     d(p, B)  = min over b in B of |p - b|                 (Euclidean, scaled coordinates)
//     h(A, B)  = sup over a in A of d(a, B)                 (directed; h(A, B) != h(B, A))
//     H(A, B)  = max(h(A, B), h(B, A))
//
// Computing h exactly: on an edge a(s), s in [0, 1], of A, d(a(s), B) = min_j d_j(s), d_j the
// distance to segment j of B, each convex in s (the distance from a point moving on a line to
// a convex set). Hence (i) the sup over the edge is at an endpoint or where the nearest segment
// changes (a point equidistant to two segments of B, where the lower envelope has a kink), and
// (ii) on any piece [s0, s1] of the edge, max d(a(s), B) <= max(d_j(s0), d_j(s1)) for EVERY j
// (convexity) and <= (d(s0) + d(s1) + |a(s1) - a(s0)|) / 2 (d is 1-Lipschitz). The algorithm
// evaluates d at every vertex of A, then bisects only the pieces whose bound (ii), taken with j
// the nearest segments at both ends, exceeds the largest distance found plus the tolerance:
// a piece whose two ends share their nearest segment is done at once. The result h_found
// satisfies h_found <= h <= h_found + tol with tol = rtol * h_found + atol, a certified bound.
//
// Nearest segments: B is monotone in t, so only its segments whose time range meets
// [t - r, t + r] can be within r of p = (t, x); they are found by binary search and a scan
// outwards that shrinks r as nearer segments are found, skipping blocks of 32 segments whose
// bounding box is farther than r. Cost: O((n_A + bisections) log n_B) plus the blocks in
// those windows, fine for 1e5 samples.
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "problems/problem.hpp"
#include "studies/measures.hpp"

namespace nsb {

class Integrator;
struct RunResult;

struct Polyline {
  std::vector<double> t, x;  // same size >= 1, t nondecreasing, all finite
  std::size_t size() const { return t.size(); }
  void add(double tk, double xk) {
    t.push_back(tk);
    x.push_back(xk);
  }
};

struct HausdorffTolerance {
  double rtol = 1e-9;
  double atol = 1e-14;
};

// The polyline scaled to (t / time_scale, x / value_scale); throws std::invalid_argument on a
// scale that is not positive and finite.
Polyline scaled(const Polyline& p, double time_scale, double value_scale);

// Distance from (t, x) to the polyline b; throws std::invalid_argument when b is not a valid
// polyline (empty, sizes differ, t decreasing, a non-finite value).
double distance_to_polyline(double t, double x, const Polyline& b);

// h(a, b): the directed distance, within the tolerance above (never below the true value by
// more than tol, never above it). Throws std::invalid_argument as distance_to_polyline.
double directed_hausdorff(const Polyline& a, const Polyline& b, HausdorffTolerance tol = {});
// H(a, b) = max(h(a, b), h(b, a)).
double hausdorff(const Polyline& a, const Polyline& b, HausdorffTolerance tol = {});

// The graph of value(t) on [0, t_end] with its jumps as vertical segments: n + 1 uniform
// samples, value at t* - delta and t* + delta for each known jump time t* (impact times), and
// the same around every other jump, located by bisection to delta = 1e-10 t_end between two
// samples whose values differ by more than jump_fraction times the largest |value| of the
// samples. A smooth part's chord error is the caller's (the grid n); a jump's vertical segment
// is off by at most delta in t.
Polyline sampled_graph(const std::function<double(double)>& value, double t_end, std::size_t n,
                       const std::vector<double>& jump_times, double jump_fraction);

// The settings the Hausdorff measurements share (the hausdorff study, claim (3)'s conditions):
// refinement levels, samples of an exact graph, and the jump threshold of sampled_graph.
inline constexpr int kHausdorffLevels = 4;
inline constexpr std::size_t kHausdorffExactSamples = 20000;
inline constexpr double kHausdorffJumpFraction = 0.02;

// ---- Graphs of runs and exact solutions, and the errors between them ----------------------
// (the study files' hausdorff measure, studies/study_file.hpp; claim (3)'s conditions)

// The graph {(t_k, value_k)} of a run of `integrator` (already init-ed) at step dt to t_end,
// the initial state first; value(state, impulses of the step, its length). The run's result
// in *result when given.
Polyline run_graph(const Problem& problem, Integrator& integrator, double dt, double t_end,
                   const std::function<double(const State&, const Vec&, double)>& value, RunResult* result);
// The graph of value(the exact state at t) on [0, t_end]: sampled_graph with
// kHausdorffExactSamples samples, the problem's impact times and the jumps of more than
// kHausdorffJumpFraction of the largest |value| made vertical.
Polyline exact_graph(const Problem& problem, const std::function<double(const State&)>& value, double t_end);

struct GraphErrors {
  double time_scale = 0.0, value_scale = 0.0;  // T, V (V: the reference's largest |value|, 1 if 0)
  double max_error = 0.0;                      // max_k |x_k - ref(t_k)| / V
  double hausdorff = 0.0, to_reference = 0.0, from_reference = 0.0;  // scaled coordinates
};
// V: value_scale when > 0, else the reference's largest |value| (1 if 0).
GraphErrors graph_errors(const Polyline& run, const Polyline& reference, const std::function<double(double)>& reference_at,
                         double time_scale, double value_scale = 0.0);

}  // namespace nsb
