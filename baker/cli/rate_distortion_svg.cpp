#include "baker/cli/rate_distortion_svg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace prt::bake {
namespace {

// Page and plot-area geometry, in SVG user units (pixels at 100%).
constexpr double kWidth = 760, kPlotLeft = 80, kPlotRight = 720, kPlotTop = 70, kPlotBottom = 420;
constexpr double kExactBand = 40;    // height above the top tick where exact settings sit
constexpr double kLineHeight = 16;   // of the notes under the plot
constexpr double kCharWidth = 6.6;   // average glyph advance of the 11 px labels, for overlap tests
constexpr double kThresholdDb = 40;  // the line people choose settings by (docs/transfer-codec.md)

std::string escapeXml(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default:
        // Control characters other than tab are not allowed in XML 1.0 at all.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t') out += '?';
        else out += c;
    }
  }
  return out;
}

std::string num(double v, const char* format = "%.2f") {
  char s[48];
  std::snprintf(s, sizeof s, format, v);
  return s;
}

// The largest 1-2-5 value <= v (down) or the smallest >= v (up), for v > 0.
double step125(double v, bool up) {
  const double decade = std::pow(10.0, std::floor(std::log10(v)));
  const double steps[] = {1, 2, 5, 10};
  if (up) {
    for (double m : steps) {
      if (m * decade >= v * (1 - 1e-9)) return m * decade;
    }
    return 10 * decade;
  }
  for (int i = 3; i >= 0; --i) {
    if (steps[i] * decade <= v * (1 + 1e-9)) return steps[i] * decade;
  }
  return decade;
}

struct Frame {
  RdAxes axes;
  double finiteTop;  // y of the top tick: below the exact band when there is one
  double x(double bytes) const {
    return kPlotLeft + (std::log10(bytes) - std::log10(axes.xMin)) / (std::log10(axes.xMax) - std::log10(axes.xMin)) *
                           (kPlotRight - kPlotLeft);
  }
  double y(double db) const {
    if (!std::isfinite(db)) return kPlotTop + kExactBand / 2;
    return finiteTop + (axes.yMax - db) / (axes.yMax - axes.yMin) * (kPlotBottom - finiteTop);
  }
};

struct Box {
  double x0, y0, x1, y1;
  bool overlaps(const Box& b) const { return x0 < b.x1 && b.x0 < x1 && y0 < b.y1 && b.y0 < y1; }
};

}  // namespace

RdAxes rateDistortionAxes(const RdPlot& plot) {
  RdAxes a{};
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  double dbLo = kThresholdDb, dbHi = kThresholdDb;
  for (const RdPoint& p : plot.points) {
    lo = std::min(lo, p.bytesPerUnit);
    hi = std::max(hi, p.bytesPerUnit);
    if (std::isfinite(p.psnrDb)) {
      dbLo = std::min(dbLo, p.psnrDb);
      dbHi = std::max(dbHi, p.psnrDb);
    } else {
      a.exactBand = true;
    }
  }
  a.xMin = step125(lo, false);
  a.xMax = step125(hi, true);
  if (a.xMax <= a.xMin) {  // one size only, on a 1-2-5 value: widen to the neighbouring steps
    a.xMin = step125(a.xMin * 0.99, false);
    a.xMax = step125(a.xMax * 1.01, true);
  }
  // A margin of 1 dB keeps marks off the frame; wide ranges get 10 dB ticks.
  const double step = dbHi - dbLo > 60 ? 10 : 5;
  a.yMin = std::floor((dbLo - 1) / step) * step;
  a.yMax = std::ceil((dbHi + 1) / step) * step;
  return a;
}

