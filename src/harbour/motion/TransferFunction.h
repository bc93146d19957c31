#pragma once

#include <array>
#include <initializer_list>

namespace harbour::motion {

/// A continuous transfer function N(s)/D(s) of order <= kMaxOrder, coefficients in ascending powers of s.
struct ContinuousTf {
  static constexpr int kMaxOrder = 3;
  std::array<double, kMaxOrder + 1> num{};  ///< n0 + n1 s + n2 s^2 + n3 s^3
  std::array<double, kMaxOrder + 1> den{};  ///< d0 + d1 s + d2 s^2 + d3 s^3
  int order = 0;

  /// Evaluates N(jw)/D(jw): gain and phase [rad] at angular frequency w [rad/s].
  void frequency_response(double w, double& gain, double& phase) const;

  /// 2nd-order high-pass s^2 / (s^2 + 2 zeta wn s + wn^2).
  static ContinuousTf high_pass2(double wn, double zeta);
  /// 2nd-order low-pass wn^2 / (s^2 + 2 zeta wn s + wn^2).
  static ContinuousTf low_pass2(double wn, double zeta);
  /// 1st-order high-pass s / (s + wb).
  static ContinuousTf high_pass1(double wb);
  /// Product of two transfer functions (orders must add up to <= kMaxOrder).
  static ContinuousTf cascade(const ContinuousTf& a, const ContinuousTf& b);
  /// This transfer function divided by s^k (integrating k times); needs at least k zeros at s = 0.
  ContinuousTf integrated(int k) const;
};

/// The discrete filter from the bilinear (Tustin) transform s = (2/T)(z-1)/(z+1), direct form II transposed.
class TustinFilter {
 public:
  TustinFilter() = default;
  TustinFilter(const ContinuousTf& tf, double step_s);

  /// Filters one sample.
  double step(double input) {
    const double y = b_[0] * input + state_[0];
    for (int i = 0; i < order_; ++i)
      state_[i] = b_[i + 1] * input - a_[i + 1] * y + (i + 1 < order_ ? state_[i + 1] : 0.0);
    return y;
  }
  void reset() { state_.fill(0.0); }
  const std::array<double, ContinuousTf::kMaxOrder + 1>& b() const { return b_; }
  const std::array<double, ContinuousTf::kMaxOrder + 1>& a() const { return a_; }

 private:
  int order_ = 0;
  std::array<double, ContinuousTf::kMaxOrder + 1> b_{}, a_{};  // a_[0] == 1
  std::array<double, ContinuousTf::kMaxOrder> state_{};
};

}  // namespace harbour::motion
