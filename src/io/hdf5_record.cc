// HDF5 records through the HDF5 C library: every dataset of the file is a channel named by its
// path ("group/dataset"). One-dimensional datasets (or N x 1 and 1 x N) of integers or floats are
// read as samples, in hyperslabs of the range asked for, so a chunked, compressed dataset of 10^9
// samples is never copied whole. Units come from a string attribute `units` (or `unit`), the
// sample rate from a numeric attribute `sample_rate_hz` (or `sample_rate`), or `wf_increment` (s):
// one number or one string each (a scalar or an array of one). Such an attribute in another form
// leaves the channel's rate or unit unusable (ChannelInfo::sample_rate_problem, unit_problem).
// Packed integer samples (the CF convention's `scale_factor` and `add_offset`, as netCDF-4 and
// xarray write them) are unpacked: value = stored * scale_factor + add_offset.
#include <fmt/format.h>
#include <hdf5.h>

#include <array>
#include <cmath>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/core/units.h"
#include "io/channel_readers.h"

namespace inertest {
namespace {

// An HDF5 identifier closed by `close` when it goes out of scope.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle(hid_t id, Closer close) : id_(id), close_(close) {}
  Handle(Handle&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), close_(other.close_) {}
  Handle& operator=(Handle&& other) noexcept {
    std::swap(id_, other.id_);
    std::swap(close_, other.close_);
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid_t id_;
  Closer close_;
};

// The innermost message of HDF5's error stack (what went wrong, in the library's words).
std::string hdf5_error_text() {
  std::string text;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* error, void* data) -> herr_t {
        auto* out = static_cast<std::string*>(data);
        if (out->empty() && error->desc != nullptr) *out = error->desc;
        return 0;
      },
      &text);
  H5Eclear2(H5E_DEFAULT);
  return text.empty() ? "unknown HDF5 error" : text;
}

// The library prints its error stack to stderr unless told not to; errors are reported as Error.
void silence_hdf5() {
  static const bool silenced = [] {
    H5open();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)silenced;
}

std::string type_name(hid_t type, bool& numeric) {
  const H5T_class_t type_class = H5Tget_class(type);
  const std::size_t size = H5Tget_size(type);
  numeric = true;
  if (type_class == H5T_FLOAT && (size == 4 || size == 8)) return fmt::format("f{}", size * 8);
  if (type_class == H5T_INTEGER && size <= 8) {
    return fmt::format("{}{}", H5Tget_sign(type) == H5T_SGN_NONE ? 'u' : 'i', size * 8);
  }
  numeric = false;
  switch (type_class) {
    case H5T_STRING: return "string";
    case H5T_COMPOUND: return "compound";
    case H5T_ENUM: return "enum";
    case H5T_ARRAY: return "array";
    case H5T_VLEN: return "vlen";
    case H5T_REFERENCE: return "reference";
    default: return fmt::format("{}-byte non-numeric", size);
  }
}

// H5T_VARIABLE, without the C cast of its macro.
constexpr std::size_t kVariableLength = static_cast<std::size_t>(-1);

// The single string of a string attribute (a scalar, or an array of one); nullopt when it holds
// anything else or cannot be read.
std::optional<std::string> read_string(hid_t attribute) {
  Handle type(H5Aget_type(attribute), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING) return std::nullopt;
  Handle space(H5Aget_space(attribute), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1) return std::nullopt;
  Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_cset(memory_type.get(), H5Tget_cset(type.get()));
  if (H5Tis_variable_str(type.get()) > 0) {
    H5Tset_size(memory_type.get(), kVariableLength);
    char* text = nullptr;
    if (H5Aread(attribute, memory_type.get(), &text) < 0 || text == nullptr) return std::nullopt;
    std::string value(text);
    H5free_memory(text);
    return value;
  }
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size + 1, '\0');
  H5Tset_size(memory_type.get(), size + 1);
  H5Tset_strpad(memory_type.get(), H5T_STR_NULLTERM);
  if (H5Aread(attribute, memory_type.get(), value.data()) < 0) return std::nullopt;
  value.resize(value.find('\0'));
  return value;
}

