// `voxhap extract`: the paper's landing-gear job (§7) for one user, offline, scripted and
// headless: pull the hydraulic actuator out of the built-in landing gear and report how it
// went (`voxhap demo` runs it as a session of three peers).

#include <cmath>
#include <iomanip>
#include <sstream>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/number_format.h"
#include "app/commands/commands.h"
#include "app/exact_checks.h"
#include "app/extraction.h"
#include "app/extraction_options.h"
#include "app/scene_source.h"
#include "app/sim_options.h"
#include "app/sim_run.h"

namespace voxhap::cli {
namespace {

std::string mm(double metres, int decimals = 2) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(decimals) << metres * 1e3 << " mm";
  return s.str();
}

/// What `voxhap extract` was given.
struct ExtractArgs {
  ExtractionArgs extraction;
  bool json = false;
};

int runExtract(const ExtractArgs& args, const CommandContext& c) {
  ExtractionOptions options =
      extractionOptions(args.extraction, c.console, kExtractionVoxelSizeM, kExtractionPointSpacingM);
  if (!args.extraction.sim.capacity) options.model.sim.coherence.capacityTests = kDemoCapacityTests;
  const std::string scriptFile = args.extraction.scriptFile();
  const MotionScript script = loadMotionScript(scriptFile);
  const Scene scene = loadScene(args.extraction.sceneName(), kDefaultSeed, c.console);
  const ExtractionResult r = runExtraction(scene, script, options, c.console);

  const FrameStats& stats = r.stats;
  const std::uint64_t deadlinesMet = stats.frames() - stats.framesOverBudget;
  const bool cameOut = r.cameOut();
  if (args.json) {
    nlohmann::ordered_json j = {{"scene", scene.sourceName},
                                {"moving", options.moving},
                                {"script", scriptFile},
                                {"voxel_size_m", options.model.staticVoxelSizeM},
                                {"point_spacing_m", options.model.pointSpacingM},
                                {"coherence", options.model.sim.coherence.enabled},
                                {"points", r.points},
                                {"duration_s", r.durationS}};
    const nlohmann::ordered_json frameSummary = frameStatsJson(stats);
    for (const auto& [key, value] : frameSummary.items()) j[key] = value;
    j["frames_within_1ms"] = deadlinesMet;
    const ExactCheckSummary& e = r.exact;
    j["max_penetration_m"] = e.maxDepthM;
    j["max_penetration_at_s"] = e.maxDepthAtS;
    j["max_penetration_frame"] =
        e.maxDepthM > 0.0 ? nlohmann::ordered_json(e.maxDepthFrame) : nlohmann::ordered_json(nullptr);
    j["max_penetration_world_m"] = {e.maxDepthWorld.x, e.maxDepthWorld.y, e.maxDepthWorld.z};
    j["max_penetration_into"] =
        e.maxDepthM > 0.0 ? nlohmann::ordered_json(e.maxDepthInto) : nlohmann::ordered_json(nullptr);
    j["min_clearance_m"] = std::isinf(e.minClearanceM) ? nlohmann::ordered_json(nullptr)
                                                       : nlohmann::ordered_json(e.minClearanceM);
    j["min_clearance_at_s"] = e.minClearanceAtS;
    j["penetration_every_frames"] = options.penetrationEvery;
    j["penetration_checks"] = e.checks;
    j["frames_with_penetration"] = e.framesWithPenetration;
    j["probe_spacing_m"] = r.probeSpacingM;
    j["probes_checked"] = r.probesChecked;
    j["near_probes"] = e.nearProbes;
    j["exact_probe_tests"] = e.candidates;
    j["exact_wall_s"] = e.wallS;
    j["path_length_m"] = r.pathLengthM;
    j["handle_progress_m"] = r.handleProgressM;
    j["actuator_progress_m"] = r.actuatorProgressM;
    j["final_lag_m"] = r.finalLagM;
    j["came_out"] = cameOut;
    j["completion_s"] = cameOut ? nlohmann::ordered_json(*r.completionS) : nlohmann::ordered_json(nullptr);
    j["clear_from_s"] =
        r.completionS ? nlohmann::ordered_json(*r.completionS) : nlohmann::ordered_json(nullptr);
    j["wall_s"] = r.wallS;
    c.out << j.dump(2) << "\n";
    return kExitOk;
  }
  c.out << "scene            " << scene.sourceName << "\nmoving           " << options.moving << " ("
        << r.points << " points at " << mm(options.model.pointSpacingM) << ", static voxels "
        << mm(options.model.staticVoxelSizeM) << ", "
        << (options.model.sim.coherence.enabled ? "time-critical sampling" : "brute force")
        << ")\nscript           " << scriptFile << "\n";
  printFrameStats(c.out, stats, options.model.sim.coherence.enabled);
  c.out << "within 1 ms      " << deadlinesMet << " of " << stats.frames() << " frames\n"
        << "max penetration  " << mm(r.exact.maxDepthM, 3) << " (exact, deepest surface probe";
  if (r.exact.maxDepthM > 0.0) {
    c.out << ", " << r.exact.maxDepthInto << ", at t = " << fixed(r.exact.maxDepthAtS, 3) << " s at ("
          << fixed(r.exact.maxDepthWorld.x, 3) << ", " << fixed(r.exact.maxDepthWorld.y, 3) << ", "
          << fixed(r.exact.maxDepthWorld.z, 3) << ") m";
  }
  c.out << "; " << r.exact.framesWithPenetration << " of " << r.exact.checks
        << " frames checked had one inside)\n"
        << "min clearance    "
        << (std::isinf(r.exact.minClearanceM)
                ? std::string("more than ") + std::to_string(voxhap::kClearanceVoxels) + " voxels"
                : mm(r.exact.minClearanceM, 3) + " at t = " + fixed(r.exact.minClearanceAtS, 3) + " s")
        << " (exact, between the actuator's and the static surfaces)\n"
        << "exact probes     " << r.probesChecked << " on the actuator, " << mm(r.probeSpacingM, 3)
        << " apart, and the static surface near it; " << fixed(r.exact.wallS, 1) << " s measuring\n"
        << "along the path   actuator " << mm(r.actuatorProgressM, 1) << ", handle "
        << mm(r.handleProgressM, 1) << " of " << mm(r.pathLengthM, 1) << "; " << mm(r.finalLagM, 1)
        << " apart at the end\n"
        << "came out         " << (cameOut ? "yes" : "no")
        << (r.completionS ? "; clear of the gear (beyond its distance field) from t = " +
                                fixed(*r.completionS, 2) + " s"
                          : std::string("; still within the gear's distance field at the end"))
        << "\nwall time        " << r.wallS << " s (model from the cache, frames and measurements)\n";
  return kExitOk;
}

}  // namespace

