#pragma once
/// A seeded model of a bad network path, for tests of the peers on one machine where
/// there is no `tc netem` (DESIGN §8): each datagram is lost with a probability, else
/// delivered after a delay drawn uniformly from [delay − jitter, delay + jitter] (never
/// below 0), and with another probability delivered a second time after its own draw.
/// Jitter wider than the gap between datagrams reorders them. Same settings and seed,
/// same fates on every machine: the draws come from std::mt19937_64, whose output the
/// standard fixes, turned into doubles by hand (the standard's distributions are not
/// portable).

#include <array>
#include <cstdint>
#include <random>

namespace voxhap::net {

struct ImpairmentSettings {
  double delayS = 0.0;         ///< mean one-way delay added, s
  double jitterS = 0.0;        ///< half-width of the uniform spread about it, s
  double lossRate = 0.0;       ///< share of datagrams dropped, 0 … 1
  double duplicateRate = 0.0;  ///< share of those delivered that come twice, 0 … 1
  std::uint64_t seed = 1;
};

/// What becomes of one datagram.
struct DatagramFate {
  int copies = 1;                          ///< 0 (lost), 1 or 2
  std::array<double, 2> delayS{0.0, 0.0};  ///< each copy's delay, s
};

class Impairment {
public:
  /// Throws Error naming the field when a setting is negative, not finite or a rate
  /// beyond 1.
  explicit Impairment(const ImpairmentSettings& settings);

  /// The fate of the next datagram.
  DatagramFate next() noexcept;

private:
  double uniform() noexcept;  ///< in [0, 1)
  double delay() noexcept;

  ImpairmentSettings settings_;
  std::mt19937_64 rng_;
};

}  // namespace voxhap::net
