// Records of named channels written by other implementations: .mat by scipy.io.savemat (v5, v7),
// HDF5 by h5py (data/lab_formats/make_records.py), TDMS by LabVIEW and NI-DAQmx (data/tdms/, from
// npTDMS's test data, with the values npTDMS's tests expect).
#include "inertest/io/channel_record.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "inertest/core/error.h"
#include "inertest/io/output_record.h"
#include "inertest/io/rate_record.h"
#include "test_util/test_util.h"

namespace inertest {
namespace {

using ::testing::HasSubstr;

// The formulas of data/lab_formats/make_records.py.
double known_rate(std::size_t i) { return 0.001 * static_cast<double>(i) - 0.25; }
double known_gyro_x(std::size_t i) { return (static_cast<double>(i % 7) - 3.0) * 0.5; }

std::string lab_file(const std::string& name) { return testing::source_path("data/lab_formats/" + name); }
std::string tdms_file(const std::string& name) { return testing::source_path("data/tdms/" + name); }

const ChannelInfo& channel_named(const ChannelRecord& record, const std::string& name) {
  return record.channels()[record.find(ColumnSelector::parse(name))];
}

TEST(ChannelRecord, DetectsFormatsByMagicBytesNotExtension) {
  EXPECT_EQ(detect_channel_record_format(lab_file("record_v5.mat")), ChannelRecordFormat::kMat);
  EXPECT_EQ(detect_channel_record_format(lab_file("record_v7.mat")), ChannelRecordFormat::kMat);
  EXPECT_EQ(detect_channel_record_format(lab_file("record.h5")), ChannelRecordFormat::kHdf5);
  EXPECT_EQ(detect_channel_record_format(tdms_file("big_endian.tdms")), ChannelRecordFormat::kTdms);
  testing::ScratchDirectory dir;
  EXPECT_EQ(detect_channel_record_format(dir.write("record.h5", "t,rate\n0,1\n")), std::nullopt);
  // An HDF5 file behind a 512-byte user block (as MATLAB v7.3 writes one) is still HDF5.
  const std::string hdf5 = testing::read_file(lab_file("record.h5"));
  const std::string blocked = dir.write("blocked.bin", std::string(512, 'x') + hdf5);
  EXPECT_EQ(detect_channel_record_format(blocked), ChannelRecordFormat::kHdf5);
}

TEST(ChannelRecord, MatV5AndV7WrittenByScipy) {
  for (const std::string name : {"record_v5.mat", "record_v7.mat"}) {
    SCOPED_TRACE(name);
    const auto record = open_channel_record(lab_file(name), ChannelRecordFormat::kMat);
    const ChannelInfo& rate = channel_named(*record, "rate");
    EXPECT_EQ(rate.type, "f64");
    EXPECT_EQ(rate.length, 1000u);
    EXPECT_EQ(channel_named(*record, "imu.gyro_x").type, "f32");
    EXPECT_EQ(channel_named(*record, "imu.temperature").type, "i16");
    const std::vector<double> samples = read_channel(*record, record->find(ColumnSelector::parse("rate")));
    ASSERT_EQ(samples.size(), 1000u);
    for (std::size_t i = 0; i < samples.size(); ++i) ASSERT_EQ(samples[i], known_rate(i)) << i;
    const std::vector<double> gyro = read_channel(*record, record->find(ColumnSelector::parse("imu.gyro_x")));
    for (std::size_t i = 0; i < gyro.size(); ++i) ASSERT_EQ(gyro[i], known_gyro_x(i)) << i;
    const std::vector<double> temperature = read_channel(*record, record->find(ColumnSelector::parse("imu.temperature")));
    EXPECT_EQ(temperature[123], 23.0);
    // A 2 x 3 matrix is listed, not read as samples.
    try {
      record->find(ColumnSelector::parse("matrix"));
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_THAT(e.message(), HasSubstr("channel 'matrix' holds f64 2x3 values, not numbers"));
    }
  }
}

// Two variables of one name, a complex one first (libFuzzer's find): matio reads the first, whose
// data (two pointers) was read as the second's 8 samples, past its end. It is an error naming the
// channel.
TEST(ChannelRecord, MatTwoVariablesOfOneNameAreAnErrorNotAnOverrun) {
  const std::string path = testing::source_path("fuzz/corpus/mat_record/two_variables_of_one_name_complex_first");
  const auto record = open_channel_record(path, ChannelRecordFormat::kMat);
  ASSERT_EQ(record->channels().size(), 2u);
  ASSERT_TRUE(record->channels()[1].numeric);
  try {
    read_channel(*record, 1);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), ::testing::HasSubstr("channel 'rate': the file holds another variable of this name before it"));
  }
}

