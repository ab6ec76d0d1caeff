// The complete elliptic integral of the first kind, an independent reference for the tests
// (pendulum periods, the intermediate-axis flip): K(k) = π / (2 AGM(1, √(1 − k²)))
// (Abramowitz & Stegun 17.6). The AGM converges quadratically: 40 rounds are far past
// double precision for any k < 1.
#pragma once

#include <cmath>

namespace rigidlab::test {

inline double elliptic_k(double k) {
  double a = 1.0, b = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40; ++i) {
    const double mean = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = mean;
  }
  return 3.14159265358979323846 / (2.0 * a);
}

}  // namespace rigidlab::test
