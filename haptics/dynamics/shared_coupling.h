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
/// of mass m, each pulled towards the other's state a old: their difference r obeys
/// m·r'' = −(k + b·d/dt)(r(t) + r(t − a)), and to first order in a that is stable while
/// m > b·a and 2b > k·a, i.e. (ζ = 1) ω_n·a < 0.5. The age a of a remote state is its
/// stream's one-way delay and the jitter buffer's play-out delay (30 ms), so even on
/// loopback the handle's ω_n = 250 rad/s is 15 times too stiff. Each instance therefore
/// counts with a second weight, its age's: w_a = min(1, (0.25 / (ω₀·a))²), ω₀ = √(k₀/m),
/// so that its spring has ω_n·a ≤ 0.25, half the bound (as the handle keeps half its own).
/// The stiffness that a allows falls as 1/a², faster than the paper's linear fade, which
/// stays for a stream that stops.
///
/// Prediction: a remote state is carried forward along its own velocities, so that
/// instances moving together pull each other back little. Without it each is pulled back
/// by k·v·a: at the handle's stiffness, 0.1 m/s behind an instance 30 ms old held the
/// landing gear's actuator in its jaws against its users' 100 N (`voxhap demo`, whose
/// passivity controllers dissipated 1.5 kJ in 30 s). It goes no further than a lower bound
/// of the age, the play-out delay: carried beyond the present, the states of instances
/// moving together would pull each one forward, k·v per second of excess, a negative
/// damping that sped a released pair up (SharedObjectCommand, 100 ms without the passivity
/// controller: 1.0 to 1.4 mm/s in 2 s, when the lead was the measured one-way delay, a
/// filtered mean above the least delay the jitter buffer plays at, plus the play-out delay).
///
/// Divergence (paper §6.1: something, a thin wall, trapped between the instances): the
/// local instance is divergent when it is further than a bound from the remote instances'
/// average, in distance or in angle, and stays so until it is back within half of it. The
/// spring never sees more than the bound's stretch, so that as a wall holds the instances
/// apart the coupling does not press harder on it (the depth limits keep the wall whole
/// anyway), and when the wall goes they close at the bounded pull, not with the energy of
/// a spring stretched by the whole gap. The pull is continuous at the bound: no step.
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
  double ageS = 0.0;     ///< how old `state` is: its stream's one-way delay and the play-out delay, s
  /// How far `state` is carried forward along its velocities, s: no more than its age
  /// (see the file comment), the play-out delay.
  double leadS = 0.0;
};

/// ω_n·a of the stiffest spring to an instance of age a (see the file comment).
inline constexpr double kSharedCouplingOmegaAge = 0.25;

/// w = max(0, 1 − τ/kSharedCouplingFadeDelayS); 1 for a negative delay, 0 for a NaN.
double delayWeight(double delayS) noexcept;

/// w_a = min(1, (kSharedCouplingOmegaAge / (ω₀·a))²) for a state `ageS` old, with ω₀ the
/// stiffest coupling's natural frequency (rad/s); 1 for an age of 0 or less, 0 for a NaN.
double ageWeight(double ageS, double omegaRadS) noexcept;

/// How far the local instance may be from the remote instances' average before it is
/// divergent (see the file comment).
struct DivergenceBound {
  double distanceM = 0.01;  ///< of the centres of mass, m
  double angleRad = 0.1;
};

/// The coupling on the local instance this frame.
struct SharedCoupling {
  CouplingWrench onLocal;       ///< force at the centre of mass, torque about it
  double stiffnessShare = 0.0;  ///< s = Σw²/Σw (0: no remote instance counts)
  RigidBodyState target;        ///< the remote instances' weighted average (meaningful when s > 0)
  double apartM = 0.0;          ///< from the local centre of mass to the target's, m
  double apartRad = 0.0;        ///< from the local orientation to the target's
  bool divergent = false;       ///< (see the file comment); false when no remote instance counts
};

/// The wrench that joins `local` (an instance of the object `model`) to `remotes` with the
/// gains `stiffest` (k₀, b₀) scaled, its spring's stretch held to `bound`, as the file
/// comment says; `wasDivergent`: the last frame's SharedCoupling::divergent. Remote
/// instances whose state is not finite, or whose orientation is not a unit quaternion, do
/// not count.
SharedCoupling sharedCouplingWrench(const CouplingGains& stiffest, const RigidBodyModel& model,
                                    const RigidBodyState& local, std::span<const RemoteInstance> remotes,
                                    const DivergenceBound& bound = {}, bool wasDivergent = false) noexcept;

}  // namespace voxhap
