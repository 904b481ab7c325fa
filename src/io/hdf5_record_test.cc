// The HDF5 reader's attributes of a dataset (hdf5_record.cc): files written here through the HDF5
// C API, in the forms h5py gives them (`d.attrs['sample_rate_hz'] = '200'` writes a variable-length
// string, `= np.array([100.0, 200.0])` an array of two doubles).
#include <fmt/format.h>
#include <hdf5.h>
#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

#include "inertest/core/error.h"
#include "inertest/io/channel_record.h"
#include "inertest/io/rate_record.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

// H5S_ALL and H5T_VARIABLE, without the C casts of their macros.
constexpr hid_t kAllOfTheSpace = 0;
constexpr std::size_t kVariableLength = static_cast<std::size_t>(-1);

// A file with one dataset "g" of the samples 1, 2, 3, 4 (f64, or stored as `stored_as`), its
// attributes added one by one.
class Hdf5File {
 public:
  explicit Hdf5File(const std::string& path, hid_t stored_as = H5T_NATIVE_DOUBLE)
      : file_(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT)) {
    const hsize_t count = 4;
    const hid_t space = H5Screate_simple(1, &count, nullptr);
    dataset_ = H5Dcreate2(file_, "g", stored_as, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
    const std::vector<double> samples = {1.0, 2.0, 3.0, 4.0};
    H5Dwrite(dataset_, H5T_NATIVE_DOUBLE, kAllOfTheSpace, kAllOfTheSpace, H5P_DEFAULT, samples.data());
    H5Sclose(space);
  }
  Hdf5File(const Hdf5File&) = delete;
  Hdf5File& operator=(const Hdf5File&) = delete;
  ~Hdf5File() {
    H5Dclose(dataset_);
    H5Fclose(file_);
  }

  // A number as a scalar (one value) or an array (several), stored as `type`.
  Hdf5File& numbers(const char* name, const std::vector<double>& values, hid_t type = H5T_NATIVE_DOUBLE) {
    const hsize_t count = values.size();
    const hid_t space = values.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr);
    const hid_t attribute = H5Acreate2(dataset_, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, H5T_NATIVE_DOUBLE, values.data());
    H5Aclose(attribute);
    H5Sclose(space);
    return *this;
  }
  // Variable-length UTF-8 strings, as h5py writes a str: a scalar (one) or an array (several).
  Hdf5File& strings(const char* name, const std::vector<const char*>& values) {
    const hsize_t count = values.size();
    const hid_t space = values.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, &count, nullptr);
    const hid_t type = H5Tcopy(H5T_C_S1);
    H5Tset_size(type, kVariableLength);
    H5Tset_cset(type, H5T_CSET_UTF8);
    const hid_t attribute = H5Acreate2(dataset_, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
    H5Awrite(attribute, type, values.data());
    H5Aclose(attribute);
    H5Tclose(type);
    H5Sclose(space);
    return *this;
  }

 private:
  hid_t file_;
  hid_t dataset_ = H5I_INVALID_HID;
};

void expect_error(const std::function<void()>& action, const std::string& path, const std::string& message) {
  try {
    action();
    ADD_FAILURE() << "no error, expected: " << message;
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->file, path);
    EXPECT_EQ(e.message(), message);
  }
}

