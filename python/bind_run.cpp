// nsbench._run (nsbench.run wraps it) and nsbench.check: a run and the conformance checks, in C++
// with the GIL released.
//
// A run goes through the command line's code (run/run_case.hpp, run/run.hpp):
// the same names, the same routing of parameters, the same checks and messages, the same
// series. The series' values are moved into the NumPy array (no copy); the states (u and v at
// every sample) are gathered by a StateSink. The summary is the command line's summary.json.
#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <signal.h>

#include <csignal>

#include "check/conformance.hpp"
#include "integrators/registry.hpp"
#include "run/run_case.hpp"
#include "problems/registry.hpp"
#include "python/bindings.hpp"

namespace nsb::python {

using namespace pybind11::literals;

namespace {

// The keyword arguments of nsbench.run that are run options; the others are parameters.
const std::vector<std::string> kRunOptions = {"sample_every", "max_force_evaluations", "states"};

// u and v at every sample, row after row.
class StateRows final : public StateSink {
 public:
  void state(const State& s, const Vec&, const Vec&, const Vec&) override {
    t.push_back(s.t);
    u.insert(u.end(), s.u.data(), s.u.data() + s.u.size());
    v.insert(v.end(), s.v.data(), s.v.data() + s.v.size());
  }
  std::vector<double> t, u, v;
};

// Ctrl-C during a run: Python's own handler only sets a flag that the run, without the GIL,
// never reads. While a run on the main thread lasts (Python's SIGINT handler being the default
// one), this handler sets the run's interrupt flag instead: the run stops between two steps and
// nsbench.run raises KeyboardInterrupt.
volatile std::sig_atomic_t interrupted = 0;
void on_sigint(int) { interrupted = 1; }

class SigintScope {
 public:
  SigintScope() {
    const py::module_ signal = py::module_::import("signal");
    const bool main_thread = py::module_::import("threading").attr("current_thread")().is(
        py::module_::import("threading").attr("main_thread")());
    if (!main_thread || !signal.attr("getsignal")(signal.attr("SIGINT")).is(signal.attr("default_int_handler"))) return;
    interrupted = 0;
    struct sigaction mine {};
    mine.sa_handler = on_sigint;
    sigemptyset(&mine.sa_mask);
    installed_ = ::sigaction(SIGINT, &mine, &previous_) == 0;
  }
  ~SigintScope() {
    if (installed_) ::sigaction(SIGINT, &previous_, nullptr);
  }
  SigintScope(const SigintScope&) = delete;
  SigintScope& operator=(const SigintScope&) = delete;
  const volatile std::sig_atomic_t* flag() const { return installed_ ? &interrupted : nullptr; }

