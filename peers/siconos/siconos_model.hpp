#pragma once
// The Siconos side of the peers, behind plain std types: Siconos 4.4's headers (Boost uBLAS
// 1.74) do not compile as C++20, so siconos_model.cpp alone is built as C++17 and nothing
// of nsbench (C++20) is visible to it. See siconos_integrator.hpp for the model built.
#include <memory>
#include <vector>

namespace nsb::siconos {

enum class Scheme { MoreauJean, SchatzmanPaoli, D1MinusLinear };

struct ModelSpec {
  Scheme scheme = Scheme::MoreauJean;
  double theta = 0.5;       // MoreauJeanOSI, SchatzmanPaoliOSI
  double lcp_tol = 1e-12;   // Lemke's tolerance
  double h = 0.0;           // the fixed step
  double t0 = 0.0;
  double restitution = 0.0;
  int ndof = 0;
  std::vector<double> mass, stiffness;  // dense, row-major, ndof x ndof
  std::vector<double> f_ext;            // constant external force (empty: none)
  std::vector<double> q0, v0;
  std::vector<std::vector<double>> gap_rows;  // one dense row of L per contact
  std::vector<double> gap_offset;             // g0 per contact
};

class Model {
 public:
  explicit Model(const ModelSpec& spec);  // throws std::runtime_error with Siconos' message
  ~Model();
  // Advances one step of h and writes the new q, v (ndof each) and each contact's impulse
  // over the step (>= 0, pushing apart).
  void step(double* q, double* v, double* impulses);

 private:
  void read(double* q, double* v, double* impulses) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nsb::siconos
