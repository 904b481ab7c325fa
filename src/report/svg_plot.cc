#include "inertest/report/svg_plot.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

#include "inertest/core/json_text.h"

namespace inertest::report {
namespace {

constexpr double kTickFont = 11.0;
constexpr double kLabelFont = 12.0;
constexpr double kTitleFont = 13.0;
constexpr double kLegendFont = 11.0;
constexpr double kMajorTick = 5.0;
constexpr double kMinorTick = 3.0;
constexpr const char* kFontFamily =
    "'DejaVu Sans', 'Noto Sans CJK SC', 'Noto Sans SC', 'WenQuanYi Micro Hei', Arial, sans-serif";
constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

// Relative slack for comparisons of computed tick values against the range ends.
constexpr double kSlack = 1e-9;

// 1, 2 or 5 times a power of ten, the nearest to raw.
double nice_step(double raw) {
  const double exponent = std::floor(std::log10(raw));
  const double power = std::pow(10.0, exponent);
  const double fraction = raw / power;
  const double nice = fraction < 1.5 ? 1.0 : fraction < 3.0 ? 2.0 : fraction < 7.0 ? 5.0 : 10.0;
  return nice * power;
}

int floor_log10(double value) { return static_cast<int>(std::floor(std::log10(value) + 1e-12)); }
int ceil_log10(double value) { return static_cast<int>(std::ceil(std::log10(value) - 1e-12)); }

std::string pixel(double value) {
  std::string text = fmt::format("{:.1f}", value);
  if (text == "-0.0") text = "0.0";
  return text;
}

std::string axis_title(const Axis& axis) {
  if (axis.unit.empty() || axis.unit == "1") return axis.label;
  return axis.label.empty() ? axis.unit : axis.label + " (" + axis.unit + ")";
}

Range resolve_range(const Axis& axis, std::vector<double> values) {
  if (axis.include_zero && axis.scale == AxisScale::linear) values.push_back(0.0);
  Range range = auto_range(values, axis.scale);
  if (axis.min) range.lo = *axis.min;
  if (axis.max) range.hi = *axis.max;
  if (!(range.hi > range.lo)) range = auto_range(std::vector<double>{range.lo, range.hi}, axis.scale);
  return range;
}

std::vector<Tick> ticks_for(const Axis& axis, Range range) {
  if (!axis.ticks.empty()) {
    std::vector<Tick> ticks;
    double step = range.hi - range.lo;
    for (std::size_t i = 1; i < axis.ticks.size(); ++i)
      step = std::min(step, std::abs(axis.ticks[i] - axis.ticks[i - 1]));
    for (double value : axis.ticks) ticks.push_back({value, format_tick(value, step > 0.0 ? step : 1.0), true});
    return ticks;
  }
  return axis.scale == AxisScale::log ? log_ticks(range.lo, range.hi) : linear_ticks(range.lo, range.hi);
}

// Everything that places one panel: its ranges, ticks and plot area.
struct PanelGeometry {
  Range x_range;
  Range y_range;
  std::vector<Tick> x_ticks;
  std::vector<Tick> y_ticks;
  Box area;
};

PanelGeometry layout(const Panel& panel, const Box& frame) {
  std::vector<double> xs;
  std::vector<double> ys;
  for (const auto& series : panel.series) {
    xs.insert(xs.end(), series.x.begin(), series.x.end());
    ys.insert(ys.end(), series.y.begin(), series.y.end());
    ys.insert(ys.end(), series.y_low.begin(), series.y_low.end());
    ys.insert(ys.end(), series.y_high.begin(), series.y_high.end());
  }
  for (const auto& reference : panel.references) {
    (reference.direction == ReferenceLine::Direction::horizontal ? ys : xs).push_back(reference.value);
  }
  PanelGeometry geometry;
  geometry.x_range = resolve_range(panel.x, xs);
  geometry.y_range = resolve_range(panel.y, ys);
  geometry.x_ticks = ticks_for(panel.x, geometry.x_range);
  geometry.y_ticks = ticks_for(panel.y, geometry.y_range);

  double widest_label = 0.0;
  for (const auto& tick : geometry.y_ticks) widest_label = std::max(widest_label, text_width(tick.label, kTickFont));
  const double left = std::max(52.0, 8.0 + kLabelFont + 8.0 + widest_label + kMajorTick + 4.0);
  const double top = panel.title.empty() ? 12.0 : 12.0 + kTitleFont + 6.0;
  const double bottom = kMajorTick + 4.0 + kTickFont + 8.0 + kLabelFont + 8.0;
  geometry.area = {frame.left + left, frame.top + top, frame.right - 22.0, frame.bottom - bottom};
  return geometry;
}

class SvgWriter {
 public:
  void line(std::string text) { out_ += std::move(text) + "\n"; }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

std::string dash_attribute(LineStyle style) {
  switch (style) {
    case LineStyle::dashed:
      return " stroke-dasharray=\"7 4\"";
    case LineStyle::dotted:
      return " stroke-dasharray=\"1.5 3\" stroke-linecap=\"round\"";
    default:
      return "";
  }
}

std::string marker_element(Marker marker, Point p, const std::string& color) {
  const std::string fill = fmt::format("fill=\"{}\"", color);
  switch (marker) {
    case Marker::circle:
      return fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"3.2\" {}/>", pixel(p.x), pixel(p.y), fill);
    case Marker::square:
      return fmt::format("<rect x=\"{}\" y=\"{}\" width=\"6\" height=\"6\" {}/>", pixel(p.x - 3), pixel(p.y - 3), fill);
    case Marker::triangle:
      return fmt::format("<path d=\"M{} {}L{} {}L{} {}Z\" {}/>", pixel(p.x), pixel(p.y - 3.8), pixel(p.x + 3.6),
                         pixel(p.y + 2.6), pixel(p.x - 3.6), pixel(p.y + 2.6), fill);
    case Marker::diamond:
      return fmt::format("<path d=\"M{} {}L{} {}L{} {}L{} {}Z\" {}/>", pixel(p.x), pixel(p.y - 4), pixel(p.x + 4),
                         pixel(p.y), pixel(p.x), pixel(p.y + 4), pixel(p.x - 4), pixel(p.y), fill);
    case Marker::none:
      break;
  }
  return "";
}

std::string polyline(const std::vector<Point>& points, const std::string& color, const Series& series) {
  std::string coordinates;
  for (const auto& p : points) {
    if (!coordinates.empty()) coordinates += ' ';
    coordinates += pixel(p.x);
    coordinates += ',';
    coordinates += pixel(p.y);
  }
  return fmt::format(
      "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{}\" "
      "stroke-linejoin=\"round\"{}/>",
      coordinates, color, series.line_width, dash_attribute(series.line));
}

bool same_point(Point a, Point b) { return std::abs(a.x - b.x) < 1e-6 && std::abs(a.y - b.y) < 1e-6; }

void draw_series(SvgWriter& svg, const Series& series, const std::string& color, const AxisMap& x_map,
                 const AxisMap& y_map, const Box& area) {
  const std::size_t count = std::min(series.x.size(), series.y.size());
  auto place = [&](double x, double y) -> std::optional<Point> {
    if (!x_map.placeable(x) || !y_map.placeable(y)) return std::nullopt;
    return Point{x_map.to_pixel(x), y_map.to_pixel(y)};
  };

  if (series.y_low.size() == count && series.y_high.size() == count) {
    std::string bars;
    for (std::size_t i = 0; i < count; ++i) {
      const auto low = place(series.x[i], series.y_low[i]);
      const auto high = place(series.x[i], series.y_high[i]);
      if (!low || !high) continue;
      const auto clipped = clip_segment(*low, *high, area);
      if (!clipped) continue;
      const auto [a, b] = *clipped;
      bars += fmt::format("M{} {}L{} {}", pixel(a.x), pixel(a.y), pixel(b.x), pixel(b.y));
      for (const Point end : {*low, *high}) {
        if (area.contains(end)) bars += fmt::format("M{} {}h6", pixel(end.x - 3), pixel(end.y));
      }
    }
    if (!bars.empty())
      svg.line(fmt::format("<path d=\"{}\" stroke=\"{}\" stroke-width=\"1\" fill=\"none\"/>", bars, color));
  }

  if (series.line != LineStyle::none) {
    std::vector<Point> run;
    auto flush = [&] {
      if (run.size() >= 2) svg.line(polyline(run, color, series));
      run.clear();
    };
    std::optional<Point> previous;
    for (std::size_t i = 0; i < count; ++i) {
      const auto current = place(series.x[i], series.y[i]);
      if (!current) {
        flush();
        previous.reset();
        continue;
      }
      if (previous) {
        const auto clipped = clip_segment(*previous, *current, area);
        if (!clipped) {
          flush();
        } else {
          if (run.empty() || !same_point(run.back(), clipped->first)) {
            flush();
            run.push_back(clipped->first);
          }
          run.push_back(clipped->second);
          if (!same_point(clipped->second, *current)) flush();
        }
      }
      previous = current;
    }
    flush();
  }

  if (series.marker != Marker::none) {
    for (std::size_t i = 0; i < count; ++i) {
      const auto p = place(series.x[i], series.y[i]);
      if (p && area.contains(*p)) svg.line(marker_element(series.marker, *p, color));
    }
  }
}

// The data of a panel in pixels: every point, and points along every line, for placing the legend.
std::vector<Point> data_pixels(const Panel& panel, const AxisMap& x_map, const AxisMap& y_map) {
  std::vector<Point> pixels;
  for (const auto& series : panel.series) {
    bool joined = false;  // whether the previous point was placed and a line joins it to this one
    for (std::size_t i = 0; i < std::min(series.x.size(), series.y.size()); ++i) {
      if (!x_map.placeable(series.x[i]) || !y_map.placeable(series.y[i])) {
        joined = false;
        continue;
      }
      const Point p{x_map.to_pixel(series.x[i]), y_map.to_pixel(series.y[i])};
      if (joined) {
        const Point q = pixels.back();
        for (double t = 0.125; t < 1.0; t += 0.125) pixels.push_back({q.x + t * (p.x - q.x), q.y + t * (p.y - q.y)});
      }
      pixels.push_back(p);
      joined = series.line != LineStyle::none;
    }
  }
  return pixels;
}

void draw_legend(SvgWriter& svg, const Panel& panel, const std::vector<std::string>& colors, const Box& area,
                 const std::vector<Point>& data) {
  if (panel.legend == LegendPosition::none) return;
  std::vector<std::size_t> entries;
  double widest = 0.0;
  for (std::size_t i = 0; i < panel.series.size(); ++i) {
    if (panel.series[i].name.empty()) continue;
    entries.push_back(i);
    widest = std::max(widest, text_width(panel.series[i].name, kLegendFont));
  }
  if (entries.empty()) return;
  constexpr double kRow = 16.0;
  constexpr double kSample = 26.0;
  const double width = 8.0 + kSample + 6.0 + widest + 8.0;
  const double height = 6.0 + kRow * static_cast<double>(entries.size()) + 2.0;
  auto box_at = [&](LegendPosition position) {
    const bool right = position == LegendPosition::top_right || position == LegendPosition::bottom_right;
    const bool top = position == LegendPosition::top_right || position == LegendPosition::top_left;
    const double left = right ? area.right - 8.0 - width : area.left + 8.0;
    const double upper = top ? area.top + 8.0 : area.bottom - 8.0 - height;
    return Box{left, upper, left + width, upper + height};
  };
  LegendPosition position = panel.legend;
  if (position == LegendPosition::automatic) {
    std::size_t fewest = std::numeric_limits<std::size_t>::max();
    for (const auto corner : {LegendPosition::top_right, LegendPosition::top_left, LegendPosition::bottom_right,
                              LegendPosition::bottom_left}) {
      const Box box = box_at(corner);
      const auto covered =
          static_cast<std::size_t>(std::count_if(data.begin(), data.end(), [&](Point p) { return box.contains(p); }));
      if (covered < fewest) {
        fewest = covered;
        position = corner;
      }
    }
  }
  const Box box = box_at(position);
  const double left = box.left;
  const double upper = box.top;
  svg.line(
      fmt::format("<g class=\"legend\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\" "
                  "fill-opacity=\"0.88\" stroke=\"#bbbbbb\"/>",
                  pixel(left), pixel(upper), pixel(width), pixel(height)));
  for (std::size_t row = 0; row < entries.size(); ++row) {
    const Series& series = panel.series[entries[row]];
    const std::string& color = colors[entries[row]];
    const double y = upper + 6.0 + kRow * (static_cast<double>(row) + 0.5);
    const double x = left + 8.0;
    if (series.line != LineStyle::none) {
      svg.line(fmt::format("<path d=\"M{} {}h{}\" stroke=\"{}\" stroke-width=\"{}\"{}/>", pixel(x), pixel(y), kSample,
                           color, series.line_width, dash_attribute(series.line)));
    } else if (!series.y_low.empty()) {
      svg.line(fmt::format("<path d=\"M{} {}v12M{} {}h6M{} {}h6\" stroke=\"{}\" stroke-width=\"1\"/>",
                           pixel(x + kSample / 2), pixel(y - 6), pixel(x + kSample / 2 - 3), pixel(y - 6),
                           pixel(x + kSample / 2 - 3), pixel(y + 6), color));
    }
    if (series.marker != Marker::none) svg.line(marker_element(series.marker, {x + kSample / 2, y}, color));
    svg.line(fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\" dominant-baseline=\"central\">{}</text>",
                         pixel(x + kSample + 6.0), pixel(y), kLegendFont, escape_xml(series.name)));
  }
  svg.line("</g>");
}

void draw_panel(SvgWriter& svg, const Panel& panel, const Box& frame, std::size_t& palette_index) {
  const PanelGeometry g = layout(panel, frame);
  const Box& area = g.area;
  const AxisMap x_map(g.x_range, panel.x.scale, area.left, area.right);
  const AxisMap y_map(g.y_range, panel.y.scale, area.bottom, area.top);

  svg.line(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\"/>", pixel(area.left),
                       pixel(area.top), pixel(area.right - area.left), pixel(area.bottom - area.top)));

