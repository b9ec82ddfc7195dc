// `voxhap demo`: the main job as a whole session (issue 14): three peers on loopback in
// the built-in landing gear for a crew, two users sharing the actuator and guiding it out
// together, a third lifting the spare actuator into its way and back, scripted; then a
// summary of what every peer showed.

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <future>
#include <iomanip>
#include <memory>
#include <sstream>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "app/cli/command.h"
#include "app/cli/number_format.h"
#include "app/commands/commands.h"
#include "app/controller/controller_run.h"
#include "app/crew_session.h"
#include "app/extraction.h"
#include "app/scene_source.h"
#include "app/session_shots.h"
#include "app/sim_options.h"
#include "app/view/view_run.h"
#include "haptics/collide/exact_penetration.h"
#include "haptics/core/error.h"
#include "haptics/device/motion_script.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/scene_model.h"
#include "haptics/voxel/voxmap.h"
#include "render/gl_context.h"

namespace voxhap::cli {
namespace {

constexpr const char* kScene = "landing-gear-crew";
/// Within this of its script's end the actuator has come out (the end is 0.43 m outside
/// the gear), m.
constexpr double kArrivedM = 0.010;

std::filesystem::path script(const char* name) {
  return std::filesystem::path(VOXHAP_ASSET_DIR) / "scripts" / name;
}

/// The pictures' size, px.
constexpr glm::ivec2 kShotSizePx{1280, 720};

/// What `voxhap demo` was given.
struct DemoArgs {
  SimOptions sim;
  bool noPassivity = false;
  bool noRealtime = false;
  bool json = false;
  std::filesystem::path screenshotDir = "voxhap-demo";
  bool noScreenshots = false;
  bool headless = false;
};

/// The live window's frame rate cap, Hz: three haptic peers share this machine with it.
constexpr double kWindowFrameRateHz = 30.0;

/// A picture the demo wrote, and what it shows.
struct ShotFigures {
  std::filesystem::path file;
  double playedS = 0.0;
  std::string what;
};

/// The figures of one peer, from its summary and the samples of it.
struct PeerFigures {
  std::string user, role;
  nlohmann::json summary;
  double finalActuatorOffM = 0.0;  ///< from the script's end, as this peer showed it last
  double divergentS = 0.0;         ///< sampled time with the actuator flagged divergent
  std::uint32_t mostContacts = 0;  ///< of its user's part
};

/// The deepest exact overlap of a pair of moving parts, over every peer's samples.
struct PairFigures {
  std::size_t a = 0, b = 0;  ///< the parts, as the session's objects
  std::unique_ptr<ExactPenetration> exact;
  double deepestM = 0.0;
  std::size_t peer = 0;
  double atS = 0.0;
};

/// cyd's view of the session at a few moments, as its peer showed it: ann's instance of the
/// actuator (the lowest-numbered sharer's, which cyd follows), and bob's too, marked, while
/// the two were divergent; and the moment they were furthest apart on cyd's peer, when they
/// ever were divergent. Throws voxhap::Error without a display.
std::vector<ShotFigures> writeDemoShots(const Scene& scene, const CrewSessionResult& r, std::size_t actuator,
                                        const std::filesystem::path& dir) {
  constexpr std::size_t kCyd = 2, kPeers = 3;
  // the session samples every peer in turn: samples[3 i + k] is peer k's i-th
  const std::size_t rounds = r.samples.size() / kPeers;
  if (rounds == 0) throw Error("the session recorded no samples");
  const auto sample = [&r](std::size_t round, std::size_t peer) -> const CrewSample& {
    return r.samples[kPeers * round + peer];
  };
  const auto roundAt = [&](double playedS) {
    std::size_t i = 0;
    while (i + 1 < rounds && sample(i, kCyd).playedS < playedS) ++i;
    return i;
  };
  std::vector<std::pair<std::size_t, std::string>> moments = {
      {roundAt(1.0), "the actuator still seated in the gear"},
      {roundAt(17.0), "the spare actuator lifted into the actuator's way, which waits"},
      {rounds - 1, "the actuator out of the gear, at its path's end"}};
  double widestM = 0.0;
  std::size_t widest = 0;
  for (std::size_t i = 0; i < rounds; ++i) {
    const CrewSample& s = sample(i, kCyd);
    if (!s.otherInstance[actuator]) continue;
    const double apartM = glm::length(s.poses[actuator].position - s.otherInstance[actuator]->position);
    if (apartM > widestM) {
      widestM = apartM;
      widest = i;
    }
  }
  if (widestM > 0.0)
    moments.emplace_back(widest, "the actuator's instances furthest apart while divergent (" +
                                     fixed(widestM * 1e3, 1) + " mm): bob's marked");

  std::filesystem::create_directories(dir);
  std::vector<SessionShot> shots;
  std::vector<ShotFigures> figures;
  const SceneObject& moved = *scene.find("actuator");
  Bounds focus;
  for (std::size_t i = 0; i < rounds; i += 10) focus.add(boundsAt(moved, sample(i, kCyd).poses[actuator]));
  for (std::size_t m = 0; m < moments.size(); ++m) {
    const CrewSample& s = sample(moments[m].first, kCyd);
    SessionShot& shot = shots.emplace_back();
    shot.file = dir / ("demo-" + std::to_string(m + 1) + ".png");
    shot.poses = s.poses;
    shot.otherInstances = s.otherInstance;
    figures.push_back({shot.file, s.playedS, moments[m].second});
  }
  writeSessionShots(scene, r.objects, focus, shots, kShotSizePx);
  return figures;
}

/// A window on cyd's peer while the session plays (a passive `voxhap view --connect`); it
/// closes when the session ends, or earlier by its user, which leaves the session playing.
/// Returns the window's summary (`voxhap view --json`), none when it could not open.
std::optional<nlohmann::json> watchSession(std::future<std::uint16_t> port,
                                           std::future<CrewSessionResult>& session, const CommandContext& c) {
  using namespace std::chrono_literals;
  while (port.wait_for(100ms) != std::future_status::ready) {
    if (session.wait_for(0s) == std::future_status::ready) return std::nullopt;  // it failed to start
  }
  ViewOptions view;
  view.scene = kScene;
  view.connect = HostPort{"127.0.0.1", port.get()};
  view.passive = true;
  view.endsWithController = true;
  view.maxFrameRateHz = kWindowFrameRateHz;
  view.json = true;
  std::ostringstream summary;
  try {
    runView(view, c.console, summary);
  } catch (const std::exception& e) {
    c.console.warning(std::string("the window closed: ") + e.what());
    return std::nullopt;
  }
  return nlohmann::json::parse(summary.str(), nullptr, false);
}

int runDemo(const DemoArgs& args, const CommandContext& c) {
  CrewSessionOptions options;
  options.scene = kScene;
  options.model = sceneModelOptions(args.sim, c.console, kExtractionVoxelSizeM, kExtractionPointSpacingM);
  // a fixed capacity, so that a loaded machine plays the same session (DESIGN §6)
  if (!args.sim.capacity) options.model.sim.coherence.capacityTests = kDemoCapacityTests;
  options.passivity = !args.noPassivity;
  options.realtime = !args.noRealtime;
  options.users = {{"ann", "actuator", true, script("actuator-extract.txt")},
                   {"bob", "actuator", true, script("actuator-extract.txt")},
                   {"cyd", "spare-actuator", false, script("crew-spare-block.txt")}};
  const MotionScript path = loadMotionScript(options.users[0].script);
  const glm::dvec3 pathEnd = path.keyframes().back().handleWorld.position;

  c.console.info("preparing " + std::string(kScene) + " (generated and voxelized once, then cached)");
  const Scene scene = loadScene(kScene, kDefaultSeed, c.console);
  const bool window = !args.headless && render::hasDisplay();
  std::promise<std::uint16_t> watched;  // cyd's peer's front-end port, for the window
  options.onStarted = [&watched](const std::vector<std::uint16_t>& ports) { watched.set_value(ports[2]); };
  // the window shows how far it has got; without one, a progress bar on a terminal
  const std::function<void(double)> progress = window ? nullptr : c.console.progress("playing the session");
  std::future<CrewSessionResult> session =
      std::async(std::launch::async, [&] { return runCrewSession(options, c.console, progress); });
  const std::optional<nlohmann::json> windowSummary =
      window ? watchSession(watched.get_future(), session, c) : std::nullopt;
  const CrewSessionResult r = session.get();

  const auto indexOf = [&r](const std::string& name) {
    return static_cast<std::size_t>(std::find(r.objects.begin(), r.objects.end(), name) - r.objects.begin());
  };
  const std::size_t actuator = indexOf("actuator");
  std::vector<PeerFigures> peers(options.users.size());
  for (std::size_t k = 0; k < peers.size(); ++k) {
    const CrewUser& u = options.users[k];
    peers[k].user = u.name;
    peers[k].role = (u.share ? "shares " : "owns ") + u.object;
    peers[k].summary = r.summaries[k];
  }
  std::vector<double> lastS(peers.size(), 0.0);
  for (const CrewSample& s : r.samples) {
    PeerFigures& p = peers[s.peer];
    p.finalActuatorOffM = glm::length(s.poses[actuator].position - pathEnd);
    if (s.divergent[actuator]) p.divergentS += s.playedS - lastS[s.peer];
    p.mostContacts = std::max(p.mostContacts, s.contacts[indexOf(options.users[s.peer].object)]);
    lastS[s.peer] = s.playedS;
  }
  const bool cameOut = std::all_of(peers.begin(), peers.end(),
                                   [](const PeerFigures& p) { return p.finalActuatorOffM < kArrivedM; });

  // exact overlap of every pair of moving parts, at the poses every peer showed, every
  // other sample of each (each measure near contact takes tens of ms)
  c.console.info("measuring overlaps exactly on the meshes");
  // each part's own surface voxmap filters the other's probes (exact_penetration.h,
  // "Filter"): without them every probe inside the other's bounding box took the exact test
  std::vector<ExactBody> bodies;
  std::vector<Voxmap> voxmaps;
  voxmaps.reserve(r.objects.size());
  for (const std::string& name : r.objects) {
    ExactBody& body = bodies.emplace_back();
    const SceneObject& object = *scene.find(name);
    for (const Part& part : object.parts) body.meshesLocal.push_back(&part.mesh);
    body.voxmapLocal = &voxmaps.emplace_back(movingSurfaceVoxmap(object, options.model, {}));
  }
  const double probeSpacingM = options.model.staticVoxelSizeM / kProbesPerVoxel;
  std::vector<PairFigures> pairs;
  for (std::size_t a = 0; a < bodies.size(); ++a) {
    for (std::size_t b = a + 1; b < bodies.size(); ++b)
      pairs.push_back({a, b, std::make_unique<ExactPenetration>(bodies[a], bodies[b], probeSpacingM)});
  }
  // a thread for each pair: they share nothing
  std::vector<std::future<void>> measuring;
  for (PairFigures& p : pairs) {
    measuring.push_back(std::async(std::launch::async, [&r, &p] {
      for (std::size_t n = 0; n < r.samples.size(); n += 2) {
        const CrewSample& s = r.samples[n];
        const PenetrationSample m = p.exact->measure(s.poses[p.a], s.poses[p.b], false);
        if (m.depthM <= p.deepestM) continue;
        p.deepestM = m.depthM;
        p.peer = s.peer;
        p.atS = s.playedS;
      }
    }));
  }
  for (std::future<void>& f : measuring) f.get();

  std::vector<ShotFigures> shots;
  if (!args.noScreenshots) {
    c.console.info("drawing cyd's view at a few moments into " + args.screenshotDir.string());
    try {
      shots = writeDemoShots(scene, r, actuator, args.screenshotDir);
    } catch (const Error& e) {
      c.console.warning(std::string("no pictures: ") + e.what());
    }
  }

  if (args.json) {
    nlohmann::ordered_json j = {{"scene", kScene},
                                {"played_s", options.playS},
                                {"wall_s", r.wallS},
                                {"passivity", options.passivity},
                                {"samples", r.samples.size()},
                                {"actuator_came_out", cameOut}};
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const PeerFigures& p : peers) {
      list.push_back({{"user", p.user},
                      {"role", p.role},
                      {"final_actuator_off_end_m", p.finalActuatorOffM},
                      {"actuator_divergent_s", p.divergentS},
                      {"most_contacts", p.mostContacts},
                      {"controller", p.summary}});
    }
    j["peers"] = list;
    nlohmann::ordered_json overlaps = nlohmann::ordered_json::array();
    for (const PairFigures& p : pairs) {
      overlaps.push_back({{"a", r.objects[p.a]},
                          {"b", r.objects[p.b]},
                          {"deepest_m", p.deepestM},
                          {"on_peer_of", p.deepestM > 0.0 ? nlohmann::ordered_json(peers[p.peer].user)
                                                          : nlohmann::ordered_json()},
                          {"at_s", p.atS}});
    }
    j["exact_overlaps"] = overlaps;
    nlohmann::ordered_json pictures = nlohmann::ordered_json::array();
    for (const ShotFigures& s : shots)
      pictures.push_back({{"file", s.file.string()}, {"played_s", s.playedS}, {"shows", s.what}});
    j["pictures"] = pictures;
    j["window"] = windowSummary ? *windowSummary : nlohmann::json();
    c.out << j.dump(2) << "\n";
    return kExitOk;
  }
  c.out << "scene            " << kScene << ": ann and bob share the actuator and pull it out along "
        << options.users[0].script.filename().string()
        << "; cyd lifts the spare actuator into its way and back ("
        << options.users[2].script.filename().string() << ")\n"
        << "played           " << fixed(options.playS, 0) << " s of scripts in " << fixed(r.wallS, 1)
        << " s; coupling " << (options.passivity ? "with" : "without") << " the passivity controller\n";
  for (const PeerFigures& p : peers) {
    const nlohmann::json& s = p.summary;
    c.out << "peer " << std::left << std::setw(12) << p.user << std::right << p.role << ": "
          << s.value("frames", 0) << " frames, period p99 " << fixed(s["period"].value("p99_us", 0.0), 0)
          << " us, " << s.value("missed_deadlines", 0) << " missed deadlines";
    std::string delays;
    for (const nlohmann::json& m : s["peer"]["members"]) {
      if (!m["one_way_ms"].is_null())
        delays += (delays.empty() ? "" : ", ") + fixed(m["one_way_ms"].get<double>(), 2);
    }
    if (!delays.empty()) c.out << "; one-way " << delays << " ms";
    for (const nlohmann::json& sh : s["peer"]["shared"]) {
      if (!sh.contains("coupling")) continue;
      const nlohmann::json& k = sh["coupling"];
      c.out << "; instances apart " << fixed(k.value("mean_apart_mm", 0.0), 3) << " mm on average, "
            << fixed(k.value("max_apart_mm", 0.0), 2) << " mm at most, divergent "
            << fixed(k.value("divergent_ticks", 0) / PeerRunOptions{}.streamHz, 1) << " s";
    }
    c.out << "; its part's most contacts " << p.mostContacts << "; actuator "
          << fixed(p.finalActuatorOffM * 1e3, 1) << " mm from the path's end\n";
  }
  for (const PairFigures& p : pairs) {
    c.out << "exact overlap    " << r.objects[p.a] << " and " << r.objects[p.b] << ": "
          << fixed(p.deepestM * 1e3, 3) << " mm";
    if (p.deepestM > 0.0) c.out << " (on " << peers[p.peer].user << "'s peer, " << fixed(p.atS, 2) << " s)";
    c.out << "\n";
  }
  c.out << "came out         " << (cameOut ? "yes" : "no") << ": the actuator "
        << (cameOut ? "reached" : "did not reach")
        << " its path's end (0.43 m outside the gear) on every peer\n";
  if (windowSummary) {
    const nlohmann::json& w = *windowSummary;
    c.out << "window           cyd's view, " << w.value("frames_cached", 0) + w.value("frames_uncached", 0)
          << " frames at " << fixed(w.value("fps_cached", 0.0), 1) << " fps (at most "
          << fixed(kWindowFrameRateHz, 0) << ")\n";
  }
  for (const ShotFigures& s : shots)
    c.out << "picture          " << s.file.string() << ": " << fixed(s.playedS, 1) << " s, " << s.what
          << "\n";
  return kExitOk;
}

}  // namespace

