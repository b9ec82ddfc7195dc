#pragma once
/// Non-penetration as an invariant of the step (DESIGN §4.4, paper §6.2: "the VPS
/// algorithms prevent part interpenetration").
///
/// Penalty forces alone cannot promise it: a contact spring of stiffness k meets a pull F
/// at depth F/k, and the coupling's pull grows with the handle's lead while the bodies'
/// integrator bounds k (sim_model.h). So after the bodies are integrated and held to
/// MaxTravel, the step is projected onto limits on the contacts' depths.
///
/// A contact row i (the shell point p_i, its direction u_i into the voxmap object and its
/// tangent-plane depth d_i at frame start: DepthRow) gains depth J_i·Δ = u_i·(Δp_shell(p_i)
/// − Δp_voxmap(p_i)) under the bodies' rigid displacements Δ (small rotations: θ × r).
/// The rows of one pair form one limit: their depth-weighted mean depth may not pass
/// L = kDepthLimitVoxels·s (nor grow, when it starts past it):
///     D̄ + Σ_i w_i J_i·Δ ≤ max(L, D̄),   w_i = (d_i − d₀) / Σ_j (d_j − d₀),   D̄ = Σ w_i d_i,
/// over the rows deeper than d₀ = L − the pair's MaxTravel bound (no shallower row can
/// reach L in one step), so that the deepest points carry the most weight. Why not one
/// limit per point, nor per pointshell chunk (both tried): the push directions are
/// quantized (the voxmap field's fall direction), so a point sliding along a curved
/// surface gains depth against its voxel's tangent plane until it crosses into the next
/// voxel. With a hard limit per point, or per chunk of 8³ voxels, the seated ball (whose
/// exact contact spreads its points over two voxels of depth, a press fit) meets hundreds
/// of such walls and cannot turn at all (0.0136 rad in 240 frames against 0.48 asked, per
/// point; not at all, per chunk); with one limit for the pair it turns at the handle's rate.
/// Why it keeps parts apart:
///   * a point not yet in contact (value F + 1 or more) lies at d ≤ (√3/2 − 1)·s before
///     the step and moves at most its pair's MaxTravel (s/2) in it, so it enters at
///     d < 0.37·s;
///   * at d ≤ s/2 a point of a face-parallel contact is still at least a voxel from the
///     voxmap's surface voxels (value F = 4 is two voxels out), which leaves more than the
///     half voxel by which the point may lie off its own exact surface;
///   * the exact-probe tests (tests/haptics/sim/non_penetration_test.cpp) check the rest,
///     the points deeper than their pair's mean among them.
/// With surface planes (ContactParams::surfaceContactM), whose depths are continuous
/// across voxels, single points may be held too: the rows measured by surface planes that
/// the solved step would take furthest past their limits get limits of their own
/// (kRowLimits a frame, in a few rounds, each bound to the tolerance of the first sweeps'
/// test), and the last pass holds every such row, not only those, within its residual:
/// a face or a rim pressed along a line of points has hundreds of them past the pair's mean
/// (a peg pulled sideways in its hole at 0.05 mm voxels: up to 1,500 of 3,400 rows).
/// Past their limits, rows are pushed back out by their springs, as before. The pull that
/// the contacts refuse is felt through the coupling, whose force the device profile
/// saturates (simulation.cpp): the body rests against the limits while the user feels the
/// coupling spring, continuous and passive.
///
/// The projection is the mass-weighted least change of the step (projected Gauss–Seidel,
/// kIterations sweeps in pair order: deterministic), so a part pressed onto a face still
/// slides along it. Every limit admits the step Δ = 0, so the projection onto them never
/// lengthens Δ in the mass norm: the refused motion's velocity goes with it and the
/// contacts never add kinetic energy. What the sweeps leave past a limit (beyond a
/// fiftieth of it) a last pass removes by scaling the whole step down (the limits are
/// linear and hold at Δ = 0, so a scaled step keeps them). The same scale holds every
/// body to its MaxTravel: a correction that turns a body carries its far points further than
/// the contact it frees, and holding that body alone would leave a remote part that pushes
/// it deeper each frame (4.6 mm at 0.5 mm voxels: a long bar pushed at its end).
///
/// Haptic thread: noexcept, allocation-free (DepthLimitScratch is sized at load).

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "haptics/collide/tangent_plane_force.h"
#include "haptics/dynamics/rigid_body.h"
#include "haptics/sim/sim_model.h"