  // Grid and tick marks.
  std::string major_grid;
  std::string minor_grid;
  std::string tick_marks;
  std::string labels;
  for (const auto& tick : g.x_ticks) {
    if (!x_map.placeable(tick.value)) continue;
    const double x = x_map.to_pixel(tick.value);
    if (x < area.left - 0.5 || x > area.right + 0.5) continue;
    (tick.major ? major_grid : minor_grid) += fmt::format("M{} {}V{}", pixel(x), pixel(area.top), pixel(area.bottom));
    tick_marks += fmt::format("M{} {}v{}", pixel(x), pixel(area.bottom), tick.major ? kMajorTick : kMinorTick);
    if (!tick.label.empty()) {
      labels += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"{}\">{}</text>\n", pixel(x),
                            pixel(area.bottom + kMajorTick + 4.0 + kTickFont * 0.8), kTickFont, escape_xml(tick.label));
    }
  }
  for (const auto& tick : g.y_ticks) {
    if (!y_map.placeable(tick.value)) continue;
    const double y = y_map.to_pixel(tick.value);
    if (y < area.top - 0.5 || y > area.bottom + 0.5) continue;
    (tick.major ? major_grid : minor_grid) += fmt::format("M{} {}H{}", pixel(area.left), pixel(y), pixel(area.right));
    tick_marks += fmt::format("M{} {}h-{}", pixel(area.left), pixel(y), tick.major ? kMajorTick : kMinorTick);
    if (!tick.label.empty()) {
      labels += fmt::format(
          "<text x=\"{}\" y=\"{}\" text-anchor=\"end\" dominant-baseline=\"central\" "
          "font-size=\"{}\">{}</text>\n",
          pixel(area.left - kMajorTick - 3.0), pixel(y), kTickFont, escape_xml(tick.label));
    }
  }
  if (!minor_grid.empty()) svg.line(fmt::format("<path d=\"{}\" stroke=\"#eeeeee\" stroke-width=\"1\"/>", minor_grid));
  if (!major_grid.empty()) svg.line(fmt::format("<path d=\"{}\" stroke=\"#d8d8d8\" stroke-width=\"1\"/>", major_grid));

  // References behind the data.
  int vertical_labels = 0;
  for (const auto& reference : panel.references) {
    const bool horizontal = reference.direction == ReferenceLine::Direction::horizontal;
    const AxisMap& map = horizontal ? y_map : x_map;
    if (!map.placeable(reference.value)) continue;
    const double at = map.to_pixel(reference.value);
    if (horizontal ? (at < area.top || at > area.bottom) : (at < area.left || at > area.right)) continue;
    const std::string path = horizontal ? fmt::format("M{} {}H{}", pixel(area.left), pixel(at), pixel(area.right))
                                        : fmt::format("M{} {}V{}", pixel(at), pixel(area.top), pixel(area.bottom));
    svg.line(fmt::format("<path d=\"{}\" stroke=\"{}\" stroke-width=\"1.2\" stroke-dasharray=\"5 3\"/>", path,
                         reference.color));
    if (!reference.label.empty()) {
      const std::string text = escape_xml(reference.label);
      if (horizontal) {
        svg.line(fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"end\" font-size=\"{}\" fill=\"{}\">{}</text>",
                             pixel(area.right - 4.0), pixel(at - 4.0), kTickFont, reference.color, text));
      } else {
        // Labels of vertical lines stack upward from the bottom, so neighbours do not overprint.
        svg.line(fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{}\">{}</text>", pixel(at + 4.0),
                             pixel(area.bottom - 6.0 - 14.0 * vertical_labels++), kTickFont, reference.color, text));
      }
    }
  }

  std::vector<std::string> colors;
  for (const auto& series : panel.series) {
    colors.push_back(series.color.empty() ? kPalette[palette_index++ % std::size(kPalette)] : series.color);
  }
  for (std::size_t i = 0; i < panel.series.size(); ++i)
    draw_series(svg, panel.series[i], colors[i], x_map, y_map, area);

  for (const auto& note : panel.notes) {
    if (!x_map.placeable(note.x) || !y_map.placeable(note.y)) continue;
    const Point p{x_map.to_pixel(note.x), y_map.to_pixel(note.y)};
    if (!area.contains(p)) continue;
    svg.line(fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\" fill=\"{}\">{}</text>", pixel(p.x + 5.0),
                         pixel(p.y - 5.0), kTickFont, note.color, escape_xml(note.text)));
  }

  // Frame, ticks, labels and titles on top.
  svg.line(fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"#666666\"/>",
                       pixel(area.left), pixel(area.top), pixel(area.right - area.left),
                       pixel(area.bottom - area.top)));
  if (!tick_marks.empty()) svg.line(fmt::format("<path d=\"{}\" stroke=\"#666666\" stroke-width=\"1\"/>", tick_marks));
  svg.line(labels);
  const std::string x_title = axis_title(panel.x);
  if (!x_title.empty()) {
    svg.line(fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"{}\">{}</text>",
                         pixel(0.5 * (area.left + area.right)), pixel(frame.bottom - 8.0), kLabelFont,
                         escape_xml(x_title)));
  }
  const std::string y_title = axis_title(panel.y);
  if (!y_title.empty()) {
    const double x = frame.left + 8.0 + kLabelFont * 0.8;
    const double y = 0.5 * (area.top + area.bottom);
    svg.line(
        fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"{}\" "
                    "transform=\"rotate(-90 {} {})\">{}</text>",
                    pixel(x), pixel(y), kLabelFont, pixel(x), pixel(y), escape_xml(y_title)));
  }
  if (!panel.title.empty()) {
    svg.line(fmt::format("<text x=\"{}\" y=\"{}\" font-size=\"{}\" font-weight=\"bold\">{}</text>", pixel(area.left),
                         pixel(frame.top + 12.0 + kTitleFont * 0.8), kTitleFont, escape_xml(panel.title)));
  }
  draw_legend(svg, panel, colors, area, data_pixels(panel, x_map, y_map));
}

}  // namespace

