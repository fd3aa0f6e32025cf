#include "chapters/06_shadows/csm_math.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.h"

namespace lp::ch06 {

namespace {
void check_terms(int terms) {
  if (terms < 1 || terms > kMaxCsmTerms)
    throw Error("convolution shadow maps: between 1 and " + std::to_string(kMaxCsmTerms) + " terms (got " +
                std::to_string(terms) + ")");
}
}  // namespace

float csm_coefficient(int k) { return float(2 * k - 1) * 3.14159265358979f; }

// [csm-cpp]
float csm_step(float x, int terms) {
  check_terms(terms);
  float sum = 0.5f;
  for (int k = 1; k <= terms; ++k) sum += 2.f * std::sin(csm_coefficient(k) * x) / csm_coefficient(k);
  return sum;
}

std::vector<float> csm_basis(float z, int terms) {
  check_terms(terms);
  std::vector<float> b;
  for (int k = 1; k <= terms; ++k) b.push_back(std::sin(csm_coefficient(k) * z)), b.push_back(std::cos(csm_coefficient(k) * z));
  return b;
}

float csm_visibility(const std::vector<float>& basis, float d, int terms) {
  check_terms(terms);
  if (basis.size() < std::size_t(2 * terms)) throw Error("csm_visibility: fewer basis values than 2 x terms");
  float sum = 0.5f;
  for (int k = 1; k <= terms; ++k) {
    const float c = csm_coefficient(k);
    // sin(c (z - d)) from the filtered sin(c z) and cos(c z).
    sum += 2.f * (basis[std::size_t(2 * k - 2)] * std::cos(c * d) - basis[std::size_t(2 * k - 1)] * std::sin(c * d)) / c;
  }
  // Doubled: the series reads 1/2 on the occluder itself (x = 0), and a receiver there is lit;
  // the step moves behind the occluder to where the series reaches 1/4.
  return std::clamp(2.f * sum, 0.f, 1.f);
}
// [/csm-cpp]

double csm_l2_error_squared(int terms) {
  // The tail to a million terms, then the rest as an integral (below 1e-7).
  double sum = 0;
  const int last = 1000000;
  for (int k = terms + 1; k <= last; ++k) {
    const double c = (2.0 * k - 1.0) * 3.14159265358979323846;
    sum += 4.0 / (c * c);
  }
  return sum + 4.0 / (3.14159265358979323846 * 3.14159265358979323846 * 2.0 * (2.0 * last));
}

}  // namespace lp::ch06