namespace voxhap {

/// The deepest tangent-plane depth a contact may reach, in voxels of its voxmap.
inline constexpr double kDepthLimitVoxels = 0.5;

/// Of the contact distance of surface planes, the depth a contact may reach: the points
/// then stay half the contact distance outside the other's exact surface.
inline constexpr double kSurfaceDepthLimitShare = 0.5;

/// The deepest mean depth a pair's contacts may reach, m: kDepthLimitVoxels of voxels
/// `voxelSizeM` for the voxels' tangent planes; with surface planes, kSurfaceDepthLimitShare
/// of their contact distance.
inline double depthLimitM(const ContactParams& params, double voxelSizeM) {
  return params.surfaceContactM > 0.0 ? kSurfaceDepthLimitShare * params.surfaceContactM
                                      : kDepthLimitVoxels * voxelSizeM;
}

/// How many rows measured by surface planes may get limits of their own in a frame.
inline constexpr std::size_t kRowLimits = 64;

/// What the projection did in one frame.
struct DepthLimitFrame {
  std::uint32_t rows = 0;       ///< rows considered
  std::uint32_t pairs = 0;      ///< pairs with rows
  std::uint32_t binding = 0;    ///< pairs whose limit the step would have passed
  std::uint32_t rowLimits = 0;  ///< rows given limits of their own (surface planes)
  double scale = 1.0;           ///< the last pass's scale of the whole step (1: none needed)
  bool travelBound = false;     ///< a body's MaxTravel set the scale
};

/// Room for the projection, sized at load time (makeSimWorkspace).
struct DepthLimitScratch {
  /// One pair's limit J·Δ ≤ target on the displacements of bodies a and b (b < 0: static).
  struct Limit {
    int bodyA = 0;
    int bodyB = kStaticEnvironment;
    glm::dvec3 linearA{0.0};   ///< ∂gain/∂Δx_a
    glm::dvec3 angularA{0.0};  ///< ∂gain/∂θ_a, m
    glm::dvec3 linearB{0.0};
    glm::dvec3 angularB{0.0};
    glm::dvec3 turnPerImpulseA{0.0};  ///< I_a⁻¹ angularA, 1/(kg·m)
    glm::dvec3 turnPerImpulseB{0.0};
    double weightSum = 0.0;    ///< Σ (d_i − d₀), m
    double meanDepthM = 0.0;   ///< D̄, m
    double limitM = 0.0;       ///< L, m
    double inverseMass = 0.0;  ///< J M⁻¹ Jᵀ, 1/kg
    double targetM = 0.0;      ///< the most the gain may be, m
    double lambda = 0.0;       ///< accumulated correction, kg·m
  };
  /// One body's displacement over the step, and its inverse mass.
  struct Delta {
    glm::dvec3 linear{0.0};   ///< of the centre of mass, world, m
    glm::dvec3 angular{0.0};  ///< rotation vector, world, rad
    /// Of the displacement the integrator asked for, what the limits refused, m and rad:
    /// the contacts' constraint wrench times h²/M.
    glm::dvec3 refusedLinear{0.0};
    glm::dvec3 refusedAngular{0.0};
    glm::dmat3 inverseInertiaWorld{0.0};
    double inverseMass = 0.0;
    /// Set by the caller each frame: a body a remote peer moves (KinematicInput). No limit
    /// moves it, so that every peer shows it where its owner has it, unless the limits
    /// cannot hold otherwise (a local part trapped between it and a third, or pushed by it
    /// faster than its MaxTravel lets it give way, or another owner's remote part pressed
    /// against it): then it yields
    /// with its own mass like any body, and goes on yielding until it has no contact left
    /// or its stream no longer moves it.
    bool kinematic = false;
    bool streamed = false;  ///< kinematic, and its stream moves it this frame
    bool yielding = false;  ///< kept from frame to frame (see kinematic)
    /// Set by the caller each frame: how far any point of the body's shell may move, m.
    double maxTravelM = std::numeric_limits<double>::infinity();
  };

  /// Room for `rowCapacity` rows in `pairs` pairs among `bodies` moving objects.
  DepthLimitScratch(std::size_t rowCapacity = 0, std::size_t pairs = 0, std::size_t bodies = 0)
      : rows(rowCapacity), limits(pairs + kRowLimits), deltas(bodies) {}

  std::vector<DepthRow> rows;  ///< this frame's rows, pair by pair, filled by the contacts' pass
  std::vector<Limit> limits;   ///< this frame's limits: the pairs' means, then rows' own
  std::vector<Delta> deltas;   ///< per moving object
};

/// Projects the step from `before` to `after` (per moving object of `objects`) onto the
/// limits of the pairs of the first `rowCount` rows of `scratch` (each row's limit and
/// objects set by the caller, a pair's rows in one run) as the file comment says; `dtS` turns removed motion
/// into removed velocity. scratch.deltas then hold what each body was refused.
DepthLimitFrame limitDepths(std::span<const MovingObjectModel> objects,
                            std::span<const RigidBodyState> before, std::span<RigidBodyState> after,
                            DepthLimitScratch& scratch, std::size_t rowCount, double dtS) noexcept;

}  // namespace voxhap