// The single number of a numeric attribute (integer or float, a scalar or an array of one);
// nullopt when it holds anything else or cannot be read.
std::optional<double> read_number(hid_t attribute) {
  Handle type(H5Aget_type(attribute), H5Tclose);
  Handle space(H5Aget_space(attribute), H5Sclose);
  const H5T_class_t type_class = H5Tget_class(type.get());
  if ((type_class != H5T_FLOAT && type_class != H5T_INTEGER) || H5Sget_simple_extent_npoints(space.get()) != 1) {
    return std::nullopt;
  }
  double value = 0.0;
  if (H5Aread(attribute, H5T_NATIVE_DOUBLE, &value) < 0) return std::nullopt;
  return value;
}

// What an attribute holds, for a message: "the string \"200\"", "2 numbers", "an enum value".
std::string describe_attribute(hid_t attribute) {
  Handle type(H5Aget_type(attribute), H5Tclose);
  Handle space(H5Aget_space(attribute), H5Sclose);
  const H5T_class_t type_class = H5Tget_class(type.get());
  const hssize_t points = H5Sget_simple_extent_npoints(space.get());
  if (type_class == H5T_STRING) {
    if (const std::optional<std::string> text = read_string(attribute)) return fmt::format("the string {:?}", *text);
    return fmt::format("{} strings", points);
  }
  if (type_class == H5T_FLOAT || type_class == H5T_INTEGER) {
    if (const std::optional<double> number = read_number(attribute)) return fmt::format("the number {}", *number);
    return fmt::format("{} numbers", points);
  }
  bool numeric = false;
  const std::string name = type_name(type.get(), numeric);
  return fmt::format("{} {} value{}", points == 1 ? "one" : std::to_string(points), name, points == 1 ? "" : "s");
}

// An attribute of a dataset read as one number or one string: absent (nullopt, no problem), the
// value, or a problem saying what it holds instead (HDF5 attributes carry any type and shape).
template <typename T>
std::optional<T> attribute_value(hid_t object, const char* name, std::string& problem) {
  if (H5Aexists(object, name) <= 0) return std::nullopt;
  Handle attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose);
  const char* expected = std::is_same_v<T, double> ? "one number" : "one string";
  if (!attribute.valid()) {
    if (problem.empty()) problem = fmt::format("the dataset's attribute {} is unreadable: {}", name, hdf5_error_text());
    return std::nullopt;
  }
  std::optional<T> value;
  if constexpr (std::is_same_v<T, double>) {
    value = read_number(attribute.get());
  } else {
    value = read_string(attribute.get());
  }
  if (!value && problem.empty()) {
    problem = fmt::format("the dataset's attribute {} is unreadable: expected {}, found {}", name, expected,
                          describe_attribute(attribute.get()));
  }
  return value;
}