TEST(ChannelRecord, Hdf5WrittenByH5pyWithUnitsRateAndChunks) {
  const auto record = open_channel_record(lab_file("record.h5"), ChannelRecordFormat::kHdf5);
  const std::size_t gyro = record->find(ColumnSelector::parse("/imu/gyro_x"));
  const ChannelInfo& info = record->channels()[gyro];
  EXPECT_EQ(info.name, "imu/gyro_x");
  EXPECT_EQ(info.type, "f64");
  EXPECT_EQ(info.unit, "deg/h");
  EXPECT_EQ(info.sample_rate_hz, 200.0);
  EXPECT_EQ(info.length, 10000u);
  EXPECT_EQ(channel_named(*record, "imu/temperature").type, "i16");
  // A range across chunk boundaries, read by hyperslab.
  std::vector<double> part(2500);
  record->read(gyro, 1234, part);
  for (std::size_t i = 0; i < part.size(); ++i) ASSERT_EQ(part[i], known_rate((1234 + i) / 10)) << i;
  EXPECT_THROW(record->read(gyro, 9999, std::span<double>(part.data(), 2)), Error);
}

TEST(ChannelRecord, RateRecordAndOutputRecordReadChannelsByName) {
  const std::vector<double> direct = read_output_record({lab_file("record_v7.mat"), "", "imu.gyro_x", std::nullopt});
  EXPECT_EQ(direct[10], known_gyro_x(10));
  std::vector<double> streamed;
  const std::size_t count = read_rate_record({lab_file("record.h5"), RateRecordFormat::kAuto, ColumnSelector::parse("imu/gyro_x")},
                                             [&](std::span<const double> chunk) { streamed.insert(streamed.end(), chunk.begin(), chunk.end()); });
  EXPECT_EQ(count, 10000u);
  EXPECT_EQ(streamed[9999], known_rate(999));
  EXPECT_EQ(stored_sample_rate({lab_file("record.h5"), RateRecordFormat::kAuto, ColumnSelector::parse("imu/gyro_x")}), 200.0);
  // The stored rate gives the times; a rate that contradicts it is an error naming both.
  const TimedRecord timed =
      read_timed_record({lab_file("record.h5"), "auto", "imu/gyro_x", std::nullopt}, std::nullopt);
  EXPECT_DOUBLE_EQ(timed.time_s[199], 1.0);
  try {
    read_timed_record({lab_file("record.h5"), "", "imu/gyro_x", std::nullopt}, 100.0);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("the sample rate given, 100 Hz, contradicts the 200 Hz stored for channel 'imu/gyro_x'"));
  }
}

// The unit of the samples: the one given, else the stored one; a given unit that contradicts the
// stored one is an error naming both (allan read a channel stored in deg/s as deg/h).
TEST(ChannelRecord, StoredUnitIsUsedAndAContradictionIsAnError) {
  const auto record = open_channel_record(lab_file("record.h5"), ChannelRecordFormat::kHdf5);
  const std::size_t gyro = record->find(ColumnSelector::parse("imu/gyro_x"));
  const std::size_t temperature = record->find(ColumnSelector::parse("imu/temperature"));
  EXPECT_EQ(resolve_unit(*record, gyro, std::nullopt), "deg/h");
  EXPECT_EQ(resolve_unit(*record, gyro, std::string("°/h")), "°/h");  // the same unit
  EXPECT_EQ(resolve_unit(*record, temperature, std::nullopt), std::nullopt);  // none stored, none given
  EXPECT_EQ(resolve_unit(*record, temperature, std::string("degC")), "degC");
  for (const char* other : {"deg/s", "m/s^2"}) {
    try {
      resolve_unit(*record, gyro, std::string(other));
      FAIL() << other;
    } catch (const Error& e) {
      EXPECT_EQ(e.location()->file, lab_file("record.h5"));
      EXPECT_EQ(e.message(), fmt::format("the unit given, {}, contradicts the unit deg/h stored for channel 'imu/gyro_x'",
                                         other));
    }
  }
  EXPECT_EQ(resolved_unit({lab_file("record.h5"), RateRecordFormat::kAuto, ColumnSelector::parse("imu/gyro_x")},
                          std::nullopt),
            "deg/h");
}