std::string rateDistortionSvg(const RdPlot& plot) {
  Frame f{rateDistortionAxes(plot), 0};
  f.finiteTop = kPlotTop + (f.axes.exactBand ? kExactBand : 0);
  const double height = kPlotBottom + 70 + kLineHeight * static_cast<double>(plot.notEncoded.size());
  const std::string unit = escapeXml(plot.unit);
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" +
                  num(kWidth, "%.0f") + "\" height=\"" + num(height, "%.0f") + "\" viewBox=\"0 0 " + num(kWidth, "%.0f") + " " +
                  num(height, "%.0f") + "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  s += "<title>Rate-distortion: " + escapeXml(plot.title) + "</title>\n";
  s += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  s += "<text x=\"" + num(kPlotLeft) + "\" y=\"24\" font-size=\"14\" font-weight=\"bold\">" + escapeXml(plot.title) + "</text>\n";
  s += "<text x=\"" + num(kPlotLeft) + "\" y=\"44\" fill=\"#444\">worst-lighting PSNR against size, one mark per codec setting; "
       "the line joins the settings no other setting beats on both</text>\n";
  s += "<rect class=\"plot-area\" x=\"" + num(kPlotLeft) + "\" y=\"" + num(kPlotTop) + "\" width=\"" + num(kPlotRight - kPlotLeft) +
       "\" height=\"" + num(kPlotBottom - kPlotTop) + "\" fill=\"none\" stroke=\"#888\"/>\n";

  // X ticks at every 1-2-5 value in range (log scale), with grid lines.
  for (double decade = std::pow(10.0, std::floor(std::log10(f.axes.xMin))); decade <= f.axes.xMax * 1.0001; decade *= 10) {
    for (double m : {1.0, 2.0, 5.0}) {
      const double v = m * decade;
      if (v < f.axes.xMin * 0.9999 || v > f.axes.xMax * 1.0001) continue;
      const std::string x = num(f.x(v));
      s += "<g class=\"tick x\"><line x1=\"" + x + "\" y1=\"" + num(kPlotTop) + "\" x2=\"" + x + "\" y2=\"" + num(kPlotBottom + 5) +
           "\" stroke=\"#ddd\"/><text x=\"" + x + "\" y=\"" + num(kPlotBottom + 18) + "\" text-anchor=\"middle\">" +
           num(v, "%g") + "</text></g>\n";
    }
  }
  // Y ticks every 5 or 10 dB.
  const double yStep = f.axes.yMax - f.axes.yMin > 60 ? 10 : 5;
  for (double db = f.axes.yMin; db <= f.axes.yMax + 1e-9; db += yStep) {
    const std::string y = num(f.y(db));
    s += "<g class=\"tick y\"><line x1=\"" + num(kPlotLeft - 5) + "\" y1=\"" + y + "\" x2=\"" + num(kPlotRight) + "\" y2=\"" + y +
         "\" stroke=\"#ddd\"/><text x=\"" + num(kPlotLeft - 8) + "\" y=\"" + num(f.y(db) + 4) + "\" text-anchor=\"end\">" +
         num(db, "%g") + "</text></g>\n";
  }
  if (f.axes.exactBand) {
    s += "<line x1=\"" + num(kPlotLeft) + "\" y1=\"" + num(f.finiteTop - kExactBand / 4) + "\" x2=\"" + num(kPlotRight) + "\" y2=\"" +
         num(f.finiteTop - kExactBand / 4) + "\" stroke=\"#888\" stroke-dasharray=\"2 3\"/>\n";
    s += "<text class=\"exact-label\" x=\"" + num(kPlotLeft - 8) + "\" y=\"" + num(f.y(std::numeric_limits<double>::infinity()) + 4) +
         "\" text-anchor=\"end\">exact</text>\n";
  }
  // Axis titles, with units.
  s += "<text x=\"" + num((kPlotLeft + kPlotRight) / 2) + "\" y=\"" + num(kPlotBottom + 40) +
       "\" text-anchor=\"middle\" font-size=\"12\">size (bytes per " + unit + ", raw, log scale)</text>\n";
  s += "<text x=\"18\" y=\"" + num((kPlotTop + kPlotBottom) / 2) + "\" text-anchor=\"middle\" font-size=\"12\" transform=\"rotate(-90 18 " +
       num((kPlotTop + kPlotBottom) / 2) + ")\">worst-lighting PSNR (dB)</text>\n";

  // The 40 dB line.
  const std::string y40 = num(f.y(kThresholdDb));
  s += "<line class=\"threshold\" x1=\"" + num(kPlotLeft) + "\" y1=\"" + y40 + "\" x2=\"" + num(kPlotRight) + "\" y2=\"" + y40 +
       "\" stroke=\"#c33\" stroke-dasharray=\"6 4\"/>\n<text x=\"" + num(kPlotRight - 4) + "\" y=\"" + num(f.y(kThresholdDb) - 4) +
       "\" text-anchor=\"end\" fill=\"#c33\">40 dB</text>\n";

  // The frontier: by size, each setting that beats every smaller one's PSNR.
  std::vector<const RdPoint*> sorted;
  for (const RdPoint& p : plot.points) sorted.push_back(&p);
  std::stable_sort(sorted.begin(), sorted.end(), [](const RdPoint* a, const RdPoint* b) { return a->bytesPerUnit < b->bytesPerUnit; });
  std::string frontier;
  double best = -std::numeric_limits<double>::infinity();
  for (const RdPoint* p : sorted) {
    if (!(p->psnrDb > best)) continue;
    best = p->psnrDb;
    if (!frontier.empty()) frontier += ' ';
    frontier += num(f.x(p->bytesPerUnit));
    frontier += ',';
    frontier += num(f.y(p->psnrDb));
  }
  s += "<polyline class=\"frontier\" points=\"" + frontier + "\" fill=\"none\" stroke=\"#36c\" stroke-width=\"1.5\"/>\n";

  // Marks, then labels placed where they overlap neither another label nor the frame.
  std::vector<Box> placed;
  for (const RdPoint& p : plot.points) {
    const double cx = f.x(p.bytesPerUnit), cy = f.y(p.psnrDb);
    placed.push_back({cx - 4, cy - 4, cx + 4, cy + 4});
  }
  for (const RdPoint& p : plot.points) {
    const double cx = f.x(p.bytesPerUnit), cy = f.y(p.psnrDb);
    const std::string psnr = std::isfinite(p.psnrDb) ? num(p.psnrDb, "%.6g") : "inf";
    s += "<circle class=\"mark\" data-setting=\"" + escapeXml(p.setting) + "\" data-bytes=\"" + num(p.bytesPerUnit, "%.6g") +
         "\" data-psnr=\"" + psnr + "\" cx=\"" + num(cx) + "\" cy=\"" + num(cy) + "\" r=\"4\" fill=\"#36c\"><title>" +
         escapeXml(p.setting) + ": " + num(p.bytesPerUnit) + " B/" + unit + ", " +
         (std::isfinite(p.psnrDb) ? num(p.psnrDb) + " dB" : std::string("exact")) + "</title></circle>\n";
  }
  for (const RdPoint& p : plot.points) {
    const double cx = f.x(p.bytesPerUnit), cy = f.y(p.psnrDb);
    const double w = kCharWidth * static_cast<double>(p.setting.size());
    struct Spot {
      double dx, dy;
      bool right;
    };
    const Spot spots[] = {{7, 4, true}, {7, -8, true}, {7, 16, true}, {-7, 4, false}, {-7, -8, false}, {-7, 16, false}};
    Spot chosen = spots[0];
    for (const Spot& sp : spots) {
      const double x0 = sp.right ? cx + sp.dx : cx + sp.dx - w;
      const Box b{x0, cy + sp.dy - 10, x0 + w, cy + sp.dy + 2};
      const bool inside = b.x0 >= kPlotLeft && b.x1 <= kPlotRight && b.y0 >= kPlotTop && b.y1 <= kPlotBottom;
      if (inside && std::none_of(placed.begin(), placed.end(), [&](const Box& o) { return o.overlaps(b); })) {
        chosen = sp;
        break;
      }
    }
    const double x0 = chosen.right ? cx + chosen.dx : cx + chosen.dx - w;
    placed.push_back({x0, cy + chosen.dy - 10, x0 + w, cy + chosen.dy + 2});
    s += "<text class=\"mark-label\" x=\"" + num(cx + chosen.dx) + "\" y=\"" + num(cy + chosen.dy) + "\" text-anchor=\"" +
         (chosen.right ? "start" : "end") + "\">" + escapeXml(p.setting) + "</text>\n";
  }
  double y = kPlotBottom + 62;
  for (const std::string& note : plot.notEncoded) {
    s += "<text class=\"note\" x=\"" + num(kPlotLeft) + "\" y=\"" + num(y) + "\" fill=\"#a00\">not encoded: " + escapeXml(note) + "</text>\n";
    y += kLineHeight;
  }
  return s + "</svg>\n";
}

}  // namespace prt::bake