class Hdf5Record final : public ChannelRecord {
 public:
  explicit Hdf5Record(const std::string& path)
      : ChannelRecord(path, ChannelRecordFormat::kHdf5), file_(H5I_INVALID_HID, H5Fclose),
        dataset_(H5I_INVALID_HID, H5Dclose) {
    silence_hdf5();
    file_ = Handle(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
    if (!file_.valid()) throw Error(SourceLocation{path, 0, 0}, "not a readable HDF5 file: " + hdf5_error_text());
    if (H5Lvisit(file_.get(), H5_INDEX_NAME, H5_ITER_INC, &Hdf5Record::visit, this) < 0) {
      throw Error(SourceLocation{path, 0, 0}, "cannot list the datasets: " + hdf5_error_text());
    }
  }

  void read(std::size_t channel, std::uint64_t first, std::span<double> out) override {
    const ChannelInfo& info = channels_.at(channel);
    const SourceLocation where{path(), 0, 0};
    if (first + out.size() > info.length) {
      throw Error(where, channel_range_context(info, first, out.size()) + fmt::format(": beyond its {} samples", info.length));
    }
    if (open_channel_ != channel) {
      dataset_ = Handle(H5Dopen2(file_.get(), info.name.c_str(), H5P_DEFAULT), H5Dclose);
      if (!dataset_.valid()) throw Error(where, fmt::format("channel '{}': cannot open the dataset: {}", info.name, hdf5_error_text()));
      open_channel_ = channel;
    }
    Handle file_space(H5Dget_space(dataset_.get()), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(file_space.get());
    std::array<hsize_t, 2> dims{1, 1};
    H5Sget_simple_extent_dims(file_space.get(), dims.data(), nullptr);
    std::array<hsize_t, 2> start{0, 0};
    std::array<hsize_t, 2> count{1, 1};
    // The one dimension longer than 1 runs along the samples (N, N x 1 or 1 x N).
    const std::size_t axis = rank == 2 && dims[0] == 1 && dims[1] != 1 ? 1 : 0;
    start[axis] = first;
    count[axis] = out.size();
    if (H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr) < 0) {
      throw Error(where, channel_range_context(info, first, out.size()) + ": " + hdf5_error_text());
    }
    const hsize_t memory_count = out.size();
    Handle memory_space(H5Screate_simple(1, &memory_count, nullptr), H5Sclose);
    if (H5Dread(dataset_.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT, out.data()) < 0) {
      throw Error(where, channel_range_context(info, first, out.size()) +
                             ": cannot read (truncated or corrupt file?): " + hdf5_error_text());
    }
    if (const Packing& packing = packings_[channel]; packing.scale != 1.0 || packing.offset != 0.0) {
      for (double& value : out) value = value * packing.scale + packing.offset;
    }
  }

 private:
  static herr_t visit(hid_t group, const char* name, const H5L_info_t* link, void* data) {
    auto* self = static_cast<Hdf5Record*>(data);
    if (link->type != H5L_TYPE_HARD) return 0;
    Handle object(H5Oopen(group, name, H5P_DEFAULT), H5Oclose);
    if (!object.valid()) {
      H5Eclear2(H5E_DEFAULT);
      return 0;
    }
    if (H5Iget_type(object.get()) != H5I_DATASET) return 0;
    self->add_dataset(name, object.get());
    return 0;
  }

  void add_dataset(const std::string& name, hid_t dataset) {
    ChannelInfo info;
    info.name = name;
    Handle type(H5Dget_type(dataset), H5Tclose);
    info.type = type_name(type.get(), info.numeric);
    Handle space(H5Dget_space(dataset), H5Sclose);
    const int rank = H5Sget_simple_extent_ndims(space.get());
    std::array<hsize_t, H5S_MAX_RANK> dims{};
    H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
    const auto points = static_cast<std::uint64_t>(H5Sget_simple_extent_npoints(space.get()));
    info.length = points;
    const bool vector = rank == 1 || (rank == 2 && (dims[0] == 1 || dims[1] == 1));
    if (!vector) {
      std::string shape;
      for (int i = 0; i < rank; ++i) {
        if (i > 0) shape += 'x';
        shape += std::to_string(dims[static_cast<std::size_t>(i)]);
      }
      info.type += ' ';
      info.type += rank == 0 ? "scalar" : shape;
      info.numeric = false;
    }
    read_unit(dataset, info);
    read_sample_rate(dataset, info);
    packings_.push_back(H5Tget_class(type.get()) == H5T_INTEGER ? read_packing(dataset, info) : Packing{});
    H5Eclear2(H5E_DEFAULT);
    channels_.push_back(std::move(info));
  }

  // The CF packing attributes `scale_factor` and `add_offset` (one number each) of an integer dataset;
  // one in another form leaves the samples unreadable, not read packed (they held 0.001 deg/h counts:
  // a mean of 0.22 for 36). A float dataset is not packed: its `scale_factor` may be the gyro's K.
  struct Packing {
    double scale = 1.0;
    double offset = 0.0;
  };
  static Packing read_packing(hid_t dataset, ChannelInfo& info) {
    std::string problem;
    const std::optional<double> scale = attribute_value<double>(dataset, "scale_factor", problem);
    const std::optional<double> offset = attribute_value<double>(dataset, "add_offset", problem);
    if (!problem.empty() || (scale && !std::isfinite(*scale)) || (offset && !std::isfinite(*offset))) {
      info.numeric = false;
      info.type += " (packing scale_factor/add_offset unreadable)";
      return {};
    }
    return {scale.value_or(1.0), offset.value_or(0.0)};
  }

  // The unit: the string attribute `units`, or `unit`. One in another form, or both naming
  // different units, is the channel's unit_problem, not a unit left out or chosen.
  static void read_unit(hid_t dataset, ChannelInfo& info) {
    const std::optional<std::string> units = attribute_value<std::string>(dataset, "units", info.unit_problem);
    const std::optional<std::string> unit = attribute_value<std::string>(dataset, "unit", info.unit_problem);
    if (!info.unit_problem.empty()) return;
    if (units && unit && !same_unit(*units, *unit)) {
      info.unit_problem =
          fmt::format("the dataset's attributes units = {:?} and unit = {:?} contradict each other", *units, *unit);
      return;
    }
    info.unit = units.value_or(unit.value_or(""));
  }

  // The sample rate: the numeric attribute `sample_rate_hz`, or `sample_rate` (Hz), or 1 /
  // `wf_increment` (s; one of 0 or less is no rate). One in another form, or two that differ by
  // more than 1e-9 relative (as resolve_sample_rate compares a given rate), is the channel's
  // sample_rate_problem, not a rate left out or chosen.
  static void read_sample_rate(hid_t dataset, ChannelInfo& info) {
    std::string& problem = info.sample_rate_problem;
    const std::optional<double> rate = attribute_value<double>(dataset, "sample_rate_hz", problem);
    const std::optional<double> rate_alias = attribute_value<double>(dataset, "sample_rate", problem);
    const std::optional<double> increment = attribute_value<double>(dataset, "wf_increment", problem);
    if (!problem.empty()) return;
    struct Stated {
      const char* attribute;
      double value;
      double rate_hz;
    };
    std::vector<Stated> stated;
    if (rate) stated.push_back({"sample_rate_hz", *rate, *rate});
    if (rate_alias) stated.push_back({"sample_rate", *rate_alias, *rate_alias});
    if (increment && *increment > 0.0) stated.push_back({"wf_increment", *increment, 1.0 / *increment});
    if (stated.empty()) return;
    const Stated& first = stated.front();
    for (const Stated& other : std::span(stated).subspan(1)) {  // not first itself: a NaN equals nothing
      if (!(std::abs(other.rate_hz - first.rate_hz) <= 1e-9 * std::abs(first.rate_hz))) {
        const auto described = [](const Stated& s) {
          return std::string(s.attribute) == "wf_increment" ? fmt::format("{} = {} s ({} Hz)", s.attribute, s.value, s.rate_hz)
                                                            : fmt::format("{} = {} Hz", s.attribute, s.value);
        };
        problem = fmt::format("the dataset's attributes {} and {} contradict each other", described(first),
                              described(other));
        return;
      }
    }
    info.sample_rate_hz = first.rate_hz;
  }

  Handle file_;
  Handle dataset_;
  std::vector<Packing> packings_;  // by channel
  std::size_t open_channel_ = static_cast<std::size_t>(-1);
};

}  // namespace

std::unique_ptr<ChannelRecord> open_hdf5_record(const std::string& path) { return std::make_unique<Hdf5Record>(path); }

}  // namespace inertest
