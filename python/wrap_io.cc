// io: the record readers, returning numpy arrays that own the vectors the readers filled.
#include <fmt/format.h>

#include "bindings.h"
#include "inertest/io/binary_record.h"
#include "inertest/io/text_table.h"

namespace inertest::python {
namespace {

// A text table as the Python side sees it: every column a numpy array (no copy of the values).
struct PythonTextTable {
  std::string source;
  std::vector<std::string> names;
  std::vector<py::array_t<double>> columns;
  py::array_t<std::size_t> row_lines;
  std::size_t first_data_line = 0;

  const py::array_t<double>& column(const std::string& name) const {
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == name) return columns[i];
    }
    std::string present;
    for (const auto& n : names) present += (present.empty() ? "" : ", ") + n;
    throw py::key_error(fmt::format("{}: no column '{}'; columns: {}", source, name, present));
  }
};

TextTableOptions::Header parse_header(const py::object& header) {
  if (header.is_none()) return TextTableOptions::Header::kDetect;
  return header.cast<bool>() ? TextTableOptions::Header::kPresent : TextTableOptions::Header::kAbsent;
}

PythonTextTable read_table(const std::filesystem::path& path, const std::optional<std::vector<py::object>>& columns,
                           const std::optional<std::string>& delimiter, const py::object& header,
                           const std::string& comment, std::size_t minimum_rows, bool record_row_lines) {
  TextTableOptions options;
  if (delimiter) {
    if (delimiter->size() != 1) throw Error(fmt::format("delimiter must be one character, not '{}'", *delimiter));
    options.delimiter = delimiter->front();
  }
  if (comment.size() != 1) throw Error(fmt::format("comment must be one character, not '{}'", comment));
  options.comment = comment.front();
  options.header = parse_header(header);
  options.minimum_rows = minimum_rows;
  options.record_row_lines = record_row_lines;
  if (columns) {
    for (const auto& column : *columns) {
      if (py::isinstance<py::int_>(column)) {
        const long index = column.cast<long>();
        if (index < 1) throw Error(fmt::format("column positions are 1-based; {} is not a position", index));
        options.columns.push_back(ColumnSelector{"", static_cast<std::size_t>(index)});
      } else {
        options.columns.push_back(ColumnSelector{column.cast<std::string>(), 0});
      }
    }
  }
  TextTable table;
  {
    py::gil_scoped_release release;
    table = read_text_table(path.string(), options);
  }
  PythonTextTable result{table.source, table.names, {}, to_numpy(std::move(table.row_lines)), table.first_data_line};
  for (auto& column : table.columns) result.columns.push_back(to_numpy(std::move(column)));
  return result;
}

}  // namespace

void wrap_io(py::module_& module) {
  using namespace pybind11::literals;
  py::class_<PythonTextTable>(module, "TextTable",
                              "Numeric columns of a text record. table['name'] (or table[i], 0-based) is a column as a\n"
                              "float64 numpy array that owns the reader's buffer (no copy).")
      .def_readonly("source", &PythonTextTable::source, "The file name, as used in error messages.")
      .def_readonly("names", &PythonTextTable::names, "Header names of the columns ('' without a header).")
      .def_readonly("columns", &PythonTextTable::columns, "The columns, in the order asked for.")
      .def_readonly("row_lines", &PythonTextTable::row_lines,
                    "1-based line of every data row (empty unless record_row_lines).")
      .def_readonly("first_data_line", &PythonTextTable::first_data_line, "1-based line of the first data row.")
      .def("__len__", [](const PythonTextTable& table) { return table.columns.empty() ? 0 : table.columns[0].size(); })
      .def("__getitem__", &PythonTextTable::column, "name"_a)
      .def("__getitem__",
           [](const PythonTextTable& table, long index) {
             const long count = static_cast<long>(table.columns.size());
             if (index < -count || index >= count) throw py::index_error(fmt::format("no column {}", index));
             return table.columns[static_cast<std::size_t>(index < 0 ? index + count : index)];
           })
      .def("to_dict",
           [](const PythonTextTable& table) {
             py::dict dict;
             // A column without a header name is keyed by its 1-based place (every key was '' and
             // only the last column was left).
             for (std::size_t i = 0; i < table.names.size(); ++i) {
               dict[py::str(table.names[i].empty() ? std::to_string(i + 1) : table.names[i])] = table.columns[i];
             }
             return dict;
           },
           "{name: column} (a column without a header name under its 1-based position in the table, '1', '2'...);\n"
           "pandas.DataFrame(table.to_dict()) makes a data frame without copying.")
      .def("__repr__", [](const PythonTextTable& table) {
        return fmt::format("<TextTable {}: {} rows, columns {}>", table.source,
                           table.columns.empty() ? 0 : table.columns[0].size(), fmt::join(table.names, ", "));
      });

  module.def("read_text_table", &read_table, "path"_a, "columns"_a = py::none(), "delimiter"_a = py::none(),
             "header"_a = py::none(), "comment"_a = "#", "minimum_rows"_a = 1, "record_row_lines"_a = true,
             "Reads numeric columns of a text record (CSV, TSV, semicolons or whitespace; comment lines and\n"
             "blank lines skipped) through a memory map, as the CLI does.\n"
             "columns: names or 1-based positions to return, in that order (None: every column).\n"
             "delimiter: one character, None to detect from the first data line.\n"
             "header: True, False, or None to detect.\n"
             "Raises inertest.Error (a ValueError) naming file, line and column for any bad cell.");

  module.def(
      "read_binary_record",
      [](const std::filesystem::path& path, const std::string& format, std::size_t channels, std::size_t channel) {
        BinaryFormat binary = BinaryFormat::parse(format);
        binary.channels = channels;
        binary.channel = channel;
        std::vector<double> samples;
        {
          py::gil_scoped_release release;
          samples = read_binary_record(path.string(), binary);
        }
        return to_numpy(std::move(samples));
      },
      "path"_a, "format"_a = "f64", "channels"_a = 1, "channel"_a = 0,
      "Reads one channel of a raw binary record (interleaved channels; format 'f64', 'f32', 'i32' or\n"
      "'i16', optionally followed by 'le' or 'be', e.g. 'f32be'; channel 0-based) as a float64 array that\n"
      "owns the reader's buffer. Raises inertest.Error for an empty file, a size that is not whole\n"
      "frames, or a NaN/Inf sample.");
}

}  // namespace inertest::python