// A rate attribute the reader could not take as one number was taken for no rate at all, and any
// --rate was accepted (QA's rate_string.h5, sample_rate_hz = "200"; rate_array.h5, [100, 200]). It is
// the channel's sample_rate_problem: the samples read, the rate, given or not, is an error naming
// the file, the dataset and the attribute.
TEST(Hdf5Record, RateAttributeThatIsNotOneNumberIsAnError) {
  testing::ScratchDirectory dir;
  const std::string text = dir.path() + "/text.h5";
  const std::string array = dir.path() + "/array.h5";
  const std::string integer = dir.path() + "/integer.h5";
  Hdf5File(text).strings("sample_rate_hz", {"200"});
  Hdf5File(array).numbers("sample_rate_hz", {100.0, 200.0});
  Hdf5File(integer).numbers("sample_rate_hz", {100.0}, H5T_NATIVE_UINT16).strings("units", {"deg/s"});
  const std::vector<std::pair<std::string, std::string>> cases = {
      {text, "the string \"200\""}, {array, "2 numbers"}};
  for (const auto& one_case : cases) {
    const std::string& path = one_case.first;  // not a structured binding: the lambdas capture it (clang 14)
    const std::string& found = one_case.second;
    SCOPED_TRACE(path);
    const auto record = open_channel_record(path, ChannelRecordFormat::kHdf5);
    EXPECT_THAT(read_channel(*record, 0), ::testing::ElementsAre(1, 2, 3, 4));
    EXPECT_EQ(record->channels()[0].sample_rate_hz, std::nullopt);
    const std::string message =
        "channel 'g': the dataset's attribute sample_rate_hz is unreadable: expected one number, found " + found;
    expect_error([&] { resolve_sample_rate(*record, 0, 100.0); }, path, message);
    expect_error([&] { resolve_sample_rate(*record, 0, std::nullopt); }, path, message);
    expect_error([&] { stored_sample_rate({path, RateRecordFormat::kAuto, ColumnSelector::parse("g")}); }, path,
                 message);
  }
  // An integer is one number.
  const auto record = open_channel_record(integer, ChannelRecordFormat::kHdf5);
  EXPECT_EQ(resolve_sample_rate(*record, 0, std::nullopt), 100.0);
  EXPECT_EQ(resolve_unit(*record, 0, std::nullopt), "deg/s");
}

// The same for the unit: a number, or several strings, is no unit the reader may leave out.
TEST(Hdf5Record, UnitAttributeThatIsNotOneStringIsAnError) {
  testing::ScratchDirectory dir;
  const std::string number = dir.path() + "/number.h5";
  const std::string several = dir.path() + "/several.h5";
  Hdf5File(number).numbers("units", {3.0});
  Hdf5File(several).strings("unit", {"deg/s", "x"});
  const std::vector<std::pair<std::string, std::string>> cases = {
      {number, "attribute units is unreadable: expected one string, found the number 3"},
      {several, "attribute unit is unreadable: expected one string, found 2 strings"}};
  for (const auto& [path, problem] : cases) {
    SCOPED_TRACE(path);
    const auto record = open_channel_record(path, ChannelRecordFormat::kHdf5);
    EXPECT_EQ(record->channels()[0].unit, "");
    for (const std::optional<std::string>& given : {std::optional<std::string>(), std::optional<std::string>("deg/s")}) {
      expect_error([&] { resolve_unit(*record, 0, given); }, path, "channel 'g': the dataset's " + problem);
    }
  }
}

// Attributes that state the rate or the unit twice must agree: the reader took the first and left
// the other unread (QA's rate_conflict.h5, sample_rate_hz = 100 and wf_increment = 0.005;
// unit_conflict.h5, units = "deg/s" and unit = "deg/h"). Agreeing ones are one rate, one unit.
TEST(Hdf5Record, AttributesThatContradictEachOtherAreAnError) {
  testing::ScratchDirectory dir;
  const std::string rates = dir.path() + "/rates.h5";
  const std::string aliases = dir.path() + "/aliases.h5";
  const std::string units = dir.path() + "/units.h5";
  Hdf5File(rates).numbers("sample_rate_hz", {100.0}).numbers("wf_increment", {0.005});
  Hdf5File(aliases).numbers("sample_rate_hz", {100.0}).numbers("sample_rate", {100.5});
  Hdf5File(units).strings("units", {"deg/s"}).strings("unit", {"deg/h"});
  expect_error([&] { resolve_sample_rate(*open_channel_record(rates, ChannelRecordFormat::kHdf5), 0, 100.0); }, rates,
               "channel 'g': the dataset's attributes sample_rate_hz = 100 Hz and wf_increment = 0.005 s (200 Hz) "
               "contradict each other");
  expect_error([&] { resolve_sample_rate(*open_channel_record(aliases, ChannelRecordFormat::kHdf5), 0, std::nullopt); },
               aliases, "channel 'g': the dataset's attributes sample_rate_hz = 100 Hz and sample_rate = 100.5 Hz "
                        "contradict each other");
  expect_error([&] { resolve_unit(*open_channel_record(units, ChannelRecordFormat::kHdf5), 0, std::nullopt); }, units,
               "channel 'g': the dataset's attributes units = \"deg/s\" and unit = \"deg/h\" contradict each other");

  const std::string agreeing = dir.path() + "/agreeing.h5";
  Hdf5File(agreeing)
      .numbers("sample_rate_hz", {100.0})
      .numbers("sample_rate", {100.0 * (1.0 + 5e-10)})
      .numbers("wf_increment", {0.01})
      .strings("units", {"deg/s"})
      .strings("unit", {"\u00b0/s"});
  const auto record = open_channel_record(agreeing, ChannelRecordFormat::kHdf5);
  EXPECT_EQ(resolve_sample_rate(*record, 0, std::nullopt), 100.0);
  EXPECT_EQ(resolve_unit(*record, 0, std::nullopt), "deg/s");
}

