// prt-bake's human-facing output: the progress bar's time estimate and formatting
// (baker/cli/progress_bar.h) and the rate-distortion plot's axes (rate_distortion_svg.h).
// Arithmetic and text only; nothing here depends on how fast the machine is.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "baker/cli/progress_bar.h"
#include "baker/cli/rate_distortion_svg.h"

namespace prt::bake {
namespace {

TEST(ProgressEstimate, ExtrapolatesTheAverageRate) {
  // A quarter done in 10 s: three quarters left at the same rate.
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds(10.0, 250, 1000), 30.0);
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds(3.0, 999, 1000), 3.0 / 999.0);
  EXPECT_DOUBLE_EQ(estimateRemainingSeconds(7.5, 1000, 1000), 0.0);
}

TEST(ProgressEstimate, UnknownBeforeTheFirstUnit) {
  EXPECT_LT(estimateRemainingSeconds(5.0, 0, 1000), 0.0);
  EXPECT_LT(estimateRemainingSeconds(0.0, 0, 0), 0.0);
  EXPECT_EQ(formatDuration(estimateRemainingSeconds(5.0, 0, 1000)), "--:--");
}

TEST(ProgressFormat, Durations) {
  EXPECT_EQ(formatDuration(0.0), "0:00");
  EXPECT_EQ(formatDuration(59.4), "0:59");
  EXPECT_EQ(formatDuration(59.6), "1:00");
  EXPECT_EQ(formatDuration(754.0), "12:34");
  EXPECT_EQ(formatDuration(3599.4), "59:59");
  EXPECT_EQ(formatDuration(3600.0), "1:00:00");
  EXPECT_EQ(formatDuration(90061.0), "25:01:01");
  EXPECT_EQ(formatDuration(359999.0), "99:59:59");
  EXPECT_EQ(formatDuration(360000.0), ">99h");
  EXPECT_EQ(formatDuration(-1.0), "--:--");
  EXPECT_EQ(formatDuration(std::numeric_limits<double>::infinity()), "--:--");
}

TEST(ProgressFormat, LineShowsElapsedAndRemaining) {
  const std::string line = formatProgressLine({"direct", 250, 1000, 4000000}, 10.0);
  EXPECT_NE(line.find("direct    ["), std::string::npos) << line;
  EXPECT_NE(line.find(" 25.0%"), std::string::npos) << line;
  EXPECT_NE(line.find("0.40 Mrays/s"), std::string::npos) << line;
  EXPECT_NE(line.find("    0:10 elapsed"), std::string::npos) << line;
  EXPECT_NE(line.find("    0:30 left"), std::string::npos) << line;
  // 10 cells, a quarter of them filled (2, rounded down).
  EXPECT_NE(line.find("[##........]"), std::string::npos) << line;
  const std::string bounce = formatProgressLine({"bounce 1", 0, 1000, 0}, 0.2);
  EXPECT_NE(bounce.find("(no rays)"), std::string::npos) << bounce;
  EXPECT_NE(bounce.find("   --:-- left"), std::string::npos) << bounce;
  // Fits an 80-column terminal even with hour-long passes and a high ray rate, and keeps one
  // length, so a redraw over a longer line leaves nothing behind.
  const std::string longest = formatProgressLine({"glossy b8", 1, 1000000, 9000000000000ull}, 359000.0);
  EXPECT_NE(longest.find("99:43:20 elapsed      >99h left"), std::string::npos) << longest;
  EXPECT_LE(longest.size(), 79u) << longest;
  EXPECT_EQ(line.size(), longest.size()) << line << "\n" << longest;
  EXPECT_EQ(bounce.size(), longest.size()) << bounce << "\n" << longest;
}

TEST(RateDistortionAxes, SpanEveryPointAndTheThreshold) {
  RdPlot plot;
  plot.points = {{"q8", 27.2, 52.3}, {"cpca8", 4.1, 38.7}, {"f32", 108.4, std::numeric_limits<double>::infinity()}};
  const RdAxes a = rateDistortionAxes(plot);
  EXPECT_DOUBLE_EQ(a.xMin, 2.0);    // 1-2-5 step below 4.1
  EXPECT_DOUBLE_EQ(a.xMax, 200.0);  // 1-2-5 step above 108.4
  EXPECT_DOUBLE_EQ(a.yMin, 35.0);   // 38.7 - 1 dB margin, down to 5 dB
  EXPECT_DOUBLE_EQ(a.yMax, 55.0);
  EXPECT_TRUE(a.exactBand);
  // All above 40 dB: the axis still reaches the threshold.
  plot.points = {{"f16", 54.0, 80.0}};
  const RdAxes b = rateDistortionAxes(plot);
  EXPECT_LE(b.yMin, 40.0);
  EXPECT_GE(b.yMax, 81.0);
  EXPECT_FALSE(b.exactBand);
  EXPECT_LT(b.xMin, 54.0);  // one size on no 1-2-5 value still gets a range around it
  EXPECT_GT(b.xMax, 54.0);
  plot.points = {{"q16", 50.0, 60.0}};
  const RdAxes c = rateDistortionAxes(plot);
  EXPECT_DOUBLE_EQ(c.xMin, 20.0);  // on a 1-2-5 value: widened to its neighbours
  EXPECT_DOUBLE_EQ(c.xMax, 100.0);
}

TEST(RateDistortionSvg, EscapesNamesAndListsUnencodedSettings) {
  RdPlot plot;
  plot.title = "a<b>&\"c\".prta";
  plot.points = {{"q8", 27.0, 50.0}};
  plot.notEncoded = {"cpca8@0.000001: CPCA cannot reach <target>"};
  const std::string svg = rateDistortionSvg(plot);
  EXPECT_EQ(svg.find("a<b>"), std::string::npos);
  EXPECT_NE(svg.find("a&lt;b&gt;&amp;&quot;c&quot;.prta"), std::string::npos);
  EXPECT_NE(svg.find("not encoded: cpca8@0.000001: CPCA cannot reach &lt;target&gt;"), std::string::npos);
  EXPECT_NE(svg.find("data-setting=\"q8\""), std::string::npos);
}

}  // namespace
}  // namespace prt::bake
