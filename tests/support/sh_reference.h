// Independent references for testing the shared SH library: nothing here reuses the
// library's recurrences.
#pragma once

#include "prt/vec3.h"

namespace prt::ref {

// Real SH y_lm (no Condon-Shortley phase) from the textbook definition: theta and phi by
// acos/atan2, P_l^m = (1-x^2)^(m/2) d^m/dx^m P_l(x) with P_l from its explicit power sum,
// normalisation by factorials. Double precision, slow. dir must be unit length.
double shTextbook(int l, int m, double x, double y, double z);

// Fujita & Kanai 2004, Table 3: real SH as Cartesian polynomials for l <= 4.
double shFujitaTable3(int l, int m, double x, double y, double z);

}  // namespace prt::ref
