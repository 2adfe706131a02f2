#pragma once
// Semi-discrete non-smooth mechanical system (docs/method.md section 1):
//
//     M U'' + F_int(U) = F_ext(t) + L^T lambda
//     g(U) = g0 + L U                       (one row of L per contact; g >= 0 is open)
//                                           (or g(U), L(U) = dg/dU: contacts_move() below)
//     Signorini:  0 <= g  _|_  lambda >= 0
//     Newton impact law on closing contacts:  0 <= Lambda  _|_  g'(+) + e g'(-) >= 0
//
// Sign convention of this suite: g >= 0 open, g' = L M^{-1} P, a positive impulse pushes
// the bodies apart (the talk uses the opposite sign of L).
//
// A Problem is pure data and physics: it knows nothing of time integration. Integrators
// see only this interface, so any integrator runs any problem.
//
// The contract (a plugin's problem follows it; `nsbench check --problem NAME` tests it):
// a constructor from its validated Params (a static parameters_spec() declares them, with
// ranges); mass_matrix() n x n symmetric, positive semi-definite (a zero diagonal entry is a
// massless dof); internal_force(u, f) writes F_int(u) into f (no allocation: it runs every
// step), tangent_stiffness its Jacobian, strain_energy V_int with F_int = dV_int/du, and
// load_potential -F_ext . u for a constant load; contacts() describes every contact once
// (Contacts below; check_contacts() holds its shapes and ranges) and keeps g0 + L U0 >= 0;
// stable_step() the explicit central-difference limit 2 / omega_max. Where the solution is
// known exactly (derived and tested on its own), exact() hands out its ExactSolution
// (problems/exact_solution.hpp: the state at t, impact times, event times). Its output is the
// ProblemOutput it inherits (problems/problem_output.hpp): observable_names() and observe()
// for the series, summary_values(); field_mesh() describes the bodies once as a mesh
// (FieldMesh: bar and plane elements, springs, point masses and rigid bodies as vertices);
// cell_stress(u, out) writes each element's stress and body_data(s, out) each vertex body's
// arrays (no allocation: `nsbench run --fields` calls them at every written step). Every
// built-in problem has a mesh; a plugin's problem that keeps the default (none) has no field
// output.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <optional>
#include <string>
#include <vector>

#include "core/parameters.hpp"
#include "problems/exact_solution.hpp"
#include "problems/problem_output.hpp"
#include "problems/state.hpp"

namespace nsb {

// Every contact of a problem, described once (docs/method.md sections 1 and 6); row i of each
// operator belongs to contact i:
//
//     normal gap   g_i   = g0_i + L_i U          (>= 0 open; g'_i = L_i M^{-1} P)
//     slip rate    u_T,i = T_i M^{-1} P - w_i    (w_i: the obstacle's own tangential velocity,
//                                                 0 for a fixed floor)
//     impulses     Lambda_N,i >= 0 along +L_i (pushes apart), Lambda_T,i along +T_i
//     Newton       0 <= Lambda_N  _|_  g'(+) + e g'(-) >= 0   (no tangential restitution)
//     Coulomb      |Lambda_T,i| <= mu_i Lambda_N,i;  < : u_T,i(+) = 0 (stick);
//                  = : u_T,i(+) Lambda_T,i <= 0 (the slip opposes the impulse)
//
// A frictionless problem leaves `tangent`, `mu` and `tangent_velocity` empty (mu = 0 on every
// contact), which every scheme treats exactly as before friction existed.
//
// 3D contacts (docs/three_d.md, the cone): a second tangent row per contact, T2 (p x n), with
// the obstacle's velocity w2 along it; the slip is u_T,i = (T_i, T2_i) M^{-1} P - (w_i, w2_i)
// in R^2, the tangential impulse Lambda_T,i = (Lambda_T1, Lambda_T2) along (+T_i, +T2_i), and
//     Coulomb cone  |Lambda_T,i| <= mu_i Lambda_N,i;  < : u_T,i(+) = 0 (stick);
//                   = : Lambda_T,i = -mu_i Lambda_N,i u_T,i(+) / |u_T,i(+)| (maximal dissipation).
// A 2D problem leaves `tangent2` and `tangent2_velocity` empty and pays nothing; a scheme runs
// a problem with the cone (has_cone()) only when it declares the capability "3D friction cone"
// (integrators/capabilities.hpp).
struct Contacts {
  SpMat normal;             // L (p x n)
  Vec gap_offset;           // g0 (p)
  double restitution = 0.0; // e in [0, 1]
  SpMat tangent;            // T (p x n), or 0 rows when frictionless
  Vec mu;                   // (p) friction coefficients >= 0, or empty
  Vec tangent_velocity;     // w (p), or empty
  SpMat tangent2;           // T2 (p x n): 3D contacts' second tangent row, or 0 rows (2D)
  Vec tangent2_velocity;    // w2 (p), or empty

