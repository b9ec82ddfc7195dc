#include "net/frontend/frontend_server.h"

#include <atomic>
#include <future>
#include <thread>

#include <asio/post.hpp>
#include <gtest/gtest.h>

#include "haptics/core/error.h"
#include "net/frontend/frontend_client.h"

namespace voxhap::net {
namespace {

using namespace std::chrono_literals;

// answers ListObjects with one object, counts frame updates and disconnections
class FakeHandler : public FrontendHandler {
public:
  void hello(pb::HelloReply& reply) override { reply.set_scene("fake"); }
  void handle(std::uint64_t, const pb::ClientMessage& request, pb::ServerMessage& reply) override {
    if (request.has_list_objects()) {
      pb::ObjectInfo& o = *reply.mutable_object_list()->add_objects();
      o.set_name("ball");
      o.set_moving(true);
    } else {
      reply.mutable_error()->set_message("not in the fake");
    }
  }
  void frameUpdate(pb::FrameUpdate& update) override { update.set_frame(stepping ? ++frames : frames); }
  void disconnected(std::uint64_t) override { ++disconnections; }
  std::uint64_t frames = 0;
  std::atomic<bool> stepping{true};  // false: the frame stands still, as in a stalled loop
  int disconnections = 0;
};

// a server on a loopback port, its io_context on a thread of its own
class FrontendServerTest : public ::testing::Test {
protected:
  void start(FrontendServerOptions options = {}) {
    server_ = std::make_unique<FrontendServer>(
        io_, asio::ip::tcp::endpoint(asio::ip::address_v4::loopback(), 0), handler_, std::move(options),
        [this](const std::string& line) { log_.push_back(line); });
    port_ = server_->endpoint().port();
    thread_ = std::thread([this] { io_.run(); });
  }
  void TearDown() override {
    if (!thread_.joinable()) return;
    asio::post(io_, [this] {
      server_.reset();
      io_.stop();
    });
    thread_.join();
  }
  // runs `fn` on the server's thread and returns its result
  template <class Fn>
  auto onServer(Fn fn) {
    std::packaged_task<decltype(fn())()> task(fn);
    auto result = task.get_future();
    asio::post(io_, [&task] { task(); });
    return result.get();
  }
  FrontendClient connect() { return FrontendClient("127.0.0.1", port_, 5000ms); }
  static pb::ClientMessage listObjects() {
    pb::ClientMessage m;
    m.mutable_list_objects();
    return m;
  }

