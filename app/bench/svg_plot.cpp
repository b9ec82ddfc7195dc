#include "app/bench/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>
#include <vector>

#include "app/cli/number_format.h"
#include "haptics/core/error.h"

namespace voxhap::cli {
namespace {

// layout of the drawing, px
constexpr double kMarginLeft = 90.0;
constexpr double kMarginRight = 170.0;  // room for the legend
constexpr double kMarginTop = 44.0;
constexpr double kMarginBottom = 64.0;
constexpr double kTickLength = 6.0;
constexpr double kMarkerRadius = 3.0;
constexpr double kLegendLineHeight = 18.0;
constexpr int kTargetTicks = 6;
constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                    "#9467bd", "#8c564b", "#e377c2", "#17becf"};

struct Series {
  std::string label;
  std::vector<std::pair<double, double>> points;  ///< (x, y) in axis space (log10 on log axes)
};

std::string xmlEscaped(const std::string& text) {
  std::string out;
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
      default:
        out.push_back(c);
    }
  }
  return out;
}

std::string px(double value) {
  return fixed(value, 1);
}

std::string seriesLabel(const BenchValue& value) {
  if (const auto* text = std::get_if<std::string>(&value)) return *text;
  if (const auto* count = std::get_if<std::int64_t>(&value)) return std::to_string(*count);
  if (const auto* number = std::get_if<double>(&value)) {
    std::ostringstream s;
    s << std::setprecision(6) << *number;
    return s.str();
  }
  return "-";
}

/// One axis: its range in axis space, ticks and how they read.
struct Axis {
  double lo = 0.0;
  double hi = 1.0;
  bool log = false;
  std::vector<double> ticks;  ///< axis space

  std::string label(double tick) const {
    if (log) {
      const int decade = static_cast<int>(std::lround(tick));
      if (decade >= -3 && decade <= 4) return fixed(std::pow(10.0, decade), decade < 0 ? -decade : 0);
      return "1e" + std::to_string(decade);
    }
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
    const double largest = std::max(std::fabs(lo), std::fabs(hi));
    if (largest >= 1e5 || (largest < 1e-3 && largest > 0.0)) return tick == 0.0 ? "0" : scientific(tick, 3);
    const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
    return fixed(tick, decimals);
  }
};

Axis makeAxis(double lo, double hi, bool log) {
  Axis axis;
  axis.log = log;
  if (log) {
    axis.lo = std::floor(lo);
    axis.hi = std::max(std::ceil(hi), axis.lo + 1.0);
    const double stride = std::max(1.0, std::ceil((axis.hi - axis.lo) / 8.0));
    for (double t = axis.lo; t <= axis.hi + 1e-9; t += stride) axis.ticks.push_back(t);
    return axis;
  }
  if (hi - lo <= 0.0) {
    const double pad = lo == 0.0 ? 1.0 : std::fabs(lo) * 0.1;
    lo -= pad;
    hi += pad;
  }
  const double rough = (hi - lo) / kTargetTicks;
  const double power = std::pow(10.0, std::floor(std::log10(rough)));
  double step = power;
  for (double factor : {1.0, 2.0, 5.0, 10.0}) {
    step = factor * power;
    if (step >= rough) break;
  }
  axis.lo = std::floor(lo / step) * step;
  axis.hi = std::ceil(hi / step) * step;
  const long count = std::lround((axis.hi - axis.lo) / step);
  for (long i = 0; i <= count; ++i) axis.ticks.push_back(axis.lo + static_cast<double>(i) * step);
  return axis;
}

double numberIn(const BenchTable& table, std::size_t row, const std::string& key, bool log) {
  const BenchValue& value = table.at(row, key);
  double number = 0.0;
  if (const auto* count = std::get_if<std::int64_t>(&value)) {
    number = static_cast<double>(*count);
  } else if (const auto* real = std::get_if<double>(&value)) {
    number = *real;
  } else {
    throw Error("--svg: column '" + key + "' of row " + std::to_string(row + 1) + " is not a number");
  }
  if (!std::isfinite(number)) {
    throw Error("--svg: column '" + key + "' of row " + std::to_string(row + 1) + " is not finite");
  }
  if (log && number <= 0.0) {
    throw Error("--svg: column '" + key + "' of row " + std::to_string(row + 1) + " is " + fixed(number, 3) +
                ", which a log axis cannot show");
  }
  return log ? std::log10(number) : number;
}

