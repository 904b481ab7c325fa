#include "inertest/report/svg_plot.h"

#include <cmath>
#include <regex>
#include <sstream>
#include <limits>

#include <nlohmann/json.hpp>

#include "test_util/test_util.h"

namespace inertest::report {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

Series make_series(const std::string& name, std::vector<double> x, std::vector<double> y);

std::vector<std::string> labels_of(const std::vector<Tick>& ticks) {
  std::vector<std::string> labels;
  for (const auto& t : ticks) {
    if (!t.label.empty()) labels.push_back(t.label);
  }
  return labels;
}

std::vector<double> values_of(const std::vector<Tick>& ticks) {
  std::vector<double> values;
  for (const auto& t : ticks) values.push_back(t.value);
  return values;
}

TEST(SvgPlotTicks, LinearUnitRangeStepsByTwoTenths) {
  const auto ticks = linear_ticks(0.0, 1.0);
  EXPECT_THAT(labels_of(ticks), ElementsAre("0", "0.2", "0.4", "0.6", "0.8", "1.0"));
  const auto values = values_of(ticks);
  ASSERT_EQ(values.size(), 6u);
  for (std::size_t i = 0; i < values.size(); ++i) EXPECT_NEAR(values[i], 0.2 * static_cast<double>(i), 1e-12);
}

TEST(SvgPlotTicks, LinearTicksStayInsideTheRange) {
  // Span 15.9 over 6 ticks: raw step 3.18 rounds to the nice step 5.
  EXPECT_THAT(labels_of(linear_ticks(-3.7, 12.2)), ElementsAre("0", "5", "10"));
  EXPECT_THAT(labels_of(linear_ticks(-10.0, 10.0)), ElementsAre("-10", "-5", "0", "5", "10"));
}

TEST(SvgPlotTicks, LinearSmallStepsGetEnoughDecimals) {
  EXPECT_THAT(labels_of(linear_ticks(0.0012, 0.0031)), ElementsAre("0.0015", "0.0020", "0.0025", "0.0030"));
}

TEST(SvgPlotTicks, LinearTinyAndHugeValuesUseExponents) {
  EXPECT_THAT(labels_of(linear_ticks(0.0, 5e-6)), ElementsAre("0", "1e-6", "2e-6", "3e-6", "4e-6", "5e-6"));
  EXPECT_THAT(labels_of(linear_ticks(0.0, 5e6)), ElementsAre("0", "1e6", "2e6", "3e6", "4e6", "5e6"));
  EXPECT_EQ(format_tick(2.5e-6, 5e-7), "2.5e-6");
  EXPECT_EQ(format_tick(-1.5e7, 1e6), "-1.5e7");
  EXPECT_EQ(format_tick(-1.55e7, 5e5), "-1.55e7");
}

TEST(SvgPlotTicks, LinearZeroIsNeverNegative) {
  for (const auto& tick : linear_ticks(-0.3, 0.3)) EXPECT_NE(tick.label, "-0.0");
  EXPECT_EQ(format_tick(-1e-18, 0.1), "0");
}

TEST(SvgPlotTicks, LinearDegenerateRangeGivesOneTick) {
  const auto ticks = linear_ticks(2.5, 2.5);
  ASSERT_EQ(ticks.size(), 1u);
  EXPECT_EQ(ticks[0].value, 2.5);
  EXPECT_EQ(ticks[0].label, "2.5");
  EXPECT_TRUE(linear_ticks(std::numeric_limits<double>::quiet_NaN(), 1.0).empty());
}

TEST(SvgPlotTicks, LogDecadesAreLabelledReadably) {
  const auto ticks = log_ticks(1e-3, 1e2);
  EXPECT_THAT(labels_of(ticks), ElementsAre("1e-3", "0.01", "0.1", "1", "10", "100"));
  std::size_t majors = 0;
  std::size_t minors = 0;
  for (const auto& t : ticks) (t.major ? majors : minors) += 1;
  EXPECT_EQ(majors, 6u);
  EXPECT_EQ(minors, 5u * 8u);  // 2..9 in each of the five decades below 100
}

TEST(SvgPlotTicks, LogDecadeLabelsOutsideTheDecimalRangeUseExponents) {
  EXPECT_EQ(format_log_tick(1, -3), "1e-3");
  EXPECT_EQ(format_log_tick(1, -2), "0.01");
  EXPECT_EQ(format_log_tick(2, -2), "0.02");
  EXPECT_EQ(format_log_tick(5, 0), "5");
  EXPECT_EQ(format_log_tick(1, 3), "1000");
  EXPECT_EQ(format_log_tick(1, 4), "1e4");
  EXPECT_EQ(format_log_tick(2, 5), "2e5");
}

TEST(SvgPlotTicks, LogManyDecadesLabelEveryOtherDecade) {
  const auto ticks = log_ticks(1e-8, 1e4);  // 13 decades: label every second one, 7 labels
  EXPECT_THAT(labels_of(ticks), ElementsAre("1e-8", "1e-6", "1e-4", "0.01", "1", "100", "1e4"));
  std::size_t decades = 0;
  for (const auto& t : ticks) decades += t.major ? 1 : 0;
  EXPECT_EQ(decades, 13u);  // every decade keeps its tick and grid line
}

TEST(SvgPlotTicks, LogRangeWithinADecadeIsLabelledAtTwoAndFive) {
  EXPECT_THAT(labels_of(log_ticks(2.0, 8.0)), ElementsAre("2", "5"));
  EXPECT_THAT(labels_of(log_ticks(0.5, 3.0)), ElementsAre("0.5", "1", "2"));
}

TEST(SvgPlotTicks, LogRangeTooNarrowFallsBackToLinearTicks) {
  const auto ticks = log_ticks(3.0, 4.0);
  EXPECT_THAT(labels_of(ticks), ElementsAre("3.0", "3.2", "3.4", "3.6", "3.8", "4.0"));
}

TEST(SvgPlotTicks, LogRejectsNonPositiveRanges) {
  EXPECT_TRUE(log_ticks(0.0, 10.0).empty());
  EXPECT_TRUE(log_ticks(-1.0, 10.0).empty());
}

TEST(SvgPlotRange, LinearWidensToNiceTicks) {
  const std::vector<double> values{3.2, 7.9, std::numeric_limits<double>::quiet_NaN()};
  const Range range = auto_range(values, AxisScale::linear);
  EXPECT_DOUBLE_EQ(range.lo, 3.0);
  EXPECT_DOUBLE_EQ(range.hi, 8.0);
}

TEST(SvgPlotRange, LinearKeepsDataOffTheFrame) {
  const std::vector<double> on_ticks{20.0, 30.0, 40.0};  // nice step 5: [20, 40] would put both ends on the frame
  const Range range = auto_range(on_ticks, AxisScale::linear);
  EXPECT_DOUBLE_EQ(range.lo, 15.0);
  EXPECT_DOUBLE_EQ(range.hi, 45.0);
  const std::vector<double> from_zero{0.0, 7.9};  // a zero end stays (a baseline, not a datum on the frame)
  EXPECT_DOUBLE_EQ(auto_range(from_zero, AxisScale::linear).lo, 0.0);
}

TEST(SvgPlotRender, ExplicitTicksReplaceTheAutomaticOnes) {
  Panel panel;
  panel.x = make_axis("β", "°");
  panel.x.ticks = {0, 90, 180, 270};
  panel.series.push_back(make_series("", {0, 90, 180, 270}, {1, 2, 3, 4}));
  Plot plot;
  plot.panels.push_back(panel);
  const std::string svg = render_svg(plot);
  for (const char* label : {">0<", ">90<", ">180<", ">270<"}) EXPECT_THAT(svg, HasSubstr(label)) << label;
  EXPECT_THAT(svg, Not(HasSubstr(">100<")));
}

TEST(SvgPlotRange, LogWidensToDecadesAndIgnoresNonPositiveValues) {
  const std::vector<double> values{0.3, 45.0, 0.0, -2.0};
  const Range range = auto_range(values, AxisScale::log);
  EXPECT_DOUBLE_EQ(range.lo, 0.1);
  EXPECT_DOUBLE_EQ(range.hi, 100.0);
}

TEST(SvgPlotRange, DegenerateRangesAreWidened) {
  const std::vector<double> single{5.0};
  const Range around_five = auto_range(single, AxisScale::linear);
  EXPECT_LT(around_five.lo, 5.0);
  EXPECT_GT(around_five.hi, 5.0);
  EXPECT_NEAR(0.5 * (around_five.lo + around_five.hi), 5.0, 1e-12);

  const std::vector<double> zeros{0.0, 0.0, 0.0};
  const Range around_zero = auto_range(zeros, AxisScale::linear);
  EXPECT_DOUBLE_EQ(around_zero.lo, -1.0);
  EXPECT_DOUBLE_EQ(around_zero.hi, 1.0);

  const std::vector<double> one_decade{1.0, 1.0};
  const Range log_one = auto_range(one_decade, AxisScale::log);
  EXPECT_DOUBLE_EQ(log_one.lo, 0.1);
  EXPECT_DOUBLE_EQ(log_one.hi, 10.0);

  const std::vector<double> none;
  EXPECT_DOUBLE_EQ(auto_range(none, AxisScale::linear).hi, 1.0);
  EXPECT_DOUBLE_EQ(auto_range(none, AxisScale::log).lo, 1.0);
  EXPECT_DOUBLE_EQ(auto_range(none, AxisScale::log).hi, 10.0);
}

TEST(SvgPlotAxisMap, LinearMapsEndsAndInteriorProportionally) {
  const AxisMap x(Range{0.0, 10.0}, AxisScale::linear, 100.0, 300.0);
  EXPECT_DOUBLE_EQ(x.to_pixel(0.0), 100.0);
  EXPECT_DOUBLE_EQ(x.to_pixel(10.0), 300.0);
  EXPECT_DOUBLE_EQ(x.to_pixel(2.5), 150.0);
  EXPECT_DOUBLE_EQ(x.to_pixel(-5.0), 0.0);                             // outside the range maps outside the pixels
  const AxisMap y(Range{0.0, 10.0}, AxisScale::linear, 400.0, 100.0);  // SVG y grows downward
  EXPECT_DOUBLE_EQ(y.to_pixel(5.0), 250.0);
  EXPECT_DOUBLE_EQ(y.to_pixel(10.0), 100.0);
}

TEST(SvgPlotAxisMap, LogMapsDecadesEvenly) {
  const AxisMap x(Range{1e-2, 1e2}, AxisScale::log, 0.0, 400.0);
  EXPECT_NEAR(x.to_pixel(1e-2), 0.0, 1e-9);
  EXPECT_NEAR(x.to_pixel(0.1), 100.0, 1e-9);
  EXPECT_NEAR(x.to_pixel(1.0), 200.0, 1e-9);
  EXPECT_NEAR(x.to_pixel(1e2), 400.0, 1e-9);
  EXPECT_NEAR(x.to_pixel(std::sqrt(10.0)), 250.0, 1e-9);
  EXPECT_FALSE(x.placeable(0.0));
  EXPECT_FALSE(x.placeable(-1.0));
  EXPECT_TRUE(std::isnan(x.to_pixel(0.0)));
}

TEST(SvgPlotAxisMap, DegenerateRangeMapsToTheMiddle) {
  const AxisMap x(Range{3.0, 3.0}, AxisScale::linear, 0.0, 100.0);
  EXPECT_DOUBLE_EQ(x.to_pixel(3.0), 50.0);
}

TEST(SvgPlotClip, SegmentInsideIsUnchanged) {
  const Box box{0, 0, 100, 100};
  const auto clipped = clip_segment({10, 10}, {90, 50}, box);
  ASSERT_TRUE(clipped);
  EXPECT_DOUBLE_EQ(clipped->first.x, 10);
  EXPECT_DOUBLE_EQ(clipped->second.y, 50);
}

TEST(SvgPlotClip, SegmentCrossingIsCutAtTheEdges) {
  const Box box{0, 0, 100, 100};
  const auto clipped = clip_segment({-50, 50}, {150, 50}, box);
  ASSERT_TRUE(clipped);
  EXPECT_DOUBLE_EQ(clipped->first.x, 0);
  EXPECT_DOUBLE_EQ(clipped->second.x, 100);
  const auto diagonal = clip_segment({50, 50}, {250, 250}, box);
  ASSERT_TRUE(diagonal);
  EXPECT_DOUBLE_EQ(diagonal->second.x, 100);
  EXPECT_DOUBLE_EQ(diagonal->second.y, 100);
  const auto vertical = clip_segment({20, -10}, {20, 300}, box);
  ASSERT_TRUE(vertical);
  EXPECT_DOUBLE_EQ(vertical->first.y, 0);
  EXPECT_DOUBLE_EQ(vertical->second.y, 100);
}

TEST(SvgPlotClip, SegmentOutsideIsDropped) {
  const Box box{0, 0, 100, 100};
  EXPECT_FALSE(clip_segment({-50, -10}, {150, -10}, box));
  EXPECT_FALSE(clip_segment({110, 0}, {200, 100}, box));
  EXPECT_FALSE(clip_segment({200, 200}, {200, 200}, box));
  EXPECT_TRUE(clip_segment({50, 50}, {50, 50}, box));
}

// Every "x,y" pair of every polyline in the SVG.
std::vector<Point> polyline_points(const std::string& svg) {
  std::vector<Point> points;
  const std::regex polyline("<polyline points=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), polyline); it != std::sregex_iterator(); ++it) {
    std::istringstream pairs((*it)[1].str());
    std::string pair;
    while (pairs >> pair) {
      const auto comma = pair.find(',');
      points.push_back({std::stod(pair.substr(0, comma)), std::stod(pair.substr(comma + 1))});
    }
  }
  return points;
}

TEST(SvgPlotRender, LinesAreClippedToThePlotArea) {
  Panel panel;
  panel.x = make_axis("Averaging time", "s", AxisScale::log);
  panel.x.min = 1.0;
  panel.x.max = 100.0;
  panel.y = make_axis("Allan deviation", "deg/h", AxisScale::log);
  panel.y.min = 0.01;
  panel.y.max = 1.0;
  Series series;
  series.name = "data";
  series.x = {0.1, 1.0, 10.0, 1000.0};  // first and last points lie outside the fixed x range
  series.y = {5.0, 0.5, 0.05, 0.005};
  panel.series.push_back(series);
  Plot plot;
  plot.width = 600;
  plot.panels.push_back(panel);
  const std::string svg = render_svg(plot);

  const Box area = plot_area(panel, Box{0, 0, 600, panel.height});
  const auto points = polyline_points(svg);
  ASSERT_GE(points.size(), 3u);
  for (const auto& p : points) {
    EXPECT_GE(p.x, area.left - 0.05);
    EXPECT_LE(p.x, area.right + 0.05);
    EXPECT_GE(p.y, area.top - 0.05);
    EXPECT_LE(p.y, area.bottom + 0.05);
  }
  // The line reaches the left and right edges of the area (it was cut there, not dropped).
  EXPECT_NEAR(points.front().x, area.left, 0.05);
  EXPECT_NEAR(points.back().x, area.right, 0.05);
  EXPECT_THAT(svg, HasSubstr(">0.01<"));
  EXPECT_THAT(svg, HasSubstr(">100<"));
  EXPECT_THAT(svg, HasSubstr("Allan deviation (deg/h)"));
}

TEST(SvgPlotRender, ErrorBarsMarkersAndLegendAreDrawn) {
  Panel panel;
  Series series;
  series.name = "measured <σ>";
  series.x = {1, 2, 3};
  series.y = {1, 2, 3};
  series.y_low = {0.5, 1.5, 2.5};
  series.y_high = {1.5, 2.5, 3.5};
  series.line = LineStyle::none;
  series.marker = Marker::circle;
  panel.series.push_back(series);
  Plot plot;
  plot.panels.push_back(panel);
  const std::string svg = render_svg(plot);
  std::size_t circles = 0;
  for (std::size_t at = svg.find("<circle"); at != std::string::npos; at = svg.find("<circle", at + 1)) ++circles;
  EXPECT_EQ(circles, 4u);             // three points and the legend's sample
  EXPECT_THAT(svg, HasSubstr("h6"));  // error bar caps
  EXPECT_THAT(svg, HasSubstr("measured &lt;σ&gt;"));
  EXPECT_THAT(svg, Not(HasSubstr("<polyline")));
}

Series make_series(const std::string& name, std::vector<double> x, std::vector<double> y) {
  Series series;
  series.name = name;
  series.x = std::move(x);
  series.y = std::move(y);
  return series;
}

TEST(SvgPlotRender, DegenerateDataRendersWithoutNonFiniteCoordinates) {
  Plot plot;
  Panel single;
  single.series.push_back(make_series("one point", {2.0}, {7.0}));
  single.series.back().marker = Marker::square;
  Panel flat;
  flat.y.scale = AxisScale::log;
  flat.series.push_back(make_series("flat", {1, 2, 3}, {4, 4, 4}));
  Panel empty;
  Panel bad_values;
  bad_values.y.scale = AxisScale::log;
  bad_values.series.push_back(make_series("", {1, 2, 3, 4}, {1, -1, std::numeric_limits<double>::quiet_NaN(), 3}));
  plot.panels = {single, flat, empty, bad_values};
  const std::string svg = render_svg(plot);
  EXPECT_FALSE(std::regex_search(svg, std::regex("(^|[^a-z])(nan|inf)", std::regex::icase)));
  // The one point is drawn, and the log panel's two placeable points are not joined across the gap.
  EXPECT_THAT(svg, HasSubstr("width=\"6\" height=\"6\""));
  EXPECT_THAT(svg, HasSubstr("<rect x="));
  EXPECT_EQ(svg.find("<svg"), 0u);
}

TEST(SvgPlotRender, StackedPanelsShareTheWidth) {
  Plot plot;
  plot.width = 500;
  Panel top;
  top.height = 200;
  Panel bottom;
  bottom.height = 150;
  plot.panels = {top, bottom};
  EXPECT_THAT(render_svg(plot), HasSubstr("viewBox=\"0 0 500.0 350.0\""));
  const Box upper = plot_area(top, Box{0, 0, 500, 200});
  const Box lower = plot_area(bottom, Box{0, 200, 500, 350});
  EXPECT_LT(upper.bottom, lower.top);
  EXPECT_DOUBLE_EQ(upper.left, lower.left);
}

TEST(SvgPlotRender, AutomaticLegendAvoidsTheData) {
  Panel panel;
  // A rising line: it runs through the bottom-left and top-right corners, so the legend goes top-left
  // (the first corner tried that covers nothing after top-right).
  panel.series.push_back(make_series("rising", {0, 1, 2, 3, 4, 5}, {0, 1, 2, 3, 4, 5}));
  panel.x.min = panel.y.min = 0.0;
  panel.x.max = panel.y.max = 5.0;
  Plot plot;
  plot.width = 600;
  plot.panels.push_back(panel);
  const std::string svg = render_svg(plot);
  const Box area = plot_area(panel, Box{0, 0, 600, panel.height});
  std::smatch match;
  ASSERT_TRUE(std::regex_search(svg, match, std::regex("<g class=\"legend\"><rect x=\"([0-9.]+)\" y=\"([0-9.]+)\"")));
  EXPECT_NEAR(std::stod(match[1].str()), area.left + 8.0, 0.05);
  EXPECT_NEAR(std::stod(match[2].str()), area.top + 8.0, 0.05);
}

// The data a plot carries for the web view's script: only when asked, after the <svg>, with the
// palette's colours resolved as drawn, non-finite numbers as null, and no "</" to end the script.
TEST(SvgPlotData, EmbeddedOnlyOnRequestWithColoursAndEscapes) {
  Panel panel;
  panel.x = make_axis("Averaging time", "s", AxisScale::log);
  panel.y = make_axis("Allan deviation", "deg/h", AxisScale::log);
  Series measured = make_series("</script><b>", {1.0, 10.0, 100.0}, {0.1, std::nan(""), 0.01});
  measured.y_low = {0.09, 0.0, 0.008};
  measured.y_high = {0.11, 0.0, 0.012};
  measured.marker = Marker::circle;
  panel.series.push_back(measured);
  Series model = make_series("model", {1.0, 100.0}, {0.1, 0.01});
  model.line = LineStyle::dashed;
  model.color = "#123456";
  panel.series.push_back(model);
  panel.references.push_back({ReferenceLine::Direction::horizontal, 0.05, "limit", "#b3261e"});
  Plot plot;
  plot.width = 600.0;
  plot.panels = {panel};

  const std::string plain = render_svg(plot);
  EXPECT_THAT(plain, Not(HasSubstr("<script")));
  plot.embed_data = true;
  const std::string with_data = render_svg(plot);
  EXPECT_EQ(with_data.substr(0, plain.size()), plain);  // the drawing is the same
  const std::string open = "<script type=\"application/json\" class=\"plot-data\">";
  const auto start = with_data.find(open);
  ASSERT_NE(start, std::string::npos);
  const std::string text = with_data.substr(start + open.size(), with_data.rfind("</script>") - start - open.size());
  EXPECT_THAT(text, Not(HasSubstr("</")));
  const auto data = nlohmann::json::parse(text);
  EXPECT_EQ(data, plot_data(plot));
  EXPECT_EQ(data["width"], 600.0);
  const auto& p = data["panels"][0];
  EXPECT_EQ(p["x"]["scale"], "log");
  EXPECT_EQ(p["y"]["unit"], "deg/h");
  EXPECT_EQ(p["series"][0]["name"], "</script><b>");
  EXPECT_EQ(p["series"][0]["color"], "#1f77b4");  // the palette's first, as drawn
  EXPECT_EQ(p["series"][0]["marker"], "circle");
  EXPECT_TRUE(p["series"][0]["y"][1].is_null());
  EXPECT_EQ(p["series"][0]["y_high"][2], 0.012);
  EXPECT_EQ(p["series"][1]["color"], "#123456");
  EXPECT_EQ(p["series"][1]["line"], "dashed");
  EXPECT_EQ(p["references"][0]["value"], 0.05);
  EXPECT_TRUE(p["x"]["min"].is_null());
}

TEST(SvgPlotText, EscapesMarkup) { EXPECT_EQ(escape_xml("a<b & \"c\"'"), "a&lt;b &amp; &quot;c&quot;&#39;"); }

TEST(SvgPlotText, CjkTextIsWiderThanLatin) {
  EXPECT_DOUBLE_EQ(text_width("ab", 10.0), 12.0);
  EXPECT_DOUBLE_EQ(text_width("带宽", 10.0), 20.0);
}

}  // namespace
}  // namespace inertest::report
