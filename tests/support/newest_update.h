#pragma once
/// The newest frame update a subscribed front-end client has had by now.

#include <chrono>
#include <optional>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "net/frontend/frontend_client.h"

namespace voxhap::test {

/// A request's reply comes after every update sent before it, so the updates kept while
/// waiting for it reach up to now (reading until a quiet gap would return a backlog's
/// first). Waits up to 10 s for the first update after a subscription.
inline net::pb::FrameUpdate newestUpdate(net::FrontendClient& client) {
  std::optional<net::pb::FrameUpdate> last;
  for (int attempt = 0; attempt < 500 && !last; ++attempt) {
    if (attempt > 0) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    net::pb::ClientMessage ask;
    ask.mutable_get_statistics();
    EXPECT_TRUE(client.request(ask).has_statistics());
    while (const auto event = client.nextEvent(std::chrono::milliseconds(0))) {
      if (event->has_frame_update()) last = event->frame_update();
    }
  }
  if (!last) throw std::runtime_error("no frame update in 10 s");
  return *last;
}

}  // namespace voxhap::test
