// core: inertest.Error (a ValueError), Figure, Record and Result, unit conversion, the version.
#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

#include "bindings.h"
#include "inertest/core/citations.h"
#include "inertest/core/filesystem_error.h"
#include "inertest/core/figure.h"
#include "inertest/core/json_text.h"
#include "inertest/core/units.h"
#include "inertest/version.h"

namespace inertest::python {

DoubleArray real_array(const py::handle& value) {
  py::detail::make_caster<DoubleArray> caster;
  if (!caster.load(value, true)) throw py::type_error("an array of real numbers is expected");
  return py::detail::cast_op<DoubleArray>(std::move(caster));
}

std::span<const double> as_span(const DoubleArray& array, const char* name, Values values) {
  if (array.ndim() != 1) {
    throw Error(fmt::format("{} must be a one-dimensional array, not {}-dimensional", name, array.ndim()));
  }
  const std::span<const double> span(array.data(), static_cast<std::size_t>(array.shape(0)));
  if (values == Values::finite) {
    const auto bad = std::find_if(span.begin(), span.end(), [](double v) { return !std::isfinite(v); });
    if (bad != span.end()) {
      throw Error(fmt::format("{}[{}] ({}) is not a finite number", name, bad - span.begin(), *bad));  // numpy's index
    }
  }
  return span;
}

void require_equal_lengths(std::initializer_list<std::pair<const char*, std::size_t>> lengths) {
  const auto& first = *lengths.begin();
  for (const auto& [name, length] : lengths) {
    if (length != first.second) {
      throw Error(fmt::format("{} has {} values but {} has {}: the arrays must have equal lengths", name, length,
                              first.first, first.second));
    }
  }
}

py::object to_plain_python(const nlohmann::json& json) {
  switch (json.type()) {
    case nlohmann::json::value_t::object: {
      py::dict dict;
      for (const auto& [key, value] : json.items()) dict[py::str(key)] = to_plain_python(value);
      return dict;
    }
    case nlohmann::json::value_t::array: {
      py::list list;
      for (const auto& value : json) list.append(to_plain_python(value));
      return list;
    }
    case nlohmann::json::value_t::string:
      return py::str(json.get_ref<const std::string&>());
    case nlohmann::json::value_t::boolean:
      return py::bool_(json.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(json.get<std::int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(json.get<std::uint64_t>());
    case nlohmann::json::value_t::number_float: {
      const double value = json.get<double>();
      if (!std::isfinite(value)) return py::none();  // the JSON text has null
      return py::float_(value);
    }
    default:
      return py::none();
  }
}

namespace {

// The keys a figure's JSON may carry beside value, unit and uncertainty, each an attribute of the
// Python Figure: "identified": false with "upper_bound" (a noise term the fit holds at zero, its
// value NaN), "significant": false with "upper_bound" (a term within 2 sigma of zero), "reason"
// (why a figure was not measured).
constexpr std::array<const char*, 4> kFigureAnnotations = {"identified", "significant", "upper_bound", "reason"};

bool is_figure_annotation(const std::string& key, const nlohmann::json& value) {
  if (key == "identified" || key == "significant") return value.is_boolean();
  if (key == "upper_bound") return value.is_number() || value.is_null();
  return key == "reason" && value.is_string();
}

// {"value": number-or-null, "unit": string}, optionally "uncertainty" and the annotations above:
// the JSON of a Figure.
bool is_figure(const nlohmann::json& json) {
  if (!json.is_object() || !json.contains("value") || !json.contains("unit")) return false;
  if (!json["unit"].is_string() || !(json["value"].is_number() || json["value"].is_null())) return false;
  return std::all_of(json.items().begin(), json.items().end(), [](const auto& item) {
    return item.key() == "value" || item.key() == "unit" ||
           (item.key() == "uncertainty" && (item.value().is_number() || item.value().is_null())) ||
           is_figure_annotation(item.key(), item.value());
  });
}

double number_or_nan(const nlohmann::json& json) {
  return json.is_number() ? json.get<double>() : std::nan("");
}

py::object attribute_value(const nlohmann::json& json);

// An array of numbers becomes a numpy array (int64 when every element is an integer, else float64
// with null as NaN); any other array a list.
py::object array_value(const nlohmann::json& json) {
  bool numbers = !json.empty();
  bool integers = numbers;
  for (const auto& element : json) {
    numbers = numbers && (element.is_number() || element.is_null());
    integers = integers && element.is_number_integer();
  }
  if (integers) {
    std::vector<std::int64_t> values;
    values.reserve(json.size());
    for (const auto& element : json) values.push_back(element.get<std::int64_t>());
    return to_numpy(std::move(values));
  }
  if (numbers) {
    std::vector<double> values;
    values.reserve(json.size());
    for (const auto& element : json) values.push_back(number_or_nan(element));
    return to_numpy(std::move(values));
  }
  py::list list;
  for (const auto& element : json) list.append(attribute_value(element));
  return list;
}

py::object attribute_value(const nlohmann::json& json) {
  if (is_figure(json)) {
    Figure figure;
    figure.value = number_or_nan(json["value"]);
    figure.unit = json["unit"].get<std::string>();
    if (json.contains("uncertainty")) figure.uncertainty = number_or_nan(json["uncertainty"]);
    py::object object = py::cast(std::move(figure));
    for (const auto& [key, value] : json.items()) {
      if (is_figure_annotation(key, value)) object.attr(key.c_str()) = to_plain_python(value);
    }
    return object;
  }
  if (json.is_object()) return py::cast(Record(json));
  if (json.is_array()) return array_value(json);
  if (json.is_number_float()) return py::float_(json.get<double>());
  return to_plain_python(json);
}

py::list member_names(const Record& record) {
  py::list names;
  if (record.json().is_object()) {
    for (const auto& [key, value] : record.json().items()) names.append(py::str(key));
  }
  return names;
}

std::string short_repr(const Record& record, const std::string& class_name) {
  std::string members;
  if (record.json().is_object()) {
    for (const auto& [key, value] : record.json().items()) members += (members.empty() ? "" : ", ") + key;
  }
  return fmt::format("<{} with {}>", class_name, members.empty() ? "no members" : members);
}

std::string figure_repr(const Figure& figure) {
  if (figure.uncertainty) {
    return fmt::format("Figure(value={}, unit='{}', uncertainty={})", figure.value, figure.unit, *figure.uncertainty);
  }
  return fmt::format("Figure(value={}, unit='{}')", figure.value, figure.unit);
}

// inertest.Error: a ValueError whose message is what the CLI prints after "inertest: error: ",
// with the location as attributes. Kept for the life of the process (never released).
PyObject* error_type = nullptr;

void wrap_error(py::module_& module) {
  error_type = PyErr_NewExceptionWithDoc(
      "inertest.Error",
      "Bad input or options: a ValueError with the message the CLI prints after 'inertest: error: '.\n"
      "Members:\n"
      "    message: str  # without the location\n"
      "    file: Optional[str]  # None where not known, as line and column\n"
      "    line: Optional[int]\n"
      "    column: Optional[int]\n",
      PyExc_ValueError, nullptr);
  module.add_object("Error", py::handle(error_type));
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      try {
        if (pointer) std::rethrow_exception(pointer);
      } catch (const std::filesystem::filesystem_error& failure) {
        throw error_of(failure);  // a path the system refuses: bad input, as on the command line
      }
    } catch (const Error& e) {
      py::object exception = py::reinterpret_borrow<py::object>(error_type)(e.what());
      exception.attr("message") = e.message();
      const auto& location = e.location();
      exception.attr("file") = location ? py::cast(location->file) : py::none();
      exception.attr("line") = location && location->line ? py::cast(location->line) : py::none();
      exception.attr("column") = location && location->column ? py::cast(location->column) : py::none();
      PyErr_SetObject(error_type, exception.ptr());
    }
  });
}

void wrap_figure(py::module_& module) {
  using namespace pybind11::literals;
  py::class_<Figure>(module, "Figure",
                     "A reported figure: value, unit and, where known, its 1-sigma uncertainty in the same unit. A\n"
                     "noise term within 2 sigma of zero also has significant (False) and upper_bound (in unit); one\n"
                     "the fit holds at zero has value NaN, identified (False) and upper_bound (None when unknown); a\n"
                     "figure the data could not give has value NaN and, where said, a reason.\n"
                     "Members:\n"
                     "    identified: bool  # a noise term only (absent elsewhere): False when the fit holds it at zero\n"
                     "    significant: bool  # a noise term only: False within 2 sigma of zero\n"
                     "    upper_bound: Optional[float]  # with identified or significant False, in unit\n"
                     "    reason: str  # a figure the data could not give, where said\n",
                     py::dynamic_attr())
      .def(py::init([](double value, std::string unit, std::optional<double> uncertainty) {
             Unit::parse(unit);
             return Figure{value, std::move(unit), uncertainty};
           }),
           "value"_a, "unit"_a = "1", "uncertainty"_a = py::none())
      .def_readwrite("value", &Figure::value, "The value, in `unit`.")
      .def_readwrite("unit", &Figure::unit, "The unit, a string that inertest.convert understands.")
      .def_readwrite("uncertainty", &Figure::uncertainty, "1-sigma uncertainty in `unit`, or None.")
      .def(
          "to",
          [](const py::object& self, const std::string& unit) {
            const auto& figure = self.cast<const Figure&>();
            py::object converted = py::cast(figure.in(unit));
            for (const char* key : kFigureAnnotations) {
              if (!py::hasattr(self, key)) continue;
              py::object value = self.attr(key);
              if (std::string_view(key) == "upper_bound" && !value.is_none()) {
                value = py::float_(convert(value.cast<double>(), figure.unit, unit));
              }
              converted.attr(key) = value;
            }
            return converted;
          },
          "unit"_a,
          "The same figure in another unit of the same dimension: its uncertainty and upper_bound too, its other "
          "annotations as they are.")
      .def(
          "to_dict",
          [](const py::object& self) {
            py::dict json = to_plain_python(nlohmann::json(self.cast<const Figure&>()));
            for (const char* key : kFigureAnnotations) {
              if (py::hasattr(self, key)) json[key] = self.attr(key);
            }
            return json;
          },
          "The figure's JSON: {'value': v, 'unit': u} plus 'uncertainty' when known and its annotations.")
      .def("__float__", [](const Figure& figure) { return figure.value; })
      .def("__eq__",
           [](const Figure& a, const py::object& other) -> py::object {
             // Not a Figure: NotImplemented, so that figure == None is False (not a TypeError).
             if (!py::isinstance<Figure>(other)) return py::reinterpret_borrow<py::object>(Py_NotImplemented);
             const auto& b = other.cast<const Figure&>();
             return py::bool_(a.value == b.value && a.unit == b.unit && a.uncertainty == b.uncertainty);
           })
      .def("__repr__", &figure_repr);
}

void wrap_record(py::module_& module) {
  using namespace pybind11::literals;
  py::class_<Record>(module, "Record",
                     "A JSON object seen through attributes: record.name is its member 'name'. A member\n"
                     "{'value', 'unit'[, 'uncertainty']} is a Figure, another object a Record, an array of\n"
                     "numbers a numpy array, any other array a list. record['name'] works too.")
      .def("__getattr__",
           [](const Record& record, const std::string& name) {
             if (!record.json().is_object() || !record.json().contains(name)) {
               throw py::attribute_error(fmt::format("no member '{}'; members: {}", name,
                                                     py::str(", ").attr("join")(member_names(record)).cast<std::string>()));
             }
             return attribute_value(record.json()[name]);
           })
      .def("__getitem__",
           [](const Record& record, const std::string& name) {
             if (!record.json().is_object() || !record.json().contains(name)) throw py::key_error(name);
             return attribute_value(record.json()[name]);
           })
      .def("__contains__",
           [](const Record& record, const std::string& name) {
             return record.json().is_object() && record.json().contains(name);
           })
      .def("__dir__",
           [](py::object self) {
             py::list names = member_names(self.cast<const Record&>());
             for (const auto& name : py::module_::import("builtins").attr("dir")(py::type::of(self))) names.append(name);
             return names;
           })
      .def("keys", &member_names, "The names of the members, as in the JSON.")
      .def(
          "to_dict", [](const Record& record) { return to_plain_python(record.json()); },
          "The JSON as plain Python objects: equal to json.loads() of what the CLI prints with --json.")
      .def(
          "json", [](const Record& record, int indent) { return json_text(record.json(), indent); }, "indent"_a = -1,
          "The JSON text (the CLI's --json output; indent >= 0 pretty-prints).")
      .def("__repr__", [](py::object self) {
        return short_repr(self.cast<const Record&>(), py::type::of(self).attr("__name__").cast<std::string>());
      });
  py::class_<Result, Record>(module, "Result", "A procedure's result: a Record with a readable report().")
      .def("report", &Result::report, "The readable multi-line summary the CLI prints without --json.");
}

void wrap_units(py::module_& module) {
  using namespace pybind11::literals;
  module.def(
      "convert",
      [](py::object value, const std::string& from_unit, const std::string& to_unit) -> py::object {
        const Unit from = Unit::parse(from_unit);
        const Unit to = Unit::parse(to_unit);
        // A number of any kind (numpy's scalars, a 0-d array, Decimal) is one; an array of any shape
        // (an IMU's (N, 3)) keeps its shape: both were refused as "not a one-dimensional array".
        const DoubleArray given = real_array(value);  // NaN converts to NaN
        if (given.ndim() == 0) return py::float_(convert(*given.data(), from, to));
        py::array_t<double> converted(std::vector<py::ssize_t>(given.shape(), given.shape() + given.ndim()));
        const double* in = given.data();
        double* out = converted.mutable_data();
        for (py::ssize_t i = 0; i < given.size(); ++i) out[i] = convert(in[i], from, to);
        return converted;
      },
      "value"_a, "from_unit"_a, "to_unit"_a,
      "Converts a number or an array (of any shape) from one unit to another of the same dimension, e.g.\n"
      "convert(1.0, 'deg/h', 'rad/s'). Units: products of named units with integer or half-integer\n"
      "powers ('deg/h', 'deg/sqrt(h)', 'deg/h/g^2', 'pulse/s', 'ppm'); 'g' is 9.80665 m/s^2.\n"
      "Raises inertest.Error (a ValueError) for an unknown unit or different dimensions.");
}

}  // namespace

void wrap_core(py::module_& module) {
  wrap_error(module);
  wrap_figure(module);
  wrap_record(module);
  wrap_units(module);
  module.attr("__version__") = version();
  py::dict citations;
  citations["misalignment"] = citations::kMisalignmentPaper;
  citations["centrifuge"] = citations::kCentrifugePaper;
  module.attr("CITATIONS") = citations;
}

}  // namespace inertest::python
