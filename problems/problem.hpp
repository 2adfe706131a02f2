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
// stable_step() the explicit central-difference limit 2 / omega_max; exact_state() and
// impact_times() only where the solution is known exactly (derived and tested on its own).
// field_mesh() describes the bodies once as a mesh (FieldMesh below: bar and plane elements,
// springs, point masses and rigid bodies as vertices); cell_stress(u, out) writes each
// element's stress and body_data(s, out) each vertex body's arrays (no allocation: `nsbench
// run --fields` calls them at every written step). Every built-in problem has a mesh; a
// plugin's problem that keeps the default (none) has no field output.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "core/parameters.hpp"

namespace nsb {

using Vec = Eigen::VectorXd;
using SpMat = Eigen::SparseMatrix<double>;
using Index = Eigen::Index;
using VecRef = Eigen::Ref<Vec>;
using ConstVecRef = Eigen::Ref<const Vec>;

// Displacement and velocity at time t. Staggered schemes document what their `v` means.
struct State {
  double t = 0.0;
  Vec u;
  Vec v;
};

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

// A problem's bodies as a mesh, for field output (ParaView) and pictures of the fields.
// Displacement and velocity are point values taken from the dofs; element cells carry one
// value per cell and stress component, vertex cells the body arrays.
//
//     point a          reference position points.row(a) (z = 0, y = 0 for bars; 3D: x, y, z)
//     its component k  displacement u[point_dofs(a, k)], 0 where point_dofs(a, k) = -1 (a
//                      clamped node, a direction the body does not move in)
//     cell c           points cells(c, 0 ..), padded with -1 past its last point (cells has
//                      as many columns as the widest cell); its number of points is its type:
//                      1  a vertex: a point mass or the centre of a rigid body ("body cell")
//                      2  a line along +x of the reference: a bar element or a spring
//                      4  a bilinear quad, counter-clockwise: a plane element
//                      8  a hexahedron in VTK_HEXAHEDRON's (hex8_elements.hpp's) order: a solid
//                      cell_body[c] is its body id (0 when there is one body)
//     element cells    cells of 2, 4 or 8 points, in order: cell_stress() rows, a column per stress component
//     body cells       the vertex cells, in their order: body_data() writes one row each,
//                      the components of the body_arrays in order (e.g. a rigid body's angle)
//
// What the stress is (which measure, where in the cell) is stated by each problem's
// cell_stress(); what a body array is, by its body_data(). Vertex cells have no stress and
// element cells no body arrays: a field is written only where it means something
// (run/field_output.hpp writes the two kinds as two datasets of one series).
// A degree of freedom that is no translation of a point (a rigid body's rotation) reaches
// the picture through a body array, not through point_dofs (which maps components linearly
// to dofs).
struct FieldArray {
  std::string name;
  int components = 1;  // 1 (scalar) or 3 (a vector, x y z)
};

struct FieldMesh {
  int dimension = 1;                           // 1: along x (bars, chains); 2: in (x, y); 3: solids
  Eigen::MatrixXd points;                      // npoints x 2 (x 3 in 3D), reference coordinates
  Eigen::MatrixXi point_dofs;                  // npoints x dimension, dof of each component or -1
  Eigen::MatrixXi cells;                       // ncells x (widest cell), point indices, -1 padded
  std::vector<int> cell_body;                  // ncells, body id
  std::vector<std::string> stress_components;  // the columns of cell_stress()
  std::vector<FieldArray> body_arrays;         // the column groups of body_data()

  Index npoints() const { return points.rows(); }
  Index ncells() const { return cells.rows(); }
  // Number of points of cell c (1 vertex, 2 line, 4 quad, 8 hexahedron).
  int cell_size(Index c) const;
  // Number of element cells (cells of 2 or more points): the rows of cell_stress().
  Index nelements() const;
  // Number of vertex cells: the rows of body_data().
  Index nbodies() const { return ncells() - nelements(); }
  // Total components of the body arrays: the columns of body_data().
  int body_columns() const;
  // Appends `part` (a mesh of the same dimension, stress components and body arrays) with
  // its dofs shifted by dof_offset and its cells given body id `body`.
  void append(const FieldMesh& part, Index dof_offset, int body);
  // Appends a vertex cell (a point mass, a rigid body's centre) at reference position (x, y),
  // its components on `dofs` (dimension entries, -1 where fixed), of body `body`.
  void add_vertex(double x, double y, std::initializer_list<int> dofs, int body);
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

class Problem {
 public:
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
  // The contact points' tangential coordinates s(u) (size p) with T(u) = ds/du, written into s:
  // what `nsbench check --problem` differentiates to test T(U) (no scheme needs it). The
  // default, for constant kinematics: T u. A problem with moving contacts and friction
  // overrides it.
  virtual void contact_slide(ConstVecRef u, VecRef s) const;

  virtual State initial_state() const = 0;
  // Largest stable step of the explicit central-difference scheme, 2 / omega_max (an
  // estimate, from the largest eigenvalue of M^{-1} K).
  virtual double stable_step() const = 0;
  // The same at configuration u, for schemes that follow a changing tangent (nonlinear
  // problems override it; a linear problem's stable step does not depend on u).
  virtual double stable_step_at(ConstVecRef /*u*/) const { return stable_step(); }

  // Problem-specific columns of series.csv (e.g. q, v, q_exact for the bouncing mass).
  virtual std::vector<std::string> observable_names() const { return {}; }
  virtual void observe(const State& /*s*/, std::span<double> /*out*/) const {}
  // The same columns after a step, for those that need the step's contact impulses (size p)
  // and its length dt (0 for the initial sample), e.g. a contact force impulse / dt. The
  // run driver calls this one; the default forwards to observe().
  virtual void observe_step(const State& s, const Vec& /*impulses*/, double /*dt*/, std::span<double> out) const {
    observe(s, out);
  }

  // Problem-specific figures of a run's summary.json (its "problem_summary" object, written
  // only when this is not empty), e.g. an exact event time; a non-finite value is written null.
  virtual std::vector<std::pair<std::string, double>> summary_values() const { return {}; }

  // The bodies' mesh (FieldMesh), for problems that describe one; nullopt otherwise.
  virtual std::optional<FieldMesh> field_mesh() const { return std::nullopt; }
  // The stress of each element cell of field_mesh() at u, written into out (nelements() x
  // stress_components.size()) without allocating. Only called when field_mesh() has a value.
  virtual void cell_stress(ConstVecRef /*u*/, Eigen::Ref<Eigen::MatrixXd> /*out*/) const {}
  // The body arrays of each vertex cell of field_mesh() in state s, written into out
  // (nbodies() x body_columns()) without allocating. Only called when body_arrays is not empty.
  virtual void body_data(const State& /*s*/, Eigen::Ref<Eigen::MatrixXd> /*out*/) const {}

  // Exact solution where one is known.
  virtual std::optional<State> exact_state(double /*t*/) const { return std::nullopt; }
  // Exact times of the impacts in [0, t_end], in order, where the problem knows them
  // (impact-time errors of study files); empty otherwise.
  virtual std::vector<double> impact_times(double /*t_end*/) const { return {}; }
};

// The diagonal of M when M is diagonal; nullopt otherwise.
std::optional<Vec> diagonal_mass(const SpMat& M);

}  // namespace nsb
