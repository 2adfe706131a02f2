// nsbench.problems(), nsbench.integrators(): what `nsbench list` prints, as data; nsbench.load_plugin();
// nsbench.Parameter, the declaration of a parameter (a Python integrator's, register_integrator).
#include <fmt/format.h>
#include <pybind11/stl.h>

#include "core/plugin.hpp"
#include "integrators/registry.hpp"
#include "problems/registry.hpp"
#include "python/bindings.hpp"
#include "studies/run_measure.hpp"

namespace nsb::python {

using namespace pybind11::literals;

py::object typed_value(const ParamSpec& spec, const std::string& text) {
  if (text.empty()) return py::none();
  switch (spec.kind) {
    case ParamSpec::Kind::Real: return py::float_(parse_real(text, spec.name));
    case ParamSpec::Kind::Integer: return py::int_(std::stol(text));
    case ParamSpec::Kind::Choice: return py::str(text);
  }
  return py::none();
}

py::dict typed_params(const ParamSpecs& specs, const Params& params) {
  py::dict d;
  for (const auto& s : specs) d[py::str(s.name)] = typed_value(s, params.values().at(s.name));
  return d;
}

std::string value_text(const std::string& key, const py::handle& value) {
  if (py::isinstance<py::bool_>(value) || !(py::isinstance<py::float_>(value) || py::isinstance<py::int_>(value) ||
                                            py::isinstance<py::str>(value) || py::hasattr(value, "__float__")))
    throw InputError(fmt::format("{}={}: a number or a string is expected, not {}", key, py::repr(value).cast<std::string>(),
                                 py::type::of(value).attr("__name__").cast<std::string>()));
  return py::str(value).cast<std::string>();
}

std::vector<std::string> assignments(const py::dict& kwargs) {
  std::vector<std::string> items;
  for (const auto& [key, value] : kwargs) {
    const auto k = key.cast<std::string>();
    items.push_back(k + "=" + value_text(k, value));
  }
  return items;
}

namespace {

const char* kind_name(ParamSpec::Kind kind) {
  switch (kind) {
    case ParamSpec::Kind::Real: return "real";
    case ParamSpec::Kind::Integer: return "integer";
    case ParamSpec::Kind::Choice: return "choice";
  }
  return "?";
}

py::list parameter_list(const ParamSpecs& specs) {
  py::list list;
  for (const auto& s : specs) {
    py::dict d;
    d["name"] = s.name;
    d["description"] = s.description;
    d["kind"] = kind_name(s.kind);
    d["default"] = typed_value(s, s.default_value);
    d["range"] = s.range_text();
    if (s.kind == ParamSpec::Kind::Choice) {
      d["choices"] = s.choices;
    } else {
      d["lower"] = s.lower, d["upper"] = s.upper;
      d["lower_open"] = s.lower_open, d["upper_open"] = s.upper_open;
    }
    list.append(d);
  }
  return list;
}

py::list problem_list() {
  py::list list;
  for (const auto& e : problem_registry())
    list.append(py::dict("name"_a = e.name, "description"_a = e.description, "parameters"_a = parameter_list(e.parameters())));
  return list;
}

py::list integrator_list() {
  py::list list;
  for (const auto& e : integrator_registry()) {
    const DeclaredCapabilities declared = e.declared();
    const Capabilities& can = declared.resolved(Params(e.parameters()));
    list.append(py::dict("name"_a = e.name, "description"_a = e.description, "parameters"_a = parameter_list(e.parameters()),
                         "reference"_a = e.reference, "peer"_a = e.peer, "friction"_a = can.friction,
                         "friction_cone"_a = can.friction_cone, "moving_contacts"_a = can.moving_contacts,
                         "needs"_a = declared.text(), "origin"_a = integrator_origin(e.name)));
  }
  return list;
}

py::list run_measure_list() {
  py::list list;
  for (const auto& e : run_measure_registry())
    list.append(py::dict("name"_a = e.name, "description"_a = e.description, "parameters"_a = parameter_list(e.parameters())));
  return list;
}

}  // namespace

void bind_registry(py::module_& m) {
  m.def("run_measures", &run_measure_list,
        "The run measures a case can observe (studies/run_measure.hpp; nsbench.study.case(observe=...)): name,\n"
        "description and parameters (as problems()).");
  m.def("problems", &problem_list,
        "The problems (as `nsbench list`): a list of dicts with name, description and parameters (each a dict:\n"
        "name, description, kind real|integer|choice, default, range as text, lower/upper/lower_open/upper_open\n"
        "or choices).");
  m.def("integrators", &integrator_list,
        "The integrators (as `nsbench list`): name, description, parameters (as problems()), reference, peer,\n"
        "friction (treats Coulomb friction), friction_cone (the 3D Coulomb cone), moving_contacts (contacts that\n"
        "follow the configuration), needs (its other declared capabilities, as `nsbench list` shows them)\n"
        "and origin ('' built in, a plugin's file, or 'python:MODULE.CLASS').");
  m.def("load_plugin", &load_plugin, "path"_a,
        "Loads a plugin module (core/plugin.hpp; as `--plugin FILE`): its problems and integrators join the\n"
        "registries. ValueError when the file is missing, not a plugin, built for another ABI or a name is taken.");
  py::class_<ParamSpec>(m, "Parameter", "A parameter's declaration: name, default, valid range, description.")
      .def_static("real", &ParamSpec::real, "name"_a, "default"_a, "lower"_a, "upper"_a, "description"_a,
                  "lower_open"_a = false, "upper_open"_a = false, "A real in [lower, upper] (open ends as flagged).")
      .def_static("integer", &ParamSpec::integer, "name"_a, "default"_a, "lower"_a, "upper"_a, "description"_a,
                  "An integer in [lower, upper].")
      .def_static("choice", &ParamSpec::choice, "name"_a, "default"_a, "choices"_a, "description"_a, "One of `choices`.")
      .def_readonly("name", &ParamSpec::name)
      .def_readonly("description", &ParamSpec::description)
      .def_property_readonly("range", &ParamSpec::range_text)
      .def("__repr__", [](const ParamSpec& s) {
        return fmt::format("Parameter({}, default {}, {})", s.name, s.default_value.empty() ? "unset" : s.default_value,
                           s.range_text());
      });
}

}  // namespace nsb::python