// A text column whose header states its unit ("gyro_x [deg/s]") holds samples in it, as a channel
// that stores one: allan read 0.01 deg/s as deg/h, a mean 3600 times too small.
TEST(ChannelRecord, AUnitATextHeaderStatesIsTheColumnsUnit) {
  const SourceLocation header{"r.csv", 1, 0};
  EXPECT_EQ(unit_stated_in_name("gyro_x [deg/s]", header), "deg/s");
  EXPECT_EQ(unit_stated_in_name("rate (deg/h) ", header), "deg/h");
  EXPECT_EQ(unit_stated_in_name("ax[ m/s^2 ]", header), "m/s^2");
  EXPECT_EQ(unit_stated_in_name("gyro (dph)", header), "dph");           // deg/h, as labs abbreviate it
  EXPECT_EQ(unit_stated_in_name("fog (pulses/s)", header), "pulses/s");  // a raw output's unit
  for (const char* none : {"gyro_x", "gx[1]", "ratio (%)", "output (raw)", "[deg/s]", "deg/s", "rate [foo]",
                           "fog (inc/s)"}) {
    EXPECT_EQ(unit_stated_in_name(none, header), std::nullopt) << none;
  }
  // A unit inertest does not read is no note: read as none, the samples were taken in deg/h.
  for (const char* unread : {"gyro (mdps)", "gyro (Deg s-1)", "gyro (DEG S-1)", "gyro (度/秒)", "gyro (º/s)",
                             "gyro (Degrees per second)"}) {
    EXPECT_THROW(unit_stated_in_name(unread, header), Error) << unread;
  }
  try {
    unit_stated_in_name("rate [deg s-1]", header);
    ADD_FAILURE() << "[deg s-1] was read as no unit";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "r.csv:1: column 'rate [deg s-1]': 'deg s-1' reads as a unit inertest does not "
                                     "know; write it as deg/s, deg/h, rad/s...");
  }
  const testing::ScratchDirectory scratch;
  std::string text = "time [s],gyro_x [deg/s],gyro_y\n";
  for (int i = 0; i < 400; ++i) text += fmt::format("{},{},{}\n", 0.01 * i, i % 2 == 0 ? 0.011 : 0.009, 1.0);
  const std::string path = scratch.write("gyro.csv", text);
  EXPECT_EQ(resolve_text_unit(path, ColumnSelector::parse("gyro_x [deg/s]"), std::nullopt), "deg/s");
  EXPECT_EQ(resolve_text_unit(path, ColumnSelector::parse("2"), std::string("°/s")), "°/s");
  EXPECT_EQ(resolve_text_unit(path, ColumnSelector::parse("3"), std::nullopt), std::nullopt);
  // A header's angle unit inertest does not read is an error unless a unit is given, which stands.
  std::string unread = "time [s],rate [deg s-1]\n";
  for (int i = 0; i < 400; ++i) unread += fmt::format("{},{}\n", 0.01 * i, i % 2 == 0 ? 0.011 : 0.009);
  const std::string unread_path = scratch.write("unread.csv", unread);
  EXPECT_THROW(resolve_text_unit(unread_path, ColumnSelector::parse("2"), std::nullopt), Error);
  EXPECT_EQ(resolve_text_unit(unread_path, ColumnSelector::parse("2"), std::string("deg/s")), "deg/s");
  EXPECT_EQ(testing::run_cli({"allan", unread_path, "--columns", "2", "--input-unit", "deg/s", "--rate", "100"}).exit_code,
            0);
  EXPECT_EQ(testing::run_cli({"allan", unread_path, "--columns", "2", "--rate", "100"}).exit_code, 2);
  testing::CliRun run = testing::run_cli({"allan", path, "--column", "2", "--rate", "100", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out).at("mean").at("unit"), "deg/s");
  EXPECT_NEAR(nlohmann::json::parse(run.out).at("mean").at("value").get<double>(), 0.01, 1e-12);
  run = testing::run_cli({"bias", path, "--column", "2", "--rate", "100", "--input-deg-h", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NEAR(nlohmann::json::parse(run.out).at("bias").at("value").get<double>(), 36.0, 1e-9);
  run = testing::run_cli({"allan", path, "--column", "2", "--rate", "100", "--input-unit", "deg/h"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, ::testing::HasSubstr(path + ":1: the unit given, deg/h, contradicts the unit deg/s the header "
                                                   "states for column 'gyro_x [deg/s]'"));
  run = testing::run_cli({"allan", path, "--columns", "2,3", "--rate", "100", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out).at("channels").at("gyro_x [deg/s]").at("mean").at("unit"), "deg/s");
  EXPECT_EQ(nlohmann::json::parse(run.out).at("channels").at("gyro_y").at("mean").at("unit"), "deg/h");
  // With a scale factor the channels are raw output: a stated rate is none (it was divided by K and
  // labelled deg/s), a channel stating nothing is taken to deg/h.
  run = testing::run_cli({"allan", path, "--columns", "2,3", "--rate", "100", "--scale-factor", "36"});
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, ::testing::HasSubstr(path + ":1: the unit deg/s the header states for column 'gyro_x [deg/s]' "
                                                   "is a rate or an acceleration, not a raw output"));
  run = testing::run_cli({"allan", path, "--columns", "3", "--rate", "100", "--scale-factor", "36", "--json"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out).at("channels").at("gyro_y").at("mean").at("unit"), "deg/h");
  EXPECT_NEAR(nlohmann::json::parse(run.out).at("channels").at("gyro_y").at("mean").at("value").get<double>(), 100.0,
              1e-9);
}

TEST(ChannelRecord, MissingChannelListsTheChannels) {
  const auto record = open_channel_record(lab_file("record.h5"), ChannelRecordFormat::kHdf5);
  try {
    record->find(ColumnSelector::parse("imu/gyro_y"));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->file, lab_file("record.h5"));
    EXPECT_EQ(e.message(), "no channel 'imu/gyro_y' in the record (channels: imu/gyro_x, imu/temperature, matrix)");
  }
}