  Index size() const { return normal.rows(); }
  // True when some contact has mu > 0: only then does a scheme need to treat friction.
  bool has_friction() const { return mu.size() > 0 && mu.maxCoeff() > 0.0; }
  double max_mu() const { return mu.size() > 0 ? mu.maxCoeff() : 0.0; }
  // True when the contacts are 3D (a second tangent row) and some has mu > 0: the cone.
  bool has_cone() const { return tangent2.rows() > 0 && has_friction(); }
  // Sets T, mu (the same on every contact) and w (the same on every contact).
  void set_friction(SpMat tangent_rows, double mu_all, double w_all);
  // The same for 3D contacts: T, T2, mu (the same on every contact), w = w2 = 0.
  void set_cone(SpMat tangent_rows, SpMat tangent2_rows, double mu_all);
};

// Contacts whose geometry moves with the bodies (docs/contacts.md): the gaps g(U), normal
// rows L(U) = dg/dU and tangent rows T(U) at one configuration, as a scheme reads them:
//
//     g'_i = L_i(U) M^{-1} P,   u_T,i = T_i(U) M^{-1} P - w_i   (velocities stay linear)
//
// Storage allocated once (Problem::contact_geometry) and refilled, values only, by
// Problem::evaluate_contacts at every configuration a scheme evaluates: the rows keep the
// sparsity pattern of contacts() (every entry that is nonzero at some configuration is
// stored), so an evaluation allocates nothing. Row-major: schemes read contacts by row.
using RowSpMat = Eigen::SparseMatrix<double, Eigen::RowMajor>;
struct ContactGeometry {
  Vec gap;          // g(U) (p)
  RowSpMat normal;  // L(U) (p x n)
  RowSpMat tangent; // T(U) (p x n), or 0 rows when frictionless
  RowSpMat tangent2; // T2(U) (p x n), or 0 rows (2D contacts)
};

// Throws InputError naming `problem` when the operators' shapes disagree (rows of T, sizes of
// g0, mu and w against L's rows, columns against ndof) or a value is outside its range.
void check_contacts(const Contacts& c, Index ndof, const std::string& problem);

class Problem;

// Throws InputError naming `problem` where the contract is broken in a way cheap to see once,
// when a scheme binds (Integrator::bind): M (`mass`) not symmetric (to 1e-12 of its largest
// entry), a diagonal entry negative or not finite, a contact closed at `initial` (a gap below
// -1e-9 (1 + |g0|) m: penetrating before the first step).
void check_problem_contract(const Problem& problem, const SpMat& mass, const State& initial);

// The model. Its output (observables, summary figures, field mesh) is the ProblemOutput it
// inherits (problems/problem_output.hpp); its exact solution is a separate interface that
// exact() hands out (problems/exact_solution.hpp).
class Problem : public ProblemOutput {
 public:
  Problem() = default;
  // A copy's 0.1.0 exact-solution view is its own (it reads the copy).
  Problem(const Problem& other) : ProblemOutput(other), legacy_exact_(this, other.legacy_exact_.enabled) {}
  Problem& operator=(const Problem& other) {
    ProblemOutput::operator=(other);
    legacy_exact_.enabled = other.legacy_exact_.enabled;
    return *this;
  }
  virtual ~Problem() = default;

  virtual std::string name() const = 0;
  // The validated parameters this instance was built with (written to every summary).
  virtual const Params& parameters() const = 0;
  virtual Index ndof() const = 0;

  // Mass matrix (n x n). Lumped and singular models are diagonal; a diagonal entry may be
  // zero for a massless dof (singular mass), which integrators must treat quasi-statically.
  virtual SpMat mass_matrix() const = 0;

  // Internal force F_int(u), written into f (size n) without allocating.
  virtual void internal_force(ConstVecRef u, VecRef f) const = 0;
  // Tangent stiffness dF_int/du at u. When K already holds this problem's sparsity pattern
  // (from an earlier call) only the values are refilled.
  virtual void tangent_stiffness(ConstVecRef u, SpMat& K) const = 0;
  // True when F_int(u) = K u with K independent of u (then K can be factorised once).
  virtual bool is_linear() const = 0;
  // Total external force at time t, written into f (size n).
  virtual void external_force(double t, VecRef f) const = 0;
  // True when F_ext does not depend on t (integrators may then evaluate it once).
  virtual bool external_force_is_constant() const { return true; }

  virtual double strain_energy(ConstVecRef u) const = 0;
  // Potential of the conservative part of F_ext (gravity); F_ext = -dV_load/du for it.
  virtual double load_potential(ConstVecRef u) const = 0;
  double potential(ConstVecRef u) const { return strain_energy(u) + load_potential(u); }
  // [J] what energy errors are relative to when the initial energy E0 is 0 (a body released
  // from rest where the potential is zero, as the bouncing bar); 0: none (the error is NaN).
  // energy_scale_text() says what it is, for the run's summary.
  virtual double energy_scale() const { return 0.0; }
  virtual std::string energy_scale_text() const { return "none"; }

