// A small SVG plotting module for the test report: linear and log axes with readable ticks,
// line and marker series with error bars, reference lines, text notes, legends, and several
// panels stacked on one x axis (Bode magnitude over phase). The output is an inline <svg>
// element (no script, no external fonts or files), so a report stays one self-contained file;
// on request it carries its data too (Plot::embed_data), for the web view's interactive plots.
//
// Geometry is exposed for tests: tick generation, data-to-pixel maps, range selection and
// segment clipping are plain functions.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

namespace inertest::report {

enum class AxisScale { linear, log };

struct Tick {
  double value = 0.0;
  std::string label;  // empty: an unlabelled (minor, or skipped decade) tick
  bool major = true;  // majors get a grid line and, when labelled, a label
};

// "Nice" ticks (steps of 1, 2 or 5 times a power of ten) covering [lo, hi], about target_count
// of them, every one labelled. lo == hi gives one tick at that value.
std::vector<Tick> linear_ticks(double lo, double hi, int target_count = 6);

// Ticks for a log axis over [lo, hi] (0 < lo <= hi): labelled majors at the decades, minors at
// 2..9 times each decade. Decade labels read 1e-3, 0.01, 0.1, 1, 10, 100, 1000, 1e4 (plain decimals
// from 0.01 to 1000, else "1eN"). Over many decades only every n-th decade is labelled (at most
// 7 labels). A range holding fewer than two decades is labelled at 2 and 5 times the decades as
// well, and one too narrow even for that gets linear ticks.
std::vector<Tick> log_ticks(double lo, double hi);

// The label of a linear tick at value, the ticks being step apart: as many decimals as the step
// needs; exponent form ("2.5e-6") when the step is below 1e-4 or the value reaches 1e6.
std::string format_tick(double value, double step);

// The label of a log tick at mantissa·10^exponent (mantissa 1..9): "0.02", "5", "2e-4", "1e4".
std::string format_log_tick(int mantissa, int exponent);

struct Range {
  double lo = 0.0;
  double hi = 1.0;
};

// The axis range for the values (non-finite values ignored; non-positive ones too on a log axis):
// a linear range is widened to the enclosing nice ticks (one step further where a value would sit
// on the frame, within 1 % of the span), a log range to the enclosing decades.
// Never degenerate: no values gives [0, 1] (log [1, 10]); equal values get a range around them.
Range auto_range(std::span<const double> values, AxisScale scale);

// Maps data values on one axis to pixels: range.lo to pixel_lo and range.hi to pixel_hi
// (pixel_lo > pixel_hi for a y axis, as SVG's y grows downward). Linear in the value, or in
// log10 of the value on a log axis.
class AxisMap {
 public:
  AxisMap(Range range, AxisScale scale, double pixel_lo, double pixel_hi);
  // The pixel of a value; on a log axis the value must be positive (NaN otherwise).
  double to_pixel(double value) const;
  // Whether the value can be placed on this axis at all (finite, and positive on a log axis).
  bool placeable(double value) const;

 private:
  double lo_;
  double hi_;
  AxisScale scale_;
  double pixel_lo_;
  double pixel_hi_;
};

struct Point {
  double x = 0.0;
  double y = 0.0;
};

struct Box {
  double left = 0.0;
  double top = 0.0;
  double right = 0.0;
  double bottom = 0.0;
  bool contains(Point p) const { return p.x >= left && p.x <= right && p.y >= top && p.y <= bottom; }
};

// The part of segment a-b inside the box (Liang-Barsky), or nothing when it lies outside.
std::optional<std::pair<Point, Point>> clip_segment(Point a, Point b, const Box& box);

enum class LineStyle { none, solid, dashed, dotted };
enum class Marker { none, circle, square, triangle, diamond };

struct Series {
  std::string name;  // the legend entry; empty keeps the series out of the legend
  std::vector<double> x;
  std::vector<double> y;
  // Error bars: absolute lower and upper ends, one per point, or both empty.
  std::vector<double> y_low;
  std::vector<double> y_high;
  LineStyle line = LineStyle::solid;
  Marker marker = Marker::none;
  std::string color;  // CSS colour; empty takes the next colour of the palette
  double line_width = 1.6;
};

struct Axis {
  std::string label;  // the quantity, e.g. "Allan deviation"
  std::string unit;   // shown as "label (unit)"; empty for none
  AxisScale scale = AxisScale::linear;
  std::optional<double> min;  // fixed ends; otherwise from the data (auto_range)
  std::optional<double> max;
  bool include_zero = false;  // linear auto range: stretch to include 0
  std::vector<double> ticks;  // labelled ticks at these values instead of the automatic ones
};

// An axis with a label and a unit, its range from the data.
Axis make_axis(std::string label, std::string unit, AxisScale scale = AxisScale::linear);

// A horizontal (y = value) or vertical (x = value) dashed line across the panel, labelled.
struct ReferenceLine {
  enum class Direction { horizontal, vertical };
  Direction direction = Direction::horizontal;
  double value = 0.0;
  std::string label;
  std::string color = "#555555";
};

// A text placed at a data point (left-aligned, just right of and above the point).
struct Note {
  double x = 0.0;
  double y = 0.0;
  std::string text;
  std::string color = "#222222";
};

// automatic: the inside corner where the legend covers the fewest data points.
enum class LegendPosition { automatic, none, top_right, top_left, bottom_right, bottom_left };

struct Panel {
  std::string title;
  Axis x;
  Axis y;
  std::vector<Series> series;
  std::vector<ReferenceLine> references;
  std::vector<Note> notes;
  LegendPosition legend = LegendPosition::automatic;
  double height = 300.0;  // pixels, margins included
};

// One figure: panels stacked top to bottom, all as wide as the plot.
struct Plot {
  double width = 900.0;
  std::vector<Panel> panels;
  // Whether render_svg follows the <svg> with the plot's data (plot_data) in a
  // <script type="application/json" class="plot-data"> element, which the web view's script
  // (inertest serve) redraws the plot from when zoomed. The drawing itself is the same either way.
  bool embed_data = false;
  // Its name for a screen reader (the <svg>'s <title>): the report's caption, else the panels' titles.
  std::string description;
};

// The plot area of a panel whose frame (margins included) is the box: what the axes map onto.
Box plot_area(const Panel& panel, const Box& frame);

// Renders the plot as one <svg> element with a viewBox (it scales to its container), followed by
// its data when plot.embed_data.
std::string render_svg(const Plot& plot);

// Everything the plot is drawn from, for a script to draw it again: {"width", "panels": [{"title",
// "height", "legend" (the LegendPosition's name), "x" and "y": {"label", "unit", "scale" ("linear" or
// "log"), "min", "max" (null when from the data), "include_zero", "ticks"}, "series": [{"name",
// "color" (the palette's colour when the series has none), "line", "marker", "line_width", "x", "y",
// "y_low", "y_high"}], "references": [{"direction", "value", "label", "color"}], "notes": [{"x",
// "y", "text", "color"}]}]}. Non-finite numbers are null.
nlohmann::json plot_data(const Plot& plot);

// Escapes &, <, >, " and ' for XML text and attribute values.
std::string escape_xml(const std::string& text);

// Approximate width in pixels of the text at the font size (CJK characters count double).
double text_width(const std::string& text, double font_size);

}  // namespace inertest::report
