// TimeBudget: unlimited budgets never expire and hand on 0 ("no limit"); limited ones expire after
// their limit, and what they hand on never drops below a millisecond's share (an expired budget must
// not turn into "no limit"); first_part keeps the start and scales the limit.
#include <doctest/doctest.h>

#include <volmap/core/time_budget.hpp>

#include <chrono>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <thread>

using volmap::TimeBudget;

TEST_CASE("TimeBudget: unlimited budgets") {
  for (double s : {0.0, -1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()}) {
    const TimeBudget b(s);
    CHECK_FALSE(b.limited());
    CHECK_FALSE(b.expired());
    CHECK(b.limit_seconds() == 0);
    CHECK(b.remaining() == 0);
    CHECK(b.option_seconds(0.5) == 0);
    CHECK_FALSE(b.first_part(0.5).limited());
  }
  CHECK_FALSE(TimeBudget().limited());
}

TEST_CASE("TimeBudget: a limited budget expires and hands on shares of what is left") {
  const TimeBudget b(10.0);  // far from expiring during this test
  CHECK(b.limited());
  CHECK_FALSE(b.expired());
  CHECK(b.remaining() <= 10.0);
  CHECK(b.remaining() > 9.0);
  CHECK(b.option_seconds(0.5) <= 5.0);
  const TimeBudget part = b.first_part(0.002);  // same start, 20 ms
  CHECK(part.limit_seconds() == doctest::Approx(0.02));
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  CHECK(part.expired());
  CHECK_FALSE(b.expired());
  CHECK(part.elapsed() >= 0.02);
  CHECK(part.remaining() == TimeBudget::kMinimumSeconds);  // never 0 (= no limit) once expired
  CHECK(part.option_seconds(0.25) == 0.25 * TimeBudget::kMinimumSeconds);
  CHECK(b.first_part(0).limited());  // a zero share of a limited budget is not "no limit"
}