std::vector<Series> collectSeries(const BenchTable& table, const SvgPlotSpec& spec) {
  for (const std::string* key : {&spec.xKey, &spec.yKey, &spec.seriesKey}) {
    if (key->empty() && key == &spec.seriesKey) continue;
    if (table.columnIndex(*key) == table.columns().size()) {
      throw Error("--svg: benchmark " + table.benchmark() + " has no column '" + *key + "'");
    }
  }
  std::vector<Series> series;
  for (std::size_t r = 0; r < table.rowCount(); ++r) {
    if (std::holds_alternative<std::monostate>(table.at(r, spec.xKey)) ||
        std::holds_alternative<std::monostate>(table.at(r, spec.yKey))) {
      continue;
    }
    const std::string label = spec.seriesKey.empty() ? spec.yKey : seriesLabel(table.at(r, spec.seriesKey));
    auto it = std::find_if(series.begin(), series.end(), [&](const Series& s) { return s.label == label; });
    if (it == series.end()) it = series.insert(series.end(), Series{label, {}});
    it->points.emplace_back(numberIn(table, r, spec.xKey, spec.logX),
                            numberIn(table, r, spec.yKey, spec.logY));
  }
  if (series.empty()) throw Error("--svg: benchmark " + table.benchmark() + " has no rows to plot");
  return series;
}

}  // namespace