void addDemoCommand(CommandTree& tree) {
  CommandHelp help;
  help.summary = "The main job: three peers pull the actuator out of the landing gear together, and report.";
  help.usage =
      "voxhap demo [--voxel-size LENGTH] [--point-spacing LENGTH] [--capacity N] [--no-passivity]\n"
      "       [--no-realtime] [--headless] [--screenshots DIR | --no-screenshots] [--cache-dir DIR]\n"
      "       [--no-cache] [--json]";
  help.description =
      "A design review of the paper's maintenance task (§7) by three engineers, each at a peer\n"
      "of their own (`voxhap peer`; here all three in this process, on loopback): ann and bob\n"
      "share the hydraulic actuator of the built-in landing gear for a crew (type-2: each\n"
      "peer simulates its own instance, coupled to the other's) and guide it out together\n"
      "along assets/scripts/actuator-extract.txt; cyd owns the spare actuator (type-1) and\n"
      "lifts it into the actuator's way and back (crew-spare-block.txt): the actuator meets it\n"
      "at about 14.6 s, waits, and goes on once it is lowered. The scene is generated and\n"
      "voxelized on first use and cached; the scripts play for 30 s, in real time, at 1 kHz on\n"
      "every peer.\n\n"
      "Summary: per peer, its frames, period p99 and missed deadlines, the one-way delays it\n"
      "measured, on the sharers how far apart the two instances were (mean, most) and for how\n"
      "long they were divergent, its part's most contacts, and how far from its path's end\n"
      "the actuator ended; the deepest exact overlap of each pair of moving parts as any peer\n"
      "showed them (Embree, both surfaces probed a quarter voxel apart, every other pose\n"
      "recorded at 20 Hz); and whether the actuator came out: reached its path's end, 0.43 m\n"
      "outside the gear, within 10 mm on every peer. The overlap with the static gear is\n"
      "measured by `voxhap extract`, the same job for one user, offline.\n\n"
      "Where there is a display (DISPLAY or WAYLAND_DISPLAY) a window shows the session live as\n"
      "cyd's peer shows it (`voxhap view --connect` on it, passive, at most 30 frames a second);\n"
      "it closes when the session ends. --headless: none.\n\n"
      "Pictures: cyd's view at 1 s, at 17 s (the spare in the actuator's way) and at the end,\n"
      "1280x720 PNG files in --screenshots DIR (default ./voxhap-demo). Where ann's and bob's\n"
      "instances of the actuator were divergent, bob's is drawn too, in translucent orange (cyd\n"
      "follows and collides with ann's); a fourth picture shows them furthest apart, when they\n"
      "ever were. Drawing needs an X display: without one (and without `xvfb-run -a`, which\n"
      "`bash tools/setup.sh demo` uses then) the demo says so and reports without pictures.\n\n"
      "Examples:\n"
      "  voxhap demo\n"
      "  xvfb-run -a voxhap demo --headless --screenshots /tmp/demo\n"
      "  voxhap demo --no-passivity --no-screenshots --json";
  auto args = std::make_shared<DemoArgs>();
  CLI::App& command = tree.add(tree.root(), "demo", std::move(help),
                               [args](const CommandContext& c) { return runDemo(*args, c); });
  addSimOptions(command, args->sim, {SimOption::VoxelSize, SimOption::PointSpacing, SimOption::Capacity});
  command.get_option("--voxel-size")->description("voxel size of the static gear (default 2.5mm)");
  command.get_option("--point-spacing")->description("point spacing of the moving parts (default 1mm)");
  command.get_option("--capacity")->description("point tests per frame (default 20000, fixed)");
  command.add_flag("--no-passivity", args->noPassivity,
                   "couple the actuator's instances without the passivity controller");
  command.add_flag("--no-realtime", args->noRealtime, "no SCHED_FIFO or mlockall for the haptic threads");
  CLI::Option* pictures =
      command
          .add_option("--screenshots", args->screenshotDir, "folder for the pictures (default ./voxhap-demo)")
          ->type_name("DIR");
  command.add_flag("--no-screenshots", args->noScreenshots, "draw no pictures")->excludes(pictures);
  command.add_flag("--headless", args->headless, "no window, even where there is a display");
  addSimOptions(command, args->sim, {SimOption::Cache});
  command.add_flag("--json", args->json, "print one JSON summary on stdout instead of text");
}

}  // namespace voxhap::cli
