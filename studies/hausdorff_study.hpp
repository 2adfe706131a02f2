#pragma once
// Pieces of the hausdorff study (studies/hausdorff_study.cpp) that the claims study and the
// tests reuse: the velocity graph of a run, the exact graph, and the errors between them.
#include <functional>

#include "run/run.hpp"
#include "studies/hausdorff.hpp"
#include "studies/study.hpp"

namespace nsb {

// The graph {(t_k, value_k)} of a run of `integrator` (already init-ed) at step dt to t_end,
// the initial state first; value(state, impulses of the step, its length). The run's result
// in *result when given.
Polyline run_graph(const Problem& problem, Integrator& integrator, double dt, double t_end,
                   const std::function<double(const State&, const Vec&, double)>& value, RunResult* result);
// The graph of value(the exact state at t) on [0, t_end]: sampled_graph with 20000 samples, the
// problem's impact times and jumps of more than 2% of the largest |value| made vertical.
Polyline exact_graph(const Problem& problem, const std::function<double(const State&)>& value, double t_end);
// Linear interpolation of a graph at t (its end values outside it).
double interpolate(const Polyline& g, double t);

struct GraphErrors {
  double time_scale = 0.0, value_scale = 0.0;  // T, V (V: the reference's largest |value|, 1 if 0)
  double max_error = 0.0;                      // max_k |x_k - ref(t_k)| / V
  double hausdorff = 0.0, to_reference = 0.0, from_reference = 0.0;  // scaled coordinates
};
// V: value_scale when > 0, else the reference's largest |value| (1 if 0).
GraphErrors graph_errors(const Polyline& run, const Polyline& reference, const std::function<double(double)>& reference_at,
                         double time_scale, double value_scale = 0.0);

// The study's fits for one integrator, per problem in the study's order: the problem's name and
// the orders in dt of the max-norm error and of the Hausdorff distance (runs the 4 refinements).
struct HausdorffOrders {
  std::string problem;
  OrderFit max_error, hausdorff;
  std::string note;  // "declined", "diverged", ... or empty
};
std::vector<HausdorffOrders> hausdorff_orders(const std::string& integrator);

}  // namespace nsb
