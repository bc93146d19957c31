#include "harbour/motion/TransferFunction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "harbour/motion/Washout.h"

namespace harbour::motion {
namespace {

constexpr double kT = 0.01;  // 100 Hz, the platform rate

// independent reference: the continuous system in controllable canonical form, integrated by RK4 at T/100
std::vector<double> continuous_response(const ContinuousTf& tf, double (*input)(double), double duration_s) {
  const int n = tf.order;
  const double dn = tf.den[n];
  double a[4], b[4];
  for (int i = 0; i <= n; ++i) {
    a[i] = tf.den[i] / dn;
    b[i] = tf.num[i] / dn;
  }
  // y = sum (b_i - b_n a_i) x_i + b_n u, with x_{i}' = x_{i+1}, x_{n-1}' = u - sum a_i x_i
  std::vector<double> x(n, 0.0), out;
  auto derivative = [&](const std::vector<double>& s, double u) {
    std::vector<double> d(n);
    for (int i = 0; i + 1 < n; ++i)
      d[i] = s[i + 1];
    double last = u;
    for (int i = 0; i < n; ++i)
      last -= a[i] * s[i];
    d[n - 1] = last;
    return d;
  };
  auto output = [&](const std::vector<double>& s, double u) {
    double y = b[n] * u;
    for (int i = 0; i < n; ++i)
      y += (b[i] - b[n] * a[i]) * s[i];
    return y;
  };
  const int sub = 100;
  const double h = kT / sub;
  for (int k = 0; k * kT <= duration_s; ++k) {
    out.push_back(output(x, input(k * kT)));
    for (int m = 0; m < sub; ++m) {
      const double t = k * kT + m * h;
      auto add = [&](const std::vector<double>& s, const std::vector<double>& d, double f) {
        std::vector<double> r(n);
        for (int i = 0; i < n; ++i)
          r[i] = s[i] + f * d[i];
        return r;
      };
      const auto k1 = derivative(x, input(t));
      const auto k2 = derivative(add(x, k1, h / 2), input(t + h / 2));
      const auto k3 = derivative(add(x, k2, h / 2), input(t + h / 2));
      const auto k4 = derivative(add(x, k3, h), input(t + h));
      for (int i = 0; i < n; ++i)
        x[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
  }
  return out;
}

double unit_step(double t) {
  return t >= 0.0 ? 1.0 : 0.0;
}

// worst difference between the Tustin filter and the continuous reference for a unit step, relative to the
// response's peak; Tustin's step response sits half a sample late, so compare with the mean of neighbours
double step_mismatch(const ContinuousTf& tf, double duration_s) {
  const std::vector<double> reference = continuous_response(tf, &unit_step, duration_s);
  TustinFilter filter(tf, kT);
  double worst = 0.0, peak = 1e-12;
  for (std::size_t k = 0; k + 1 < reference.size(); ++k) {
    const double y = filter.step(1.0);
    const double half_late = 0.5 * (reference[k] + reference[k + 1]);
    if (k > 0) worst = std::max(worst, std::abs(y - half_late));
    peak = std::max(peak, std::abs(reference[k]));
  }
  return worst / peak;
}

TEST(TransferFunction, SecondOrderHighPassStepMatchesItsAnalyticResponse) {
  // s^2/(s^2 + 2 zeta wn s + wn^2): y(t) = e^(-zeta wn t) (cos wd t - zeta/sqrt(1-zeta^2) sin wd t)
  const double wn = 1.25, zeta = 0.707, wd = wn * std::sqrt(1 - zeta * zeta);
  TustinFilter f(ContinuousTf::high_pass2(wn, zeta), kT);
  double worst = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const double y = f.step(1.0);
    const double t = (k + 0.5) * kT;  // Tustin's step response sits half a sample late
    const double exact =
        std::exp(-zeta * wn * t) * (std::cos(wd * t) - zeta / std::sqrt(1 - zeta * zeta) * std::sin(wd * t));
    if (k > 0) worst = std::max(worst, std::abs(y - exact));
  }
  EXPECT_LT(worst, 2e-3);
}

TEST(TransferFunction, LowPassAndFirstOrderHighPassStepsMatchAnalyticResponses) {
  TustinFilter lp(ContinuousTf::low_pass2(1.25, 1.0), kT), hp(ContinuousTf::high_pass1(0.125), kT);
  double worst_lp = 0.0, worst_hp = 0.0;
  for (int k = 0; k < 3000; ++k) {
    const double t = (k + 0.5) * kT;
    const double ylp = lp.step(1.0), yhp = hp.step(1.0);
    worst_lp =
        std::max(worst_lp, std::abs(ylp - (1 - (1 + 1.25 * t) * std::exp(-1.25 * t))));  // critically damped
    worst_hp = std::max(worst_hp, std::abs(yhp - std::exp(-0.125 * t)));
  }
  EXPECT_LT(worst_lp, 2e-3);
  EXPECT_LT(worst_hp, 2e-3);
}

TEST(TransferFunction, WashoutChannelsStepMatchTheContinuousSystem) {
  const WashoutSettings w;
  EXPECT_LT(step_mismatch(ClassicalWashout::translation_to_displacement(w.surge_sway), 40.0), 0.01);
  EXPECT_LT(step_mismatch(ClassicalWashout::rotation_to_angle(w.rotation), 5.0), 0.03);
  EXPECT_LT(step_mismatch(ClassicalWashout::tilt_low_pass(w.tilt), 10.0), 0.01);
}

TEST(TransferFunction, SineSteadyStateMatchesGainAndPhase) {
  const WashoutSettings w;
  const ContinuousTf tfs[] = {ClassicalWashout::translation_to_displacement(w.surge_sway),
                              ClassicalWashout::rotation_to_angle(w.rotation),
                              ContinuousTf::high_pass2(1.25, 0.707), ContinuousTf::low_pass2(1.25, 0.707)};
  for (const ContinuousTf& tf : tfs)
    for (const double omega : {0.3, 1.0, 3.0, 10.0}) {
      TustinFilter f(tf, kT);
      // run 60 periods, then fit the last 10 periods to a sin + b cos
      const int settle = static_cast<int>(50 * 2 * std::numbers::pi / omega / kT);
      const int fit = static_cast<int>(10 * 2 * std::numbers::pi / omega / kT);
      double ss = 0, sc = 0, cc = 0, ys = 0, yc = 0;
      for (int k = 0; k < settle + fit; ++k) {
        const double t = k * kT, y = f.step(std::sin(omega * t));
        if (k < settle) continue;
        const double s = std::sin(omega * t), c = std::cos(omega * t);
        ss += s * s, sc += s * c, cc += c * c, ys += y * s, yc += y * c;
      }
      const double det = ss * cc - sc * sc;
      const double a = (ys * cc - yc * sc) / det, b = (yc * ss - ys * sc) / det;
      double gain = 0, phase = 0;
      tf.frequency_response(omega, gain, phase);
      EXPECT_NEAR(std::hypot(a, b), gain, 0.01 * gain) << "omega " << omega;
      EXPECT_NEAR(std::remainder(std::atan2(b, a) - phase, 2 * std::numbers::pi), 0.0, 0.01)
          << "omega " << omega;
    }
}

}  // namespace
}  // namespace harbour::motion