 private:
  struct sigaction previous_ {};
  bool installed_ = false;
};

// A rows x cols array owning `values` (moved, not copied).
py::array_t<double> owned_array(std::vector<double>&& values, std::size_t rows, std::size_t cols) {
  auto* heap = new std::vector<double>(std::move(values));
  py::capsule owner(heap, [](void* p) { delete static_cast<std::vector<double>*>(p); });
  return py::array_t<double>({rows, cols}, heap->data(), owner);
}

long integer_option(const py::dict& options, const char* key, long fallback, long lower) {
  if (!options.contains(key)) return fallback;
  const std::string text = value_text(key, options[key]);
  const double x = parse_real(text, key);
  if (x < lower || x != static_cast<long>(x) || x > 1e15)
    throw InputError(fmt::format("{} {}: must be an integer >= {}", key, text, lower));
  return static_cast<long>(x);
}

// problem: a name (its parameters among kwargs) or a Problem already built (then kwargs hold
// the integrator's parameters only).
py::tuple run_case(const py::object& problem, const std::string& integrator, const py::object& dt, const py::object& t_end,
                   const py::kwargs& kwargs) {
  py::dict options, parameters;
  for (const auto& [key, value] : kwargs) {
    const auto k = key.cast<std::string>();
    (std::find(kRunOptions.begin(), kRunOptions.end(), k) != kRunOptions.end() ? options : parameters)[key] = value;
  }
  const std::vector<std::string> sets = assignments(parameters);
  RunCase c;
  const Problem* p = nullptr;
  if (py::isinstance<Problem>(problem)) {
    p = &problem.cast<const Problem&>();
    const auto routed = route_overrides(sets, find_problem(p->name()).parameters(), find_integrator(integrator).parameters());
    if (!routed.problem.empty())
      throw InputError(fmt::format("{}: a parameter of the problem, given with a Problem already built: pass the "
                                   "problem's name instead, or build the Problem with it",
                                   routed.problem.begin()->first));
    c.integrator = make_integrator(integrator, routed.integrator);
  } else {
    if (!py::isinstance<py::str>(problem))
      throw InputError(fmt::format("problem: {} given; valid: a problem's name (str) or an nsbench.Problem",
                                   py::str(py::type::of(problem).attr("__name__")).cast<std::string>()));
    c = make_run_case(problem.cast<std::string>(), integrator, sets);
    p = c.problem.get();
  }
  RunOptions o = parse_run_options(value_text("dt", dt), value_text("t_end", t_end),
                                   options.contains("sample_every") ? value_text("sample_every", options["sample_every"]) : "1",
                                   OptionStyle::Python);
  o.max_force_evaluations = integer_option(options, "max_force_evaluations", 0, 0);
  if (options.contains("states") && !py::isinstance<py::bool_>(options["states"]))
    throw InputError(fmt::format("states {}: valid: True or False", py::repr(options["states"]).cast<std::string>()));
  const bool states = options.contains("states") ? options["states"].cast<bool>() : true;
  if (c.integrator->conditionally_stable() && o.dt > p->stable_step())
    if (PyErr_WarnEx(PyExc_RuntimeWarning,
                 fmt::format("dt {} is above the stable step {:.4g} of {} for {} (ratio {:.3g}): expect a blow-up", o.dt,
                             p->stable_step(), p->name(), c.integrator->name(), o.dt / p->stable_step()).c_str(), 1) < 0)
      throw py::error_already_set();  // warnings turned into errors
  StateRows rows;
  if (states) o.state_sink = &rows;
  RunResult result;
  {
    const SigintScope sigint;
    o.interrupt = sigint.flag();
    try {
      py::gil_scoped_release free;  // a Python integrator takes it back for its own calls
      c.integrator->init(*p, p->initial_state());
      result = run(*p, *c.integrator, o);
    } catch (const RunCancelled&) {
      throw py::error_already_set();  // the step's KeyboardInterrupt or SystemExit, restored by it
    }
  }
  if (result.status == RunStatus::Interrupted && o.interrupt) {
    PyErr_SetNone(PyExc_KeyboardInterrupt);
    throw py::error_already_set();
  }
  const std::string summary = summary_to_json(*p, *c.integrator, o, result);
  const std::size_t ncol = result.series.columns.size(), n = static_cast<std::size_t>(p->ndof());
  const std::size_t nrow = result.series.rows(), nstate = rows.t.size();
  return py::make_tuple(result.series.columns, owned_array(std::move(result.series.values), nrow, ncol),
                        owned_array(std::move(rows.t), nstate, 1), owned_array(std::move(rows.u), nstate, n),
                        owned_array(std::move(rows.v), nstate, n), summary);
}

py::list check(const std::optional<std::string>& integrator, const std::optional<std::string>& problem) {
  if (!integrator && !problem) throw InputError("check: give integrator=NAME or problem=NAME (or both)");
  std::vector<std::pair<std::string, std::vector<CheckVerdict>>> checked;
  {
    py::gil_scoped_release free;
    if (integrator) checked.emplace_back("integrator " + *integrator, check_integrator(find_integrator(*integrator)));
    if (problem) checked.emplace_back("problem " + *problem, check_problem(find_problem(*problem)));
  }
  py::list list;
  for (const auto& [what, verdicts] : checked)
    for (const auto& v : verdicts)
      list.append(py::dict("subject"_a = what, "property"_a = v.property, "outcome"_a = outcome_name(v.outcome),
                           "figure"_a = v.figure));
  return list;
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("_run", &run_case, "problem"_a, "integrator"_a, "dt"_a, "t_end"_a,
        "nsbench.run's C++ side: (columns, series rows x columns, state times, u, v, summary JSON).");
  m.def("check", &check, "integrator"_a = py::none(), "problem"_a = py::none(),
        "The conformance checks of `nsbench check` (check/conformance.hpp): a list of dicts with\n"
        "subject, property, outcome ('pass', 'FAIL', 'not measured') and figure.");
}

}  // namespace nsb::python