// Written by LabVIEW (npTDMS's test data; values as npTDMS's tests expect them).
TEST(ChannelRecord, TdmsWrittenByLabview) {
  const auto record = open_channel_record(tdms_file("Digital_Input.tdms"), ChannelRecordFormat::kTdms);
  const std::size_t line = record->find(ColumnSelector::parse(
      "07/09/2012 06:58:23 PM - Digital Input - Decimated Data_Level1/Dev1_port3_line7 - line 0"));
  EXPECT_EQ(record->channels()[line].type, "u8");
  std::vector<double> first(10);
  record->read(line, 0, first);
  EXPECT_THAT(first, ::testing::ElementsAre(0, 1, 0, 1, 0, 1, 0, 1, 0, 1));
}

TEST(ChannelRecord, TdmsBigEndianWrittenByLabview) {
  const auto record = open_channel_record(tdms_file("big_endian.tdms"), ChannelRecordFormat::kTdms);
  const std::size_t sweep = record->find(ColumnSelector::parse("Measured Data/Phase sweep"));
  std::vector<double> first(10);
  record->read(sweep, 0, first);
  const std::vector<double> expected = {0.0000000, 0.0634176, 0.1265799, 0.1892325, 0.2511234,
                                        0.3120033, 0.3716271, 0.4297548, 0.4861524, 0.5405928};
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(first[i], expected[i], 5e-8) << i;
}

// DAQmx raw data: int16 samples in a strided buffer, scaled by the channel's NI_Scale[1] (linear),
// whose input source 0 is NI_Scale[0]: no Scale_Type, so the DAQmx scaler's own (raw) value.
TEST(ChannelRecord, TdmsDaqmxRawDataScaled) {
  const auto record = open_channel_record(tdms_file("raw1.tdms"), ChannelRecordFormat::kTdms);
  const std::size_t first_channel = record->find(ColumnSelector::parse("Layer Data/First  Channel"));
  std::vector<double> first(10);
  record->read(first_channel, 0, first);
  const std::vector<double> expected = {-0.18402661, 0.14801477, -0.24506363, -0.29725028, -0.20020142,
                                        0.18158513,  0.02380444, 0.20661031,  0.20447401,  0.2517777};
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(first[i], expected[i], 5e-9) << i;
}

}  // namespace
}  // namespace inertest

namespace inertest {
namespace {

// A TDMS file assembled here byte by byte as NI's format description lays it out (the layouts no
// file above has): an interleaved segment, then a raw-data-only segment repeating the object list
// and indices contiguously, and the same metadata as a .tdms_index file.
class TdmsBytes {
 public:
  void u32(std::uint32_t v) { append(&v, 4); }
  void u64(std::uint64_t v) { append(&v, 8); }
  void i32(std::int32_t v) { append(&v, 4); }
  void f64(double v) { append(&v, 8); }
  void text(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    bytes += s;
  }
  std::string bytes;

