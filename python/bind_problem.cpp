// nsbench.Problem, nsbench.State: a problem built by name with its parameters, its operators as
// NumPy arrays and scipy.sparse matrices (problems/problem.hpp says what each one is).
#include <fmt/format.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "problems/registry.hpp"
#include "python/bindings.hpp"

namespace nsb::python {

using namespace pybind11::literals;

py::object to_scipy(const SpMat& matrix) {
  SpMat m = matrix;
  m.makeCompressed();
  const auto nnz = m.nonZeros();
  py::array_t<double> data(nnz, m.valuePtr());
  py::array_t<int> indices(nnz, m.innerIndexPtr());
  py::array_t<int> indptr(m.outerSize() + 1, m.outerIndexPtr());
  return py::module_::import("scipy.sparse")
      .attr("csc_matrix")(py::make_tuple(data, indices, indptr), "shape"_a = py::make_tuple(m.rows(), m.cols()));
}

py::array_t<double> vector_view(Vec& v, const py::handle& owner) { return py::array_t<double>(v.size(), v.data(), owner); }

namespace {

// Copies `values` into v, whose size stays (a state's vectors have the problem's ndof).
void assign(Vec& v, const Eigen::Ref<const Vec>& values, const char* what) {
  if (values.size() != v.size())
    throw InputError(fmt::format("{}: {} values given, the state has {}", what, values.size(), v.size()));
  v = values;
}

void check_size(const Problem& p, Index size, const char* what) {
  if (size != p.ndof()) throw InputError(fmt::format("{}: {} values given, {} has ndof = {}", what, size, p.name(), p.ndof()));
}

std::unique_ptr<Problem> make(const std::string& name, const py::kwargs& kwargs) {
  std::map<std::string, std::string> overrides;
  for (const auto& [key, value] : kwargs) overrides[key.cast<std::string>()] = value_text(key.cast<std::string>(), value);
  return make_problem(name, overrides);
}

// Rows of `rows`, or p x n zeros where a problem leaves them empty (frictionless, 2D).
py::object rows_or_zeros(const SpMat& rows, Index p, Index n) { return to_scipy(rows.rows() ? rows : SpMat(p, n)); }
Vec values_or_zeros(const Vec& values, Index p) { return values.size() ? values : Vec(Vec::Zero(p)); }

py::dict contacts_dict(const Contacts& c) {
  const Index p = c.size(), n = c.normal.cols();
  return py::dict("L"_a = to_scipy(c.normal), "g0"_a = Vec(c.gap_offset), "e"_a = c.restitution,
                  "T"_a = rows_or_zeros(c.tangent, p, n), "mu"_a = values_or_zeros(c.mu, p),
                  "w"_a = values_or_zeros(c.tangent_velocity, p), "T2"_a = rows_or_zeros(c.tangent2, p, n),
                  "w2"_a = values_or_zeros(c.tangent2_velocity, p), "cone"_a = c.has_cone());
}

// g(u), L(u), T(u), T2(u) of a problem whose contacts move (Problem::evaluate_contacts); for
// constant kinematics the same as g0 + L u and the constant rows.
py::dict contact_geometry_dict(const Problem& p, const Eigen::Ref<const Vec>& u) {
  check_size(p, u.size(), "u");
  ContactGeometry at = p.contact_geometry();
  p.evaluate_contacts(u, at);
  const Index m = p.ncontacts(), n = p.ndof();
  return py::dict("g"_a = Vec(at.gap), "L"_a = to_scipy(SpMat(at.normal)), "T"_a = rows_or_zeros(SpMat(at.tangent), m, n),
                  "T2"_a = rows_or_zeros(SpMat(at.tangent2), m, n));
}

// The exact solution's events and values by name (problems/exact_solution.hpp, ExactEvent and
// ExactValue): what a study compares a run's stop, onset or first rebound against.
template <class E>
E named(const std::vector<std::pair<const char*, E>>& names, const std::string& name, const char* what) {
  std::vector<std::string> valid;
  for (const auto& [n, e] : names) {
    if (name == n) return e;
    valid.push_back(n);
  }
  throw InputError(fmt::format("{} '{}': unknown; valid: {}", what, name, fmt::join(valid, ", ")));
}

const std::vector<std::pair<const char*, ExactEvent>> kExactEvents = {
    {"contact_start", ExactEvent::contact_start}, {"slip_stop", ExactEvent::slip_stop}, {"rest", ExactEvent::rest},
    {"roll_onset", ExactEvent::roll_onset}, {"jam", ExactEvent::jam}};
const std::vector<std::pair<const char*, ExactValue>> kExactValues = {
    {"contact_duration", ExactValue::contact_duration}, {"stop_distance", ExactValue::stop_distance},
    {"stays_stopped", ExactValue::stays_stopped}, {"first_rebound_speed", ExactValue::first_rebound_speed},
    {"impact_ratio", ExactValue::impact_ratio}, {"housner_ratio", ExactValue::housner_ratio},
    {"wave_time", ExactValue::wave_time}};

}  // namespace

void bind_problem(py::module_& m) {
  py::class_<State>(m, "State", "Displacement u and velocity v (NumPy views, writable) at time t.")
      .def(py::init<>())
      .def_property("t", [](const State& s) { return usable(s).t; }, [](State& s, double t) { usable(s).t = t; })
      .def_property("u", [](py::object self) { return vector_view(usable(self.cast<State&>()).u, self); },
                    [](State& s, const Eigen::Ref<const Vec>& x) { assign(usable(s).u, x, "u"); })
      .def_property("v", [](py::object self) { return vector_view(usable(self.cast<State&>()).v, self); },
                    [](State& s, const Eigen::Ref<const Vec>& x) { assign(usable(s).v, x, "v"); })
      .def("__repr__", [](const State& s) { return fmt::format("State(t={}, ndof={})", usable(s).t, s.u.size()); });

  py::class_<Problem>(m, "Problem",
                      "A problem by name, its parameters as keyword arguments (as `--set` on the command line):\n"
                      "    nsbench.Problem('bouncing-bar', N=100)\n"
                      "ValueError for an unknown name or a parameter outside its range. Vectors are NumPy arrays,\n"
                      "matrices scipy.sparse.csc_matrix (copies).")
      .def(py::init(&make), "name"_a)
      .def_property_readonly("name", &Problem::name)
      .def_property_readonly("parameters", [](const Problem& p) {
        return typed_params(find_problem(p.name()).parameters(), p.parameters());
      }, "The parameters it was built with, defaults included.")
      .def_property_readonly("ndof", &Problem::ndof)
      .def("mass_matrix", [](const Problem& p) { return to_scipy(p.mass_matrix()); }, "M (n x n).")
      .def("tangent_stiffness", [](const Problem& p, const Eigen::Ref<const Vec>& u) {
        check_size(p, u.size(), "u");
        SpMat K;
        p.tangent_stiffness(u, K);
        return to_scipy(K);
      }, "u"_a, "dF_int/du at u.")
      .def_property_readonly("is_linear", &Problem::is_linear)
      .def_property_readonly("external_force_is_constant", &Problem::external_force_is_constant)
      .def("internal_force", [](const Problem& p, const Eigen::Ref<const Vec>& u, const py::object& out) -> py::object {
        check_size(p, u.size(), "u");
        if (out.is_none()) {
          Vec f(p.ndof());
          p.internal_force(u, f);
          return py::cast(std::move(f));
        }
        // Written in place (no allocation in a Python integrator's step): a float64 array, contiguous and writable.
        using Contiguous = py::array_t<double, py::array::c_style>;
        if (!py::isinstance<Contiguous>(out) || !out.cast<py::array>().writeable())
          throw InputError("out: a writable, contiguous float64 NumPy array is expected");
        auto a = py::reinterpret_borrow<Contiguous>(out);
        check_size(p, a.size(), "out");
        Eigen::Map<Vec> f(a.mutable_data(), a.size());
        p.internal_force(u, f);
        return py::none();
      }, "u"_a, "out"_a = py::none(),
           "F_int(u); written into `out` (a float64 array of size ndof) when given (then returns None).")
      .def("external_force", [](const Problem& p, double t) {
        Vec f(p.ndof());
        p.external_force(t, f);
        return f;
      }, "t"_a, "F_ext(t).")
      .def("strain_energy", [](const Problem& p, const Eigen::Ref<const Vec>& u) {
        check_size(p, u.size(), "u");
        return p.strain_energy(u);
      }, "u"_a, "V_int(u), F_int = dV_int/du.")
      .def("load_potential", [](const Problem& p, const Eigen::Ref<const Vec>& u) {
        check_size(p, u.size(), "u");
        return p.load_potential(u);
      }, "u"_a, "Potential of the constant load, -F_ext . u.")
      .def("kinetic_energy", [](const Problem& p, const Eigen::Ref<const Vec>& v) {
        check_size(p, v.size(), "v");
        return 0.5 * v.dot(p.mass_matrix() * v);
      }, "v"_a, "v^T M v / 2.")
      .def_property_readonly("contacts", [](const Problem& p) { return contacts_dict(p.contacts()); },
                             "dict: L (p x n, csc), g0, T (p x n, csc; zero without friction), mu, w (the obstacle's\n"
                             "tangential velocity), e (restitution); 3D contacts: T2 and w2 along the second tangent\n"
                             "(zero in 2D), cone (True when the Coulomb cone applies). Constant kinematics: the gap is\n"
                             "g = g0 + L u >= 0; where contacts_move, the rows at the initial configuration\n"
                             "(evaluate_contacts gives them at any u).")
      .def_property_readonly("contacts_move", &Problem::contacts_move,
                             "True when the contacts follow the configuration (g(u), L(u), T(u) not constant).")
      .def("evaluate_contacts", &contact_geometry_dict, "u"_a,
           "dict: g (the gaps g(u)), L, T and T2 (p x n, csc; zero where a problem has none) at u.")
      .def("initial_state", &Problem::initial_state)
      .def("stable_step", &Problem::stable_step, "2 / omega_max of the explicit central-difference scheme.")
      .def("exact_state", [](const Problem& p, double t) { return p.exact() ? p.exact()->state(t) : std::nullopt; }, "t"_a,
           "The exact State at t (the problem's exact solution), or None where none is known.")
      .def("impact_times", [](const Problem& p, double t_end) {
        return p.exact() ? p.exact()->impact_times(t_end) : std::vector<double>{};
      }, "t_end"_a, "Exact impact times in [0, t_end] where known (the problem's exact solution).")
      .def("exact_event", [](const Problem& p, const std::string& name) {
        const ExactEvent e = named(kExactEvents, name, "exact_event");
        return p.exact() ? p.exact()->event_time(e) : std::nullopt;
      }, "name"_a,
           "The exact time of an event (contact_start, slip_stop, rest, roll_onset, jam): inf when the solution\n"
           "knows it never happens, None where it does not time it (or no exact solution is known).")
      .def("exact_value", [](const Problem& p, const std::string& name) {
        const ExactValue v = named(kExactValues, name, "exact_value");
        return p.exact() ? p.exact()->value(v) : std::nullopt;
      }, "name"_a,
           "An exact scalar (contact_duration, stop_distance, stays_stopped, first_rebound_speed, impact_ratio,\n"
           "housner_ratio, wave_time), None where the solution does not define it.")
      .def_property_readonly("observables", &Problem::observable_names, "The problem's own columns of a run's series.")
      .def("__repr__", [](const Problem& p) { return fmt::format("Problem('{}', ndof={})", p.name(), p.ndof()); });
}

}  // namespace nsb::python
