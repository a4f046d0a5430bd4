#include "plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

namespace mechsim::plot {
namespace {

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::uint32_t big_endian_u32(const std::string& bytes, std::size_t offset) {
  std::uint32_t v = 0;
  for (std::size_t i = 0; i < 4; ++i) v = (v << 8) | static_cast<unsigned char>(bytes[offset + i]);
  return v;
}

Figure two_panel_figure() {
  Series sine{"sin(t) with 'quotes' and x_1^2", {}, {}, "lines"};
  Series cosine{"cos(t)", {}, {}, "dashed"};
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.1 * i;
    sine.x.push_back(t);
    sine.y.push_back(std::sin(t));
    cosine.x.push_back(t);
    cosine.y.push_back(std::cos(t));
  }
  Series decay{"exp(-t)", {}, {}, "linespoints"};
  for (int i = 0; i <= 20; ++i) {
    decay.x.push_back(0.5 * i);
    decay.y.push_back(std::exp(-0.5 * i));
  }
  Panel top{.title = "Signals: it's a \"test\"",
            .xlabel = "t [s]",
            .ylabel = "value [-]",
            .series = {sine, cosine}};
  top.yrange = std::make_pair(-1.5, 1.5);
  top.hlines = {{1.0, "upper limit"}, {-1.0, "lower limit"}};
  Panel bottom{.title = "Decay", .xlabel = "t [s]", .ylabel = "y", .series = {decay}};
  bottom.logy = true;
  return Figure{
      .title = "Two panels", .panels = {top, bottom}, .width_px = 800, .height_px_per_panel = 300};
}

TEST(Plot, TwoPanelFigureIsAPngOfTheRequestedSize) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string path = ::testing::TempDir() + "/plot_test_two_panels.png";
  std::remove(path.c_str());
  std::string why;
  ASSERT_TRUE(write_png(two_panel_figure(), path, &why)) << why;
  const std::string png = read_bytes(path);
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR (the first chunk) holds width and height: 800 wide, two 300 px panels plus the
  // 30 px title band.
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(big_endian_u32(png, 16), 800u);
  EXPECT_EQ(big_endian_u32(png, 20), 630u);
  std::remove(path.c_str());
}

TEST(Plot, PanelWithoutDataStillPlots) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  const std::string path = ::testing::TempDir() + "/plot_test_empty.png";
  Figure figure;
  figure.panels.push_back(Panel{.title = "empty", .series = {Series{"nothing", {}, {}, "lines"}}});
  std::string why;
  EXPECT_TRUE(write_png(figure, path, &why)) << why;
  EXPECT_EQ(read_bytes(path).substr(0, 4), "\x89PNG");
  std::remove(path.c_str());
}

TEST(Plot, MalformedFiguresAreRefusedWithAReason) {
  const std::string path = ::testing::TempDir() + "/plot_test_malformed.png";
  std::string why;
  EXPECT_FALSE(write_png(Figure{}, path, &why));
  EXPECT_EQ(why, "the figure has no panels");

  Figure mismatched;
  mismatched.panels.push_back(Panel{.series = {Series{"s", {0, 1, 2}, {0, 1}, "lines"}}});
  EXPECT_FALSE(write_png(mismatched, path, &why));
  EXPECT_EQ(why, "series 's' has 3 x values but 2 y values");

  Figure bad_style;
  bad_style.panels.push_back(Panel{.series = {Series{"s", {0}, {0}, "dotted"}}});
  EXPECT_FALSE(write_png(bad_style, path, &why));
  EXPECT_NE(why.find("unknown style 'dotted'"), std::string::npos) << why;
  EXPECT_FALSE(std::ifstream(path).good());  // nothing written
}

TEST(Plot, UnwritableDestinationIsReportedNotThrown) {
  if (!gnuplot_available()) GTEST_SKIP() << "gnuplot is not installed";
  std::string why;
  EXPECT_FALSE(write_png(two_panel_figure(), "/nonexistent-mechsim-dir/figure.png", &why));
  EXPECT_NE(why.find("cannot write /nonexistent-mechsim-dir/figure.png"), std::string::npos) << why;
}

}  // namespace
}  // namespace mechsim::plot