 private:
  void append(const void* v, std::size_t n) { bytes.append(static_cast<const char*>(v), n); }
};

std::string lead_in(const char* tag, std::uint32_t toc, std::uint64_t next, std::uint64_t raw) {
  TdmsBytes b;
  b.bytes = tag;
  b.u32(toc);
  b.u32(4713);
  b.u64(next);
  b.u64(raw);
  return b.bytes;
}

TEST(ChannelRecord, TdmsInterleavedThenContiguousSegmentsAndIndexFile) {
  constexpr std::uint32_t kMeta = 2, kNewList = 4, kRaw = 8, kInterleaved = 32;
  TdmsBytes meta;
  meta.u32(2);  // objects
  meta.text("/'g'/'a'");
  meta.u32(20);  // index length
  meta.u32(3);   // tdsTypeI32
  meta.u32(1);
  meta.u64(3);
  meta.u32(1);  // one property
  meta.text("unit_string");
  meta.u32(0x20);
  meta.text("deg/h");
  meta.text("/'g'/'b''s'");
  meta.u32(20);
  meta.u32(10);  // tdsTypeDoubleFloat
  meta.u32(1);
  meta.u64(3);
  meta.u32(1);
  meta.text("wf_increment");
  meta.u32(10);
  meta.f64(0.01);
  TdmsBytes interleaved;
  for (int i = 0; i < 3; ++i) {
    interleaved.i32(10 + i);
    interleaved.f64(0.5 * i);
  }
  TdmsBytes contiguous;
  for (int i = 0; i < 3; ++i) contiguous.i32(20 + i);
  for (int i = 0; i < 3; ++i) contiguous.f64(-1.0 - i);
  const std::string first = meta.bytes + interleaved.bytes;
  std::string file = lead_in("TDSm", kMeta | kNewList | kRaw | kInterleaved, first.size(), meta.bytes.size()) + first;
  file += lead_in("TDSm", kRaw, contiguous.bytes.size(), 0) + contiguous.bytes;
  const std::string index = lead_in("TDSh", kMeta | kNewList | kRaw | kInterleaved, first.size(), meta.bytes.size()) +
                            meta.bytes + lead_in("TDSh", kRaw, contiguous.bytes.size(), 0);
  testing::ScratchDirectory dir;
  const std::string path = dir.write("made.tdms", file);
  for (const bool with_index : {false, true}) {
    SCOPED_TRACE(with_index ? "with index" : "without index");
    if (with_index) dir.write("made.tdms_index", index);
    const auto record = open_channel_record(path, ChannelRecordFormat::kTdms);
    const std::size_t a = record->find(ColumnSelector::parse("g/a"));
    const std::size_t b = record->find(ColumnSelector::parse("g/b's"));
    EXPECT_EQ(record->channels()[a].unit, "deg/h");
    EXPECT_EQ(record->channels()[a].type, "i32");
    EXPECT_EQ(record->channels()[b].sample_rate_hz, 100.0);
    EXPECT_THAT(read_channel(*record, a), ::testing::ElementsAre(10, 11, 12, 20, 21, 22));
    EXPECT_THAT(read_channel(*record, b), ::testing::ElementsAre(0, 0.5, 1, -1, -2, -3));
  }
  // An index file that does not match the data file is refused, naming the offset.
  dir.write("made.tdms_index", lead_in("TDSh", kMeta | kNewList | kRaw, first.size(), meta.bytes.size()) + meta.bytes);
  try {
    open_channel_record(path, ChannelRecordFormat::kTdms);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.message(), HasSubstr("byte offset 0: the segment lead-in differs from the one in the index file"));
  }
}

}  // namespace
}  // namespace inertest

