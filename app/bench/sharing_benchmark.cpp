// `voxhap bench sharing`: a shared object's two instances (type-2, issue 14) coupled
// through a simulated network, offline and deterministic: how closely the unheld instance
// tracks the held one against the one-way delay, with and without the passivity controller;
// whether the pair stays stable once let go; and the coupling's bandwidth with 100 Hz
// states. Each instance is integrated at 1 kHz with its own SharedObjectPort, exactly as a
// peer's haptic thread runs it (haptics/runtime/shared_object_port.h); only the network is
// simulated: every 10 ms each instance's state is sent, lost with some probability, and
// arrives after the delay plus a uniform jitter. The ports are told the mean one-way delay
// (a peer measures it from echoed timestamps: net/peer/one_way_delay.h). No contacts: a
// free box, so that what is measured is the coupling alone. With the default gains
// (virtual_coupling.h: ω_n·h fixed) the results do not depend on the box's mass.

#include <algorithm>
#include <cmath>
#include <numbers>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "app/bench/benchmark.h"
#include "haptics/core/error.h"
#include "haptics/dynamics/mass_properties.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/runtime/shared_object_port.h"
#include "net/peer/impairment.h"

namespace voxhap::cli {
namespace {

constexpr double kDtS = 1e-3;
constexpr std::int64_t kFrameUs = 1'000;
constexpr std::int64_t kStreamUs = 10'000;  ///< 100 Hz
constexpr double kAmplitudeM = 0.010;       ///< of the held instance's handle, along x
constexpr PeerId kHeldPeer = 1, kUnheldPeer = 2;

struct SharingBenchArgs {
  bool quick = false;
  double jitterMs = 50.0;
  double lossShare = 0.2;
};

/// One run's settings.
struct Link {
  double delayS = 0.0;
  double jitterS = 0.0;
  double lossShare = 0.0;
  bool passivity = true;
};

/// One run's figures.
struct Run {
  double trackingRmsM = 0.0;  ///< |held − unheld| while the handle moves
  double maxApartM = 0.0;
  double gain = 0.0;            ///< unheld amplitude over held, at the drive frequency
  double releasedApartM = 0.0;  ///< at the end, after both are let go
  /// The pair's kinetic energy relative to its common motion, the most in the first
  /// second after the release and in the last.
  double releasedEnergyJ = 0.0;
  double laterEnergyJ = 0.0;
  double dissipatedJ = 0.0;  ///< by both passivity controllers
};

/// A state in flight to the other instance.
struct InFlight {
  std::int64_t arrivalUs = 0;
  RemoteSample sample;
  double inJ = 0.0;
};

/// One instance: its body, its port and what is on its way to it.
struct Instance {
  RigidBodyState body;
  SharedObjectPort port;
  std::vector<InFlight> arriving;
};

/// How long the handle holds still where the drag ended before it lets go, s: the held
/// instance comes to rest on it, so that the release leaves no momentum to the pair.
constexpr double kHoldS = 3.0;

/// The held instance's handle follows x = A·sin(2πft) for `driveS`, holds still for
/// kHoldS, then both instances are free for `releaseS`.
Run simulate(const RigidBodyModel& model, const Link& link, double frequencyHz, double driveS,
             double releaseS) {
  const CouplingGains gains = defaultCouplingGains(model, kDtS);
  Instance held{restingState(model), {}, {}};
  Instance unheld{restingState(model), {}, {}};
  const glm::dvec3 restCom = held.body.comWorld;
  // the relay's model of the path (net/peer/impairment.h): a delay drawn uniformly from
  // [delay, delay + jitter], a share lost; seeded, so the same fates on every machine
  net::Impairment path({.delayS = link.delayS + 0.5 * link.jitterS,
                        .jitterS = 0.5 * link.jitterS,
                        .lossRate = link.lossShare,
                        .duplicateRate = 0.0,
                        .seed = 1});
  Run run;
  double squaredSum = 0.0;
  std::size_t drivenFrames = 0;
  // projections of the x motions on the drive's sine and cosine, over whole periods
  double heldSin = 0.0, heldCos = 0.0, unheldSin = 0.0, unheldCos = 0.0;
  const double omega = 2.0 * std::numbers::pi * frequencyHz;
  const double settleS = std::min(0.5 * driveS, std::max(2.0, 2.0 / frequencyHz));
  const double periodS = 1.0 / frequencyHz;
  const double projectFromS = driveS - std::floor((driveS - settleS) / periodS) * periodS;
  const auto endUs = static_cast<std::int64_t>((driveS + kHoldS + releaseS) * 1e6);
  const auto driveUs = static_cast<std::int64_t>(driveS * 1e6);
  const auto releaseUs = static_cast<std::int64_t>((driveS + kHoldS) * 1e6);

  for (std::int64_t nowUs = 0; nowUs < endUs; nowUs += kFrameUs) {
    const double t = 1e-6 * static_cast<double>(nowUs);
    // the network: states sent every 10 ms, taken when they arrive
    for (auto [from, to, peer] :
         {std::tuple{&held, &unheld, kHeldPeer}, std::tuple{&unheld, &held, kUnheldPeer}}) {
      if (nowUs % kStreamUs == 0) {
        const net::DatagramFate fate = path.next();
        if (fate.copies > 0)
          to->arriving.push_back({nowUs + static_cast<std::int64_t>(fate.delayS[0] * 1e6),
                                  {nowUs, from->body},
                                  from->port.last().inJ});
      }
      std::erase_if(to->arriving, [&](const InFlight& f) {
        if (f.arrivalUs > nowUs) return false;
        to->port.take(peer, f.sample, f.inJ, f.arrivalUs);
        return true;
      });
      to->port.setDelay(peer, link.delayS + 0.5 * link.jitterS);
    }
    for (Instance* i : {&held, &unheld}) {
      const SharedObjectPort::Frame& f = i->port.step(nowUs, model, i->body, gains, link.passivity, kDtS);
      glm::dvec3 force = f.wrench.forceWorld, torque = f.wrench.torqueWorld;
      if (i == &held && nowUs < releaseUs) {
        const bool driving = nowUs < driveUs;
        const Pose handle{glm::dvec3(kAmplitudeM * std::sin(omega * std::min(t, driveS)), 0.0, 0.0),
                          identityQuat()};
        const glm::dvec3 handleVelocity(driving ? kAmplitudeM * omega * std::cos(omega * t) : 0.0, 0.0, 0.0);
        const CouplingWrench w =
            couplingWrench(gains, handle, handleVelocity, glm::dvec3(0.0), model, i->body);
        force += w.forceWorld;
        torque += w.torqueWorld;
      }
      integrate(model, i->body, force, torque, kDtS);
    }
    const double apartM = glm::length(held.body.comWorld - unheld.body.comWorld);
    if (nowUs < driveUs) {
      run.maxApartM = std::max(run.maxApartM, apartM);
      if (t >= settleS) {
        squaredSum += apartM * apartM;
        ++drivenFrames;
      }
      if (t >= projectFromS) {
        const double heldX = held.body.comWorld.x - restCom.x, unheldX = unheld.body.comWorld.x - restCom.x;
        heldSin += heldX * std::sin(omega * t);
        heldCos += heldX * std::cos(omega * t);
        unheldSin += unheldX * std::sin(omega * t);
        unheldCos += unheldX * std::cos(omega * t);
      }
    } else if (nowUs >= releaseUs) {
      // the pair's energy in the frame of its common motion: what the coupling could make
      const double sinceS = t - (driveS + kHoldS);
      const glm::dvec3 relativeVelocity = held.body.linearVelocityWorld - unheld.body.linearVelocityWorld;
      const double energyJ = 0.25 * model.massKg * glm::dot(relativeVelocity, relativeVelocity);
      if (sinceS < 1.0) run.releasedEnergyJ = std::max(run.releasedEnergyJ, energyJ);
      if (sinceS >= releaseS - 1.0) run.laterEnergyJ = std::max(run.laterEnergyJ, energyJ);
    }
  }
  run.trackingRmsM = drivenFrames > 0 ? std::sqrt(squaredSum / static_cast<double>(drivenFrames)) : 0.0;
  const double heldAmplitude = std::hypot(heldSin, heldCos);
  run.gain = heldAmplitude > 0.0 ? std::hypot(unheldSin, unheldCos) / heldAmplitude : 0.0;
  run.releasedApartM = glm::length(held.body.comWorld - unheld.body.comWorld);
  run.dissipatedJ = held.port.last().dissipatedJ + unheld.port.last().dissipatedJ;
  return run;
}

RigidBodyModel boxModel() {
  // 20 × 6 × 6 cm, 2 kg: about the landing gear's actuator body
  TriangleMesh mesh;
  appendBox(mesh, glm::dmat4(1.0), glm::dvec3(0.10, 0.03, 0.03));
  SceneObject box;
  box.name = "shared box";
  box.parts.push_back(makePart("box", glm::vec4(1.0f), std::move(mesh)));
  const double volumeM3 = computeMassProperties(box, 1.0).volumeM3;
  return makeRigidBodyModel(computeMassProperties(box, 2.0 / volumeM3), box.name);
}

BenchTable runSharingBench(const SharingBenchArgs& args, Console& console) {
  if (!(args.jitterMs >= 0.0 && args.jitterMs <= 500.0)) throw UsageError("--jitter wants 0 to 500 ms");
  if (!(args.lossShare >= 0.0 && args.lossShare < 1.0))
    throw UsageError("--loss wants a share from 0 to below 1");
  BenchTable table("sharing", {{"sweep", "sweep", BenchStyle::Text},
                               {"one_way_ms", "one-way ms", BenchStyle::Fixed, 0},
                               {"passivity", "passivity", BenchStyle::Text},
                               {"frequency_hz", "freq Hz", BenchStyle::Fixed, 2},
                               {"tracking_rms_m", "tracking rms mm", BenchStyle::Millimetres, 3},
                               {"max_apart_m", "most apart mm", BenchStyle::Millimetres, 3},
                               {"gain", "gain", BenchStyle::Fixed, 3},
                               {"released_apart_m", "released apart mm", BenchStyle::Millimetres, 4},
                               {"released_energy_j", "energy at release J", BenchStyle::Scientific},
                               {"later_energy_j", "energy later J", BenchStyle::Scientific},
                               {"stable", "stable", BenchStyle::Text},
                               {"dissipated_j", "dissipated J", BenchStyle::Scientific}});
  const RigidBodyModel model = boxModel();
  const double jitterS = 1e-3 * args.jitterMs;
  const auto add = [&table](const std::string& sweep, const Link& link, double frequencyHz, const Run& r) {
    const std::size_t row = table.addRow();
    table.set(row, "sweep", sweep);
    table.set(row, "one_way_ms", std::round(1e6 * link.delayS) / 1e3);  // whole µs
    table.set(row, "passivity", std::string(link.passivity ? "on" : "off"));
    table.set(row, "frequency_hz", frequencyHz);
    table.set(row, "tracking_rms_m", r.trackingRmsM);
    table.set(row, "max_apart_m", r.maxApartM);
    table.set(row, "gain", r.gain);
    table.set(row, "released_apart_m", r.releasedApartM);
    table.set(row, "released_energy_j", r.releasedEnergyJ);
    table.set(row, "later_energy_j", r.laterEnergyJ);
    // stable: the pair's relative energy does not grow once nobody puts any in
    table.set(row, "stable", std::string(r.laterEnergyJ <= r.releasedEnergyJ + 1e-12 ? "yes" : "no"));
    table.set(row, "dissipated_j", r.dissipatedJ);
  };

  // tracking against delay: a slow drag (0.2 Hz, 10 mm), then 20 s let go
  const std::vector<double> delaysMs = args.quick
                                           ? std::vector<double>{0, 300, 1000}
                                           : std::vector<double>{0, 50, 100, 200, 300, 500, 700, 900, 1000};
  // whole periods and a quarter: the drag ends at its far end, 10 mm from where the
  // instances began, so that an unheld instance that never followed ends 10 mm away
  const double driveS = args.quick ? 11.25 : 21.25;
  const double releaseS = args.quick ? 10.0 : 20.0;
  std::size_t done = 0;
  const std::size_t total = 2 * delaysMs.size() + 2 * (args.quick ? 3 : 8);
  const auto progress = console.progress("simulating the shared box");
  for (const double delayMs : delaysMs) {
    for (const bool passivity : {true, false}) {
      const Link link{1e-3 * delayMs, jitterS, args.lossShare, passivity};
      add("delay", link, 0.2, simulate(model, link, 0.2, driveS, releaseS));
      if (progress) progress(static_cast<double>(++done) / static_cast<double>(total));
    }
  }
  // bandwidth: the unheld instance's amplitude over the held one's against the frequency
  const std::vector<double> frequenciesHz = args.quick
                                                ? std::vector<double>{0.2, 1.0, 5.0}
                                                : std::vector<double>{0.1, 0.2, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0};
  for (const double delayMs : {0.0, 100.0}) {
    for (const double f : frequenciesHz) {
      const Link link{1e-3 * delayMs, jitterS, args.lossShare, true};
      add("bandwidth", link, f, simulate(model, link, f, args.quick ? 10.0 : 20.0, 2.0));
      if (progress) progress(static_cast<double>(++done) / static_cast<double>(total));
    }
  }
  table.extra["jitter_ms"] = args.jitterMs;
  table.extra["loss_share"] = args.lossShare;
  table.extra["stream_hz"] = 1e6 / static_cast<double>(kStreamUs);
  table.extra["mass_kg"] = model.massKg;
  return table;
}

}  // namespace

Benchmark sharingBenchmark() {
  Benchmark b;
  b.name = "sharing";
  b.summary = "A shared object's two instances through a simulated network: tracking, stability, bandwidth.";
  b.usage = "[--quick] [--jitter MS] [--loss SHARE]";
  b.description =
      "Two users share a free 2 kg box (type-2, `voxhap peer --share`): each peer integrates its\n"
      "own instance at 1 kHz, coupled to the other's through the same SharedObjectPort as a\n"
      "peer's haptic thread, with or without the passivity controller. Only the network is\n"
      "simulated, deterministically: each instance's state every 10 ms (100 Hz), a share of\n"
      "them lost (--loss, default 0.2), the rest arriving after the one-way delay plus a\n"
      "uniform jitter (--jitter, default 50 ms); the ports are told the mean delay. No contacts.\n\n"
      "Sweep 'delay' (one-way 0 to 1000 ms, passivity on and off): one user drags its instance\n"
      "10 mm to and fro at 0.2 Hz for 21.25 s (ending 10 mm out), holds it still for 3 s, then\n"
      "both let go for 20 s. 'tracking rms' is the distance between the instances during the\n"
      "drag (after 2 s), 'most apart' its largest, 'released apart' at the end; 'stable' says\n"
      "whether the pair's relative kinetic energy in the last second after the release is at\n"
      "most what it was in the first (nobody puts any in then). Sweep 'bandwidth' (one-way 0\n"
      "and 100 ms, passivity on): the drag at 0.1 to 5 Hz for 20 s; 'gain' is the unheld\n"
      "instance's amplitude at that frequency over the held one's (1: it follows; the bandwidth\n"
      "is where it falls below 0.707).\n\n"
      "Examples:\n"
      "  voxhap bench sharing\n"
      "  voxhap bench sharing --quick --jitter 0 --loss 0 --json";
  b.addOptions = [](CLI::App& command) {
    auto args = std::make_shared<SharingBenchArgs>();
    command.add_flag("--quick", args->quick, "three delays and three frequencies, 10 s drags");
    command.add_option("--jitter", args->jitterMs, "uniform jitter added to the delay, ms (default 50)")
        ->type_name("MS");
    command.add_option("--loss", args->lossShare, "share of states lost, 0 to below 1 (default 0.2)")
        ->type_name("SHARE");
    return [args](Console& console) { return runSharingBench(*args, console); };
  };
  return b;
}

}  // namespace voxhap::cli
