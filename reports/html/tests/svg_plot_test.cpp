// The page's SVG plots: round ticks, points where the axes put them, what cannot be drawn said.
#include <gtest/gtest.h>

#include <cmath>

#include "reports/html/svg_plot.hpp"

namespace cullcheck::html {
namespace {

PlotSeries make_series(const std::string& name, std::vector<PlotPoint> points) {
  PlotSeries s;
  s.name = name;
  s.points = std::move(points);
  return s;
}

TEST(PlotAxis, LinearTicksAreRoundAndCoverTheData) {
  const Axis a({0.3, 97.0}, false);
  EXPECT_DOUBLE_EQ(a.lo(), 0.0);
  EXPECT_DOUBLE_EQ(a.hi(), 100.0);
  EXPECT_EQ(a.ticks(), (std::vector<double>{0, 20, 40, 60, 80, 100}));
  EXPECT_EQ(a.tick_label(40.0), "40");
  const Axis b({0.52, 1.97}, false);
  EXPECT_DOUBLE_EQ(b.lo(), 0.5);
  EXPECT_DOUBLE_EQ(b.hi(), 2.0);
  EXPECT_EQ(b.ticks(), (std::vector<double>{0.5, 1.0, 1.5, 2.0}));
  EXPECT_EQ(b.tick_label(b.ticks()[1]), "1.0");
  const Axis c({0.011, 0.029}, false);
  EXPECT_EQ(c.tick_label(c.ticks()[1]), "0.015") << "a step of 0.005 needs three decimals";
}

TEST(PlotAxis, LogarithmicAxesSpanWholeDecadesAndIgnoreWhatTheyCannotShow) {
  const Axis a({0.05, 300.0, 0.0, -1.0, NAN}, true);
  EXPECT_DOUBLE_EQ(a.lo(), 0.01);
  EXPECT_DOUBLE_EQ(a.hi(), 1000.0);
  EXPECT_EQ(a.ticks().size(), 6u);
  EXPECT_FALSE(a.drawable(0.0));
  EXPECT_FALSE(a.drawable(-1.0));
  EXPECT_TRUE(a.drawable(0.05));
  EXPECT_DOUBLE_EQ(a.pixel(1.0, 0.0, 500.0), 200.0);  // two of five decades along
  EXPECT_EQ(a.tick_label(0.01), "0.01");
  EXPECT_EQ(a.tick_label(1e5), "1e5");
}

TEST(PlotAxis, OneValueOrNoneStillGivesAnAxis) {
  const Axis one({5.0}, false);
  EXPECT_LT(one.lo(), 5.0);
  EXPECT_GT(one.hi(), 5.0);
  const Axis none({}, false);
  EXPECT_DOUBLE_EQ(none.lo(), 0.0);
  EXPECT_DOUBLE_EQ(none.hi(), 1.0);
  const Axis zero({0.2, 0.9}, false, /*include_zero=*/true);
  EXPECT_DOUBLE_EQ(zero.lo(), 0.0);
}

TEST(SvgPlot, DrawsEachPointWhereTheAxesPutIt) {
  Plot p;
  p.id = "plot-test";
  p.title = "t";
  p.series.push_back(make_series("a <b>", {{0.0, 0.0}, {100.0, 100.0}}));
  const std::string svg = svg_plot(p);
  // Plot area: x from 70 to width - legend (860 - 290 = 570), y from 380 - 52 = 328 up to 34.
  EXPECT_NE(svg.find("<circle cx=\"70.00\" cy=\"328.00\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("<circle cx=\"570.00\" cy=\"34.00\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("points=\"70.00,328.00 570.00,34.00\""), std::string::npos);
  EXPECT_NE(svg.find("id=\"plot-test\""), std::string::npos);
  EXPECT_NE(svg.find("data-points=\"2\""), std::string::npos);
  EXPECT_NE(svg.find("a &lt;b&gt;"), std::string::npos) << "series names are escaped";
  EXPECT_EQ(svg.find("a <b>"), std::string::npos);
}

TEST(SvgPlot, SaysWhenThereIsNothingToDrawAndCountsHiddenPoints) {
  Plot empty;
  empty.id = "e";
  EXPECT_NE(svg_plot(empty).find("no data in this report"), std::string::npos);
  Plot log;
  log.id = "l";
  log.log_y = true;
  log.series.push_back(make_series("s", {{1.0, 0.0}, {2.0, 10.0}, {3.0, -4.0}}));
  const std::string svg = svg_plot(log);
  EXPECT_NE(svg.find("data-points=\"1\""), std::string::npos);
  EXPECT_NE(svg.find("2 points not drawn"), std::string::npos);
}

TEST(SvgPlot, SeriesColoursComeFromAFixedPalette) {
  EXPECT_EQ(series_colour(0), "#0072b2");
  EXPECT_EQ(series_colour(1), "#d55e00");
  EXPECT_EQ(series_colour(16), series_colour(0));
}

}  // namespace
}  // namespace cullcheck::html