namespace inertest {
namespace {

constexpr std::uint32_t kTocMetaData = 2, kTocNewObjList = 4, kTocRawData = 8, kTocInterleaved = 32, kTocDaqmx = 128;
constexpr std::uint32_t kRawDataInputSource = 0xFFFFFFFF;

// A DAQmx segment of one channel "/'g'/'c'": i16 raw values in a 2-byte stride (format changing
// scaler, index 0x1269), the NI_Scale[n] properties given as (type, name, number or text).
struct ScaleProperty {
  std::string name;
  std::uint32_t type;  // 7 u32, 10 f64, 0x20 string
  double number = 0.0;
  std::string text = {};
};

void write_properties(TdmsBytes& meta, const std::vector<ScaleProperty>& properties) {
  meta.u32(static_cast<std::uint32_t>(properties.size()));
  for (const ScaleProperty& p : properties) {
    meta.text(p.name);
    meta.u32(p.type);
    if (p.type == 0x20) {
      meta.text(p.text);
    } else if (p.type == 7) {
      meta.u32(static_cast<std::uint32_t>(p.number));
    } else {
      meta.f64(p.number);
    }
  }
}

std::string daqmx_file(const std::vector<std::int16_t>& raw, const std::vector<ScaleProperty>& properties) {
  TdmsBytes meta;
  meta.u32(1);
  meta.text("/'g'/'c'");
  meta.u32(0x1269);
  meta.u32(0xFFFFFFFF);  // DAQmx raw data type
  meta.u32(1);
  meta.u64(raw.size());
  meta.u32(1);  // one scaler: i16 (DAQmx type 3), buffer 0, byte offset 0, sample format bitmap, scale id 0
  for (const std::uint32_t v : {3u, 0u, 0u, 0u, 0u}) meta.u32(v);
  meta.u32(1);  // one raw buffer, 2 bytes wide
  meta.u32(2);
  write_properties(meta, properties);
  std::string data;
  for (const std::int16_t v : raw) data.append(reinterpret_cast<const char*>(&v), 2);
  return lead_in("TDSm", kTocMetaData | kTocNewObjList | kTocRawData | kTocDaqmx, meta.bytes.size() + data.size(),
                 meta.bytes.size()) +
         meta.bytes + data;
}

// NI_Scale[n]: linear y = slope x + intercept of the output of scale `source` (0xFFFFFFFF: the raw data).
std::vector<ScaleProperty> linear_scale(std::size_t n, double slope, double intercept, double source) {
  const std::string prefix = fmt::format("NI_Scale[{}]_", n);
  return {{prefix + "Scale_Type", 0x20, 0.0, "Linear"},
          {prefix + "Linear_Slope", 10, slope},
          {prefix + "Linear_Y_Intercept", 10, intercept},
          {prefix + "Linear_Input_Source", 7, source}};
}

std::vector<ScaleProperty> scales(std::initializer_list<std::vector<ScaleProperty>> each) {
  std::vector<ScaleProperty> all{{"NI_Number_Of_Scales", 7, static_cast<double>(each.size())}};
  for (const auto& scale : each) all.insert(all.end(), scale.begin(), scale.end());
  return all;
}

// The metadata of objects "/'g'/'a'", "/'g'/'b'"... each with a raw data index of `type` and its count.
std::string object_list(std::uint32_t type, const std::vector<std::uint64_t>& counts) {
  TdmsBytes meta;
  meta.u32(static_cast<std::uint32_t>(counts.size()));
  for (std::size_t i = 0; i < counts.size(); ++i) {
    meta.text(fmt::format("/'g'/'{}'", static_cast<char>('a' + i)));
    meta.u32(20);
    meta.u32(type);
    meta.u32(1);
    meta.u64(counts[i]);
    meta.u32(0);  // no properties
  }
  return meta.bytes;
}

std::string tdms_segment(std::uint32_t toc, const std::string& metadata, const std::string& data) {
  return lead_in("TDSm", toc, metadata.size() + data.size(), metadata.size()) + metadata + data;
}

// A channel of plain (not DAQmx) raw data that NI_Scaling_Status "unscaled" says its NI_Scale[n]
// properties scale, as npTDMS reads it: its counts were read as the rate (21.6 for 36.0 deg/h).
// "scaled" data are the values already.
TEST(ChannelRecord, TdmsUnscaledPlainDataIsScaled) {
  const testing::ScratchDirectory dir;
  for (const char* status : {"unscaled", "scaled"}) {
    TdmsBytes meta;
    meta.u32(1);
    meta.text("/'g'/'a'");
    meta.u32(20);
    meta.u32(2);  // i16
    meta.u32(1);
    meta.u64(3);
    std::vector<ScaleProperty> properties = scales({linear_scale(0, 0.001, 36.0, kRawDataInputSource)});
    properties.push_back({"NI_Scaling_Status", 0x20, 0.0, status});
    write_properties(meta, properties);
    std::string data;
    for (const std::int16_t v : {std::int16_t{-100}, std::int16_t{0}, std::int16_t{250}}) {
      data.append(reinterpret_cast<const char*>(&v), 2);
    }
    const std::string path =
        dir.write(fmt::format("{}.tdms", status), tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData, meta.bytes, data));
    const std::vector<double> values = read_channel(*open_channel_record(path, ChannelRecordFormat::kTdms), 0);
    if (std::string(status) == "unscaled") {
      EXPECT_THAT(values, ::testing::ElementsAre(35.9, 36.0, 36.25));
    } else {
      EXPECT_THAT(values, ::testing::ElementsAre(-100.0, 0.0, 250.0));
    }
  }
}

// Interleaved data holds one value of each object a frame: objects of different counts in one
// interleaved segment were read frame by frame past the shorter one's values (QA's
// t11_inter_counts.tdms: f64 means of -3e304) with no error.
TEST(ChannelRecord, TdmsInterleavedObjectsOfDifferentCountsAreAnError) {
  constexpr std::uint32_t kI32 = 3;
  TdmsBytes values;
  for (int i = 0; i < 5; ++i) values.i32(i);
  const std::string first = tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData, object_list(kI32, {2, 2}),
                                         values.bytes.substr(0, 16));
  testing::ScratchDirectory dir;
  const std::string path = dir.write(
      "counts.tdms", first + tdms_segment(kTocMetaData | kTocRawData | kTocInterleaved, object_list(kI32, {3, 2}),
                                          values.bytes.substr(0, 20)));
  try {
    open_channel_record(path, ChannelRecordFormat::kTdms);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->file, path);
    EXPECT_EQ(e.message(), fmt::format("byte offset {}: interleaved raw data with 3 values of object /'g'/'a' but 2 of "
                                       "object /'g'/'b': interleaved data holds the same number of values of every "
                                       "object",
                                       first.size()));
  }
}

