// Deliberately naive real-SH evaluator: the baseline of the SH evaluation benchmark.
//
// Per direction: theta = acos(z), phi = atan2(y, x). Then for each (l, m) independently: the
// associated Legendre P_l^|m|(cos theta) from scratch by the three-term recurrence in l
// starting at P_m^m; the normalisation K_lm with its factorials recomputed every time;
// cos(m phi) / sin(m phi) by std::cos / std::sin. Double precision. Nothing is shared between coefficients or with the
// library's Lisle & Huang recurrence (shared/prt/sh_basis.cpp), so it is also an independent
// check of it.
//
// Conventions match shared/prt/sh_basis.h: flat index i = l(l+1)+m, z is the polar axis,
// no Condon-Shortley phase:
//   y_lm = sqrt(2) K_lm cos(m phi) P_l^m(cos theta)            m > 0
//   y_lm = sqrt(2) K_l|m| sin(|m| phi) P_l^|m|(cos theta)      m < 0
//   y_l0 = K_l0 P_l(cos theta)
//   K_lm = sqrt((2l+1)/(4 pi) (l-|m|)!/(l+|m|)!)
#pragma once

namespace prt::bench {

// One basis value y_lm at polar angle theta and azimuth phi; -l <= m <= l.
double naiveShValue(int l, int m, double theta, double phi);

// All order*order values (l = 0..order-1) of the unit direction (x, y, z) into
// out[l(l+1)+m]: theta and phi once, then naiveShValue for each (l, m).
void naiveShEval(int order, double x, double y, double z, float* out);

}  // namespace prt::bench