  asio::io_context io_;
  FakeHandler handler_;
  std::unique_ptr<FrontendServer> server_;
  std::vector<std::string> log_;  // written on the server's thread only
  std::uint16_t port_ = 0;
  std::thread thread_;
};

TEST_F(FrontendServerTest, HelloThenARequestGetsItsReply) {
  start();
  FrontendClient client = connect();
  EXPECT_EQ(client.hello("test").scene(), "fake");
  const pb::ServerMessage reply = client.request(listObjects());
  ASSERT_TRUE(reply.has_object_list());
  EXPECT_EQ(reply.object_list().objects(0).name(), "ball");
  pb::ClientMessage unknown;  // no request set, as from a newer client
  EXPECT_TRUE(client.request(unknown).has_error());
  EXPECT_TRUE(client.isOpen());
}

TEST_F(FrontendServerTest, AWrongVersionClosesThatConnectionOnly) {
  start();
  FrontendClient good = connect();
  good.hello("good");
  FrontendClient bad = connect();
  pb::ClientMessage hello;
  hello.mutable_hello()->set_protocol_version(99);
  const pb::ServerMessage reply = bad.request(hello);
  ASSERT_TRUE(reply.has_error());
  EXPECT_NE(reply.error().message().find("version 99"), std::string::npos);
  EXPECT_TRUE(bad.waitClosed(5000ms));
  EXPECT_TRUE(good.request(listObjects()).has_object_list());
  EXPECT_EQ(onServer([this] { return server_->counters().violations; }), 1u);
}

TEST_F(FrontendServerTest, ATokenIsRequiredWhenSet) {
  FrontendServerOptions options;
  options.token = "s3cret";
  start(options);
  FrontendClient wrong = connect();
  EXPECT_THROW(wrong.hello("wrong", "s3creT"), Error);
  EXPECT_TRUE(wrong.waitClosed(5000ms));
  FrontendClient none = connect();
  EXPECT_THROW(none.hello("none"), Error);
  FrontendClient right = connect();
  EXPECT_NO_THROW(right.hello("right", "s3cret"));
  EXPECT_TRUE(right.request(listObjects()).has_object_list());
}

TEST_F(FrontendServerTest, ARequestBeforeTheHelloIsAViolation) {
  start();
  FrontendClient client = connect();
  EXPECT_TRUE(client.request(listObjects()).has_error());
  EXPECT_TRUE(client.waitClosed(5000ms));
}

TEST_F(FrontendServerTest, BadFramesCloseTheirConnection) {
  FrontendServerOptions options;
  options.maxFrameBytes = 1024;
  start(options);
  const std::vector<std::string> bad = {
      std::string("\x01\x10\x00\x00", 4),              // announces 4097 bytes
      std::string("\x03\x00\x00\x00\xff\xff\xff", 7),  // not a protobuf message
  };
  for (const std::string& bytes : bad) {
    FrontendClient client = connect();
    client.hello("bad");
    client.sendRaw(bytes);
    EXPECT_TRUE(client.waitClosed(5000ms));
  }
  EXPECT_EQ(onServer([this] { return server_->counters().violations; }), bad.size());
  FrontendClient after = connect();
  after.hello("after");
  EXPECT_TRUE(after.request(listObjects()).has_object_list());
}

TEST_F(FrontendServerTest, IdsThatDoNotIncreaseAreAViolation) {
  start();
  FrontendClient client = connect();
  client.hello("test");
  pb::ClientMessage again = listObjects();
  again.set_id(1);  // the hello's
  std::string frame;
  appendFrame(frame, again.SerializeAsString());
  client.sendRaw(frame);
  EXPECT_TRUE(client.waitClosed(5000ms));
}

TEST_F(FrontendServerTest, AConnectionEndingInsideAFrameIsLogged) {
  start();
  {
    FrontendClient client = connect();
    client.hello("test");
    client.sendRaw(std::string("\x10\x00\x00\x00\x08", 5));
  }
  for (int i = 0; i < 500 && onServer([this] { return handler_.disconnections; }) == 0; ++i)
    std::this_thread::sleep_for(10ms);
  EXPECT_EQ(onServer([this] { return handler_.disconnections; }), 1);
  const std::vector<std::string> log = onServer([this] { return log_; });
  ASSERT_FALSE(log.empty());
  EXPECT_NE(log.back().find("inside a frame"), std::string::npos) << log.back();
}

TEST_F(FrontendServerTest, SubscribersGetFrameUpdatesUntilTheyStop) {
  start();
  FrontendClient client = connect();
  client.hello("test");
  pb::ClientMessage subscribe;
  subscribe.mutable_subscribe()->set_rate_hz(200.0);
  ASSERT_TRUE(client.request(subscribe).has_done());
  std::uint64_t last = 0;
  for (int i = 0; i < 5; ++i) {
    const auto event = client.nextEvent(5000ms);
    ASSERT_TRUE(event && event->has_frame_update());
    EXPECT_GT(event->frame_update().frame(), last);
    last = event->frame_update().frame();
  }
  subscribe.mutable_subscribe()->set_rate_hz(5000.0);
  const pb::ServerMessage refused = client.request(subscribe);
  ASSERT_TRUE(refused.has_error());
  EXPECT_EQ(refused.error().field(), "rate_hz");
  subscribe.mutable_subscribe()->set_rate_hz(0.0);
  ASSERT_TRUE(client.request(subscribe).has_done());
  while (client.nextEvent(0ms)) {
  }  // those sent before the stop
  EXPECT_FALSE(client.nextEvent(100ms));
}

TEST_F(FrontendServerTest, AFrameThatDidNotAdvanceIsNotSentAgain) {
  start();
  FrontendClient client = connect();
  client.hello("test");
  pb::ClientMessage subscribe;
  subscribe.mutable_subscribe()->set_rate_hz(500.0);
  ASSERT_TRUE(client.request(subscribe).has_done());
  ASSERT_TRUE(client.nextEvent(5000ms));
  handler_.stepping = false;
  while (client.nextEvent(50ms)) {
  }                                       // those in flight, and at most one of the standing frame
  EXPECT_FALSE(client.nextEvent(100ms));  // 50 updates were due
  EXPECT_GT(onServer([this] { return server_->counters().updatesUnchanged; }), 0u);
  handler_.stepping = true;
  EXPECT_TRUE(client.nextEvent(5000ms));
}

TEST_F(FrontendServerTest, ClientsOverTheLimitAreRefused) {
  FrontendServerOptions options;
  options.maxClients = 1;
  start(options);
  FrontendClient first = connect();
  first.hello("first");
  FrontendClient second = connect();
  EXPECT_TRUE(second.waitClosed(5000ms));
  EXPECT_EQ(onServer([this] { return server_->counters().refused; }), 1u);
}

}  // namespace
}  // namespace voxhap::net
