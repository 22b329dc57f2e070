#pragma once
// Neumaier's compensated summation: the error of a long sum stays at a few ulps of the result
// instead of growing with the number of terms. Volume checks at 1e-12 relative depend on it.

#include <cmath>

namespace sandtin {

class CompensatedSum {
  public:
    void add(double x) {
        const double t = sum_ + x;
        if (std::abs(sum_) >= std::abs(x)) {
            compensation_ += (sum_ - t) + x;
        } else {
            compensation_ += (x - t) + sum_;
        }
        sum_ = t;
    }
    double value() const { return sum_ + compensation_; }

  private:
    double sum_ = 0.0;
    double compensation_ = 0.0;
};

}  // namespace sandtin
