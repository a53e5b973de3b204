// volmap/core/time_budget.hpp — a soft wall-clock budget on the steady clock.
// Conventions: a budget starts when it is made and holds a limit in seconds; a limit <= 0 (or not
// finite) means "no limit". Algorithms check it between units of work (soft limit: the unit that
// is running finishes). Option structs of the library take `time_limit_seconds` doubles with
// 0 = none; option_seconds() converts a budget into that convention without ever turning an
// expired budget into "no limit" (it returns at least a millisecond's share).
#pragma once

#include <chrono>
#include <cmath>

namespace volmap {

class TimeBudget {
 public:
  using Clock = std::chrono::steady_clock;

  // No limit, starting now.
  TimeBudget() : start_(Clock::now()) {}
  // `seconds` from now; <= 0 or not finite: no limit.
  explicit TimeBudget(double seconds) : start_(Clock::now()), limit_(std::isfinite(seconds) && seconds > 0 ? seconds : 0) {}

  bool limited() const { return limit_ > 0; }
  double limit_seconds() const { return limit_; }  // 0 when unlimited
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  // The limit is reached (never for an unlimited budget).
  bool expired() const { return limited() && elapsed() >= limit_; }
  // Seconds left, at least 1 ms while limited (so that handing it on never means "no limit");
  // 0 when unlimited.
  double remaining() const {
    if (!limited()) return 0;
    const double left = limit_ - elapsed();
    return left > kMinimumSeconds ? left : kMinimumSeconds;
  }
  // The value for an option's `time_limit_seconds` (0 = none): `fraction` of remaining().
  double option_seconds(double fraction = 1.0) const { return limited() ? fraction * remaining() : 0; }
  // The first `fraction` of this budget: same start, limit × fraction (unlimited stays unlimited).
  TimeBudget first_part(double fraction) const {
    TimeBudget b = *this;
    b.limit_ = limited() && fraction > 0 ? fraction * limit_ : 0;
    if (limited() && !(b.limit_ > 0)) b.limit_ = kMinimumSeconds;
    return b;
  }

  static constexpr double kMinimumSeconds = 1e-3;

 private:
  Clock::time_point start_;
  double limit_ = 0;
};

}  // namespace volmap
