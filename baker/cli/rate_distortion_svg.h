// The rate-distortion plot of `prt-bake compress-report --svg`: one mark per codec setting
// at (size, worst-lighting PSNR), the 40 dB line, axes with ticks and units, as a
// self-contained SVG 1.1 document (no scripts, fonts or external references) that any
// browser or image viewer shows. docs/baker.md, "compress-report --svg".
#pragma once

#include <string>
#include <vector>

namespace prt::bake {

struct RdPoint {
  std::string setting;   // the setting's name, the mark's label
  double bytesPerUnit;   // bytes per vertex (or per texel), > 0
  double psnrDb;         // worst-lighting PSNR; +infinity for an exact setting
};

struct RdPlot {
  std::string title;                    // first line above the plot (the asset and pass)
  std::string unit = "vertex";          // "vertex" or "texel": the x axis is bytes per unit
  std::vector<RdPoint> points;          // at least one
  std::vector<std::string> notEncoded;  // "setting: why" of settings without numbers, listed below
};

// Geometry of the plot, exposed so tests can check where a value lands. The x axis is
// logarithmic (settings span 3 to 110 bytes a vertex), the y axis linear in dB; exact
// settings (infinite PSNR) sit in a band above the top tick, labelled "exact".
struct RdAxes {
  double xMin, xMax;  // bytes per unit at the left and right edges of the plot area
  double yMin, yMax;  // dB at the bottom and top ticks
  bool exactBand;     // whether any point is exact
};

// The axis ranges for `plot`: x spans whole 1-2-5 steps around every point, y whole 5 dB
// (or 10 dB for wide ranges) steps around every finite PSNR and 40 dB.
RdAxes rateDistortionAxes(const RdPlot& plot);

// The whole SVG document for `plot` (UTF-8 text). Marks are <circle class="mark"> with
// data-setting, data-bytes and data-psnr attributes; axis ticks are <g class="tick x|y">
// holding a <line> and a <text> whose content is the tick's value.
std::string rateDistortionSvg(const RdPlot& plot);

}  // namespace prt::bake