void addExtractCommand(CommandTree& tree) {
  CommandHelp help;
  help.summary = "The main job for one user, offline: pull the actuator out of the landing gear, and report.";
  help.usage =
      "voxhap extract [--voxel-size LENGTH] [--point-spacing LENGTH] [--capacity N] [--brute-force]\n"
      "       [--duration SECONDS] [--penetration-every N] [--probe-spacing LENGTH] [--script FILE]\n"
      "       [--scene SCENE --move NAME] [--cache-dir DIR] [--no-cache] [--json]";
  help.description =
      "The paper's maintenance task (§7): the hydraulic actuator of the built-in landing gear\n"
      "(generated on first use and cached under $VOXHAP_CACHE_DIR, $XDG_CACHE_HOME/voxhap or\n"
      "~/.cache/voxhap, as are its voxels) is pulled out by a scripted handle through the 6-DOF\n"
      "virtual coupling, at 1 kHz simulated time, with time-critical sampling at a fixed\n"
      "capacity of 20,000 point tests a frame (--capacity), so that a loaded machine runs the\n"
      "same job; a progress bar goes to stderr on a terminal.\n\n"
      "The path (assets/scripts/actuator-extract.txt): the actuator lies along x with its two\n"
      "eyes between the plates of two clevises, pins out. Straight along its axis each eye runs\n"
      "into its clevis base within 15 mm, so it cannot be pulled lengthwise: it leaves the\n"
      "clevises sideways (-y, 0.16 m, rocked ±1° about the vertical as a fitter would), drops\n"
      "0.36 m below the hydraulic lines that run alongside (beside the brace under it), then\n"
      "comes out sideways under the lines (-y, 1.09 m), at 0.1 m/s, then holds: 18 s in all.\n\n"
      "Summary: frames; frames whose compute time stayed within the 1 ms frame; missed\n"
      "deadlines as the engine counts them (more points in contact than the capacity: nothing\n"
      "moved); contacts (max and mean); max force; mean MaxTravel share; the max exact\n"
      "penetration; how far the actuator's centre got along the path against the handle's;\n"
      "whether it came out: reached the path's end (within 10 mm) clear of the gear, and from\n"
      "when on it stayed clear (every point beyond the static distance field, i.e. more than\n"
      "8 voxels from any static surface; checked every 100 frames).\n\n"
      "With --json the same figures as one document; completion_s is the time from which it\n"
      "stayed clear when it came out (null otherwise), clear_from_s the same whether or not it\n"
      "reached the path's end.\n\n"
      "Exact penetration: the deepest any point of the actuator's surface gets inside a static\n"
      "part, or any point of the static surface inside the actuator, measured with Embree on\n"
      "the meshes after the run, at the poses it recorded (probing between frames would evict\n"
      "the frames' data from the caches and so slow, and change, the run). Both surfaces are\n"
      "sampled by probes a quarter of a static voxel apart (--probe-spacing), on every\n"
      "triangle's vertices, edges and interior, so that an edge or a face cutting in between\n"
      "vertices is seen; the static surface only where the actuator comes near it. A probe\n"
      "is inside when rays from it cross a part an odd number of times (three rays voting); its depth is its "
      "distance to\n"
      "the other surface. To keep this cheap, voxmaps filter first (the static scene's, and\n"
      "the actuator's at the point spacing, voxelized through the cache): a probe in a\n"
      "free-space voxel of the other body is outside, one in an interior voxel inside, and\n"
      "only probes in surface voxels take the vote; groups of probes far from the other body\n"
      "are skipped at once. Measured every frame by default (--penetration-every N checks\n"
      "every Nth frame and the last). Vertex and edge probes up to 4 voxels out get their\n"
      "exact distance to the other surface instead: the min clearance.\n\n"
      "Examples:\n"
      "  voxhap extract\n"
      "  voxhap extract --voxel-size 1.25mm --point-spacing 0.7mm --json\n"
      "  voxhap extract --brute-force --duration 2";
  auto args = std::make_shared<ExtractArgs>();
  CLI::App& command = tree.add(tree.root(), "extract", std::move(help),
                               [args](const CommandContext& c) { return runExtract(*args, c); });
  SimOptions& sim = args->extraction.sim;
  addSimOptions(
      command, sim,
      {SimOption::VoxelSize, SimOption::PointSpacing, SimOption::PaperContact, SimOption::Capacity,
       SimOption::VoxelMemory, SimOption::BruteForce, SimOption::DeviceProfile, SimOption::Duration});
  command.get_option("--voxel-size")->description("voxel size of the static gear (default 2.5mm)");
  command.get_option("--point-spacing")->description("point spacing of the actuator (default 1mm)");
  command.get_option("--duration")->description("simulated time (default: the whole script, 18 s)");
  command.get_option("--capacity")->description("point tests per frame (default 20000, fixed)");
  addExtractionOptions(command, args->extraction);
  addSimOptions(command, sim, {SimOption::Cache});
  command.add_flag("--json", args->json, "print one JSON summary on stdout instead of text");
}

}  // namespace voxhap::cli
