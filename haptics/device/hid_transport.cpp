#include "haptics/device/hid_transport.h"

#include <cwchar>

#include <hidapi/hidapi.h>

#include "haptics/core/error.h"

namespace voxhap {
namespace {

// hidapi's strings are wchar_t (UTF-32 on Linux)
std::string utf8FromWide(const wchar_t* wide) {
  std::string out;
  if (wide == nullptr) return out;
  for (; *wide != L'\0'; ++wide) {
    auto c = static_cast<std::uint32_t>(*wide);
    if (c > 0x10ffff) c = 0xfffd;
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xc0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3f));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xe0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (c & 0x3f));
    } else {
      out += static_cast<char>(0xf0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (c & 0x3f));
    }
  }
  return out;
}

class HidapiTransport final : public HidTransport {
public:
  HidapiTransport() {
    if (hid_init() != 0) throw Error("hidapi: cannot initialise: " + utf8FromWide(hid_error(nullptr)));
  }
  ~HidapiTransport() override { close(); }
  HidapiTransport(const HidapiTransport&) = delete;
  HidapiTransport& operator=(const HidapiTransport&) = delete;

  std::vector<HidDeviceInfo> enumerate() override {
    std::vector<HidDeviceInfo> devices;
    hid_device_info* list = hid_enumerate(0, 0);
    for (const hid_device_info* d = list; d != nullptr; d = d->next) {
      HidDeviceInfo info;
      info.path = d->path != nullptr ? d->path : "";
      info.vendorId = d->vendor_id;
      info.productId = d->product_id;
      info.usagePage = d->usage_page;
      info.usage = d->usage;
      info.name = utf8FromWide(d->product_string);
      devices.push_back(std::move(info));
    }
    hid_free_enumeration(list);
    return devices;
  }

  bool open(const std::string& path) override {
    close();
    device_ = hid_open_path(path.c_str());
    if (device_ == nullptr) {
      lastError_ = utf8FromWide(hid_error(nullptr));
      return false;
    }
    return true;
  }

  int read(std::span<std::uint8_t> buffer, int timeoutMs) override {
    if (device_ == nullptr) {
      lastError_ = "no device open";
      return -1;
    }
    const int n = hid_read_timeout(device_, buffer.data(), buffer.size(), timeoutMs);
    if (n < 0) lastError_ = utf8FromWide(hid_error(device_));
    return n;
  }

  void close() noexcept override {
    if (device_ != nullptr) hid_close(device_);
    device_ = nullptr;
  }

  std::string lastError() const override { return lastError_; }

private:
  hid_device* device_ = nullptr;
  std::string lastError_;
};

}  // namespace

std::unique_ptr<HidTransport> makeHidapiTransport() {
  return std::make_unique<HidapiTransport>();
}

}  // namespace voxhap
