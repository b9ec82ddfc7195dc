#pragma once
/// Time-domain passivity of a shared object's coupling (issue 14; Hannaford and Ryu,
/// "Time-domain passivity control of haptic interfaces", IEEE TRA 2002; for ports joined
/// by a delayed network, Artigas, Ryu, Preusche and Hirzinger, "Network representation and
/// passivity of delayed teleoperation systems", IROS 2011).
///
/// Every sharing peer's coupling (shared_coupling.h) is one port of one network: the
/// springs and dampers of all the peers and the delays between them. Energy flows in at a
/// port when the local instance works against its coupling, and out when the coupling
/// works on the instance: power P = F·v + τ·ω. The network creates none iff, over all
/// ports, what has come out never exceeds what has gone in. Each peer streams what has
/// gone in at its port, and its observer allows its port out at most its share of all the
/// input it knows of:
///     E_obs = (E_in + Σ_others E_in,j) / N − E_out ≥ 0,
/// with the others' E_in as last received (older is smaller: it only errs on the safe
/// side). Summed over the N ports, Σ E_out ≤ Σ E_in: passive.
///
/// In discrete time (which leaks energy of its own: Jazayeri and Tavakoli, "A passivity
/// criterion for sampled-data bilateral teleoperation systems", WHC 2011) the observer
/// charges each frame's work as it was done: the wrench times the displacement the step
/// made. Semi-implicit Euler moves by h·v', not h·v, and with a stiff coupling the
/// difference, h²·F²/m a frame, is what feeds a delayed loop. The controller scales the
/// coupling's wrench on the instance by the largest c ≤ 1 whose predicted work,
/// c·h·(F·v + τ·ω) + c²·h²·(F·F/m + τ·I⁻¹·τ) (the wrench's own share of the new
/// velocity), fits what the observer allows; what it takes away is counted as dissipated.
///
/// What is left of a port's share fades with the time constant kForgetS (an energy tank
/// that leaks: only more conservative, so still passive). Without it, energy put in while
/// a user moved the object stayed available to a delayed loop after the user let go: a
/// 4 g box shared at the handle's gains, 100 Hz, no delay, went from 1 µJ at the release
/// to 5.6 mJ before the controller had spent it; with the fading, to 77 µJ
/// (tests/haptics/sim/shared_instances_test.cpp).
///
/// The price: energy a spring stores only because the remote instance moved (the delay's
/// doing) is not given back. Two instances apart with no input since (put apart by a jump,
/// not by a user) stay apart.
///
/// Per frame: noexcept, allocation-free.

#include <cstddef>

#include "haptics/dynamics/rigid_body.h"
#include "haptics/dynamics/virtual_coupling.h"

namespace voxhap {

class CouplingPassivity {
public:
  /// The time constant with which what is left of a port's share fades, s.
  static constexpr double kForgetS = 0.1;

  /// `onLocal` (the coupling on the local instance of `model` this frame) made passive,
  /// given the instance's state at the frame's start, the other ports' inJ() as last
  /// received, added up, and how many ports there are (N, at least 2; fewer: `onLocal`
  /// unchanged). Call it every frame with the state the last frame's step left.
  CouplingWrench passive(const CouplingWrench& onLocal, const RigidBodyModel& model,
                         const RigidBodyState& local, double othersInJ, std::size_t ports,
                         double dtS) noexcept;

  double inJ() const noexcept { return inJ_; }                  ///< in at this port so far, J
  double outJ() const noexcept { return outJ_; }                ///< out at this port so far, J
  double dissipatedJ() const noexcept { return dissipatedJ_; }  ///< by the controller so far, J
  /// The observer before this frame's output, J: ≥ 0 up to rounding when only the
  /// coupling moves the instance; other forces that move it along the wrench do more work
  /// than predicted and can take it below, and then the port gives nothing out until
  /// input covers the debt.
  double observedJ() const noexcept { return observedJ_; }

private:
  double inJ_ = 0.0;
  double outJ_ = 0.0;
  double dissipatedJ_ = 0.0;
  double observedJ_ = 0.0;
  double forgottenJ_ = 0.0;  ///< of the share, faded (kForgetS)
  // the last frame's wrench and where the instance started it, to charge its work
  bool charged_ = true;
  CouplingWrench last_;
  RigidBodyState lastStart_;
};

}  // namespace voxhap
