#pragma once
/// A line-and-marker plot of benchmark rows as a standalone SVG document (`voxhap
/// bench … --svg FILE`): one numeric column against another, one polyline per value
/// of a grouping column, axes with ticks and labels, each axis linear or log10.

#include <string>

#include "app/bench/bench_table.h"

namespace voxhap::cli {

struct SvgPlotSpec {
  std::string title;      ///< above the plot; empty: "<benchmark>: y against x"
  std::string xKey;       ///< numeric column along x
  std::string yKey;       ///< numeric column along y
  std::string seriesKey;  ///< one series per distinct value of this column; empty: one series
  std::string xLabel;     ///< empty: xKey
  std::string yLabel;     ///< empty: yKey
  bool logX = false;      ///< log10 x axis (every plotted x must be > 0)
  bool logY = false;      ///< log10 y axis (every plotted y must be > 0)
  int widthPx = 720;
  int heightPx = 480;
};

/// The plot of `table` as an SVG document, series in order of first appearance, points
/// of a series in row order. Rows whose x or y is not measured are skipped. Throws
/// voxhap::Error when a key is not a column, a plotted cell is not a finite number, a
/// log axis gets a value ≤ 0, or nothing is left to plot.
std::string svgPlot(const BenchTable& table, const SvgPlotSpec& spec);

}  // namespace voxhap::cli
