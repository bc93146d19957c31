#include "harbour/motion/TransferFunction.h"

#include <cmath>
#include <complex>

#include "harbour/core/Assert.h"

namespace harbour::motion {
namespace {

using Poly = std::array<double, ContinuousTf::kMaxOrder + 1>;

// product of two polynomials in ascending powers (result truncated to the array size)
Poly multiply(const Poly& a, int na, const Poly& b, int nb) {
  Poly r{};
  for (int i = 0; i <= na; ++i)
    for (int j = 0; j <= nb && i + j <= ContinuousTf::kMaxOrder; ++j)
      r[i + j] += a[i] * b[j];
  return r;
}

// (z - 1)^k (z + 1)^(n - k) in ascending powers of z
Poly tustin_term(int k, int n) {
  Poly r{};
  r[0] = 1.0;
  int degree = 0;
  for (int m = 0; m < n; ++m) {
    const Poly factor = m < k ? Poly{-1.0, 1.0} : Poly{1.0, 1.0};
    r = multiply(r, degree, factor, 1);
    ++degree;
  }
  return r;
}

}  // namespace

void ContinuousTf::frequency_response(double w, double& gain, double& phase) const {
  std::complex<double> n = 0, d = 0, s_power = 1, s{0.0, w};
  for (int k = 0; k <= order; ++k, s_power *= s) {
    n += num[k] * s_power;
    d += den[k] * s_power;
  }
  const std::complex<double> h = n / d;
  gain = std::abs(h);
  phase = std::arg(h);
}

ContinuousTf ContinuousTf::high_pass2(double wn, double zeta) {
  return {{0, 0, 1, 0}, {wn * wn, 2 * zeta * wn, 1, 0}, 2};
}
ContinuousTf ContinuousTf::low_pass2(double wn, double zeta) {
  return {{wn * wn, 0, 0, 0}, {wn * wn, 2 * zeta * wn, 1, 0}, 2};
}
ContinuousTf ContinuousTf::high_pass1(double wb) {
  return {{0, 1, 0, 0}, {wb, 1, 0, 0}, 1};
}

ContinuousTf ContinuousTf::cascade(const ContinuousTf& a, const ContinuousTf& b) {
  HARBOUR_ASSERT(a.order + b.order <= kMaxOrder, "cascade exceeds the maximum order");
  return {multiply(a.num, a.order, b.num, b.order), multiply(a.den, a.order, b.den, b.order),
          a.order + b.order};
}

ContinuousTf ContinuousTf::integrated(int k) const {
  ContinuousTf r = *this;
  for (int i = 0; i < k; ++i)
    HARBOUR_ASSERT(r.num[i] == 0.0, "integration needs zeros at s = 0");
  for (int i = 0; i <= kMaxOrder; ++i)
    r.num[i] = i + k <= kMaxOrder ? num[i + k] : 0.0;
  return r;
}

TustinFilter::TustinFilter(const ContinuousTf& tf, double step_s) : order_(tf.order) {
  // substitute s = c (z-1)/(z+1), multiply by (z+1)^n: sum_k x_k c^k (z-1)^k (z+1)^(n-k)
  const int n = tf.order;
  const double c = 2.0 / step_s;
  Poly bz{}, az{};
  double ck = 1.0;
  for (int k = 0; k <= n; ++k, ck *= c) {
    const Poly term = tustin_term(k, n);
    for (int i = 0; i <= n; ++i) {
      bz[i] += tf.num[k] * ck * term[i];
      az[i] += tf.den[k] * ck * term[i];
    }
  }
  // ascending powers of z -> coefficients of z^-i: index i of the filter is power n - i
  const double a0 = az[n];
  HARBOUR_ASSERT(a0 != 0.0, "degenerate transfer function");
  for (int i = 0; i <= n; ++i) {
    b_[i] = bz[n - i] / a0;
    a_[i] = az[n - i] / a0;
  }
}

}  // namespace harbour::motion
