#include "net/peer/one_way_delay.h"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

namespace voxhap::net {
namespace {

TEST(OneWayDelay, NothingIsReportedBeforeTheFirstRoundTrip) {
  OneWayDelay d;
  EXPECT_LT(d.oneWayMs(), 0.0);
  d.addRoundTrip(-1.0);
  d.addRoundTrip(std::numeric_limits<double>::quiet_NaN());
  d.addRoundTrip(std::numeric_limits<double>::infinity());
  EXPECT_LT(d.oneWayMs(), 0.0);
  d.addRoundTrip(40.0);
  EXPECT_EQ(d.oneWayMs(), 20.0);
  EXPECT_EQ(d.roundTripMs(), 40.0);
}

TEST(OneWayDelay, JitterWithinTheBandLeavesTheReportedDelayAlone) {
  OneWayDelay d;
  d.addRoundTrip(200.0);  // 100 ms one way: the band is ±10 ms
  for (int i = 0; i < 200; ++i) d.addRoundTrip(i % 2 == 0 ? 180.0 : 225.0);
  EXPECT_EQ(d.oneWayMs(), 100.0);
  EXPECT_NE(d.roundTripMs(), 200.0);  // the filter moved
}

TEST(OneWayDelay, ARiseBeyondTheBandIsFollowedToWithinTheBand) {
  OneWayDelay d;
  d.addRoundTrip(20.0);  // 10 ms one way: the band is ±2 ms
  int changes = 0;
  double last = d.oneWayMs();
  for (int i = 0; i < 200; ++i) {
    d.addRoundTrip(600.0);
    if (d.oneWayMs() != last) ++changes;
    last = d.oneWayMs();
  }
  EXPECT_NEAR(d.oneWayMs(), 300.0, 0.1 * 300.0);
  // in steps of at least the band, not at every echo
  EXPECT_GT(changes, 3);
  EXPECT_LT(changes, 60);
}

}  // namespace
}  // namespace voxhap::net