// A raw data index's count times the value size must fit in 64 bits and, in a segment whose lead-in
// gives its length, within the segment's raw data. QA's t12_overflow.tdms: 2^61 + 1000 f64 values
// wrapped to 8000 bytes and read as 1000 samples with no error.
TEST(ChannelRecord, TdmsValueCountBeyondTheSegmentIsAnError) {
  constexpr std::uint32_t kF64 = 10;
  TdmsBytes values;
  for (int i = 0; i < 1000; ++i) values.f64(i);
  testing::ScratchDirectory dir;
  const std::string overflow = dir.write(
      "overflow.tdms", tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData,
                                    object_list(kF64, {(std::uint64_t{1} << 61) + 1000}), values.bytes));
  try {
    open_channel_record(overflow, ChannelRecordFormat::kTdms);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->file, overflow);
    // The object's path follows the lead-in (28 bytes) and the object count (4).
    EXPECT_EQ(e.message(), "byte offset 32: object /'g'/'a' has 2305843009213694952 values of 8 bytes, more than "
                           "2^64 bytes (a corrupt raw data index)");
  }
  const std::string beyond = dir.write(
      "beyond.tdms", tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData, object_list(kF64, {1000}),
                                  values.bytes.substr(0, 4000)));
  try {
    open_channel_record(beyond, ChannelRecordFormat::kTdms);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.message(), "byte offset 0: the raw data indices of the segment's objects give 8000 bytes a chunk, but "
                           "the segment holds 4000 bytes of raw data (a corrupt raw data index)");
  }
  // A segment the writer could not finish (next segment offset 0xFFFFFFFFFFFFFFFF) holds what fits.
  const std::string metadata = object_list(kF64, {1000});
  const std::string unfinished = dir.write(
      "unfinished.tdms", lead_in("TDSm", kTocMetaData | kTocNewObjList | kTocRawData, ~std::uint64_t{0}, metadata.size()) +
                             metadata + values.bytes.substr(0, 4000));
  EXPECT_EQ(read_channel(*open_channel_record(unfinished, ChannelRecordFormat::kTdms), 0).size(), 500u);
}

// Metadata of the object "/'g'/'a'" with an i32 raw data index of `count` values (0: the index of
// the previous segment) and the property wf_increment.
std::string object_with_increment(std::uint64_t count, double increment) {
  TdmsBytes meta;
  meta.u32(1);
  meta.text("/'g'/'a'");
  if (count == 0) {
    meta.u32(0);
  } else {
    meta.u32(20);
    meta.u32(3);
    meta.u32(1);
    meta.u64(count);
  }
  meta.u32(1);
  meta.text("wf_increment");
  meta.u32(10);
  meta.f64(increment);
  return meta.bytes;
}