std::vector<Tick> linear_ticks(double lo, double hi, int target_count) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return {};
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) return {Tick{lo, format_tick(lo, lo == 0.0 ? 1.0 : std::abs(lo) / 10.0), true}};
  const double step = nice_step((hi - lo) / static_cast<double>(std::max(2, target_count) - 1));
  std::vector<Tick> ticks;
  const double first = std::ceil(lo / step - kSlack);
  const double last = std::floor(hi / step + kSlack);
  for (double k = first; k <= last; k += 1.0) {
    double value = k * step;
    if (std::abs(value) < step * kSlack) value = 0.0;
    ticks.push_back({value, format_tick(value, step), true});
  }
  return ticks;
}

std::vector<Tick> log_ticks(double lo, double hi) {
  if (!(lo > 0.0) || !(hi > 0.0) || !std::isfinite(lo) || !std::isfinite(hi)) return {};
  if (hi < lo) std::swap(lo, hi);
  const int first_decade = floor_log10(lo);
  const int last_decade = floor_log10(hi);
  auto inside = [&](double v) { return v >= lo * (1.0 - kSlack) && v <= hi * (1.0 + kSlack); };
  int decades = 0;
  for (int e = first_decade; e <= last_decade; ++e) decades += inside(std::pow(10.0, e)) ? 1 : 0;
  const int label_every = std::max(1, (decades + 6) / 7);
  const bool label_twos_and_fives = decades < 2;

  std::vector<Tick> ticks;
  int labelled = 0;
  for (int e = first_decade; e <= last_decade; ++e) {
    for (int m = 1; m <= 9; ++m) {
      const double value = m * std::pow(10.0, e);
      if (!inside(value)) continue;
      Tick tick{value, "", m == 1};
      if (m == 1 && ((e % label_every) + label_every) % label_every == 0) tick.label = format_log_tick(m, e);
      if (label_twos_and_fives && (m == 2 || m == 5)) {
        tick.major = true;
        tick.label = format_log_tick(m, e);
      }
      labelled += tick.label.empty() ? 0 : 1;
      ticks.push_back(std::move(tick));
    }
  }
  if (labelled < 2) return linear_ticks(lo, hi, 5);
  return ticks;
}