std::string svgPlot(const BenchTable& table, const SvgPlotSpec& spec) {
  const std::vector<Series> series = collectSeries(table, spec);
  double xLo = series[0].points[0].first, xHi = xLo;
  double yLo = series[0].points[0].second, yHi = yLo;
  for (const Series& s : series) {
    for (const auto& [x, y] : s.points) {
      xLo = std::min(xLo, x);
      xHi = std::max(xHi, x);
      yLo = std::min(yLo, y);
      yHi = std::max(yHi, y);
    }
  }
  const Axis xAxis = makeAxis(xLo, xHi, spec.logX);
  const Axis yAxis = makeAxis(yLo, yHi, spec.logY);

  const double width = std::max(spec.widthPx, 320);
  const double height = std::max(spec.heightPx, 240);
  const double left = kMarginLeft, right = width - kMarginRight;
  const double top = kMarginTop, bottom = height - kMarginBottom;
  auto toX = [&](double x) { return left + (x - xAxis.lo) / (xAxis.hi - xAxis.lo) * (right - left); };
  auto toY = [&](double y) { return bottom - (y - yAxis.lo) / (yAxis.hi - yAxis.lo) * (bottom - top); };
  const std::string xLabel = spec.xLabel.empty() ? spec.xKey : spec.xLabel;
  const std::string yLabel = spec.yLabel.empty() ? spec.yKey : spec.yLabel;
  const std::string title =
      spec.title.empty() ? table.benchmark() + ": " + yLabel + " against " + xLabel : spec.title;

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << px(width) << "\" height=\"" << px(height)
      << "\" viewBox=\"0 0 " << px(width) << ' ' << px(height)
      << "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg << "<rect x=\"0\" y=\"0\" width=\"" << px(width) << "\" height=\"" << px(height)
      << "\" fill=\"white\"/>\n";
  svg << "<text x=\"" << px((left + right) / 2) << "\" y=\"" << px(top / 2 + 6)
      << "\" text-anchor=\"middle\" font-size=\"15\">" << xmlEscaped(title) << "</text>\n";

  // grid, ticks and tick labels
  svg << "<g stroke=\"#dddddd\" stroke-width=\"1\">\n";
  for (double t : xAxis.ticks) {
    svg << "<line x1=\"" << px(toX(t)) << "\" y1=\"" << px(top) << "\" x2=\"" << px(toX(t)) << "\" y2=\""
        << px(bottom) << "\"/>\n";
  }
  for (double t : yAxis.ticks) {
    svg << "<line x1=\"" << px(left) << "\" y1=\"" << px(toY(t)) << "\" x2=\"" << px(right) << "\" y2=\""
        << px(toY(t)) << "\"/>\n";
  }
  svg << "</g>\n<g stroke=\"black\" stroke-width=\"1\">\n";
  svg << "<line x1=\"" << px(left) << "\" y1=\"" << px(bottom) << "\" x2=\"" << px(right) << "\" y2=\""
      << px(bottom) << "\"/>\n";
  svg << "<line x1=\"" << px(left) << "\" y1=\"" << px(top) << "\" x2=\"" << px(left) << "\" y2=\""
      << px(bottom) << "\"/>\n";
  for (double t : xAxis.ticks) {
    svg << "<line x1=\"" << px(toX(t)) << "\" y1=\"" << px(bottom) << "\" x2=\"" << px(toX(t)) << "\" y2=\""
        << px(bottom + kTickLength) << "\"/>\n";
  }
  for (double t : yAxis.ticks) {
    svg << "<line x1=\"" << px(left - kTickLength) << "\" y1=\"" << px(toY(t)) << "\" x2=\"" << px(left)
        << "\" y2=\"" << px(toY(t)) << "\"/>\n";
  }
  svg << "</g>\n<g fill=\"black\">\n";
  for (double t : xAxis.ticks) {
    svg << "<text x=\"" << px(toX(t)) << "\" y=\"" << px(bottom + kTickLength + 14)
        << "\" text-anchor=\"middle\">" << xmlEscaped(xAxis.label(t)) << "</text>\n";
  }
  for (double t : yAxis.ticks) {
    svg << "<text x=\"" << px(left - kTickLength - 4) << "\" y=\"" << px(toY(t) + 4)
        << "\" text-anchor=\"end\">" << xmlEscaped(yAxis.label(t)) << "</text>\n";
  }
  svg << "<text x=\"" << px((left + right) / 2) << "\" y=\"" << px(height - 14)
      << "\" text-anchor=\"middle\">" << xmlEscaped(xLabel + (spec.logX ? " (log)" : "")) << "</text>\n";
  svg << "<text x=\"18\" y=\"" << px((top + bottom) / 2)
      << "\" text-anchor=\"middle\" transform=\"rotate(-90 18 " << px((top + bottom) / 2) << ")\">"
      << xmlEscaped(yLabel + (spec.logY ? " (log)" : "")) << "</text>\n";
  svg << "</g>\n";

  // one polyline with markers per series, and its legend entry
  for (std::size_t i = 0; i < series.size(); ++i) {
    const std::string colour = kPalette[i % std::size(kPalette)];
    svg << "<g stroke=\"" << colour << "\" fill=\"" << colour
        << "\">\n<polyline fill=\"none\" stroke-width=\"1.5\" points=\"";
    for (std::size_t p = 0; p < series[i].points.size(); ++p) {
      svg << (p == 0 ? "" : " ") << px(toX(series[i].points[p].first)) << ','
          << px(toY(series[i].points[p].second));
    }
    svg << "\"/>\n";
    for (const auto& [x, y] : series[i].points) {
      svg << "<circle cx=\"" << px(toX(x)) << "\" cy=\"" << px(toY(y)) << "\" r=\"" << px(kMarkerRadius)
          << "\"/>\n";
    }
    const double legendY = top + 10 + static_cast<double>(i) * kLegendLineHeight;
    svg << "<line x1=\"" << px(right + 16) << "\" y1=\"" << px(legendY) << "\" x2=\"" << px(right + 40)
        << "\" y2=\"" << px(legendY) << "\" stroke-width=\"1.5\"/>\n";
    svg << "<text x=\"" << px(right + 46) << "\" y=\"" << px(legendY + 4)
        << "\" stroke=\"none\" fill=\"black\">" << xmlEscaped(series[i].label) << "</text>\n</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace voxhap::cli
