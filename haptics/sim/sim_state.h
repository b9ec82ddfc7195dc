#pragma once
/// What peers replicate of a simulation (DESIGN §7) and nothing else: the frame, the
/// time, every moving object's body, the force layer and who owns each object. A peer
/// that joins late restores it from a snapshot (saveState/restoreState); peers compare
/// hashState to find divergence. Everything else a frame needs is per peer and lives in
/// SimWorkspace.

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "haptics/collide/contact_params.h"
#include "haptics/dynamics/rigid_body.h"
#include "haptics/sim/sim_model.h"

namespace voxhap {

/// A peer of a collaborative session (DESIGN §8); 0 is no peer.
using PeerId = std::uint32_t;
/// The owner of an object no peer owns: every peer integrates its own copy (one user, or
/// type-2 sharing). step() integrates every object whoever owns it; the peer layer moves
/// the objects that remote peers own as kinematic bodies.
inline constexpr PeerId kNoPeer = 0;

struct SimState {
  std::uint64_t frame = 0;
  double timeS = 0.0;
  std::vector<RigidBodyState> bodies;  ///< per moving object
  /// The force layer in use (collision offsetting, paper §3.2), adjustable between frames
  /// with setForceLayer; starts at the model's.
  std::uint8_t forceLayer = kDefaultForceLayer;
  std::vector<PeerId> owners;  ///< per moving object
};

/// A state with every object at rest where the scene file puts it, owned by no peer.
SimState makeSimState(const SimModel& model);

/// A 64-bit XXH3 hash of what saveState writes (so equal states, and only they, hash
/// equal, up to collisions). RigidBodyState::skippedSteps, a local diagnostic, is left
/// out of both. Noexcept and allocation-free: the haptic thread may call it.
std::uint64_t hashState(const SimState& state) noexcept;

/// The state as bytes (little-endian, versioned, the doubles' exact bits), for a snapshot.
std::vector<std::byte> saveState(const SimState& state);

/// The state `bytes` hold, checked against `model`: throws voxhap::Error naming what is
/// wrong when they are not a state snapshot, of another version, of another number of
/// objects, truncated or longer, or hold a non-finite or non-unit value or a force layer
/// outside the model's voxmaps. Make a new SimWorkspace after restoring (makeSimWorkspace).
SimState restoreState(const SimModel& model, std::span<const std::byte> bytes);

}  // namespace voxhap