std::string format_tick(double value, double step) {
  if (!(step > 0.0) || !std::isfinite(step)) step = 1.0;
  if (std::abs(value) < step * 1e-6) return "0";
  const int step_exponent = floor_log10(step);
  if (step_exponent < -4 || std::abs(value) >= 1e6) {
    int exponent = floor_log10(std::abs(value));
    const int decimals = std::max(0, exponent - step_exponent);
    double mantissa = value / std::pow(10.0, exponent);
    if (std::abs(std::round(mantissa * std::pow(10.0, decimals))) >= 10.0 * std::pow(10.0, decimals)) {
      mantissa /= 10.0;
      ++exponent;
    }
    return fmt::format("{:.{}f}e{}", mantissa, decimals, exponent);
  }
  return fmt::format("{:.{}f}", value, std::max(0, -step_exponent));
}

std::string format_log_tick(int mantissa, int exponent) {
  if (exponent >= -2 && exponent <= 3) {
    return fmt::format("{:.{}f}", mantissa * std::pow(10.0, exponent), std::max(0, -exponent));
  }
  return fmt::format("{}e{}", mantissa, exponent);
}

Range auto_range(std::span<const double> values, AxisScale scale) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  for (double v : values) {
    if (!std::isfinite(v) || (scale == AxisScale::log && v <= 0.0)) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (scale == AxisScale::log) {
    if (lo > hi) return {1.0, 10.0};
    int first = floor_log10(lo);
    int last = ceil_log10(hi);
    if (last <= first) {
      --first;
      ++last;
    }
    return {std::pow(10.0, first), std::pow(10.0, last)};
  }
  if (lo > hi) return {0.0, 1.0};
  const double data_lo = lo;
  const double data_hi = hi;
  if (lo == hi) {
    const double half_width = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= half_width;
    hi += half_width;
  }
  const double step = nice_step((hi - lo) / 5.0);
  Range range{std::floor(lo / step + kSlack) * step, std::ceil(hi / step - kSlack) * step};
  // Keep the data off the frame, where markers would be cut in half.
  const double margin = 0.01 * (range.hi - range.lo);
  if (data_lo - range.lo < margin && data_lo != 0.0) range.lo -= step;
  if (range.hi - data_hi < margin && data_hi != 0.0) range.hi += step;
  return range;
}

