#pragma once
/// Network endpoints and tokens on the command line: `--listen HOST:PORT`,
/// `--connect HOST:PORT`, `--token FILE`.

#include <cstdint>
#include <string>

namespace voxhap::cli {

struct HostPort {
  std::string host;  ///< an IPv4 address, or an IPv6 one without its brackets
  std::uint16_t port = 0;
};

/// "HOST:PORT" (an IPv4 address or a bracketed IPv6 one); throws UsageError naming
/// `option` (e.g. "--listen") when it is not one.
HostPort parseHostPort(const std::string& text, const std::string& option);

/// The token in `file`: its bytes without the trailing line end. Throws voxhap::Error
/// naming `option` when the file cannot be read or holds nothing.
std::string readTokenFile(const std::string& file, const std::string& option);

}  // namespace voxhap::cli
