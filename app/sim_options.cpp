#include "app/sim_options.h"

#include <algorithm>

#include <CLI/CLI.hpp>

#include "app/cache_options.h"
#include "app/cli/option_values.h"
#include "app/scene_source.h"
#include "haptics/core/error.h"
#include "haptics/device/device_profile.h"

namespace voxhap::cli {

void addSimOptions(CLI::App& command, SimOptions& o, std::initializer_list<SimOption> which) {
  for (const SimOption option : which) {
    switch (option) {
      case SimOption::VoxelSize:
        addLengthOption(command, "--voxel-size", o.voxelSizeM, "voxel size of the static scene, e.g. 0.35mm");
        break;
      case SimOption::PointSpacing:
        addLengthOption(command, "--point-spacing", o.pointSpacingM,
                        "point spacing of the moving objects (default: the voxel size)");
        break;
      case SimOption::PointOffset:
        addLengthOption(command, "--point-offset", o.pointOffsetM,
                        "move every point along its normal, negative inward (e.g. -0.175mm); "
                        "overrides the scene's point_offset of each object",
                        LengthSign::Any);
        break;
      case SimOption::ForceLayerOf:
        addRepeatedOption(command, "--force-layer-of", "OBJECT=N",
                          "the force layer (voxel value N, 1 … 255) of moving OBJECT's pairs, its own "
                          "instead of the session's (a mating part, paper §3.2); overrides the scene's "
                          "force_layer; repeat for more objects",
                          [&o](const std::string& text) {
                            const std::size_t equals = text.rfind('=');
                            if (equals == std::string::npos || equals == 0)
                              throw UsageError("--force-layer-of wants OBJECT=N, not '" + text + "'");
                            const std::uint64_t layer =
                                parseUnsigned(text.substr(equals + 1), "force-layer-of");
                            if (layer < 1 || layer > 255)
                              throw UsageError("--force-layer-of wants a force layer of 1 … 255, not " +
                                               std::to_string(layer));
                            o.forceLayerOf[text.substr(0, equals)] = static_cast<std::uint8_t>(layer);
                          });
        break;
      case SimOption::PointLayer:
        addParsedOption(command, "--point-layer", "K",
                        "take points from the free-space layer K voxels out (0 … 8; collision offset)",
                        [&o](const std::string& text) {
                          o.pointLayer = static_cast<int>(
                              std::min<std::uint64_t>(parseUnsigned(text, "point-layer"), 1000));
                        });
        break;
      case SimOption::NoAwareness:
        command.add_flag("--no-awareness", o.noAwareness,
                         "turn geometrical awareness off (every point samples the surface field)");
        break;
      case SimOption::PreContactDamping:
        command.add_flag("--pre-contact-damping", o.preContactDamping,
                         "damp points approaching in the layer just outside the force layer");
        break;
      case SimOption::PaperContact:
        command.add_flag("--paper-contact,!--surface-contact", o.paperContact,
                         "contact by the paper's voxel planes: parts rest 1.6-1.9 voxels apart (default: "
                         "contact finer than a voxel, by exact surface planes kept with the voxels, parts "
                         "resting about 0.4 point spacings apart; --surface-contact says so explicitly)");
        break;
      case SimOption::Capacity:
        addParsedOption(command, "--capacity", "N", "point tests per frame (default: measured online)",
                        [&o](const std::string& text) {
                          o.capacity = parseUnsigned(text, "capacity");
                          if (*o.capacity < 1) throw UsageError("--capacity wants at least one point test");
                        });
        break;
      case SimOption::VoxelMemory:
        addParsedOption(
            command, "--voxel-memory", "SIZE",
            "most memory the static voxels may take, e.g. 2GiB; more is paged from the cache",
            [&o](const std::string& text) { o.voxelMemoryBytes = parseBytes(text, "voxel-memory"); });
        break;
      case SimOption::BruteForce:
        command.add_flag("--brute-force", o.bruteForce,
                         "test every point every frame (no time-critical sampling), for comparison");
        break;
      case SimOption::NoDrifting:
        command.add_flag("--no-drifting", o.noDrifting,
                         "look every due point up in the voxmap (no point drifting, paper §5.2)");
        break;
      case SimOption::FrameHelper:
        command.add_flag("--frame-helper", o.frameHelper,
                         "a second thread, pinned to a spare core, tests half the due points and sums "
                         "half the contact forces of large frames (the same results; it keeps that core "
                         "busy while frames run)");
        break;
      case SimOption::DeviceProfile:
        addParsedOption(command, "--device-profile", "NAME",
                        "the device's force, torque and stiffness limits, one of: " + deviceProfileNames() +
                            " (default " + std::string(kDefaultDeviceProfile) + ")",
                        [&o](const std::string& text) {
                          try {
                            o.deviceLimits = deviceProfile(text).limits;
                          } catch (const Error& e) {
                            throw UsageError(std::string("--device-profile: ") + e.what());
                          }
                        });
        break;
      case SimOption::Duration:
        addParsedOption(command, "--duration", "SECONDS", "simulated time (default: the whole script)",
                        [&o](const std::string& text) { o.durationS = parseSeconds(text, "duration"); });
        break;
      case SimOption::ProbeSpacing:
        addLengthOption(command, "--probe-spacing", o.probeSpacingM,
                        "spacing of the exact penetration's surface probes (default: voxel size / 4)");
        break;
      case SimOption::Cache:
        command.add_option("--cache-dir", o.cacheDir, "voxel cache folder (default ~/.cache/voxhap/voxels)")
            ->type_name("DIR");
        command.add_flag("--no-cache", o.noCache, "build voxels afresh; neither read nor write the cache");
        break;
    }
  }
}

std::shared_ptr<FrameHelper> frameHelperFor(const SimOptions& options) {
  return options.frameHelper ? std::make_shared<FrameHelper>() : nullptr;
}

CacheOptions voxelCacheOptions(const SimOptions& options) {
  return {options.cacheDir.value_or((userCacheDir() / "voxels").string()), !options.noCache};
}

SceneModelOptions sceneModelOptions(const SimOptions& o, Console& console, double defaultVoxelSizeM,
                                    std::optional<double> defaultPointSpacingM) {
  SceneModelOptions options;
  options.staticVoxelSizeM = o.voxelSizeM.value_or(defaultVoxelSizeM);
  options.pointSpacingM = o.pointSpacingM.value_or(defaultPointSpacingM.value_or(options.staticVoxelSizeM));
  if (o.pointOffsetM) options.pointDisplacementM = *o.pointOffsetM;
  if (o.pointLayer) options.pointFreeLayer = *o.pointLayer;
  options.forceLayerOf = o.forceLayerOf;
  options.sim.geometricalAwareness = !o.noAwareness;
  options.sim.preContactDamping = o.preContactDamping;
  if (!o.paperContact) {
    if (o.pointLayer.value_or(0) > 0)
      throw UsageError(
          "--point-layer takes the points off the surface, where surface contact (the default) "
          "needs them: add --paper-contact");
    options.sim.surfaceContact = true;
  }
  options.sim.coherence.enabled = !o.bruteForce;
  options.sim.coherence.pointDrifting = !o.noDrifting;
  if (o.capacity) options.sim.coherence.capacityTests = static_cast<double>(*o.capacity);
  if (o.deviceLimits) options.sim.deviceLimits = *o.deviceLimits;
  const CacheOptions cache = voxelCacheOptions(o);
  useVoxelCache(options, cache, console);
  if (o.voxelMemoryBytes) {
    const std::uint64_t budget = *o.voxelMemoryBytes;
    Console* warnings = &console;
    options.budgetedVoxelizeFn = [cache, budget, warnings](std::span<const SceneObject* const> objects,
                                                           const VoxelizeOptions& vo,
                                                           const ProgressFn& progress) {
      BudgetedVoxmap v = voxelizeWithinBudget(objects, vo, cache, budget, progress);
      for (const std::string& w : v.warnings) warnings->warning(w);
      if (v.pager) {
        warnings->note("static voxels: " + std::to_string(v.wordBytes >> 20) +
                       " MiB of words paged through " +
                       std::to_string((v.pager->slotCount() * v.voxmap.pagedArrays().blockBytes) >> 20) +
                       " MiB of memory");
      }
      return v;
    };
  }
  return options;
}

}  // namespace voxhap::cli
