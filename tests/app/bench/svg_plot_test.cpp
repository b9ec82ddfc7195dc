// The SVG plot of benchmark rows: well-formed, one polyline per series, axes with
// ticks and labels, log axes, and clear errors for what it cannot plot.

#include "app/bench/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "haptics/core/error.h"

namespace {

using voxhap::cli::BenchStyle;
using voxhap::cli::BenchTable;
using voxhap::cli::SvgPlotSpec;

/// Rows of error against voxel size for three methods, as `bench error` will have.
BenchTable errorLikeTable() {
  BenchTable table("error", {{"method", "method", BenchStyle::Text},
                             {"voxel_size_m", "voxel mm", BenchStyle::Millimetres, 2},
                             {"error_m", "error mm", BenchStyle::Millimetres, 3},
                             {"points", "points", BenchStyle::Count}});
  const char* methods[] = {"plain", "awareness", "coherence <&>"};
  for (int m = 0; m < 3; ++m) {
    for (double size : {0.15e-3, 0.35e-3, 1.0e-3, 2.5e-3}) {
      const std::size_t r = table.addRow();
      table.set(r, "method", std::string(methods[m]));
      table.set(r, "voxel_size_m", size);
      table.set(r, "error_m", size * (0.3 + 0.2 * m));
      table.set(r, "points", static_cast<std::int64_t>(std::lround(1.0 / (size * size))));
    }
  }
  return table;
}

int occurrences(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

/// Checks that every tag is closed in order and attribute quotes are balanced; returns
/// the first problem, or "" for well-formed markup.
std::string markupProblem(const std::string& svg) {
  std::vector<std::string> open;
  std::size_t at = 0;
  while ((at = svg.find('<', at)) != std::string::npos) {
    const std::size_t end = svg.find('>', at);
    if (end == std::string::npos) return "unterminated tag at " + std::to_string(at);
    const std::string tag = svg.substr(at + 1, end - at - 1);
    if (std::count(tag.begin(), tag.end(), '"') % 2 != 0) return "unbalanced quotes in <" + tag + ">";
    if (tag.find('<') != std::string::npos) return "'<' inside <" + tag + ">";
    const bool closing = !tag.empty() && tag[0] == '/';
    const bool selfClosing = !tag.empty() && tag.back() == '/';
    const std::string name =
        tag.substr(closing ? 1 : 0, tag.find_first_of(" /", closing ? 1 : 0) - (closing ? 1 : 0));
    if (closing) {
      if (open.empty() || open.back() != name) return "</" + name + "> closes nothing open";
      open.pop_back();
    } else if (!selfClosing) {
      open.push_back(name);
    }
    at = end + 1;
  }
  return open.empty() ? "" : "<" + open.back() + "> never closed";
}

TEST(SvgPlot, IsWellFormedWithOnePolylinePerSeries) {
  SvgPlotSpec spec;
  spec.xKey = "voxel_size_m";
  spec.yKey = "error_m";
  spec.seriesKey = "method";
  spec.xLabel = "voxel size, m";
  spec.yLabel = "error, m";
  const std::string svg = voxhap::cli::svgPlot(errorLikeTable(), spec);
  EXPECT_EQ(svg.rfind("<svg ", 0), 0u) << svg.substr(0, 80);
  EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
  EXPECT_EQ(markupProblem(svg), "");
  EXPECT_EQ(occurrences(svg, "<polyline"), 3);
  EXPECT_EQ(occurrences(svg, "<circle"), 12);  // a marker per row
  EXPECT_NE(svg.find(">voxel size, m<"), std::string::npos);
  EXPECT_NE(svg.find(">error, m<"), std::string::npos);
  EXPECT_NE(svg.find("coherence &lt;&amp;&gt;"), std::string::npos);  // text is escaped
  EXPECT_GE(occurrences(svg, "text-anchor=\"end\""), 3);              // y tick labels
}

TEST(SvgPlot, LogAxesTickAtDecades) {
  SvgPlotSpec spec;
  spec.xKey = "voxel_size_m";
  spec.yKey = "points";
  spec.logX = true;
  spec.logY = true;
  const std::string svg = voxhap::cli::svgPlot(errorLikeTable(), spec);
  EXPECT_EQ(markupProblem(svg), "");
  EXPECT_EQ(occurrences(svg, "<polyline"), 1);        // no grouping column: one series
  EXPECT_NE(svg.find(">0.001<"), std::string::npos);  // decade ticks on x
  EXPECT_NE(svg.find(">1e7<"), std::string::npos);    // and on y (1/0.15 mm² ≈ 4.4e7)
  EXPECT_NE(svg.find("(log)"), std::string::npos);
}

TEST(SvgPlot, SkipsUnmeasuredRowsAndRefusesWhatItCannotPlot) {
  BenchTable table = errorLikeTable();
  const std::size_t r = table.addRow();
  table.set(r, "method", std::string("plain"));  // x and y not measured: skipped
  SvgPlotSpec spec;
  spec.xKey = "voxel_size_m";
  spec.yKey = "error_m";
  spec.seriesKey = "method";
  EXPECT_EQ(occurrences(voxhap::cli::svgPlot(table, spec), "<circle"), 12);

  spec.yKey = "nope";
  EXPECT_THROW(voxhap::cli::svgPlot(table, spec), voxhap::Error);
  spec.yKey = "method";  // text
  EXPECT_THROW(voxhap::cli::svgPlot(table, spec), voxhap::Error);
  const std::size_t zero = table.addRow();
  table.set(zero, "voxel_size_m", 0.0);
  table.set(zero, "error_m", 1.0);
  spec.yKey = "error_m";
  spec.logX = true;
  EXPECT_THROW(voxhap::cli::svgPlot(table, spec), voxhap::Error);
  SvgPlotSpec xy;
  xy.xKey = "x";
  xy.yKey = "y";
  EXPECT_THROW(voxhap::cli::svgPlot(BenchTable("empty", {{"x", "x"}, {"y", "y"}}), xy), voxhap::Error);
}

}  // namespace