AxisMap::AxisMap(Range range, AxisScale scale, double pixel_lo, double pixel_hi)
    : scale_(scale), pixel_lo_(pixel_lo), pixel_hi_(pixel_hi) {
  lo_ = scale == AxisScale::log ? std::log10(range.lo) : range.lo;
  hi_ = scale == AxisScale::log ? std::log10(range.hi) : range.hi;
}

bool AxisMap::placeable(double value) const {
  return std::isfinite(value) && (scale_ == AxisScale::linear || value > 0.0);
}

double AxisMap::to_pixel(double value) const {
  if (!placeable(value)) return std::numeric_limits<double>::quiet_NaN();
  const double v = scale_ == AxisScale::log ? std::log10(value) : value;
  if (hi_ == lo_) return 0.5 * (pixel_lo_ + pixel_hi_);
  return pixel_lo_ + (v - lo_) / (hi_ - lo_) * (pixel_hi_ - pixel_lo_);
}

std::optional<std::pair<Point, Point>> clip_segment(Point a, Point b, const Box& box) {
  // Liang-Barsky: the segment a + t·(b - a), t in [0, 1], against the four box edges.
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  double t0 = 0.0;
  double t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {a.x - box.left, box.right - a.x, a.y - box.top, box.bottom - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return std::nullopt;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      if (t > t1) return std::nullopt;
      t0 = std::max(t0, t);
    } else {
      if (t < t0) return std::nullopt;
      t1 = std::min(t1, t);
    }
  }
  const Point start = t0 == 0.0 ? a : Point{a.x + t0 * dx, a.y + t0 * dy};
  const Point end = t1 == 1.0 ? b : Point{a.x + t1 * dx, a.y + t1 * dy};
  return std::pair{start, end};
}

