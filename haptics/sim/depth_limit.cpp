#include "haptics/sim/depth_limit.h"

#include <algorithm>
#include <cmath>

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

/// Normalises the sums of `l` into its limit and fills in what the solver needs.
void finish(Limit& l, std::span<const Delta> deltas) {
  const double perWeight = 1.0 / l.weightSum;
  l.linearA *= perWeight;
  l.angularA *= perWeight;
  l.linearB *= perWeight;
  l.angularB *= perWeight;
  l.meanDepthM *= perWeight;
  l.targetM = std::max(l.limitM - l.meanDepthM, 0.0);
  const Delta& a = deltas[static_cast<std::size_t>(l.bodyA)];
  l.turnPerImpulseA = a.inverseInertiaWorld * l.angularA;
  l.inverseMass = a.inverseMass * glm::dot(l.linearA, l.linearA) + glm::dot(l.angularA, l.turnPerImpulseA);
  if (l.bodyB >= 0) {
    const Delta& b = deltas[static_cast<std::size_t>(l.bodyB)];
    l.turnPerImpulseB = b.inverseInertiaWorld * l.angularB;
    l.inverseMass += b.inverseMass * glm::dot(l.linearB, l.linearB) + glm::dot(l.angularB, l.turnPerImpulseB);
  }
}

/// Sums each pair's rows (a run with the same two objects) into its limit; returns how
/// many pairs.
std::size_t groupRows(DepthLimitScratch& s, std::size_t rowCount, std::span<const RigidBodyState> before) {
  std::size_t count = 0;
  for (std::size_t r = 0; r < rowCount; ++r) {
    const DepthRow& row = s.rows[r];
    const double weight = row.depthM - row.floorM;
    if (!(weight > 0.0)) continue;
    if (count == 0 || s.limits[count - 1].bodyA != row.shellObject ||
        s.limits[count - 1].bodyB != row.voxmapObject) {
      Limit& l = s.limits[count++];
      l = Limit{};
      l.bodyA = row.shellObject;
      l.bodyB = row.voxmapObject;
      l.limitM = row.limitM;
    }
    addRow(s.limits[count - 1], row, weight, before);
  }
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

DepthLimitFrame limitDepths(std::span<const MovingObjectModel> objects,
                            std::span<const RigidBodyState> before, std::span<RigidBodyState> after,
                            DepthLimitScratch& s, std::size_t rowCount, double dtS) noexcept {
  DepthLimitFrame frame;
  frame.rows = static_cast<std::uint32_t>(rowCount);
  for (Delta& d : s.deltas) d.refusedLinear = d.refusedAngular = glm::dvec3(0.0);
  if (rowCount == 0) return frame;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    Delta& d = s.deltas[i];
    d.linear = after[i].comWorld - before[i].comWorld;
    d.angular = rotationVector(after[i].orientation * glm::conjugate(before[i].orientation));
    d.inverseMass = objects[i].body.inverseMassPerKg;
    d.inverseInertiaWorld = inverseInertiaWorld(objects[i].body, before[i].orientation);
  }
  const std::size_t count = groupRows(s, rowCount, before);
  frame.pairs = static_cast<std::uint32_t>(count);
  for (std::size_t k = 0; k < count; ++k) {
    finish(s.limits[k], s.deltas);
    const Limit& l = s.limits[k];
    if (gainOf(l, s.deltas) > l.targetM + kToleranceOfLimit * l.limitM) ++frame.binding;
  }
  if (frame.binding == 0) return frame;
  // what the integrator asked for; what is kept is taken off at the end
  for (Delta& d : s.deltas) {
    d.refusedLinear = d.linear;
    d.refusedAngular = d.angular;
  }
  for (int iteration = 0; iteration < kIterations; ++iteration) sweep(s, count);

  // what the sweeps left: the whole step scaled down until every limit holds
  double scale = 1.0;
  for (std::size_t k = 0; k < count; ++k) {
    const Limit& l = s.limits[k];
    const double allowed = l.targetM + kResidualOfLimit * l.limitM;
    const double gain = gainOf(l, s.deltas);
    if (gain > allowed) scale = std::min(scale, allowed / gain);
  }
  frame.scale = scale;

  for (std::size_t i = 0; i < objects.size(); ++i) {
    Delta& d = s.deltas[i];
    d.linear *= scale;
    d.angular *= scale;
    d.refusedLinear -= d.linear;
    d.refusedAngular -= d.angular;
    after[i].comWorld = before[i].comWorld + d.linear;
    after[i].orientation = glm::normalize(quatFromRotationVector(d.angular) * before[i].orientation);
    after[i].linearVelocityWorld -= d.refusedLinear / dtS;
    after[i].angularVelocityWorld -= d.refusedAngular / dtS;
  }
  return frame;
}

}  // namespace voxhap
