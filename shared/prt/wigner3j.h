// Wigner 3j symbols by Racah's closed form, and the complex Gaunt coefficients built from them.
// Used to build the real-SH triple-product tensor (prt/sh_triple_product.h); exposed so tests can
// pin known values.
#pragma once

namespace prt {

// Largest j accepted: Racah's sum needs (j1+j2+j3+1)!, and its alternating terms cancel more as
// j grows; up to 20 the result keeps ~1e-13 absolute accuracy (the tensor needs j <= 7).
inline constexpr int kMaxWignerJ = 20;

// (j1 j2 j3; m1 m2 m3) for integer arguments. Returns 0 where a selection rule makes the symbol
// zero (|m| > j, m1+m2+m3 != 0, triangle violated), and NaN when a j is negative or above
// kMaxWignerJ. Safe on any input.
double wigner3j(int j1, int j2, int j3, int m1, int m2, int m3);

// Complex Gaunt coefficient: the integral over the sphere of Y_l1^m1 Y_l2^m2 Y_l3^m3 (no
// conjugates), for the orthonormal complex SH *with* the Condon-Shortley phase:
// sqrt((2l1+1)(2l2+1)(2l3+1)/4pi) (l1 l2 l3; 0 0 0) (l1 l2 l3; m1 m2 m3). Same range rules.
double complexGaunt(int l1, int l2, int l3, int m1, int m2, int m3);

}  // namespace prt
