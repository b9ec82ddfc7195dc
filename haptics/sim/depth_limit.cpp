#include "haptics/sim/depth_limit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

namespace voxhap {
namespace {

/// Gauss–Seidel sweeps over the pairs' limits.
constexpr int kIterations = 32;
/// A pair's limit binds when the step takes it past its target by more than this share of its
/// limit (rounding).
constexpr double kToleranceOfLimit = 1e-6;
/// What the last pass lets the sweeps leave past a limit, as a share of it, before it
/// scales the whole step down.
constexpr double kResidualOfLimit = 0.02;
/// Rounds of giving passing rows limits of their own.
constexpr int kRowRounds = 4;
/// Rows given limits of their own in one round: the furthest past.
constexpr std::size_t kRowsPerRound = kRowLimits / kRowRounds;

using Delta = DepthLimitScratch::Delta;
using Limit = DepthLimitScratch::Limit;

double gainOf(const Limit& l, std::span<const Delta> deltas) {
  const Delta& a = deltas[static_cast<std::size_t>(l.bodyA)];
  double gain = glm::dot(l.linearA, a.linear) + glm::dot(l.angularA, a.angular);
  if (l.bodyB >= 0) {
    const Delta& b = deltas[static_cast<std::size_t>(l.bodyB)];
    gain += glm::dot(l.linearB, b.linear) + glm::dot(l.angularB, b.angular);
  }
  return gain;
}

/// Adds `weight` times the row's Jacobian and depth to `l`.
void addRow(Limit& l, const DepthRow& row, double weight, std::span<const RigidBodyState> before) {
  const glm::dvec3& u = row.intoVoxmapWorld;
  const auto a = static_cast<std::size_t>(row.shellObject);
  // u·(θ × r) = θ·(r × u)
  l.linearA += weight * u;
  l.angularA += weight * glm::cross(row.pointWorld - before[a].comWorld, u);
  if (row.voxmapObject >= 0) {
    const auto b = static_cast<std::size_t>(row.voxmapObject);
    l.linearB -= weight * u;
    l.angularB -= weight * glm::cross(row.pointWorld - before[b].comWorld, u);
  }
  l.meanDepthM += weight * row.depthM;
  l.weightSum += weight;
}

/// Normalises the sums of `l` into its limit.
void normalise(Limit& l) {
  const double perWeight = 1.0 / l.weightSum;
  l.linearA *= perWeight;
  l.angularA *= perWeight;
  l.linearB *= perWeight;
  l.angularB *= perWeight;
  l.meanDepthM *= perWeight;
  l.targetM = std::max(l.limitM - l.meanDepthM, 0.0);
}

/// Fills in what the solver needs of the bodies' masses, and starts it afresh.
void setMasses(Limit& l, std::span<const Delta> deltas) {
  l.lambda = 0.0;
  const Delta& a = deltas[static_cast<std::size_t>(l.bodyA)];
  l.turnPerImpulseA = a.inverseInertiaWorld * l.angularA;
  l.inverseMass = a.inverseMass * glm::dot(l.linearA, l.linearA) + glm::dot(l.angularA, l.turnPerImpulseA);
  if (l.bodyB >= 0) {
    const Delta& b = deltas[static_cast<std::size_t>(l.bodyB)];
    l.turnPerImpulseB = b.inverseInertiaWorld * l.angularB;
    l.inverseMass += b.inverseMass * glm::dot(l.linearB, l.linearB) + glm::dot(l.angularB, l.turnPerImpulseB);
  }
}

/// A limit of the objects of `row`, with its limit and no rows yet.
Limit limitOf(const DepthRow& row) {
  Limit l;
  l.bodyA = row.shellObject;
  l.bodyB = row.voxmapObject;
  l.limitM = row.limitM;
  return l;
}

/// Sums each pair's rows (a run with the same two objects) into its limit; returns how
/// many pairs.
std::size_t groupRows(DepthLimitScratch& s, std::size_t rowCount, std::span<const RigidBodyState> before) {
  std::size_t count = 0;
  for (std::size_t r = 0; r < rowCount; ++r) {
    DepthRow& row = s.rows[r];
    row.limited = false;
    const double weight = row.depthM - row.floorM;
    if (!(weight > 0.0)) continue;
    if (count == 0 || s.limits[count - 1].bodyA != row.shellObject ||
        s.limits[count - 1].bodyB != row.voxmapObject) {
      s.limits[count++] = limitOf(row);
    }
    addRow(s.limits[count - 1], row, weight, before);
  }
  for (std::size_t k = 0; k < count; ++k) normalise(s.limits[k]);
  return count;
}

void sweep(DepthLimitScratch& s, std::size_t count) {
  for (std::size_t k = 0; k < count; ++k) {
    Limit& l = s.limits[k];
    if (!(l.inverseMass > 0.0)) continue;
    const double lambda = std::max(0.0, l.lambda + (gainOf(l, s.deltas) - l.targetM) / l.inverseMass);
    const double change = lambda - l.lambda;
    if (change == 0.0) continue;
    l.lambda = lambda;
    Delta& a = s.deltas[static_cast<std::size_t>(l.bodyA)];
    a.linear -= change * a.inverseMass * l.linearA;
    a.angular -= change * l.turnPerImpulseA;
    if (l.bodyB >= 0) {
      Delta& b = s.deltas[static_cast<std::size_t>(l.bodyB)];
      b.linear -= change * b.inverseMass * l.linearB;
      b.angular -= change * l.turnPerImpulseB;
    }
  }
}

}  // namespace

namespace {

/// Sets each body's displacement from `before` to `after` and its inverse mass (zero for a
/// kinematic body that does not yield), and readies the limits; how many bind.
std::uint32_t setUp(std::span<const MovingObjectModel> objects, std::span<const RigidBodyState> before,
                    std::span<const RigidBodyState> after, DepthLimitScratch& s, std::size_t count) {
  for (std::size_t i = 0; i < objects.size(); ++i) {
    Delta& d = s.deltas[i];
    d.linear = after[i].comWorld - before[i].comWorld;
    d.angular = rotationVector(after[i].orientation * glm::conjugate(before[i].orientation));
    const bool fixed = d.kinematic && !d.yielding;
    d.inverseMass = fixed ? 0.0 : objects[i].body.inverseMassPerKg;
    d.inverseInertiaWorld =
        fixed ? glm::dmat3(0.0) : inverseInertiaWorld(objects[i].body, before[i].orientation);
  }
  std::uint32_t binding = 0;
  for (std::size_t k = 0; k < count; ++k) {
    setMasses(s.limits[k], s.deltas);
    const Limit& l = s.limits[k];
    if (gainOf(l, s.deltas) > l.targetM + kToleranceOfLimit * l.limitM) ++binding;
  }
  return binding;
}

/// How far the step as solved so far would take `row` past its own limit (target
/// max(L − d, 0)), m; ≤ 0 when it would not.
double rowExcessM(const DepthRow& row, std::span<const Delta> deltas,
                  std::span<const RigidBodyState> before) {
  const glm::dvec3& u = row.intoVoxmapWorld;
  const auto a = static_cast<std::size_t>(row.shellObject);
  double gain = glm::dot(u, deltas[a].linear) +
                glm::dot(glm::cross(row.pointWorld - before[a].comWorld, u), deltas[a].angular);
  if (row.voxmapObject >= 0) {
    const auto b = static_cast<std::size_t>(row.voxmapObject);
    gain -= glm::dot(u, deltas[b].linear) +
            glm::dot(glm::cross(row.pointWorld - before[b].comWorld, u), deltas[b].angular);
  }
  return gain - std::max(row.limitM - row.depthM, 0.0);
}

/// Gives a limit of its own to each of the (at most kRowsPerRound) surface-plane rows that
/// the step as solved so far takes furthest past their limits, beyond the tolerance (room
/// allowing, each row once), after the first `count` limits; returns how many.
std::size_t limitPassingRows(DepthLimitScratch& s, std::size_t count, std::size_t rowCount,
                             std::span<const RigidBodyState> before) {
  // the worst rows so far, by excess as a share of their limits, worst first (ties: lower index)
  std::array<std::pair<double, std::size_t>, kRowsPerRound> worst{};
  std::size_t found = 0;
  for (std::size_t r = 0; r < rowCount; ++r) {
    const DepthRow& row = s.rows[r];
    if (!row.surfacePlane || row.limited) continue;
    const double share = rowExcessM(row, s.deltas, before) / row.limitM;
    if (!(share > kToleranceOfLimit)) continue;
    if (found == worst.size() && share <= worst.back().first) continue;
    std::size_t at = std::min(found, worst.size() - 1);
    while (at > 0 && worst[at - 1].first < share) {
      worst[at] = worst[at - 1];
      --at;
    }
    worst[at] = {share, r};
    found = std::min(found + 1, worst.size());
  }
  const std::size_t added = std::min(found, s.limits.size() - count);
  for (std::size_t k = 0; k < added; ++k) {
    DepthRow& row = s.rows[worst[k].second];
    Limit& l = s.limits[count + k];
    l = limitOf(row);
    addRow(l, row, 1.0, before);
    normalise(l);
    setMasses(l, s.deltas);
    row.limited = true;
  }
  return added;
}

/// The scale of the whole step that keeps every surface-plane row within the last pass's
/// residual of its own limit.
double surfaceRowScale(const DepthLimitScratch& s, std::size_t rowCount,
                       std::span<const RigidBodyState> before) {
  double scale = 1.0;
  for (std::size_t r = 0; r < rowCount; ++r) {
    const DepthRow& row = s.rows[r];
    if (!row.surfacePlane) continue;
    const double targetM = std::max(row.limitM - row.depthM, 0.0);
    const double allowed = targetM + kResidualOfLimit * row.limitM;
    const double gain = rowExcessM(row, s.deltas, before) + targetM;
    if (gain > allowed) scale = std::min(scale, allowed / gain);
  }
  return scale;
}

/// The scale of the whole step as solved that keeps every body it moves within its
/// MaxTravel (beyond rounding: a body held to it before the projection is at it).
double travelScale(std::span<const MovingObjectModel> objects, std::span<const Delta> deltas) {
  constexpr double kRounding = 1e-9;
  double scale = 1.0;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Delta& d = deltas[i];
    if (d.kinematic && !d.yielding) continue;
    const double travelM = glm::length(d.linear) + glm::length(d.angular) * objects[i].shellRadiusM;
    if (travelM > d.maxTravelM * (1.0 + kRounding)) scale = std::min(scale, d.maxTravelM / travelM);
  }
  return scale;
}

/// Whether scaling the steps of all but the remote bodies that do not yield keeps every
/// limit: it does unless those remote bodies' steps alone take one past its target (a
/// limit's gain is linear in the scale, from theirs alone to the solved step's).
bool scalingTheRestKeepsLimits(const DepthLimitScratch& s, std::size_t count) {
  auto streamed = [&s](int body, const glm::dvec3& linear, const glm::dvec3& angular) {
    if (body < 0) return 0.0;
    const Delta& d = s.deltas[static_cast<std::size_t>(body)];
    return d.kinematic && !d.yielding ? glm::dot(linear, d.linear) + glm::dot(angular, d.angular) : 0.0;
  };
  for (std::size_t k = 0; k < count; ++k) {
    const Limit& l = s.limits[k];
    const double gain = streamed(l.bodyA, l.linearA, l.angularA) + streamed(l.bodyB, l.linearB, l.angularB);
    if (gain > l.targetM + kToleranceOfLimit * l.limitM) return false;
  }
  return true;
}

/// The sweeps, then the scale of the whole step that the last pass needs.
double solve(DepthLimitScratch& s, std::size_t count) {
  for (int iteration = 0; iteration < kIterations; ++iteration) sweep(s, count);
  double scale = 1.0;
  for (std::size_t k = 0; k < count; ++k) {
    const Limit& l = s.limits[k];
    const double allowed = l.targetM + kResidualOfLimit * l.limitM;
    const double gain = gainOf(l, s.deltas);
    if (gain > allowed) scale = std::min(scale, allowed / gain);
  }
  return scale;
}

}  // namespace