  // The contacts (normal and tangent rows, gaps, restitution, friction); see Contacts.
  virtual const Contacts& contacts() const = 0;
  // Shorthands: L (p x n), g0 (size p), Newton restitution coefficient e in [0, 1].
  const SpMat& gap_operator() const { return contacts().normal; }
  const Vec& gap_offset() const { return contacts().gap_offset; }
  double restitution() const { return contacts().restitution; }
  Index ncontacts() const { return contacts().size(); }
  // True when the contacts follow the configuration: g(U) is not g0 + L U with L and T fixed
  // (a rigid body's corner turning with it). contacts() then holds the rows at the initial
  // configuration U0 (L(U0), T(U0)) with the pattern of every configuration, and
  // g0 = g(U0) - L(U0) U0 (g0 + L U is the gap linearised at U0); the schemes that treat
  // moving contacts (capability "moving contacts", integrators/capabilities.hpp) read the
  // contacts through evaluate_contacts instead, the others decline such a problem. False
  // (constant kinematics): evaluate_contacts is never needed and nothing changes.
  virtual bool contacts_move() const { return false; }
  // Writes g(u), L(u) and T(u) into `out` (storage from contact_geometry()), values only,
  // without allocating. The default, for constant kinematics: gap = g0 + L u, rows left as
  // contact_geometry() set them. A problem whose contacts move overrides it.
  virtual void evaluate_contacts(ConstVecRef u, ContactGeometry& out) const;
  // Storage for evaluate_contacts: the rows of contacts() (row-major) and a gap of size p.
  ContactGeometry contact_geometry() const;
  // Where the contact points are, for `nsbench check --problem` (no scheme needs it): row i of
  // `x` (p x 3: x, y, z; z = 0 in 2D) the position at u of the material point of the body that
  // touches at u_at on contact i. Its velocity dx_i/du U' is what the laws see: T_i U' and
  // T2_i U' must be its components along two orthonormal tangents orthogonal to the normal
  // direction of L_i (docs/contacts.md), which the check tests by differences of x_i, with no
  // need for T = ds/du (on a curved 3D obstacle no orthonormal pair of tangents is a pair of
  // gradients). False (the default): not given; the check then tests T = ds/du (contact_slide).
  virtual bool contact_points(ConstVecRef /*u_at*/, ConstVecRef /*u*/, Eigen::Ref<Eigen::MatrixXd> /*x*/) const {
    return false;
  }
  // Tangential coordinates s(u) (size p) with T(u) = ds/du, written into s: what the check
  // differentiates to test T(U) when contact_points is not given (integrable tangents: a flat
  // obstacle, 2D). The default, for constant kinematics: T u.
  virtual void contact_slide(ConstVecRef u, VecRef s) const;
  // The same along the second tangent of 3D contacts: s2(u) with T2(u) = ds2/du (the default,
  // for constant kinematics: T2 u).
  virtual void contact_slide2(ConstVecRef u, VecRef s2) const;

  virtual State initial_state() const = 0;
  // Largest stable step of the explicit central-difference scheme, 2 / omega_max (an
  // estimate, from the largest eigenvalue of M^{-1} K).
  virtual double stable_step() const = 0;
  // The same at configuration u, for schemes that follow a changing tangent (nonlinear
  // problems override it; a linear problem's stable step does not depend on u).
  virtual double stable_step_at(ConstVecRef /*u*/) const { return stable_step(); }

  // The exact solution where one is known (problems/exact_solution.hpp), nullptr otherwise;
  // it lives as long as the problem. The default: none, or the view of a 0.1.0 plugin's
  // exact_state() and impact_times() below.
  virtual const ExactSolution* exact() const { return legacy_exact_.enabled ? &legacy_exact_ : nullptr; }

  // 0.1.0's exact-solution functions, kept one minor version for plugins that override them
  // (deprecated, problems/plugin_compat.hpp: hand out an ExactSolution from exact()). The
  // built-ins never do. A class that is both a Problem and its own ExactSolution and does not
  // override impact_times says `using ExactSolution::impact_times;` (two bases, one name).
  virtual std::optional<State> exact_state(double /*t*/) const { return std::nullopt; }
  virtual std::vector<double> impact_times(double /*t_end*/) const { return {}; }

 private:
  template <class Base, class T>
  friend struct PluginCompat;
  // exact() of a 0.1.0 plugin: its exact_state() and impact_times() as an ExactSolution.
  struct LegacyExact final : ExactSolution {
    LegacyExact(const Problem* owner, bool on) : problem(owner), enabled(on) {}
    std::optional<State> state(double t) const override { return problem->exact_state(t); }
    std::vector<double> impact_times(double t_end) const override { return problem->impact_times(t_end); }
    const Problem* problem;
    bool enabled;
  };
  LegacyExact legacy_exact_{this, false};
};

// The diagonal of M when M is diagonal; nullopt otherwise.
std::optional<Vec> diagonal_mass(const SpMat& M);

}  // namespace nsb

#include "problems/plugin_compat.hpp"
