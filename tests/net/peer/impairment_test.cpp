#include "net/peer/impairment.h"

#include <cmath>

#include <gtest/gtest.h>

#include "haptics/core/error.h"

namespace voxhap::net {
namespace {

TEST(Impairment, ACleanPathDeliversEachDatagramOnceAtOnce) {
  Impairment clean({});
  for (int i = 0; i < 1000; ++i) {
    const DatagramFate f = clean.next();
    ASSERT_EQ(f.copies, 1);
    ASSERT_EQ(f.delayS[0], 0.0);
  }
}

TEST(Impairment, DelaysStayWithinTheJitterAboutTheDelayAndSpreadOverIt) {
  Impairment path({0.1, 0.02, 0.0, 0.0, 7});
  double lowest = 1.0, highest = 0.0, sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double d = path.next().delayS[0];
    ASSERT_GE(d, 0.08);
    ASSERT_LE(d, 0.12);
    lowest = std::min(lowest, d);
    highest = std::max(highest, d);
    sum += d;
  }
  EXPECT_LT(lowest, 0.0805);
  EXPECT_GT(highest, 0.1195);
  EXPECT_NEAR(sum / n, 0.1, 0.0005);  // 5 standard errors of a uniform mean
}

TEST(Impairment, JitterWiderThanTheDelayNeverGivesANegativeDelay) {
  Impairment path({0.001, 0.01, 0.0, 0.0, 3});
  int zero = 0;
  for (int i = 0; i < 1000; ++i) {
    const double d = path.next().delayS[0];
    ASSERT_GE(d, 0.0);
    zero += d == 0.0;
  }
  EXPECT_GT(zero, 300);  // 45 % of draws fall below zero and are held at it
}

TEST(Impairment, LossAndDuplicationHappenAtTheirRates) {
  Impairment path({0.05, 0.0, 0.05, 0.1, 11});
  const int n = 100000;
  int lost = 0, twice = 0;
  for (int i = 0; i < n; ++i) {
    const DatagramFate f = path.next();
    lost += f.copies == 0;
    twice += f.copies == 2;
  }
  // within 5 standard deviations of the binomial counts
  EXPECT_NEAR(lost, 0.05 * n, 5 * std::sqrt(n * 0.05 * 0.95));
  EXPECT_NEAR(twice, 0.95 * 0.1 * n, 5 * std::sqrt(n * 0.095 * 0.905));
}

TEST(Impairment, TheSameSeedGivesTheSameFatesAndAnotherSeedOthers) {
  const ImpairmentSettings s{0.1, 0.05, 0.2, 0.2, 42};
  Impairment a(s), b(s);
  ImpairmentSettings other = s;
  other.seed = 43;
  Impairment c(other);
  int differ = 0;
  for (int i = 0; i < 1000; ++i) {
    const DatagramFate fa = a.next(), fb = b.next(), fc = c.next();
    ASSERT_EQ(fa.copies, fb.copies);
    ASSERT_EQ(fa.delayS, fb.delayS);
    differ += fa.copies != fc.copies || fa.delayS != fc.delayS;
  }
  EXPECT_GT(differ, 500);
}

TEST(Impairment, BadSettingsNameTheirField) {
  auto message = [](ImpairmentSettings s) -> std::string {
    try {
      Impairment{s};
    } catch (const Error& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_EQ(message({-0.1, 0, 0, 0, 1}).rfind("delay must", 0), 0u);
  EXPECT_EQ(message({0, std::nan(""), 0, 0, 1}).rfind("jitter must", 0), 0u);
  EXPECT_EQ(message({0, 0, 1.5, 0, 1}).rfind("loss must", 0), 0u);
  EXPECT_EQ(message({0, 0, 0, -1, 1}).rfind("duplicate must", 0), 0u);
}

}  // namespace
}  // namespace voxhap::net