Axis make_axis(std::string label, std::string unit, AxisScale scale) {
  Axis axis;
  axis.label = std::move(label);
  axis.unit = std::move(unit);
  axis.scale = scale;
  return axis;
}

Box plot_area(const Panel& panel, const Box& frame) { return layout(panel, frame).area; }

std::string render_svg(const Plot& plot) {
  double height = 0.0;
  for (const auto& panel : plot.panels) height += panel.height;
  SvgWriter svg;
  // role="img" with a <title>: a screen reader names the plot (it had no name).
  std::string name = plot.description;
  for (std::size_t i = 0; plot.description.empty() && i < plot.panels.size(); ++i) {
    if (!plot.panels[i].title.empty()) name += (name.empty() ? "" : "; ") + plot.panels[i].title;
  }
  svg.line(
      fmt::format("<svg class=\"plot\" viewBox=\"0 0 {} {}\" width=\"{}\" height=\"{}\" role=\"img\" "
                  "font-family=\"{}\" fill=\"#222222\">",
                  pixel(plot.width), pixel(height), pixel(plot.width), pixel(height), kFontFamily));
  if (!name.empty()) svg.line("<title>" + escape_xml(name) + "</title>");
  double top = 0.0;
  std::size_t palette_index = 0;
  for (const auto& panel : plot.panels) {
    svg.line("<g class=\"panel\">");
    draw_panel(svg, panel, {0.0, top, plot.width, top + panel.height}, palette_index);
    svg.line("</g>");
    top += panel.height;
  }
  svg.line("</svg>");
  if (plot.embed_data) {
    // "</" could end the script element early; JSON allows "<\/" for it.
    const std::string data = json_text(plot_data(plot));
    std::string escaped;
    escaped.reserve(data.size());
    for (std::size_t i = 0; i < data.size(); ++i) {
      escaped += data[i];
      if (data[i] == '<' && i + 1 < data.size() && data[i + 1] == '/') escaped += '\\';
    }
    svg.line("<script type=\"application/json\" class=\"plot-data\">" + escaped + "</script>");
  }
  return svg.take();
}

