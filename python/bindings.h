// Shared helpers of the Python module `inertest` (pybind11): numpy arrays in and out without copies,
// results as objects whose attributes are their JSON names, and the wrap function of every part.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
// File paths as str or os.PathLike (pathlib.Path), as Python's own open() takes them.
#include <pybind11/stl/filesystem.h>

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "inertest/core/error.h"
#include "inertest/core/procedure_spec.h"

namespace inertest::python {

namespace py = pybind11;

// A numpy array of float64 as the Python side hands it in: converted (forcecast) and made
// C-contiguous by pybind11 only when it is not already, so a float64 array is never copied.
using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;
// The same in the layout it has (strides kept): for 2-D arrays whose columns are read where they
// are, as a Fortran-ordered one (pandas' to_numpy() of float columns) is.
using StridedDoubleArray = py::array_t<double, py::array::forcecast>;

}  // namespace inertest::python

namespace pybind11::detail {

// The conversion of DoubleArray and StridedDoubleArray, as array_t's (above), for arrays of real
// numbers only: numpy's cast would drop a complex array's imaginary part (with a warning) and turn
// datetime64 stamps into counts of seconds, to be taken as rates, and a boolean mask passed by
// mistake into ones and zeros. Integers and floats convert; booleans (as is_number refuses a bool),
// complex, datetime, timedelta, text and raw bytes are a TypeError naming the dtype.
template <typename Array>
struct real_array_caster {
  using type = Array;
  bool load(handle src, bool convert) {
    if (!convert && !type::check_(src)) return false;
    const array given = array::ensure(src);  // an ndarray as it is; a sequence as numpy infers it
    if (given) {
      const char kind = given.dtype().kind();
      if (kind == 'b' || kind == 'c' || kind == 'M' || kind == 'm' || kind == 'S' || kind == 'U' || kind == 'V') {
        throw type_error("an array of real numbers is expected, not of dtype " +
                         std::string(str(given.dtype()).cast<std::string>()));
      }
    }
    value = type::ensure(src);
    return static_cast<bool>(value);
  }
  static handle cast(const handle& src, return_value_policy /* policy */, handle /* parent */) { return src.inc_ref(); }
  PYBIND11_TYPE_CASTER(type, handle_type_name<type>::name);
};

template <>
struct pyobject_caster<inertest::python::DoubleArray> : real_array_caster<inertest::python::DoubleArray> {};
template <>
struct pyobject_caster<inertest::python::StridedDoubleArray> : real_array_caster<inertest::python::StridedDoubleArray> {};

}  // namespace pybind11::detail

namespace inertest::python {

// `value` as a DoubleArray through the caster above, for an argument taken as a py::object: a
// py::cast to an array type constructs it directly, and would take complex or boolean values.
DoubleArray real_array(const py::handle& value);

// A view of a one-dimensional array's buffer; `name` is the argument's name for the error. A NaN or
// an infinity is an Error naming its place (as a record's is), unless `values` is Values::any.
enum class Values { finite, any };
std::span<const double> as_span(const DoubleArray& array, const char* name, Values values = Values::finite);

// A Python number: int, float, or numpy's scalars (np.int64, np.float32...), but not a bool, a text
// or an array.
inline bool is_number(const py::handle& value) {
  return PyNumber_Check(value.ptr()) != 0 && !py::isinstance<py::bool_>(value) && !py::isinstance<py::array>(value);
}

// Throws Error unless every array has the length of the first; `names` name them in the message.
void require_equal_lengths(std::initializer_list<std::pair<const char*, std::size_t>> lengths);

// A numpy array that owns the moved vector (released through a capsule), so nothing is copied.
template <typename T>
py::array_t<T> to_numpy(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule release(owned, [](void* pointer) { delete static_cast<std::vector<T>*>(pointer); });
  return py::array_t<T>(static_cast<py::ssize_t>(owned->size()), owned->data(), release);
}

// JSON as plain Python objects (dict, list, float, int, str, bool, None): what json.loads gives for
// the JSON the CLI prints. Non-finite numbers become None, as the JSON text has null.
py::object to_plain_python(const nlohmann::json& json);

// A JSON object seen through attributes: `record.name` is the member "name", a member of the form
// {"value", "unit"[, "uncertainty"]} is a Figure, another object a Record, an array of numbers a
// numpy array, any other array a list. to_dict() gives the JSON as plain Python objects.
class Record {
 public:
  explicit Record(nlohmann::json json) : json_(std::move(json)) {}
  virtual ~Record() = default;
  Record(const Record&) = default;
  Record& operator=(const Record&) = default;

  const nlohmann::json& json() const { return json_; }

 private:
  nlohmann::json json_;
};

// A procedure's result: its JSON (Record) and its readable report.
class Result : public Record {
 public:
  Result(nlohmann::json json, std::string report) : Record(std::move(json)), report_(std::move(report)) {}
  const std::string& report() const { return report_; }

 private:
  std::string report_;
};

// One Python class per result type, so that results have their own names and docstrings.
template <typename Tag>
class ResultOf : public Result {
 public:
  using Result::Result;
};

// Binds ResultOf<Tag> as `name`, a subclass of Result. The doc ends with a "Members:" section, one
// line per JSON key in stub syntax (`    name: Type  # comment`), which python/generate_stubs.py
// copies into the type stubs.
template <typename Tag>
void bind_result(py::module_& module, const char* name, const std::string& doc) {
  py::class_<ResultOf<Tag>, Result>(module, name, doc.c_str());
}

// The doc of a declared procedure's result: its title and clause, then its members from the spec.
std::string result_doc(const ProcedureSpec& spec);

// Wraps a procedure's result (anything with to_json() and report()) as the Python class of Tag.
template <typename Tag, typename CppResult>
ResultOf<Tag> make_result(const CppResult& result) {
  return ResultOf<Tag>(result.to_json(), result.report());
}

// Wraps the result of a declared procedure (core/procedure_spec.h) as the Python class of Tag: its
// JSON and its report made by the spec's writers, as the CLI and plans make them.
template <typename Tag, typename CppResult>
ResultOf<Tag> make_spec_result(const ProcedureSpec& spec, const CppResult& result) {
  const nlohmann::json fields = spec.fields_of(&result);
  return ResultOf<Tag>(procedure_json(spec, fields), procedure_text(spec, fields));
}

// Runs work; an Error without a location gets `source` (when given) as its location, as the CLI
// does for a procedure on one input file.
template <typename Work>
auto with_source(const std::optional<std::string>& source, Work&& work) {
  try {
    return work();
  } catch (const Error& e) {
    if (e.location() || !source || source->empty()) throw;
    throw Error(SourceLocation{*source, 0, 0}, e.message());
  }
}

void wrap_core(py::module_& module);
void wrap_io(py::module_& module);
void wrap_procedures(py::module_& module);
void wrap_misalignment(py::module_& module);
void wrap_centrifuge(py::module_& module);
void wrap_allan(py::module_& module);
void wrap_sim(py::module_& module);
void wrap_campaign(py::module_& module);
// After the others: a declared procedure without a function of its own gets a generic one.
void wrap_specs(py::module_& module);

}  // namespace inertest::python
