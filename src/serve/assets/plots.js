// The web view's interactive plots (inertest serve, issue 17). Every <svg class="plot"> followed by
// its data (<script type="application/json" class="plot-data">, report::plot_data) is drawn again
// from that data, as report/svg_plot.cc draws it, and can then be
//   * zoomed: drag a rectangle (or along x only), or turn the mouse wheel; pan in "Pan" mode;
//     double-click or "Reset" for the whole plot; the axes' ticks are recomputed (log axes too);
//   * read: the nearest point's value with its uncertainty (or interval) and unit, on hover;
//   * downloaded: "SVG" (the plot as shown) and "CSV" (all its data, every series).
// A URL fragment #zoom=N:x0:x1[:y0:y1] opens plot N (0-based, in page order) zoomed.
// Plain JavaScript, no outside resource; window.inertestPlots exposes the plots for tests.
(function () {
  'use strict';
  var TICK_FONT = 11, LABEL_FONT = 12, TITLE_FONT = 13, LEGEND_FONT = 11, MAJOR_TICK = 5, MINOR_TICK = 3;
  var SLACK = 1e-9;
  var zh = (document.documentElement.lang || '').indexOf('zh') === 0;
  var WORDS = zh ? {zoom: '框选缩放', pan: '平移', reset: '复位', svg: '下载 SVG', csv: '下载 CSV', series: '曲线', panel: '图'}
                 : {zoom: 'Zoom', pan: 'Pan', reset: 'Reset', svg: 'SVG', csv: 'CSV', series: 'series', panel: 'panel'};

  // ---- Axes: the same ticks and ranges as svg_plot.cc ----
  function niceStep(raw) {
    var exponent = Math.floor(Math.log10(raw));
    var power = Math.pow(10, exponent);
    var fraction = raw / power;
    var nice = fraction < 1.5 ? 1 : fraction < 3 ? 2 : fraction < 7 ? 5 : 10;
    return nice * power;
  }
  function floorLog10(v) { return Math.floor(Math.log10(v) + 1e-12); }
  function ceilLog10(v) { return Math.ceil(Math.log10(v) - 1e-12); }

  function formatTick(value, step) {
    if (!(step > 0) || !isFinite(step)) step = 1;
    if (Math.abs(value) < step * 1e-6) return '0';
    var stepExponent = floorLog10(step);
    if (stepExponent < -4 || Math.abs(value) >= 1e6) {
      var exponent = floorLog10(Math.abs(value));
      var decimals = Math.max(0, exponent - stepExponent);
      var mantissa = value / Math.pow(10, exponent);
      if (Math.abs(Math.round(mantissa * Math.pow(10, decimals))) >= 10 * Math.pow(10, decimals)) {
        mantissa /= 10;
        exponent += 1;
      }
      return mantissa.toFixed(decimals) + 'e' + exponent;
    }
    return value.toFixed(Math.max(0, -stepExponent));
  }
  function formatLogTick(mantissa, exponent) {
    if (exponent >= -2 && exponent <= 3) return (mantissa * Math.pow(10, exponent)).toFixed(Math.max(0, -exponent));
    return mantissa + 'e' + exponent;
  }
  function linearTicks(lo, hi, target) {
    if (!isFinite(lo) || !isFinite(hi)) return [];
    if (hi < lo) { var t = lo; lo = hi; hi = t; }
    if (hi === lo) return [{value: lo, label: formatTick(lo, lo === 0 ? 1 : Math.abs(lo) / 10), major: true}];
    var step = niceStep((hi - lo) / (Math.max(2, target) - 1));
    var ticks = [];
    var last = Math.floor(hi / step + SLACK);
    for (var k = Math.ceil(lo / step - SLACK); k <= last; k += 1) {
      var value = k * step;
      if (Math.abs(value) < step * SLACK) value = 0;
      ticks.push({value: value, label: formatTick(value, step), major: true});
    }
    return ticks;
  }
  function logTicks(lo, hi) {
    if (!(lo > 0) || !(hi > 0) || !isFinite(lo) || !isFinite(hi)) return [];
    if (hi < lo) { var t = lo; lo = hi; hi = t; }
    var first = floorLog10(lo), last = floorLog10(hi);
    function inside(v) { return v >= lo * (1 - SLACK) && v <= hi * (1 + SLACK); }
    var decades = 0;
    for (var e = first; e <= last; ++e) decades += inside(Math.pow(10, e)) ? 1 : 0;
    var every = Math.max(1, Math.floor((decades + 6) / 7));
    var twosAndFives = decades < 2;
    var ticks = [], labelled = 0;
    for (e = first; e <= last; ++e) {
      for (var m = 1; m <= 9; ++m) {
        var value = m * Math.pow(10, e);
        if (!inside(value)) continue;
        var tick = {value: value, label: '', major: m === 1};
        if (m === 1 && ((e % every) + every) % every === 0) tick.label = formatLogTick(m, e);
        if (twosAndFives && (m === 2 || m === 5)) { tick.major = true; tick.label = formatLogTick(m, e); }
        labelled += tick.label ? 1 : 0;
        ticks.push(tick);
      }
    }
    return labelled < 2 ? linearTicks(lo, hi, 5) : ticks;
  }
  function autoRange(values, scale) {
    var lo = Infinity, hi = -Infinity;
    values.forEach(function (v) {
      if (v === null || !isFinite(v) || (scale === 'log' && v <= 0)) return;
      lo = Math.min(lo, v);
      hi = Math.max(hi, v);
    });
    if (scale === 'log') {
      if (lo > hi) return {lo: 1, hi: 10};
      var a = floorLog10(lo), b = ceilLog10(hi);
      if (b <= a) { a -= 1; b += 1; }
      return {lo: Math.pow(10, a), hi: Math.pow(10, b)};
    }
    if (lo > hi) return {lo: 0, hi: 1};
    var dataLo = lo, dataHi = hi;
    if (lo === hi) {
      var half = lo === 0 ? 1 : 0.1 * Math.abs(lo);
      lo -= half;
      hi += half;
    }
    var step = niceStep((hi - lo) / 5);
    var range = {lo: Math.floor(lo / step + SLACK) * step, hi: Math.ceil(hi / step - SLACK) * step};
    var margin = 0.01 * (range.hi - range.lo);
    if (dataLo - range.lo < margin && dataLo !== 0) range.lo -= step;
    if (range.hi - dataHi < margin && dataHi !== 0) range.hi += step;
    return range;
  }
  function textWidth(text, size) {
    var width = 0;
    for (var i = 0; i < text.length; ++i) {
      var c = text.charCodeAt(i);
      width += size * (c < 0x80 ? 0.6 : c >= 0x3000 ? 1.0 : 0.65);
    }
    return width;
  }
  function placeable(value, scale) { return value !== null && isFinite(value) && (scale === 'linear' || value > 0); }
  // The map of one axis from data to pixels, and back.
  function axisMap(range, scale, pixelLo, pixelHi) {
    var lo = scale === 'log' ? Math.log10(range.lo) : range.lo;
    var hi = scale === 'log' ? Math.log10(range.hi) : range.hi;
    return {
      toPixel: function (value) {
        var v = scale === 'log' ? Math.log10(value) : value;
        return hi === lo ? 0.5 * (pixelLo + pixelHi) : pixelLo + (v - lo) / (hi - lo) * (pixelHi - pixelLo);
      },
      toValue: function (pixel) {
        var v = lo + (pixel - pixelLo) / (pixelHi - pixelLo) * (hi - lo);
        return scale === 'log' ? Math.pow(10, v) : v;
      }
    };
  }
  function axisTitle(axis) {
    if (!axis.unit || axis.unit === '1') return axis.label;
    return axis.label ? axis.label + ' (' + axis.unit + ')' : axis.unit;
  }
  function px(v) { var s = v.toFixed(1); return s === '-0.0' ? '0.0' : s; }
  function esc(text) {
    return String(text).replace(/&/g, '&amp;').replace(/</g, '&lt;').replace(/>/g, '&gt;')
      .replace(/"/g, '&quot;').replace(/'/g, '&#39;');
  }

  // ---- Drawing ----
  // The ranges a panel shows: its zoom, else as svg_plot.cc chooses them from the data.
  function panelRanges(panel, view) {
    var xs = [], ys = [];
    panel.series.forEach(function (s) {
      xs = xs.concat(s.x);
      ys = ys.concat(s.y, s.y_low, s.y_high);
    });
    panel.references.forEach(function (r) { (r.direction === 'horizontal' ? ys : xs).push(r.value); });
    function resolve(axis, values) {
      if (axis.include_zero && axis.scale === 'linear') values.push(0);
      var range = autoRange(values, axis.scale);
      if (axis.min !== null) range.lo = axis.min;
      if (axis.max !== null) range.hi = axis.max;
      if (!(range.hi > range.lo)) range = autoRange([range.lo, range.hi], axis.scale);
      return range;
    }
    return {x: view.x || resolve(panel.x, xs), y: view.y || resolve(panel.y, ys)};
  }
  function ticksFor(axis, range, zoomed) {
    if (axis.ticks.length && !zoomed) {
      var step = range.hi - range.lo;
      for (var i = 1; i < axis.ticks.length; ++i) step = Math.min(step, Math.abs(axis.ticks[i] - axis.ticks[i - 1]));
      return axis.ticks.map(function (v) { return {value: v, label: formatTick(v, step > 0 ? step : 1), major: true}; });
    }
    return axis.scale === 'log' ? logTicks(range.lo, range.hi) : linearTicks(range.lo, range.hi, 6);
  }
  function dash(line) {
    return line === 'dashed' ? ' stroke-dasharray="7 4"' : line === 'dotted' ? ' stroke-dasharray="1.5 3" stroke-linecap="round"' : '';
  }
  function marker(kind, x, y, color) {
    var fill = ' fill="' + esc(color) + '"';
    if (kind === 'circle') return '<circle cx="' + px(x) + '" cy="' + px(y) + '" r="3.2"' + fill + '/>';
    if (kind === 'square') return '<rect x="' + px(x - 3) + '" y="' + px(y - 3) + '" width="6" height="6"' + fill + '/>';
    if (kind === 'triangle') {
      return '<path d="M' + px(x) + ' ' + px(y - 3.8) + 'L' + px(x + 3.6) + ' ' + px(y + 2.6) + 'L' + px(x - 3.6) + ' ' +
        px(y + 2.6) + 'Z"' + fill + '/>';
    }
    if (kind === 'diamond') {
      return '<path d="M' + px(x) + ' ' + px(y - 4) + 'L' + px(x + 4) + ' ' + px(y) + 'L' + px(x) + ' ' + px(y + 4) + 'L' +
        px(x - 4) + ' ' + px(y) + 'Z"' + fill + '/>';
    }
    return '';
  }

  // Draws panel p of plot into its frame; records on plot.geometry[p] what the mouse needs.
  function drawPanel(plot, p, top) {
    var panel = plot.data.panels[p];
    var view = plot.view[p];
    var zoomed = !!(view.x || view.y);
    var ranges = panelRanges(panel, view);
    var xTicks = ticksFor(panel.x, ranges.x, !!view.x);
    var yTicks = ticksFor(panel.y, ranges.y, !!view.y);
    var widest = 0;
    yTicks.forEach(function (t) { widest = Math.max(widest, textWidth(t.label, TICK_FONT)); });
    var frame = {left: 0, top: top, right: plot.data.width, bottom: top + panel.height};
    var area = {
      left: frame.left + Math.max(52, 8 + LABEL_FONT + 8 + widest + MAJOR_TICK + 4),
      top: frame.top + (panel.title ? 12 + TITLE_FONT + 6 : 12),
      right: frame.right - 22,
      bottom: frame.bottom - (MAJOR_TICK + 4 + TICK_FONT + 8 + LABEL_FONT + 8)
    };
    var xMap = axisMap(ranges.x, panel.x.scale, area.left, area.right);
    var yMap = axisMap(ranges.y, panel.y.scale, area.bottom, area.top);
    plot.geometry[p] = {area: area, x: ranges.x, y: ranges.y, xMap: xMap, yMap: yMap, panel: panel};
    function inArea(x, y) { return x >= area.left - 0.01 && x <= area.right + 0.01 && y >= area.top - 0.01 && y <= area.bottom + 0.01; }
    var clip = plot.id + '-clip-' + p;
    var out = '<g class="panel" data-panel="' + p + '" data-area="' + [area.left, area.top, area.right, area.bottom].join(' ') +
      '" data-x-range="' + ranges.x.lo + ' ' + ranges.x.hi + '" data-y-range="' + ranges.y.lo + ' ' + ranges.y.hi +
      '" data-zoomed="' + zoomed + '">\n';
    out += '<clipPath id="' + clip + '"><rect x="' + area.left + '" y="' + area.top + '" width="' + (area.right - area.left) +
      '" height="' + (area.bottom - area.top) + '"/></clipPath>\n';
    out += '<rect x="' + px(area.left) + '" y="' + px(area.top) + '" width="' + px(area.right - area.left) + '" height="' +
      px(area.bottom - area.top) + '" fill="#ffffff"/>\n';

    var major = '', minor = '', marks = '', labels = '';
    xTicks.forEach(function (t) {
      if (!placeable(t.value, panel.x.scale)) return;
      var x = xMap.toPixel(t.value);
      if (x < area.left - 0.5 || x > area.right + 0.5) return;
      var d = 'M' + px(x) + ' ' + px(area.top) + 'V' + px(area.bottom);
      if (t.major) major += d; else minor += d;
      marks += 'M' + px(x) + ' ' + px(area.bottom) + 'v' + (t.major ? MAJOR_TICK : MINOR_TICK);
      if (t.label) {
        labels += '<text class="tick x" data-value="' + t.value + '" x="' + px(x) + '" y="' +
          px(area.bottom + MAJOR_TICK + 4 + TICK_FONT * 0.8) + '" text-anchor="middle" font-size="' + TICK_FONT + '">' +
          esc(t.label) + '</text>\n';
      }
    });
    yTicks.forEach(function (t) {
      if (!placeable(t.value, panel.y.scale)) return;
      var y = yMap.toPixel(t.value);
      if (y < area.top - 0.5 || y > area.bottom + 0.5) return;
      var d = 'M' + px(area.left) + ' ' + px(y) + 'H' + px(area.right);
      if (t.major) major += d; else minor += d;
      marks += 'M' + px(area.left) + ' ' + px(y) + 'h-' + (t.major ? MAJOR_TICK : MINOR_TICK);
      if (t.label) {
        labels += '<text class="tick y" data-value="' + t.value + '" x="' + px(area.left - MAJOR_TICK - 3) + '" y="' + px(y) +
          '" text-anchor="end" dominant-baseline="central" font-size="' + TICK_FONT + '">' + esc(t.label) + '</text>\n';
      }
    });
    if (minor) out += '<path d="' + minor + '" stroke="#eeeeee" stroke-width="1"/>\n';
    if (major) out += '<path d="' + major + '" stroke="#d8d8d8" stroke-width="1"/>\n';

    var verticalLabels = 0;
    panel.references.forEach(function (r) {
      var horizontal = r.direction === 'horizontal';
      if (!placeable(r.value, horizontal ? panel.y.scale : panel.x.scale)) return;
      var at = horizontal ? yMap.toPixel(r.value) : xMap.toPixel(r.value);
      if (horizontal ? (at < area.top || at > area.bottom) : (at < area.left || at > area.right)) return;
      var d = horizontal ? 'M' + px(area.left) + ' ' + px(at) + 'H' + px(area.right) : 'M' + px(at) + ' ' + px(area.top) + 'V' + px(area.bottom);
      out += '<path d="' + d + '" stroke="' + esc(r.color) + '" stroke-width="1.2" stroke-dasharray="5 3"/>\n';
      if (!r.label) return;
      if (horizontal) {
        out += '<text x="' + px(area.right - 4) + '" y="' + px(at - 4) + '" text-anchor="end" font-size="' + TICK_FONT +
          '" fill="' + esc(r.color) + '">' + esc(r.label) + '</text>\n';
      } else {
        out += '<text x="' + px(at + 4) + '" y="' + px(area.bottom - 6 - 14 * verticalLabels++) + '" font-size="' + TICK_FONT +
          '" fill="' + esc(r.color) + '">' + esc(r.label) + '</text>\n';
      }
    });

    // The series: error bars, lines and markers, clipped to the area. A line runs through the points in
    // view and on to the neighbour on either side, so that it reaches the frame.
    var occupied = [];
    panel.series.forEach(function (s, k) {
      var n = Math.min(s.x.length, s.y.length);
      var pts = [], shown = 0;
      for (var i = 0; i < n; ++i) {
        if (placeable(s.x[i], panel.x.scale) && placeable(s.y[i], panel.y.scale)) {
          var q = {i: i, x: xMap.toPixel(s.x[i]), y: yMap.toPixel(s.y[i])};
          q.inside = inArea(q.x, q.y);
          shown += q.inside ? 1 : 0;
          pts.push(q);
        } else {
          pts.push(null);
        }
      }
      out += '<g class="series" data-series="' + k + '" data-shown="' + shown + '" clip-path="url(#' + clip + ')">\n';
      if (s.y_low.length === n && s.y_high.length === n) {
        var bars = '';
        pts.forEach(function (q) {
          if (!q || !placeable(s.y_low[q.i], panel.y.scale) || !placeable(s.y_high[q.i], panel.y.scale)) return;
          var lo = yMap.toPixel(s.y_low[q.i]), hi = yMap.toPixel(s.y_high[q.i]);
          if (q.x < area.left - 0.01 || q.x > area.right + 0.01 || Math.max(lo, hi) < area.top || Math.min(lo, hi) > area.bottom) return;
          bars += 'M' + px(q.x) + ' ' + px(lo) + 'V' + px(hi) + 'M' + px(q.x - 3) + ' ' + px(lo) + 'h6M' + px(q.x - 3) + ' ' + px(hi) + 'h6';
        });
        if (bars) out += '<path class="bars" d="' + bars + '" stroke="' + esc(s.color) + '" stroke-width="1" fill="none"/>\n';
      }
      if (s.line !== 'none') {
        var run = [];
        var flush = function () {
          if (run.length >= 2) {
            out += '<polyline points="' + run.map(function (q) { return px(q.x) + ',' + px(q.y); }).join(' ') +
              '" data-index="' + run.map(function (q) { return q.i; }).join(' ') + '" fill="none" stroke="' + esc(s.color) +
              '" stroke-width="' + s.line_width + '" stroke-linejoin="round"' + dash(s.line) + '/>\n';
          }
          run = [];
        };
        for (i = 0; i < pts.length; ++i) {
          var q = pts[i];
          if (!q) { flush(); continue; }
          var before = i > 0 && pts[i - 1] && pts[i - 1].inside;
          var after = i + 1 < pts.length && pts[i + 1] && pts[i + 1].inside;
          if (q.inside || before || after) run.push(q); else flush();
        }
        flush();
      }
      if (s.marker !== 'none') {
        pts.forEach(function (q) {
          if (q && q.inside) out += marker(s.marker, q.x, q.y, s.color).replace('/>', ' data-index="' + q.i + '"/>') + '\n';
        });
      }
      pts.forEach(function (q) { if (q && q.inside) occupied.push(q); });
      out += '</g>\n';
    });

    panel.notes.forEach(function (note) {
      if (!placeable(note.x, panel.x.scale) || !placeable(note.y, panel.y.scale)) return;
      var x = xMap.toPixel(note.x), y = yMap.toPixel(note.y);
      if (!inArea(x, y)) return;
      out += '<text x="' + px(x + 5) + '" y="' + px(y - 5) + '" font-size="' + TICK_FONT + '" fill="' + esc(note.color) + '">' +
        esc(note.text) + '</text>\n';
    });

    out += '<rect x="' + px(area.left) + '" y="' + px(area.top) + '" width="' + px(area.right - area.left) + '" height="' +
      px(area.bottom - area.top) + '" fill="none" stroke="#666666"/>\n';
    if (marks) out += '<path d="' + marks + '" stroke="#666666" stroke-width="1"/>\n';
    out += labels;
    var xTitle = axisTitle(panel.x), yTitle = axisTitle(panel.y);
    if (xTitle) {
      out += '<text x="' + px(0.5 * (area.left + area.right)) + '" y="' + px(frame.bottom - 8) + '" text-anchor="middle" font-size="' +
        LABEL_FONT + '">' + esc(xTitle) + '</text>\n';
    }
    if (yTitle) {
      var tx = frame.left + 8 + LABEL_FONT * 0.8, ty = 0.5 * (area.top + area.bottom);
      out += '<text x="' + px(tx) + '" y="' + px(ty) + '" text-anchor="middle" font-size="' + LABEL_FONT + '" transform="rotate(-90 ' +
        px(tx) + ' ' + px(ty) + ')">' + esc(yTitle) + '</text>\n';
    }
    if (panel.title) {
      out += '<text x="' + px(area.left) + '" y="' + px(frame.top + 12 + TITLE_FONT * 0.8) + '" font-size="' + TITLE_FONT +
        '" font-weight="bold">' + esc(panel.title) + '</text>\n';
    }
    out += legend(panel, area, occupied);
    return out + '</g>\n';
  }

  // The legend in the corner the panel asks for, or (automatic) the inside corner covering the
  // fewest points in view.
  function legend(panel, area, occupied) {
    var entries = panel.series.filter(function (s) { return s.name; });
    if (!entries.length || panel.legend === 'none') return '';
    var width = 0;
    entries.forEach(function (s) { width = Math.max(width, textWidth(s.name, LEGEND_FONT)); });
    width += 22 + 6 + 12;
    var height = 8 + 16 * entries.length;
    var corners = {
      top_right: [area.right - width - 6, area.top + 6], top_left: [area.left + 6, area.top + 6],
      bottom_right: [area.right - width - 6, area.bottom - height - 6], bottom_left: [area.left + 6, area.bottom - height - 6]
    };
    var chosen = panel.legend;
    if (!corners[chosen]) {
      var best = Infinity;
      ['top_right', 'top_left', 'bottom_right', 'bottom_left'].forEach(function (name) {
        var c = corners[name];
        var covered = occupied.filter(function (q) {
          return q.x >= c[0] && q.x <= c[0] + width && q.y >= c[1] && q.y <= c[1] + height;
        }).length;
        if (covered < best) { best = covered; chosen = name; }
      });
    }
    var x0 = corners[chosen][0], y0 = corners[chosen][1];
    var out = '<g class="legend"><rect x="' + px(x0) + '" y="' + px(y0) + '" width="' + px(width) + '" height="' + px(height) +
      '" fill="#ffffff" fill-opacity="0.85" stroke="#cccccc"/>\n';
    entries.forEach(function (s, i) {
      var x = x0 + 6, y = y0 + 12 + 16 * i;
      if (s.line !== 'none') {
        out += '<path d="M' + px(x) + ' ' + px(y) + 'h22" stroke="' + esc(s.color) + '" stroke-width="' + s.line_width + '"' + dash(s.line) + '/>\n';
      }
      if (s.marker !== 'none') out += marker(s.marker, x + 11, y, s.color) + '\n';
      out += '<text x="' + px(x + 28) + '" y="' + px(y) + '" font-size="' + LEGEND_FONT + '" dominant-baseline="central">' +
        esc(s.name) + '</text>\n';
    });
    return out + '</g>\n';
  }

  function draw(plot) {
    // The plot's name for a screen reader (its <title>, render_svg's) stays through every redraw.
    var title = plot.svg.querySelector('title');
    var out = title ? '<title>' + esc(title.textContent) + '</title>\n' : '', top = 0;
    plot.geometry = [];
    plot.data.panels.forEach(function (panel, p) {
      out += drawPanel(plot, p, top);
      top += panel.height;
    });
    plot.svg.innerHTML = out + '<rect class="rubber" x="0" y="0" width="0" height="0" fill="#1f6feb" fill-opacity="0.12" ' +
      'stroke="#1f6feb" stroke-dasharray="4 2" visibility="hidden"/>';
    plot.svg.setAttribute('data-zoomed', plot.view.some(function (v) { return v.x || v.y; }));
  }

  // ---- Numbers with their uncertainty ----
  // A value to the decimal of its uncertainty's second significant digit: "0.01534 ± 0.00021 deg/h".
  function withUncertainty(value, low, high, unit) {
    var suffix = unit && unit !== '1' ? ' ' + unit : '';
    if (low === null || high === null || low === undefined || !isFinite(low) || !isFinite(high) || high - low <= 0) {
      return plain(value) + suffix;
    }
    var up = high - value, down = value - low;
    var u = Math.max(up, down);
    var place = Math.floor(Math.log10(u)) - 1;
    function at(v) {
      if (Math.abs(value) >= 1e6 || (value !== 0 && Math.abs(value) < 1e-3)) {
        return v.toExponential(Math.max(1, floorLog10(Math.abs(v) || u) - place));
      }
      return place < 0 ? v.toFixed(-place) : String(Math.round(v / Math.pow(10, place)) * Math.pow(10, place));
    }
    if (Math.abs(up - down) <= 0.02 * u) return at(value) + ' ± ' + at(0.5 * (up + down)) + suffix;
    return at(value) + ' (+' + at(up) + ' / −' + at(down) + ')' + suffix;
  }
  function plain(value) {
    if (value === 0) return '0';
    var a = Math.abs(value);
    return a >= 1e6 || a < 1e-3 ? value.toExponential(4) : String(Number(value.toPrecision(6)));
  }

  // ---- Downloads ----
  function csvField(text) {
    text = String(text);
    return /[",\n]/.test(text) ? '"' + text.replace(/"/g, '""') + '"' : text;
  }
  function number(v) { return v === null || v === undefined ? '' : String(v); }
  // Every point of every series: panel, series, x, y, y_low, y_high, the columns named with units.
  function csv(plot) {
    var first = plot.data.panels[0];
    var lines = [[WORDS.panel, WORDS.series, axisTitle(first.x) || 'x', axisTitle(first.y) || 'y', 'y_low', 'y_high'].map(csvField).join(',')];
    plot.data.panels.forEach(function (panel, p) {
      panel.series.forEach(function (s, k) {
        var name = s.name || WORDS.series + ' ' + (k + 1);
        for (var i = 0; i < Math.min(s.x.length, s.y.length); ++i) {
          lines.push([p + 1 + (plot.data.panels.length > 1 ? ' ' + axisTitle(panel.y) : ''), name, number(s.x[i]), number(s.y[i]),
                      number(s.y_low.length ? s.y_low[i] : null), number(s.y_high.length ? s.y_high[i] : null)].map(csvField).join(','));
        }
      });
    });
    return lines.join('\n') + '\n';
  }
  function svgText(plot) {
    var copy = plot.svg.cloneNode(true);
    copy.setAttribute('xmlns', 'http://www.w3.org/2000/svg');
    var rubber = copy.querySelector('.rubber');
    if (rubber) rubber.parentNode.removeChild(rubber);
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + new XMLSerializer().serializeToString(copy) + '\n';
  }
  function download(text, type, name) {
    var url = URL.createObjectURL(new Blob([text], {type: type}));
    var link = document.createElement('a');
    link.href = url;
    link.download = name;
    document.body.appendChild(link);
    link.click();
    document.body.removeChild(link);
    setTimeout(function () { URL.revokeObjectURL(url); }, 1000);
  }
  function fileName(plot, extension) {
    var base = (document.title || 'plot').replace(/[^A-Za-z0-9_.\-]+/g, '_').replace(/^_+|_+$/g, '') || 'plot';
    return base + '-' + plot.id + '.' + extension;
  }

  // ---- Mouse ----
  function svgPoint(plot, event) {
    var r = plot.svg.getBoundingClientRect();
    var box = plot.svg.viewBox.baseVal;
    return {x: (event.clientX - r.left) * box.width / r.width, y: (event.clientY - r.top) * box.height / r.height};
  }
  function panelAt(plot, q) {
    for (var p = 0; p < plot.geometry.length; ++p) {
      var a = plot.geometry[p].area;
      if (q.x >= a.left && q.x <= a.right && q.y >= a.top && q.y <= a.bottom) return p;
    }
    return -1;
  }
  function ordered(a, b) { return a < b ? {lo: a, hi: b} : {lo: b, hi: a}; }
  // Zooms: x over [x0, x1] pixels on every panel (they share x), y over [y0, y1] on panel p.
  function zoomTo(plot, p, x0, x1, y0, y1) {
    var g = plot.geometry[p];
    var x = x1 !== null ? ordered(g.xMap.toValue(x0), g.xMap.toValue(x1)) : null;
    plot.view.forEach(function (v, i) {
      if (x) v.x = x;
      if (i === p && y1 !== null) v.y = ordered(g.yMap.toValue(y0), g.yMap.toValue(y1));
    });
    draw(plot);
  }
  function reset(plot) {
    plot.view = plot.data.panels.map(function () { return {x: null, y: null}; });
    draw(plot);
  }
  function nearest(plot, q) {
    var p = panelAt(plot, q);
    if (p < 0) return null;
    var g = plot.geometry[p], panel = g.panel, best = null, bestDistance = 30 * 30;
    panel.series.forEach(function (s, k) {
      for (var i = 0; i < Math.min(s.x.length, s.y.length); ++i) {
        if (!placeable(s.x[i], panel.x.scale) || !placeable(s.y[i], panel.y.scale)) continue;
        var dx = g.xMap.toPixel(s.x[i]) - q.x, dy = g.yMap.toPixel(s.y[i]) - q.y;
        var d = dx * dx + dy * dy;
        if (d < bestDistance) { bestDistance = d; best = {panel: p, series: k, index: i}; }
      }
    });
    return best;
  }
  function showTip(plot, event) {
    var q = svgPoint(plot, event);
    var hit = nearest(plot, q);
    var tip = plot.tip;
    if (!hit) { tip.hidden = true; return; }
    var panel = plot.data.panels[hit.panel], s = panel.series[hit.series], i = hit.index;
    var bars = s.y_low.length > i && s.y_high.length > i;
    tip.innerHTML = '<span class="tip-series">' + esc(s.name || WORDS.series + ' ' + (hit.series + 1)) + '</span><br>' +
      '<span class="tip-value">' + esc(withUncertainty(s.y[i], bars ? s.y_low[i] : null, bars ? s.y_high[i] : null, panel.y.unit)) +
      '</span><br><span class="tip-x">' + esc((panel.x.label || 'x') + ' = ' + withUncertainty(s.x[i], null, null, panel.x.unit)) + '</span>';
    tip.setAttribute('data-panel', hit.panel);
    tip.setAttribute('data-series', hit.series);
    tip.setAttribute('data-index', i);
    tip.hidden = false;
    var box = plot.box.getBoundingClientRect();
    var left = event.clientX - box.left + 14, top = event.clientY - box.top + 14;
    if (left + tip.offsetWidth > box.width) left = event.clientX - box.left - tip.offsetWidth - 10;
    tip.style.left = left + 'px';
    tip.style.top = top + 'px';
  }

  function attach(plot) {
    var drag = null;
    var svg = plot.svg;
    svg.addEventListener('mousedown', function (event) {
      if (event.button !== 0) return;
      var q = svgPoint(plot, event), p = panelAt(plot, q);
      if (p < 0) return;
      event.preventDefault();
      drag = {panel: p, start: q, last: q, ranges: plot.view.map(function (v) { return {x: v.x, y: v.y}; })};
    });
    window.addEventListener('mousemove', function (event) {
      if (!drag) return;
      var q = svgPoint(plot, event), g = plot.geometry[drag.panel], a = g.area;
      q = {x: Math.min(Math.max(q.x, a.left), a.right), y: Math.min(Math.max(q.y, a.top), a.bottom)};
      if (plot.mode === 'pan') {
        var dx = q.x - drag.last.x, dy = q.y - drag.last.y;
        drag.last = q;
        zoomTo(plot, drag.panel, a.left - dx, a.right - dx, a.bottom - dy, a.top - dy);
        return;
      }
      drag.last = q;
      var rubber = svg.querySelector('.rubber'), flat = Math.abs(q.y - drag.start.y) < 5;
      rubber.setAttribute('x', Math.min(q.x, drag.start.x));
      rubber.setAttribute('width', Math.abs(q.x - drag.start.x));
      rubber.setAttribute('y', flat ? a.top : Math.min(q.y, drag.start.y));
      rubber.setAttribute('height', flat ? a.bottom - a.top : Math.abs(q.y - drag.start.y));
      rubber.setAttribute('visibility', 'visible');
    });
    window.addEventListener('mouseup', function () {
      if (!drag) return;
      var d = drag;
      drag = null;
      if (plot.mode === 'pan') return;
      var wide = Math.abs(d.last.x - d.start.x) >= 5, tall = Math.abs(d.last.y - d.start.y) >= 5;
      if (wide || tall) {
        zoomTo(plot, d.panel, wide ? d.start.x : null, wide ? d.last.x : null, tall ? d.start.y : null, tall ? d.last.y : null);
      } else {
        svg.querySelector('.rubber').setAttribute('visibility', 'hidden');
      }
    });
    svg.addEventListener('wheel', function (event) {
      var q = svgPoint(plot, event), p = panelAt(plot, q);
      if (p < 0) return;
      event.preventDefault();
      var a = plot.geometry[p].area, f = event.deltaY < 0 ? 0.8 : 1.25;
      zoomTo(plot, p, q.x - (q.x - a.left) * f, q.x + (a.right - q.x) * f, q.y + (a.bottom - q.y) * f, q.y - (q.y - a.top) * f);
    }, {passive: false});
    svg.addEventListener('dblclick', function () { reset(plot); });
    svg.addEventListener('mousemove', function (event) { if (!drag) showTip(plot, event); });
    svg.addEventListener('mouseleave', function () { plot.tip.hidden = true; });
  }

  function button(text, title, action) {
    var b = document.createElement('button');
    b.type = 'button';
    b.textContent = text;
    b.title = title;
    b.addEventListener('click', action);
    return b;
  }

  function setUp(script, n) {
    var svg = script.previousElementSibling;
    if (!svg || svg.tagName.toLowerCase() !== 'svg') return null;
    var plot = {id: 'plot-' + n, data: JSON.parse(script.textContent), svg: svg, mode: 'zoom'};
    var box = document.createElement('div');
    box.className = 'plot-box';
    box.id = plot.id;
    svg.parentNode.insertBefore(box, svg);
    box.appendChild(svg);
    var tools = document.createElement('div');
    tools.className = 'plot-tools';
    var zoom = button(WORDS.zoom, 'drag a rectangle to zoom', function () { setMode('zoom'); });
    var pan = button(WORDS.pan, 'drag to pan', function () { setMode('pan'); });
    function setMode(mode) {
      plot.mode = mode;
      zoom.setAttribute('aria-pressed', mode === 'zoom');
      pan.setAttribute('aria-pressed', mode === 'pan');
    }
    setMode('zoom');
    tools.appendChild(zoom);
    tools.appendChild(pan);
    tools.appendChild(button(WORDS.reset, 'the whole plot (or double-click)', function () { reset(plot); }));
    var svgButton = button(WORDS.svg, 'the plot as shown, as an SVG file', function () {
      download(svgText(plot), 'image/svg+xml', fileName(plot, 'svg'));
    });
    svgButton.className = 'download-svg';
    var csvButton = button(WORDS.csv, 'the data of every series, as CSV', function () {
      download(csv(plot), 'text/csv', fileName(plot, 'csv'));
    });
    csvButton.className = 'download-csv';
    tools.appendChild(svgButton);
    tools.appendChild(csvButton);
    box.insertBefore(tools, svg);
    plot.tip = document.createElement('div');
    plot.tip.className = 'plot-tip';
    plot.tip.hidden = true;
    box.appendChild(plot.tip);
    plot.box = box;
    reset(plot);
    attach(plot);
    return plot;
  }

  var plots = [];
  Array.prototype.forEach.call(document.querySelectorAll('script.plot-data'), function (script) {
    var plot = setUp(script, plots.length);
    if (plot) plots.push(plot);
  });

  // #zoom=N:x0:x1[:y0:y1]
  var match = /(?:^#|&)zoom=(\d+):([^:&]+):([^:&]+)(?::([^:&]+):([^:&]+))?/.exec(window.location.hash);
  if (match && plots[+match[1]]) {
    var plot = plots[+match[1]];
    plot.view.forEach(function (v) { v.x = ordered(+match[2], +match[3]); });
    if (match[5] !== undefined) plot.view[0].y = ordered(+match[4], +match[5]);
    draw(plot);
    plot.box.scrollIntoView();
  }

  window.inertestPlots = {
    plots: plots,
    csv: function (n) { return csv(plots[n]); },
    svg: function (n) { return svgText(plots[n]); },
    format: withUncertainty
  };
})();