namespace {

nlohmann::json numbers(const std::vector<double>& values) {
  nlohmann::json out = nlohmann::json::array();
  for (double v : values) out.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json());
  return out;
}

nlohmann::json number_or_null(std::optional<double> value) {
  return value && std::isfinite(*value) ? nlohmann::json(*value) : nlohmann::json();
}

nlohmann::json axis_data(const Axis& axis) {
  return {{"label", axis.label},
          {"unit", axis.unit},
          {"scale", axis.scale == AxisScale::log ? "log" : "linear"},
          {"min", number_or_null(axis.min)},
          {"max", number_or_null(axis.max)},
          {"include_zero", axis.include_zero},
          {"ticks", numbers(axis.ticks)}};
}

const char* line_name(LineStyle style) {
  switch (style) {
    case LineStyle::none: return "none";
    case LineStyle::dashed: return "dashed";
    case LineStyle::dotted: return "dotted";
    case LineStyle::solid: break;
  }
  return "solid";
}

const char* marker_name(Marker marker) {
  switch (marker) {
    case Marker::circle: return "circle";
    case Marker::square: return "square";
    case Marker::triangle: return "triangle";
    case Marker::diamond: return "diamond";
    case Marker::none: break;
  }
  return "none";
}

const char* legend_name(LegendPosition position) {
  switch (position) {
    case LegendPosition::none: return "none";
    case LegendPosition::top_right: return "top_right";
    case LegendPosition::top_left: return "top_left";
    case LegendPosition::bottom_right: return "bottom_right";
    case LegendPosition::bottom_left: return "bottom_left";
    case LegendPosition::automatic: break;
  }
  return "automatic";
}

}  // namespace

