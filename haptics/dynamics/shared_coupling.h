#pragma once
/// The multi-user virtual coupling of a shared object (type-2; paper §6.1, Fig. 8; DESIGN
/// §4.8 and §8): every sharing peer integrates its own instance of the object, and a
/// spring-damper joins it to the other peers' instances. Its wrench acts on the local
/// instance as an external wrench (FrameInputs::externalWrenches).
///
/// Delay: a remote instance counts with the weight w = max(0, 1 − τ/1 s) (the paper: the
/// stiffness falls linearly to zero at 1 s), τ being the one-way delay of its stream or,
/// when the stream has stopped, the age of its newest state if that is larger. A peer that
/// stops sending therefore fades out within a second, and is gone without a step.
///
/// Several remote instances (N sharing peers): the coupling pulls towards their w-weighted
/// average with stiffness k₀·s, s = Σw²/Σw (the weights' mean, each weighted by itself).
/// That is a spring of k₀·w_j²/Σw to each instance j: at most k₀·w_j, what its own delay
/// allows, and all together at most k₀ whatever N, so N peers do not stiffen it N-fold.
/// An instance of weight 0 adds nothing, so one that joins or leaves makes no step. The
/// damping keeps the damping ratio: b₀·√s.
///
/// Gains k₀, b₀ (the caller's). On the local instance the coupling adds to the handle's:
/// with k₀, b₀ no stiffer than the handle's defaults (virtual_coupling.cpp: ω_n·h = 0.25,
/// ζ = 1) the two together have twice its a and c, a + 2c = 2.125 < 4, stable at 1 kHz
/// however the target moves (the remote instances, 100 Hz or more, are played out at 1 kHz
/// by the jitter buffer). The loop through the network is another matter. Two instances
/// of mass m, each pulled towards the other's state τ old: their difference r obeys
/// m·r'' = −(k + b·d/dt)(r(t) + r(t − τ)), and to first order in τ that is stable while
/// m > b·τ and 2b > k·τ, i.e. (ζ = 1) ω_n·τ < 0.5. The handle's ω_n = 250 rad/s allows
/// 2 ms; at 100 ms it is 5 rad/s. The stiffness that τ allows falls as 1/τ², so the
/// paper's linear fade weakens the loop but does not make it stable by itself.
///
/// Per frame: noexcept, allocation-free.

#include <span>

#include "haptics/dynamics/rigid_body.h"
#include "haptics/dynamics/virtual_coupling.h"

namespace voxhap {

/// The one-way delay at which a remote instance's weight reaches zero, s.
inline constexpr double kSharedCouplingFadeDelayS = 1.0;

/// Another peer's instance of the shared object, as this frame sees it.
struct RemoteInstance {
  RigidBodyState state;  ///< played out to this frame (jitter buffer)
  double delayS = 0.0;   ///< its stream's one-way delay, or its newest state's age if larger, s
};

/// w = max(0, 1 − τ/kSharedCouplingFadeDelayS); 1 for a negative delay, 0 for a NaN.
double delayWeight(double delayS) noexcept;

/// The coupling on the local instance this frame.
struct SharedCoupling {
  CouplingWrench onLocal;       ///< force at the centre of mass, torque about it
  double stiffnessShare = 0.0;  ///< s = Σw²/Σw (0: no remote instance counts)
  RigidBodyState target;        ///< the remote instances' weighted average (meaningful when s > 0)
};

/// The wrench that joins `local` (an instance of the object `model`) to `remotes` with the
/// gains `stiffest` (k₀, b₀) scaled as the file comment says. Remote instances whose state
/// is not finite, or whose orientation is not a unit quaternion, do not count.
SharedCoupling sharedCouplingWrench(const CouplingGains& stiffest, const RigidBodyModel& model,
                                    const RigidBodyState& local,
                                    std::span<const RemoteInstance> remotes) noexcept;

}  // namespace voxhap
