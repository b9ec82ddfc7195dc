#pragma once
/// The newest frame update a subscribed front-end client has had by now (waiting up to
/// 10 s for the first after a subscription), or the test fails.

#include <stdexcept>

#include <gtest/gtest.h>

#include "net/frontend/frontend_client.h"

namespace voxhap::test {

inline net::pb::FrameUpdate newestUpdate(net::FrontendClient& client) {
  const std::optional<net::pb::FrameUpdate> last = client.newestUpdate();
  if (!last) throw std::runtime_error("no frame update in 10 s");
  return *last;
}

}  // namespace voxhap::test
