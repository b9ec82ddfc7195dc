#include "net/peer/impairment.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "haptics/core/error.h"

namespace voxhap::net {
namespace {

void requireAtLeastZero(double value, const char* field) {
  if (!(value >= 0.0) || !std::isfinite(value))
    throw Error(std::string(field) + " must be finite and ≥ 0, not " + std::to_string(value));
}

void requireRate(double value, const char* field) {
  if (!(value >= 0.0 && value <= 1.0))
    throw Error(std::string(field) + " must be from 0 to 1, not " + std::to_string(value));
}

}  // namespace

Impairment::Impairment(const ImpairmentSettings& settings) : settings_(settings), rng_(settings.seed) {
  requireAtLeastZero(settings.delayS, "delay");
  requireAtLeastZero(settings.jitterS, "jitter");
  requireRate(settings.lossRate, "loss");
  requireRate(settings.duplicateRate, "duplicate");
}

double Impairment::uniform() noexcept {
  return static_cast<double>(rng_() >> 11) * 0x1.0p-53;
}

double Impairment::delay() noexcept {
  return std::max(0.0, settings_.delayS + settings_.jitterS * (2.0 * uniform() - 1.0));
}

DatagramFate Impairment::next() noexcept {
  // every datagram takes the same four draws, so one fate never shifts the next ones
  const bool lost = uniform() < settings_.lossRate;
  const bool twice = uniform() < settings_.duplicateRate;
  const double first = delay();
  const double second = delay();
  if (lost) return DatagramFate{0, {0.0, 0.0}};
  return DatagramFate{twice ? 2 : 1, {first, twice ? second : 0.0}};
}

}  // namespace voxhap::net