// A sample interval stored in single precision (0.01 s as a float: 100.0000022 Hz) agrees with the
// 100 Hz given; 100.01 Hz does not.
TEST(Hdf5Record, ARateStoredAsAFloatAgreesWithTheRateItRounds) {
  const testing::ScratchDirectory dir;
  const std::string path = dir.path() + "/float.h5";
  Hdf5File(path).numbers("wf_increment", {static_cast<double>(0.01F)});
  const auto record = open_channel_record(path, ChannelRecordFormat::kHdf5);
  EXPECT_NEAR(resolve_sample_rate(*record, 0, 100.0), 100.0, 1e-5);
  EXPECT_THROW(resolve_sample_rate(*record, 0, 100.01), Error);
}

// Packed samples (CF scale_factor and add_offset, as netCDF-4 and xarray write integers) are
// unpacked; packing attributes that are not one number each leave the channel unreadable.
TEST(Hdf5Record, PackedSamplesAreUnpacked) {
  const testing::ScratchDirectory dir;
  const std::string packed = dir.path() + "/packed.h5";
  Hdf5File(packed, H5T_NATIVE_INT16).numbers("scale_factor", {0.5}).numbers("add_offset", {36.0});
  EXPECT_THAT(read_channel(*open_channel_record(packed, ChannelRecordFormat::kHdf5), 0),
              ::testing::ElementsAre(36.5, 37.0, 37.5, 38.0));
  // Floats are not packed: a scale_factor there may be the gyro's K, and is left alone.
  const std::string floats = dir.path() + "/floats.h5";
  Hdf5File(floats).numbers("scale_factor", {0.5}).strings("add_offset", {"none"});
  EXPECT_THAT(read_channel(*open_channel_record(floats, ChannelRecordFormat::kHdf5), 0),
              ::testing::ElementsAre(1.0, 2.0, 3.0, 4.0));
  const std::string bad = dir.path() + "/bad.h5";
  Hdf5File(bad, H5T_NATIVE_INT16).numbers("scale_factor", {0.5, 2.0});
  const auto record = open_channel_record(bad, ChannelRecordFormat::kHdf5);
  EXPECT_FALSE(record->channels()[0].numeric);
  EXPECT_THAT(record->channels()[0].type, ::testing::HasSubstr("packing scale_factor/add_offset unreadable"));
}

// A unit as a logger writes it (DEG/S) is the unit it names: records of rates read as deg/h
// (--input-deg-h) are converted from it. One inertest does not know is an error, not deg/h: taken
// as deg/h, a channel of 2 deg/s stored as DEG/S gave a bias of 2 deg/h instead of 7200.
TEST(Hdf5Record, ARateRecordIsReadInTheUnitItStoresHoweverSpelt) {
  const testing::ScratchDirectory dir;
  const std::string capitals = dir.path() + "/capitals.h5";
  Hdf5File(capitals).numbers("sample_rate_hz", {1.0}).strings("units", {"DEG/S"});
  testing::CliRun run = testing::run_cli({"bias", capitals, "--input-deg-h", "--smoothing", "1", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NEAR(nlohmann::json::parse(run.out).at("bias").at("value").get<double>(), 2.5 * 3600.0, 1e-9);
  const std::string unknown = dir.path() + "/unknown.h5";
  Hdf5File(unknown).numbers("sample_rate_hz", {1.0}).strings("units", {"furlong/fortnight"});
  run = testing::run_cli({"bias", unknown, "--input-deg-h", "--smoothing", "1"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, ::testing::HasSubstr(unknown + ": channel 'g' stores the unit 'furlong/fortnight', which inertest "
                                                      "does not know"));
}

}  // namespace
}  // namespace inertest
