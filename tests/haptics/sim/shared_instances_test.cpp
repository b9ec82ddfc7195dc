// Two peers' instances of one shared box (type-2, issue 14) in the full simulation step:
// each peer's LocalSimulation integrates its own instance on a plate under gravity, with
// the shared coupling (and, when asked, its passivity controller) as the external wrench,
// from the other's state as sent at 100 Hz and delivered `delay` later. User A slides the
// box 40 mm over 1 s and lets go at 2 s; user B does not hold it. The figures (tracking
// error, settling, energy after the release) are the issue's "tracking error against
// delay"; the test holds what must not fail: after the release the passivity controller
// never lets them move more than they would without it, brings them to rest up to 100 ms,
// and at no delay B follows A closely.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "haptics/dynamics/coupling_passivity.h"
#include "haptics/dynamics/shared_coupling.h"
#include "support/contact_scenes.h"
#include "support/delayed_stream.h"

namespace voxhap {
namespace {

using test::at;

SimModel plateAndBox() {
  Scene scene;
  scene.objects.push_back(test::plate());
  scene.objects.push_back(test::meshObject("box", ObjectRole::Dynamic, [](TriangleMesh& m) {
    appendBox(m, at(0.0, 0.0, 0.0055), glm::dvec3(0.01, 0.01, 0.005));
  }));
  SceneModelOptions options = test::ampleCapacityOptions();
  options.staticVoxelSizeM = 0.001;
  options.pointSpacingM = 0.001;
  options.sim.gravityWorld = glm::dvec3(0.0, 0.0, -9.81);
  return buildSceneModel(scene, {"box"}, options);
}

struct SharedRun {
  double trackingM = 0.0;        ///< largest distance between the instances while A moves, m
  double settledM = 0.0;         ///< between them 1 s after A's move ended, m
  double keAtReleaseJ = 0.0;     ///< both instances' kinetic energy when A lets go, J
  double keLargestAfterJ = 0.0;  ///< and its largest after, J
  double keAtEndJ = 0.0;
  double dissipatedJ = 0.0;  ///< by the passivity controllers, J
};

SharedRun runShared(const SimModel& model, const CouplingGains& gains, double delayS, bool passive) {
  constexpr int kMoveFrames = 1000, kReleaseFrame = 2000, kFrames = 4000;
  const double dtS = model.dtS;
  std::array<LocalSimulation, 2> sims = {LocalSimulation(model), LocalSimulation(model)};
  std::array<CouplingPassivity, 2> ports;
  std::array<bool, 2> divergent{};
  const int delayFrames = static_cast<int>(std::lround(delayS / dtS));
  std::array<test::DelayedStream, 2> streams = {test::DelayedStream(delayFrames),
                                                test::DelayedStream(delayFrames)};
  SharedRun run;
  for (int frame = 0; frame < kFrames; ++frame) {
    for (std::size_t i = 0; i < 2; ++i) streams[i].send(frame, sims[i].state.bodies[0], ports[i].inJ());
    std::array<ExternalWrench, 2> wrench{};
    for (std::size_t i = 0; i < 2; ++i) {
      const test::DelayedStream::Sent* newest = streams[1 - i].newest(frame);
      if (newest == nullptr) continue;
      const RigidBodyState& local = sims[i].state.bodies[0];
      const std::vector<RemoteInstance> remote = {{newest->state, (frame - newest->frame) * dtS}};
      const SharedCoupling c =
          sharedCouplingWrench(gains, model.objects[0].body, local, remote, {}, divergent[i]);
      divergent[i] = c.divergent;
      const CouplingWrench w =
          passive ? ports[i].passive(c.onLocal, model.objects[0].body, local, newest->inJ, 2, dtS)
                  : c.onLocal;
      wrench[i] = {w.forceWorld, w.torqueWorld};
    }
    const double t = std::min(1.0, static_cast<double>(frame) / kMoveFrames);
    const HandleInput a{Pose{glm::dvec3(0.04 * t, 0.0, 0.0), identityQuat()}, {}, frame < kReleaseFrame};
    const HandleInput none{{}, {}, false};
    sims[0].step(std::span(&a, 1), std::span(&wrench[0], 1));
    sims[1].step(std::span(&none, 1), std::span(&wrench[1], 1));
    const double apartM = glm::length(sims[0].state.bodies[0].comWorld - sims[1].state.bodies[0].comWorld);
    if (frame <= kMoveFrames) run.trackingM = std::max(run.trackingM, apartM);
    if (frame == kMoveFrames + 1000) run.settledM = apartM;
    const double ke = kineticEnergyJ(model.objects[0].body, sims[0].state.bodies[0]) +
                      kineticEnergyJ(model.objects[0].body, sims[1].state.bodies[0]);
    if (frame == kReleaseFrame) run.keAtReleaseJ = ke;
    if (frame > kReleaseFrame) run.keLargestAfterJ = std::max(run.keLargestAfterJ, ke);
    run.keAtEndJ = ke;
  }
  run.dissipatedJ = ports[0].dissipatedJ() + ports[1].dissipatedJ();
  return run;
}

TEST(SharedInstances, ThePassivityControllerCalmsThePairAfterTheReleaseAndBFollowsA) {
  const SimModel model = plateAndBox();
  const RigidBodyModel& body = model.objects[0].body;
  const CouplingGains stiffest = defaultCouplingGains(body, model.dtS);
  const double omegaN = std::sqrt(stiffest.linearStiffnessNPerM / body.massKg);
  for (const double delayS : {0.0, 0.01, 0.1, 0.3, 0.9}) {
    // the delay's first-order bound, ω_n·τ < 0.5, with a margin (shared_coupling.h)
    // (the stream's 100 Hz adds up to 10 ms)
    const double share = std::min(1.0, std::pow(0.25 / (delayS + 0.01) / omegaN, 2.0));
    const CouplingGains soft = scaledCouplingGains(stiffest, body, share, 1.0);
    const SharedRun stiff = runShared(model, stiffest, delayS, false);
    const SharedRun guarded = runShared(model, stiffest, delayS, true);
    const SharedRun bounded = runShared(model, soft, delayS, false);
    for (const auto& [name, r] : {std::pair{"stiff", stiff}, std::pair{"stiff+passivity", guarded},
                                  std::pair{"soft (bound)", bounded}}) {
      std::printf(
          "[ figures  ] delay %4.0f ms %-16s tracking %7.2f mm, apart 1 s after %7.2f mm; KE at release %.2e "
          "J, "
          "largest after %.2e, at end %.2e; dissipated %.2e J\n",
          delayS * 1e3, name, r.trackingM * 1e3, r.settledM * 1e3, r.keAtReleaseJ, r.keLargestAfterJ,
          r.keAtEndJ, r.dissipatedJ);
    }
    // after the release the controller never lets the pair move more than it would without
    EXPECT_LE(guarded.keLargestAfterJ, stiff.keLargestAfterJ) << delayS;
    // up to 100 ms it brings them to rest within 2 s (beyond, energy put in before the
    // release keeps arriving for a delay, and they move on slowly)
    if (delayS <= 0.1) {
      EXPECT_LT(guarded.keAtEndJ, 1e-9) << delayS;
    }
    if (delayS == 0.0) {
      EXPECT_LT(guarded.trackingM, 0.002);
    }
  }
}

}  // namespace
}  // namespace voxhap