nlohmann::json plot_data(const Plot& plot) {
  nlohmann::json panels = nlohmann::json::array();
  std::size_t palette_index = 0;  // as draw_panel takes the palette's colours
  for (const auto& panel : plot.panels) {
    nlohmann::json series = nlohmann::json::array();
    for (const auto& s : panel.series) {
      series.push_back({{"name", s.name},
                        {"color", s.color.empty() ? kPalette[palette_index++ % std::size(kPalette)] : s.color},
                        {"line", line_name(s.line)},
                        {"marker", marker_name(s.marker)},
                        {"line_width", s.line_width},
                        {"x", numbers(s.x)},
                        {"y", numbers(s.y)},
                        {"y_low", numbers(s.y_low)},
                        {"y_high", numbers(s.y_high)}});
    }
    nlohmann::json references = nlohmann::json::array();
    for (const auto& r : panel.references) {
      references.push_back({{"direction", r.direction == ReferenceLine::Direction::horizontal ? "horizontal" : "vertical"},
                            {"value", number_or_null(r.value)},
                            {"label", r.label},
                            {"color", r.color}});
    }
    nlohmann::json notes = nlohmann::json::array();
    for (const auto& n : panel.notes) {
      notes.push_back({{"x", number_or_null(n.x)}, {"y", number_or_null(n.y)}, {"text", n.text}, {"color", n.color}});
    }
    panels.push_back({{"title", panel.title},
                      {"height", panel.height},
                      {"legend", legend_name(panel.legend)},
                      {"x", axis_data(panel.x)},
                      {"y", axis_data(panel.y)},
                      {"series", std::move(series)},
                      {"references", std::move(references)},
                      {"notes", std::move(notes)}});
  }
  return {{"width", plot.width}, {"panels", std::move(panels)}};
}

std::string escape_xml(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

double text_width(const std::string& text, double font_size) {
  double width = 0.0;
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const std::size_t length = byte < 0x80 ? 1 : byte < 0xE0 ? 2 : byte < 0xF0 ? 3 : 4;
    // ASCII about 0.6 em in DejaVu Sans; CJK (3-byte UTF-8) a full em; other letters (°, σ, √) 0.65 em.
    width += font_size * (length == 1 ? 0.6 : length >= 3 && byte >= 0xE3 ? 1.0 : 0.65);
    i += length;
  }
  return width;
}

}  // namespace inertest::report
