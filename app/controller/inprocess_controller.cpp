#include "app/controller/inprocess_controller.h"

#include "haptics/core/error.h"

namespace voxhap::cli {

InProcessController::InProcessController(ControllerOptions options, Console& console) {
  options.listenHost = "127.0.0.1";
  options.listenPort = 0;
  options.json = true;
  options.stopRequested = &stopRequested_;
  options.onListening = [this](std::uint16_t port) {
    listened_ = true;
    listening_.set_value(port);
  };
  std::future<std::uint16_t> listening = listening_.get_future();
  thread_ = std::thread([this, options = std::move(options), &console] {
    try {
      runController(options, console, summary_);
    } catch (const std::exception& e) {
      error_ = e.what();
      if (!listened_) listening_.set_exception(std::current_exception());
    }
    stopped_ = true;
  });
  try {
    port_ = listening.get();
  } catch (...) {
    thread_.join();
    throw;
  }
}

InProcessController::~InProcessController() {
  stopRequested_ = true;
  if (thread_.joinable()) thread_.join();
}

std::string InProcessController::stopAndWait() {
  stopRequested_ = true;
  if (thread_.joinable()) thread_.join();
  if (!error_.empty()) throw Error("the controller stopped: " + error_);
  return summary_.str();
}

}  // namespace voxhap::cli