// A wf_increment that changes between segments: the samples are readable, but no one rate applies,
// given or stored (as a type that changes between segments makes a channel unreadable). The reader
// took the last increment for every sample: QA's t7_rate_change.tdms (0.01 s, then 0.02 s) read as 50 Hz.
TEST(ChannelRecord, TdmsIncrementChangingBetweenSegmentsHasNoSampleRate) {
  TdmsBytes values;
  for (int i = 0; i < 2; ++i) values.i32(7 + i);
  const std::string first = tdms_segment(kTocMetaData | kTocNewObjList | kTocRawData, object_with_increment(2, 0.01),
                                         values.bytes);
  testing::ScratchDirectory dir;
  const std::string changed =
      dir.write("changed.tdms", first + tdms_segment(kTocMetaData | kTocRawData, object_with_increment(0, 0.02), values.bytes));
  const auto record = open_channel_record(changed, ChannelRecordFormat::kTdms);
  EXPECT_THAT(read_channel(*record, 0), ::testing::ElementsAre(7, 8, 7, 8));
  EXPECT_EQ(record->channels()[0].sample_rate_hz, std::nullopt);
  const std::string problem = "channel 'g/a': wf_increment is 0.01 s for samples 1..2, then 0.02 s: the samples are not "
                              "evenly spaced, so no one sample rate applies";
  for (const std::optional<double> given : {std::optional<double>(), std::optional<double>(100.0)}) {
    try {
      resolve_sample_rate(*record, 0, given);
      FAIL() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.location()->file, changed);
      EXPECT_EQ(e.message(), problem);
    }
  }
  EXPECT_THROW(stored_sample_rate({changed, RateRecordFormat::kAuto, ColumnSelector::parse("g/a")}), Error);
  // Changed by a last segment without raw data: the samples' increment is not the file's.
  const std::string after = dir.write(
      "after.tdms", first + tdms_segment(kTocMetaData, object_with_increment(0, 0.02), ""));
  EXPECT_EQ(open_channel_record(after, ChannelRecordFormat::kTdms)->channels()[0].sample_rate_problem,
            "wf_increment is 0.01 s for samples 1..2, then 0.02 s (set after the last sample): the samples are not "
            "evenly spaced, so no one sample rate applies");
  // The same increment stated again is one rate.
  const std::string same =
      dir.write("same.tdms", first + tdms_segment(kTocMetaData | kTocRawData, object_with_increment(0, 0.01), values.bytes));
  const auto same_record = open_channel_record(same, ChannelRecordFormat::kTdms);
  EXPECT_EQ(same_record->channels()[0].sample_rate_problem, "");
  EXPECT_EQ(resolve_sample_rate(*same_record, 0, std::nullopt), 100.0);
}

// Input source 0xFFFFFFFF is the raw data and N the output of NI_Scale[N] (npTDMS's
// RAW_DATA_INPUT_SOURCE): raw 1, 2, 3 through x + 1, then 2x + 2, then 3x + 3 read 21, 27, 33. The
// reader took an input source of 0 for the raw data and read 15, 21, 27.
TEST(ChannelRecord, TdmsDaqmxScaleChainFollowsInputSources) {
  testing::ScratchDirectory dir;
  const std::string path =
      dir.write("chain.tdms", daqmx_file({1, 2, 3}, scales({linear_scale(0, 1.0, 1.0, kRawDataInputSource),
                                                              linear_scale(1, 2.0, 2.0, 0), linear_scale(2, 3.0, 3.0, 1)})));
  const auto record = open_channel_record(path, ChannelRecordFormat::kTdms);
  EXPECT_THAT(read_channel(*record, 0), ::testing::ElementsAre(21, 27, 33));
  // A scale whose input source is a scale without a Scale_Type takes the DAQmx scaler's value (raw).
  const std::string undefined =
      dir.write("undefined.tdms", daqmx_file({1, 2, 3}, scales({{}, linear_scale(1, 2.0, 0.5, 0)})));
  EXPECT_THAT(read_channel(*open_channel_record(undefined, ChannelRecordFormat::kTdms), 0),
              ::testing::ElementsAre(2.5, 4.5, 6.5));
}

TEST(ChannelRecord, TdmsDaqmxScaleInputSourceOutOfRangeOrCyclicIsAnError) {
  testing::ScratchDirectory dir;
  const std::string beyond =
      dir.write("beyond.tdms", daqmx_file({1, 2, 3}, scales({linear_scale(0, 1.0, 0.0, kRawDataInputSource),
                                                               linear_scale(1, 2.0, 0.0, 5)})));
  try {
    open_channel_record(beyond, ChannelRecordFormat::kTdms);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->file, beyond);
    EXPECT_EQ(e.message(), "channel 'g/c': NI_Scale[1]_Linear_Input_Source is 5, neither 0xFFFFFFFF (the raw data) "
                           "nor one of the channel's 2 scales (NI_Number_Of_Scales)");
  }
  const std::string cycle = dir.write(
      "cycle.tdms", daqmx_file({1, 2, 3}, scales({linear_scale(0, 1.0, 0.0, 1), linear_scale(1, 2.0, 0.0, 0)})));
  try {
    open_channel_record(cycle, ChannelRecordFormat::kTdms);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.location()->file, cycle);
    EXPECT_EQ(e.message(), "channel 'g/c': the input sources of its scales form a cycle, NI_Scale[0] <- NI_Scale[1] "
                           "<- NI_Scale[0] (each takes the output of the next)");
  }
}

}  // namespace
}  // namespace inertest
