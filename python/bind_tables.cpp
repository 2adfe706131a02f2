// nsbench.study's tables: the C++ Table, Column and Figure (studies/table.hpp), written by the
// same writers as every study's (CSV, Markdown, LaTeX, with their stamps and footnotes), and
// the measures library's functions of a run's numbers (studies/measures.hpp, hausdorff.hpp,
// ranking.hpp) on NumPy arrays. A study written in Python returns these tables; the driver
// writes them into the report and --verify reads them back (studies/verify.hpp).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "python/bindings.hpp"
#include "studies/hausdorff.hpp"
#include "studies/measures.hpp"
#include "studies/ranking.hpp"
#include "studies/table.hpp"
#include "studies/verify.hpp"

namespace nsb::python {

using namespace pybind11::literals;

namespace {

// `value` with the fields named by the keyword arguments set (each a field the class binds: a
// misspelt one is a ValueError naming it): the constructors' keyword arguments.
template <class T>
T with_fields(const T& value, const py::kwargs& kwargs, const char* what) {
  py::object self = py::cast(value);
  for (const auto& [key, field] : kwargs) {
    if (!py::hasattr(self, key)) throw InputError(fmt::format("{}: no field '{}'", what, py::str(key).cast<std::string>()));
    self.attr(key) = field;
  }
  return self.cast<T>();
}

void bind_table_classes(py::module_& m) {
  py::class_<Column>(m, "Column", "A table's column (studies/table.hpp): name, unit, format (fmt spec), description, "
                                  "timing (skipped by --verify), interval (names of the low and high columns)")
      .def(py::init([](const std::string& name, const py::kwargs& kwargs) {
             return with_fields(Column{.name = name, .unit = "", .format = "{:.3e}", .description = ""}, kwargs, "Column");
           }), "name"_a)
      .def_readwrite("name", &Column::name)
      .def_readwrite("unit", &Column::unit)
      .def_readwrite("format", &Column::format)
      .def_readwrite("description", &Column::description)
      .def_readwrite("timing", &Column::timing)
      .def_readwrite("interval", &Column::interval);
  py::class_<Figure>(m, "Figure", "A figure scripts/figures.py draws from a table's CSV (studies/table.hpp)")
      .def(py::init([](const std::string& id, const py::kwargs& kwargs) {
             Figure f;
             f.id = id;
             return with_fields(f, kwargs, "Figure");
           }), "id"_a)
      .def_readwrite("id", &Figure::id).def_readwrite("title", &Figure::title).def_readwrite("x", &Figure::x)
      .def_readwrite("y", &Figure::y).def_readwrite("series", &Figure::series).def_readwrite("panels", &Figure::panels)
      .def_readwrite("log_x", &Figure::log_x).def_readwrite("log_y", &Figure::log_y).def_readwrite("slopes", &Figure::slopes)
      .def_readwrite("small_multiples", &Figure::small_multiples).def_readwrite("deviation", &Figure::deviation)
      .def_readwrite("overlay", &Figure::overlay).def_readwrite("caption", &Figure::caption);
  py::class_<Table>(m, "Table", "A study's table (studies/table.hpp): cells are None (n/a), float, int or str")
      .def(py::init([](const std::string& id, const py::kwargs& kwargs) {
             Table t;
             t.id = id;
             return with_fields(t, kwargs, "Table");
           }), "id"_a)
      .def_readwrite("id", &Table::id).def_readwrite("title", &Table::title).def_readwrite("caption", &Table::caption)
      .def_readwrite("columns", &Table::columns).def_readwrite("metadata", &Table::metadata)
      .def_readwrite("figures", &Table::figures).def_readwrite("csv_only", &Table::csv_only)
      .def_readwrite("headline", &Table::headline).def_readwrite("lead", &Table::lead)
      .def_readonly("rows", &Table::rows)
      .def("add_row", [](Table& t, std::vector<Cell> row) {
             if (row.size() != t.columns.size())
               throw InputError(fmt::format("table {}: a row of {} cells for {} columns", t.id, row.size(), t.columns.size()));
             t.add_row(std::move(row));
           }, "row"_a);
  m.def("to_csv", &to_csv, "table"_a);
  m.def("to_markdown", &to_markdown, "table"_a);
  m.def("to_latex", &to_latex, "table"_a);
  m.def("verify_table", [](const Table& t, const std::string& report_csv, double rtol, double atol) {
          const VerifyResult r = verify_table(t, report_csv, {rtol, atol});
          return py::make_tuple(r.cells_compared, r.differences);
        }, "table"_a, "report_csv"_a, "rtol"_a = 1e-9, "atol"_a = 0.0,
        "Compares a table with the CSV text of a report of it (studies/verify.hpp): (cells compared, differences).");
}

py::dict fit_dict(double value, double low, double high, int points, const char* name) {
  return py::dict(py::arg(name) = value, "low"_a = low, "high"_a = high, "points"_a = points);
}

Polyline polyline(const std::vector<double>& t, const std::vector<double>& x) {
  if (t.size() != x.size() || t.empty()) throw InputError(fmt::format("hausdorff: a graph of {} times and {} values", t.size(), x.size()));
  return {t, x};
}

void bind_measures(py::module_& m) {
  m.def("fit_line", [](const std::vector<double>& x, const std::vector<double>& y) {
          const LineFit f = fit_line(x, y);
          return fit_dict(f.slope, f.low, f.high, f.points, "slope");
        }, "x"_a, "y"_a, "Least squares y = a + b x with the 95% interval of b (studies/measures.hpp, fit_line).");
  m.def("fit_order", [](const std::vector<double>& h, const std::vector<double>& e) {
          const OrderFit f = fit_order(h, e);
          return fit_dict(f.order, f.low, f.high, f.points, "order");
        }, "h"_a, "errors"_a, "The convergence order in log-log with its 95% interval (studies/measures.hpp, fit_order).");
  m.def("drift_rule", [](const std::vector<double>& times, const std::vector<double>& envelope, double round_off) {
          const Drift d = drift_rule(times, envelope, round_off);
          return py::dict("drift"_a = d.drift, "low"_a = d.low, "high"_a = d.high, "over_run"_a = d.over_run,
                          "windows"_a = d.windows, "no_drift"_a = d.no_drift);
        }, "times"_a, "envelope"_a, "round_off"_a,
        "The drift rule on an envelope (studies/measures.hpp, drift_rule): the slope with its 95% interval, the drift over "
        "the run and the verdict; the energy-balance run measure's 'drift'.");
  m.def("observed_order", &observed_order, "h1"_a, "e1"_a, "h2"_a, "e2"_a);
  m.def("above_round_off", &above_round_off, "error"_a);
  m.def("compared_impacts", &compared_impacts, "exact"_a, "count"_a, "min_flight"_a);
  m.def("contact_phases", [](const std::vector<double>& t, const std::vector<double>& impulse, double min_flight) {
          if (t.size() != impulse.size()) throw InputError("contact_phases: t and impulse differ in length");
          ContactPhases phases(min_flight);
          for (std::size_t k = 0; k < t.size(); ++k) phases.add(t[k], impulse[k] > 0.0);
          return phases.starts();
        }, "t"_a, "impulse"_a, "min_flight"_a = 0.0,
        "The start times of the contact phases of a run's samples (ContactPhases, studies/measures.hpp): "
        "sample every step for the impact times.");
  m.def("hausdorff", [](const std::vector<double>& ta, const std::vector<double>& xa, const std::vector<double>& tb,
                        const std::vector<double>& xb, double time_scale, double value_scale) {
          return hausdorff(scaled(polyline(ta, xa), time_scale, value_scale), scaled(polyline(tb, xb), time_scale, value_scale));
        }, "t_a"_a, "x_a"_a, "t_b"_a, "x_b"_a, "time_scale"_a = 1.0, "value_scale"_a = 1.0,
        "The Hausdorff distance between the graphs (t, x) of two histories in scaled coordinates (studies/hausdorff.hpp).");
}

double number_or_nan(const py::dict& d, const char* key) {
  return d.contains(key) && !d[key].is_none() ? d[key].cast<double>() : kNaN;
}

// A ranking's problems from dicts: label, error_source, floor, targets and curves, each curve
// integrator, reference, peer and points (run, cost, error, removed, spread).
RankingProblem ranking_problem(const py::dict& d) {
  RankingProblem p{d["label"].cast<std::string>(), d["error_source"].cast<std::string>(),
                   d.contains("floor") ? d["floor"].cast<double>() : 0.0, d["targets"].cast<std::vector<double>>(), {}};
  for (const auto& c : d["curves"].cast<py::list>()) {
    const auto curve = c.cast<py::dict>();
    WorkCurve w{curve["integrator"].cast<std::string>(), curve.contains("reference") && curve["reference"].cast<bool>(), {},
                curve.contains("peer") && curve["peer"].cast<bool>()};
    for (const auto& q : curve["points"].cast<py::list>()) {
      const auto point = q.cast<py::dict>();
      w.points.push_back({point["run"].cast<std::string>(), number_or_nan(point, "cost"), number_or_nan(point, "error"),
                          point.contains("removed") ? point["removed"].cast<std::string>() : "", number_or_nan(point, "spread")});
    }
    p.curves.push_back(std::move(w));
  }
  return p;
}

void bind_ranking(py::module_& m) {
  m.def("ranking_table", [](const std::string& id, const std::string& title, const Column& error, const std::string& cost,
                            const py::list& problems) {
          std::vector<RankingProblem> ranked;
          for (const auto& p : problems) ranked.push_back(ranking_problem(p.cast<py::dict>()));
          return ranking_table(id, title, error, cost, ranked);
        }, "id"_a, "title"_a, "error"_a, "cost"_a, "problems"_a,
        "The headline ranking (studies/ranking.hpp): the cheapest integrator reaching each target error, ties said.\n"
        "problems: dicts of label, error_source, floor (0: exact), targets and curves; a curve: integrator,\n"
        "reference, peer (bools) and points, each run (its label), cost (CPU s), error, spread, removed (a rule's name).");
}

}  // namespace

void bind_tables(py::module_& m) {
  bind_table_classes(m);
  bind_measures(m);
  bind_ranking(m);
}

}  // namespace nsb::python
