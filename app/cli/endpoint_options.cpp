#include "app/cli/endpoint_options.h"

#include <fstream>
#include <sstream>

#include "app/cli/option_values.h"
#include "haptics/core/error.h"

namespace voxhap::cli {

HostPort parseHostPort(const std::string& text, const std::string& option) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0 || colon + 1 == text.size())
    throw UsageError(option + " wants HOST:PORT, e.g. 127.0.0.1:7400, not '" + text + "'");
  HostPort endpoint;
  endpoint.host = text.substr(0, colon);
  if (endpoint.host.size() > 2 && endpoint.host.front() == '[' && endpoint.host.back() == ']')
    endpoint.host = endpoint.host.substr(1, endpoint.host.size() - 2);
  const std::uint64_t port =
      parseUnsigned(text.substr(colon + 1), option.substr(option.find_first_not_of('-')));
  if (port > 65535) throw UsageError(option + ": port " + std::to_string(port) + " is beyond 65535");
  endpoint.port = static_cast<std::uint16_t>(port);
  return endpoint;
}

std::string readTokenFile(const std::string& file, const std::string& option) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error(option + ": cannot read " + file);
  std::ostringstream s;
  s << in.rdbuf();
  std::string token = s.str();
  while (!token.empty() && (token.back() == '\n' || token.back() == '\r')) token.pop_back();
  if (token.empty()) throw Error(option + ": " + file + " is empty");
  return token;
}

}  // namespace voxhap::cli