DepthLimitFrame limitDepths(std::span<const MovingObjectModel> objects,
                            std::span<const RigidBodyState> before, std::span<RigidBodyState> after,
                            DepthLimitScratch& s, std::size_t rowCount, double dtS) noexcept {
  DepthLimitFrame frame;
  frame.rows = static_cast<std::uint32_t>(rowCount);
  for (Delta& d : s.deltas) d.refusedLinear = d.refusedAngular = glm::dvec3(0.0);
  std::size_t count = rowCount == 0 ? 0 : groupRows(s, rowCount, before);
  frame.pairs = static_cast<std::uint32_t>(count);
  // a remote body yields only while its stream moves it and it touches what it was trapped
  // against: one that stands (nobody's, or its stream not begun) traps nothing, and stays
  // where every peer has it
  for (std::size_t i = 0; i < s.deltas.size(); ++i) {
    Delta& d = s.deltas[i];
    const auto body = static_cast<int>(i);
    d.streamed = d.kinematic &&
                 (after[i].comWorld != before[i].comWorld || after[i].orientation != before[i].orientation);
    d.yielding = d.streamed && d.yielding &&
                 std::any_of(s.limits.begin(), s.limits.begin() + static_cast<std::ptrdiff_t>(count),
                             [body](const Limit& l) { return l.bodyA == body || l.bodyB == body; });
  }
  if (rowCount == 0) return frame;
  frame.binding = setUp(objects, before, after, s, count);
  double scale = frame.binding == 0 ? 1.0 : solve(s, count);
  // a pair's mean may hold while some of its points pass it: those measured exactly and
  // furthest past get limits of their own, a few rounds
  for (int round = 0; round < kRowRounds; ++round) {
    const std::size_t added = limitPassingRows(s, count, rowCount, before);
    if (added == 0) break;
    count += added;
    frame.rowLimits += static_cast<std::uint32_t>(added);
    scale = solve(s, count);
  }
  // the rows still past their own limits beyond the residual (more of them than there is
  // room for), and the bodies the corrections would carry past their MaxTravel
  const double limitsScale = std::min(scale, surfaceRowScale(s, rowCount, before));
  double travel = travelScale(objects, s.deltas);
  scale = std::min(limitsScale, travel);
  if (frame.binding == 0 && frame.rowLimits == 0 && scale == 1.0) return frame;
  const bool remote =
      std::any_of(s.deltas.begin(), s.deltas.end(), [](const Delta& d) { return d.streamed; });
  if (remote && (limitsScale < 1.0 || (travel < 1.0 && !scalingTheRestKeepsLimits(s, count)))) {
    // a local part trapped against a remote one that moves, or pushed by it faster than it
    // can give way, or two owners' remote parts streamed into each other: the remote ones
    // yield too
    for (Delta& d : s.deltas) d.yielding = d.streamed;
    setUp(objects, before, after, s, count);
    scale = solve(s, count);
    travel = travelScale(objects, s.deltas);
    scale = std::min({scale, surfaceRowScale(s, rowCount, before), travel});
  }
  frame.scale = scale;
  frame.travelBound = travel < 1.0 && scale == travel;

  for (std::size_t i = 0; i < objects.size(); ++i) {
    Delta& d = s.deltas[i];
    // a remote body that did not yield is exactly where its stream put it (rebuilding its
    // pose from the rotation vector would round it off its target)
    if (d.kinematic && !d.yielding) continue;
    // of what the integrator asked for, what is not kept
    const glm::dvec3 askedLinear = after[i].comWorld - before[i].comWorld;
    const glm::dvec3 askedAngular =
        rotationVector(after[i].orientation * glm::conjugate(before[i].orientation));
    d.linear *= scale;
    d.angular *= scale;
    d.refusedLinear = askedLinear - d.linear;
    d.refusedAngular = askedAngular - d.angular;
    after[i].comWorld = before[i].comWorld + d.linear;
    after[i].orientation = glm::normalize(quatFromRotationVector(d.angular) * before[i].orientation);
    after[i].linearVelocityWorld -= d.refusedLinear / dtS;
    after[i].angularVelocityWorld -= d.refusedAngular / dtS;
  }
  return frame;
}

}  // namespace voxhap
