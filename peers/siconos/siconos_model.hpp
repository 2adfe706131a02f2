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
  double gamma = 0.5;       // MoreauJeanOSI's activation forecast y_k + gamma h y'_k <= 0
  double lcp_tol = 1e-12;   // Lemke's tolerance (frictionless contacts)
  double friction_tol = 1e-12;    // the NSGS friction solver's tolerance (MoreauJean with friction)
  int friction_max_iter = 1000;   // and its cap on Gauss-Seidel sweeps
  // FrictionContact(3) on every contact (MoreauJean only): rows (L_i, T_i, T2_i), a tangent
  // row zero where the problem has none, mu_i = 0 where it has no mu. Set for 3D contacts
  // with friction (tangent2_rows given) and on request for any problem.
  bool fc3d = false;
  double h = 0.0;           // the fixed step
  double t0 = 0.0;
  double restitution = 0.0;
  int ndof = 0;
  std::vector<double> mass, stiffness;  // dense, row-major, ndof x ndof
  std::vector<double> f_ext;            // constant external force (empty: none)
  std::vector<double> q0, v0;
  std::vector<std::vector<double>> gap_rows;  // one dense row of L per contact
  std::vector<double> gap_offset;             // g0 per contact
  // Coulomb friction (MoreauJean only): one dense row of T and one mu per contact; empty when
  // frictionless, and then the contacts are exactly those of the frictionless model.
  std::vector<std::vector<double>> tangent_rows;
  std::vector<double> mu;
  std::vector<std::vector<double>> tangent2_rows;  // 3D contacts: one dense row of T2 per contact, or empty
};

// What the friction solver did in the step (frictionless: iterations 0, converged).
struct StepStats {
  long iterations = 0;
  bool converged = true;
};

class Model {
 public:
  explicit Model(const ModelSpec& spec);  // throws std::runtime_error with Siconos' message
  ~Model();
  // Each contact's impulses over a step: normal (>= 0, pushing apart) and, with friction,
  // tangential along +T and (FrictionContact(3)) along +T2.
  struct Impulses {
    double* normal;
    double* tangential;
    double* tangential2;
  };
  // Advances one step of h and writes the new q, v (ndof each) and the step's impulses.
  StepStats step(double* q, double* v, const Impulses& impulses);

 private:
  void read(double* q, double* v, const Impulses& impulses) const;

  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nsb::siconos
