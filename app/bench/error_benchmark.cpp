// `voxhap bench error`: time against error over the analytic scenes of CONVENTIONS
// (sphere on plane, box on plane, ball in socket, peg in hole, crossed rods), swept over
// voxel size, field bit width, geometrical awareness and coherence.
//
// Each run lets the object settle (free under gravity; the upper rod held by its handle,
// lowered onto the exact touching pose), then measures at the final pose:
//   gap_m            the signed gap between the exact meshes, Embree ground truth:
//                    positive = clearance, negative = the deepest sampled point of either
//                    surface inside the other (see signedGapM);
//   force_angle_deg  the angle between the contact force and the analytic normal, which is
//                    +z in every scene here: the plane's normal; the common normal of the
//                    crossed rods; for the ball and the peg the resultant that balances
//                    gravity;
//   compute_p50_us   the median time of step() over the run.
// Every point shell is taken at the voxel size of the static voxmap, or --points-per-voxel
// times finer (the ball's displaced half a voxel inward, as in the rotation benchmark). With 2-bit fields the
// largest value is the first free layer, so the force layer moves there (3 instead of 4).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <set>

#include <CLI/CLI.hpp>
#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "app/bench/analytic_scenes.h"
#include "app/bench/benchmark.h"
#include "app/cache_options.h"
#include "app/cli/number_format.h"
#include "app/sim_options.h"
#include "haptics/core/error.h"
#include "haptics/geometry/embree_scene.h"
#include "haptics/geometry/mesh_builder.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/sim/local_simulation.h"
#include "haptics/sim/scene_model.h"
#include "haptics/voxel/voxel_encoding.h"

namespace voxhap::cli {
namespace {

constexpr double kDefaultSizesM[] = {2e-3, 1e-3, 0.5e-3, 0.25e-3};
constexpr int kDefaultBits[] = {2, 4, 8};
const glm::dvec3 kGravity(0.0, 0.0, -9.81);
/// Objects start this many voxels above touching (inside the force layer's reach at 2).
constexpr double kStartGapVoxels = 3.0;
/// Sampling of the exact meshes for the gap: edges every kEdgeSampleM, near the other
/// object only (its bounds grown by kGapMarginM); farther than that is "no contact".
constexpr double kEdgeSampleM = 20e-6;
constexpr double kGapMarginM = 5e-3;
/// The upper rod: its handle goes from the start to the exact touching pose in this time.
constexpr double kRodLowerS = 0.2;
constexpr double kRodHalfM = 0.004;
constexpr double kRodHalfLengthM = 0.03;

/// One analytic scene of the sweep.
struct ErrorScene {
  const char* name;
  const char* moving;      ///< the object that moves
  bool held;               ///< coupled to a handle lowered onto the touching pose (else free)
  bool displaceHalfVoxel;  ///< points half a voxel inward (mating surfaces)
  int frames;              ///< settling frames
  bool quick;              ///< in --quick
  std::function<Scene(double voxelM)> build;
};

Scene sphereOnPlane(double voxelM) {
  Scene scene;
  scene.sourceName = "sphere-on-plane";
  scene.objects.push_back(plateObject("plate", 0.03, 0.01));
  constexpr double r = 0.01;
  scene.objects.push_back(sphereObject("sphere", {0.0, 0.0, r + kStartGapVoxels * voxelM}, r));
  return scene;
}

Scene boxOnPlane(double voxelM) {
  Scene scene;
  scene.sourceName = "box-on-plane";
  scene.objects.push_back(plateObject("plate", 0.03, 0.01));
  const glm::dvec3 half(0.01, 0.01, 0.005);
  scene.objects.push_back(boxObject("box", {0.0003, -0.0007, half.z + kStartGapVoxels * voxelM}, half));
  return scene;
}

/// Height of the lower rod's top edge: square rods turned 45° about their axes.
double rodEdgeM() {
  return kRodHalfM * std::numbers::sqrt2;
}

Scene crossedRods(double voxelM) {
  Scene scene;
  scene.sourceName = "crossed-rods";
  SceneObject lower = boxObject("lower", glm::dvec3(0.0), glm::dvec3(kRodHalfLengthM, kRodHalfM, kRodHalfM),
                                ObjectRole::Static);
  TriangleMesh mesh;
  appendBox(mesh, glm::rotate(glm::dmat4(1.0), std::numbers::pi / 4, glm::dvec3(1.0, 0.0, 0.0)),
            glm::dvec3(kRodHalfLengthM, kRodHalfM, kRodHalfM));
  lower.parts[0] = makePart("lower", glm::vec4(1.0f), std::move(mesh));
  scene.objects.push_back(std::move(lower));
  SceneObject upper = boxObject("upper", glm::dvec3(0.0), glm::dvec3(kRodHalfM, kRodHalfLengthM, kRodHalfM));
  TriangleMesh upperMesh;
  const glm::dmat4 at =
      glm::translate(glm::dmat4(1.0), glm::dvec3(0.0, 0.0, 2.0 * rodEdgeM() + kStartGapVoxels * voxelM));
  appendBox(upperMesh, glm::rotate(at, std::numbers::pi / 4, glm::dvec3(0.0, 1.0, 0.0)),
            glm::dvec3(kRodHalfM, kRodHalfLengthM, kRodHalfM));
  upper.parts[0] = makePart("upper", glm::vec4(1.0f), std::move(upperMesh));
  scene.objects.push_back(std::move(upper));
  return scene;
}

const std::vector<ErrorScene>& errorScenes() {
  static const std::vector<ErrorScene> scenes = {
      {"sphere-on-plane", "sphere", false, false, 1200, true, sphereOnPlane},
      {"box-on-plane", "box", false, false, 1200, true, boxOnPlane},
      {"ball-and-socket", "ball", false, true, 600, false, [](double) { return makeBallAndSocket(); }},
      {"peg-in-hole", "peg", false, false, 1000, false, [](double) { return makePegInHole(); }},
      {"crossed-rods", "upper", true, false, 1000, false, crossedRods},
  };
  return scenes;
}

std::vector<BenchColumn> errorColumns() {
  return {
      {"scene", "scene", BenchStyle::Text},
      {"contact", "contact", BenchStyle::Text},
      {"voxel_size_m", "voxel mm", BenchStyle::Millimetres, 2},
      {"bits", "bits", BenchStyle::Count},
      {"awareness", "aware", BenchStyle::Count},
      {"coherence", "coherent", BenchStyle::Count},
      {"point_spacing_m", "spacing mm", BenchStyle::Millimetres, 3},
      {"points", "points", BenchStyle::Count},
      {"compute_p50_us", "p50 us", BenchStyle::Fixed, 1},
      {"gap_m", "gap mm", BenchStyle::Millimetres, 3},
      {"force_angle_deg", "angle deg", BenchStyle::Fixed, 2},
      {"abs_gap_m", "|gap| mm", BenchStyle::Millimetres, 3},
      {"gap_over_voxel", "gap/voxel", BenchStyle::Fixed, 2},
      {"contacts", "contacts", BenchStyle::Count},
      {"speed_mps", "speed m/s", BenchStyle::Scientific},
      {"drop_m", "drop mm", BenchStyle::Millimetres, 3},
      {"missed_deadlines", "missed", BenchStyle::Count},
  };
}

/// Samples of `mesh`: its vertices and points every kEdgeSampleM along its edges, those
/// inside `near` only.
std::vector<glm::dvec3> meshSamples(const TriangleMesh& mesh, const Bounds& near) {
  auto inside = [&near](const glm::dvec3& p) {
    return p.x >= near.min.x && p.y >= near.min.y && p.z >= near.min.z && p.x <= near.max.x &&
           p.y <= near.max.y && p.z <= near.max.z;
  };
  std::vector<glm::dvec3> samples;
  for (const glm::vec3& v : mesh.positionsWorld) {
    if (inside(glm::dvec3(v))) samples.emplace_back(v);
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const glm::uvec3& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) edges.emplace(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]));
  }
  for (const auto& [a, b] : edges) {
    const glm::dvec3 pa(mesh.positionsWorld[a]), pb(mesh.positionsWorld[b]);
    const auto n = static_cast<int>(std::ceil(glm::length(pb - pa) / kEdgeSampleM));
    for (int i = 1; i < n; ++i) {
      const glm::dvec3 p = pa + (pb - pa) * (static_cast<double>(i) / n);
      if (inside(p)) samples.push_back(p);
    }
  }
  return samples;
}

Bounds boundsOf(const TriangleMesh& mesh, double growM) {
  Bounds b;
  for (const glm::vec3& v : mesh.positionsWorld) b.add(glm::dvec3(v));
  b.min -= glm::dvec3(growM);
  b.max += glm::dvec3(growM);
  return b;
}

/// The least signed distance of `samples` to the surface of `scene`: positive outside,
/// negative inside; +infinity when none is within kGapMarginM.
double leastSignedDistance(std::span<const glm::dvec3> samples, const EmbreeScene& scene) {
  double least = std::numeric_limits<double>::infinity();
  InsideVoteScratch vote;
  for (const glm::dvec3& p : samples) {
    const std::optional<ClosestSurfacePoint> q = scene.closestPoint(p, kGapMarginM);
    if (!q) continue;
    const double d = scene.insideAnyPart(p, 1e3, vote) ? -q->distanceM : q->distanceM;
    least = std::min(least, d);
  }
  return least;
}

/// The signed gap between `moving` (its mesh at `pose`) and the static meshes: the least
/// signed distance of samples of either surface (vertices, and edges every 20 µm) to the
/// other, near it. Exact for a vertex or an edge facing a face or an edge, as at rest on
/// a plane, in a socket, on a rim or across a rod; when they overlap, the deepest sampled
/// point of either surface inside the other (for crossing edges that is the depth to
/// the nearest face, below the depth along the common normal). Infinity: more than 5 mm.
double signedGapM(const Scene& scene, const SceneObject& moving, const Pose& pose) {
  const TriangleMesh movingMesh = posedMesh(moving, pose);
  std::vector<const TriangleMesh*> staticMeshes;
  for (const SceneObject& object : scene.objects) {
    if (&object == &moving) continue;
    for (const Part& part : object.parts) staticMeshes.push_back(&part.mesh);
  }
  const TriangleMesh* movingOne[] = {&movingMesh};
  const EmbreeScene movingScene(movingOne);
  const EmbreeScene staticScene(staticMeshes);
  double gap = leastSignedDistance(meshSamples(movingMesh, scene.bounds()), staticScene);
  const Bounds nearMoving = boundsOf(movingMesh, kGapMarginM);
  for (const TriangleMesh* mesh : staticMeshes) {
    gap = std::min(gap, leastSignedDistance(meshSamples(*mesh, nearMoving), movingScene));
  }
  return gap;
}

/// The upper rod's handle: from the start down to the exact touching pose in kRodLowerS, then held.
HandleInput rodHandleAt(double tS, double startGapM) {
  const double f = std::min(tS / kRodLowerS, 1.0);
  HandleInput h{{glm::dvec3(0.0, 0.0, -startGapM * f), identityQuat()}, {}, true};
  if (tS < kRodLowerS) h.velocity.linearWorld = glm::dvec3(0.0, 0.0, -startGapM / kRodLowerS);
  return h;
}

/// How one row's model is built, beside its scene and voxel size.
struct ModelSetting {
  int bits;
  bool aware;
  bool surface;        ///< contact by surface planes, else the paper's
  int pointsPerVoxel;  ///< point spacing = voxel size / pointsPerVoxel
};

void measureModel(const ErrorScene& es, const Scene& scene, SimModel& model, double voxelM,
                  const ModelSetting& setting, bool coherent, BenchTable& table) {
  model.coherence.enabled = coherent;
  LocalSimulation sim(model);
  const SimState& state = sim.state;
  std::vector<double> computeUs;
  computeUs.reserve(static_cast<std::size_t>(es.frames));
  const double startZM = state.bodies[0].comWorld.z;
  HandleInput handles[1];
  for (int f = 0; f < es.frames; ++f) {
    if (es.held) handles[0] = rodHandleAt(state.timeS + model.dtS, kStartGapVoxels * voxelM);
    sim.step(handles);
    computeUs.push_back(sim.lastStepS * 1e6);
  }
  const SceneObject& moving = *scene.find(es.moving);
  const double gap = signedGapM(scene, moving, objectPose(model, state, 0));
  const glm::dvec3 force = sim.object(0).contactForceWorld;

  const std::size_t r = table.addRow();
  table.set(r, "scene", std::string(es.name));
  table.set(r, "contact", std::string(setting.surface ? "surface" : "paper"));
  table.set(r, "voxel_size_m", voxelM);
  table.set(r, "bits", std::int64_t{setting.bits});
  table.set(r, "awareness", std::int64_t{setting.aware ? 1 : 0});
  table.set(r, "coherence", std::int64_t{coherent ? 1 : 0});
  table.set(r, "point_spacing_m", voxelM / setting.pointsPerVoxel);
  table.set(r, "points", static_cast<std::int64_t>(model.objects[0].shell.size()));
  table.set(r, "compute_p50_us", percentile(computeUs, 0.5));
  if (std::isfinite(gap)) {
    table.set(r, "gap_m", gap);
    // floored at 1 µm, below the ground truth's resolution, for the log axis of the plot
    table.set(r, "abs_gap_m", std::max(std::abs(gap), 1e-6));
    table.set(r, "gap_over_voxel", gap / voxelM);
  }
  if (glm::length(force) > 0.0) {
    const double cosine = std::clamp(force.z / glm::length(force), -1.0, 1.0);
    table.set(r, "force_angle_deg", std::acos(cosine) * 180.0 / std::numbers::pi);
  }
  table.set(r, "contacts", static_cast<std::int64_t>(sim.object(0).contacts));
  table.set(r, "speed_mps", glm::length(state.bodies[0].linearVelocityWorld));
  table.set(r, "drop_m", startZM - state.bodies[0].comWorld.z);
  table.set(r, "missed_deadlines", static_cast<std::int64_t>(sim.workspace.counters.missedDeadlines));
}

/// What `voxhap bench error` was given.
struct ErrorArgs {
  bool quick = false;
  std::vector<std::string> scenes;  ///< --scene, in order
  std::vector<double> voxelSizesM;  ///< --voxel-size, in order
  std::vector<int> bitWidths;       ///< --bits, in order
  std::vector<bool> surface;        ///< --contact, in order: surface planes (true) or the paper's
  std::vector<int> pointsPerVoxel;  ///< --points-per-voxel, in order
  SimOptions sim;                   ///< --capacity and the cache
};

BenchTable runError(const ErrorArgs& args, Console& console) {
  const bool quick = args.quick;
  std::vector<double> sizes = args.voxelSizesM;
  if (sizes.empty()) sizes.assign(std::begin(kDefaultSizesM), std::end(kDefaultSizesM));
  std::vector<int> bitWidths = args.bitWidths;
  if (bitWidths.empty()) bitWidths.assign(std::begin(kDefaultBits), std::end(kDefaultBits));
  const std::vector<std::string>& sceneNames = args.scenes;
  std::vector<bool> awareness = {true, false};
  if (quick) {
    sizes = {kDefaultSizesM[0]};
    bitWidths = {4};
    awareness = {true};
  }
  const double capacity = args.sim.capacity ? static_cast<double>(*args.sim.capacity) : 0.0;
  const CacheOptions cache = voxelCacheOptions(args.sim);

  BenchTable table("error", errorColumns());
  table.extra["quick"] = quick;
  table.extra["capacity"] = capacity > 0.0 ? "fixed" : "measured online";
  table.extra["gap_sampling_m"] = kEdgeSampleM;
  table.extra["force_layer_2_bit"] = VoxelEncoding::forBits(2).maxValue();
  std::vector<const ErrorScene*> chosen;
  for (const ErrorScene& es : errorScenes()) {
    const bool named = std::find(sceneNames.begin(), sceneNames.end(), es.name) != sceneNames.end();
    if (sceneNames.empty() ? (!quick || es.quick) : named) chosen.push_back(&es);
  }
  std::vector<bool> contacts = args.surface;
  if (contacts.empty()) contacts = {false, true};
  std::vector<int> densities = args.pointsPerVoxel;
  if (densities.empty()) densities = {1};
  std::vector<ModelSetting> settings;
  for (const int bits : bitWidths) {
    for (const bool aware : awareness) {
      for (const bool surface : contacts) {
        for (const int density : densities) settings.push_back({bits, aware, surface, density});
      }
    }
  }
  const std::size_t total = chosen.size() * sizes.size() * settings.size();
  std::size_t done = 0;
  const ProgressFn progress = console.progress("error");
  for (const ErrorScene* es : chosen) {
    for (const double voxelM : sizes) {
      const Scene scene = es->build(voxelM);
      if (voxelM == sizes.front() && std::string(es->name) == "ball-and-socket") {
        table.extra["ball_seat_gap_m"] =
            signedGapM(scene, *scene.find(es->moving), Pose{glm::dvec3(0.0), identityQuat()});
      }
      for (const ModelSetting& setting : settings) {
        SceneModelOptions options;
        options.staticVoxelSizeM = voxelM;
        options.pointSpacingM = voxelM / setting.pointsPerVoxel;
        options.bitsPerField = setting.bits;
        options.pointDisplacementM = es->displaceHalfVoxel ? -0.5 * voxelM : 0.0;
        options.sim.gravityWorld = kGravity;
        options.sim.geometricalAwareness = setting.aware;
        options.sim.surfaceContact = setting.surface;
        if (!setting.surface)
          options.sim.forceLayer =
              std::min(kDefaultForceLayer, VoxelEncoding::forBits(setting.bits).maxValue());
        options.sim.coherence.capacityTests = capacity;
        useVoxelCache(options, cache, console);
        SimModel model = buildSceneModel(scene, {es->moving}, options);
        model.objects[0].coupled = es->held;
        for (const bool coherent : {true, false})
          measureModel(*es, scene, model, voxelM, setting, coherent, table);
        if (progress) progress(static_cast<double>(++done) / static_cast<double>(total));
      }
    }
  }
  if (table.rowCount() == 0) throw UsageError("error: nothing to measure");
  return table;
}

}  // namespace

Benchmark errorBenchmark() {
  Benchmark b;
  b.name = "error";
  b.summary = "Time against error: gap and force direction at rest in the analytic scenes.";
  b.usage =
      "[--quick] [--scene NAME …] [--voxel-size LENGTH …] [--bits 2|4|8 …] [--contact paper|surface …]\n"
      "       [--points-per-voxel N …] [--capacity N] [--cache-dir DIR] [--no-cache]";
  b.description =
      "Sphere on plane, box on plane, ball in socket (built-in, ball seated, points half a\n"
      "voxel inward), peg in hole (built-in, 0.2 mm clearance, the peg dropped from 1 mm above\n"
      "the mouth) and crossed square rods (the upper held by its handle, lowered onto the\n"
      "exact touching pose), swept over voxel sizes 2, 1, 0.5 and 0.25 mm (points at the\n"
      "same spacing, or --points-per-voxel N times finer), 2-, 4- and 8-bit fields (2-bit:\n"
      "force layer 3, the only free layer), geometrical awareness on and off, the paper's\n"
      "contact (the voxels' tangent planes) and contact finer than a voxel (exact surface\n"
      "planes kept with the voxels), and coherence on (capacity measured online unless\n"
      "--capacity) and off. Free objects fall from 3 voxels above touching under gravity.\n\n"
      "After settling: gap_m, the signed gap between the exact meshes at the final pose from\n"
      "Embree (closest distances of vertices and 20 um edge samples of either surface to\n"
      "the other; negative: the deepest such point inside the other), force_angle_deg, the\n"
      "angle of the contact force from the analytic normal (+z in every scene: the plane's\n"
      "normal, the rods' common normal, the resultant that carries the weight), and\n"
      "compute_p50_us, the median frame. Also: final contacts, speed (settled?), drop_m (how\n"
      "far the moving object's centre fell: the peg has entered its hole when it dropped\n"
      "more than the 1 mm it hung above the mouth) and missed deadlines. The SVG plots\n"
      "compute_p50_us against |gap_m| (floored at 1 um), one series per contact.\n\n"
      "Contact finer than a voxel pushes a point from 0.75 point spacings off the surface, so\n"
      "its rest gap follows the spacing: with points a voxel apart a sphere or a box rests\n"
      "0.3 to 0.6 voxel off the plane, with --points-per-voxel 2 about 0.2 voxel.\n\n"
      "--quick: sphere and box on plane at 2 mm, 4-bit, aware, both contacts, coherence on\n"
      "and off.\n\n"
      "Examples:\n"
      "  voxhap bench error --quick --json\n"
      "  voxhap bench error --csv error.csv --svg error.svg\n"
      "  voxhap bench error --scene crossed-rods --voxel-size 0.5mm --bits 4 --contact surface\n"
      "  voxhap bench error --voxel-size 1mm --bits 4 --contact surface --points-per-voxel 1 \\\n"
      "      --points-per-voxel 2";
  b.addOptions = [](CLI::App& command) -> BenchRunFn {
    auto args = std::make_shared<ErrorArgs>();
    command.add_flag("--quick", args->quick, "a small subset for CI (see above)");
    addRepeatedOption(command, "--scene", "NAME", "a scene to measure (repeatable; default all five)",
                      [&scenes = args->scenes](const std::string& name) {
                        if (std::none_of(errorScenes().begin(), errorScenes().end(),
                                         [&](const ErrorScene& e) { return name == e.name; })) {
                          throw UsageError("--scene: no scene '" + name +
                                           "' (sphere-on-plane, box-on-plane, ball-and-socket, peg-in-hole, "
                                           "crossed-rods)");
                        }
                        scenes.push_back(name);
                      });
    addLengthListOption(command, "--voxel-size", args->voxelSizesM,
                        "a voxel size (repeatable; default 2, 1, 0.5, 0.25 mm)");
    addRepeatedOption(command, "--bits", "N", "a field bit width, 2, 4 or 8 (repeatable; default all three)",
                      [&bitWidths = args->bitWidths](const std::string& text) {
                        const auto bits = parseUnsigned(text, "bits");
                        if (bits != 2 && bits != 4 && bits != 8)
                          throw UsageError("--bits wants 2, 4 or 8, got " + text);
                        bitWidths.push_back(static_cast<int>(bits));
                      });
    addRepeatedOption(command, "--contact", "KIND",
                      "paper (the voxels' tangent planes) or surface (surface planes, finer than a voxel); "
                      "repeatable; default both",
                      [&surface = args->surface](const std::string& kind) {
                        if (kind != "paper" && kind != "surface")
                          throw UsageError("--contact wants paper or surface, got " + kind);
                        surface.push_back(kind == "surface");
                      });
    addRepeatedOption(command, "--points-per-voxel", "N",
                      "points per voxel edge: point spacing = voxel size / N, 1 to 4 (repeatable; default 1)",
                      [&densities = args->pointsPerVoxel](const std::string& text) {
                        const auto n = parseUnsigned(text, "points-per-voxel");
                        if (n < 1 || n > 4) throw UsageError("--points-per-voxel wants 1 to 4, got " + text);
                        densities.push_back(static_cast<int>(n));
                      });
    addSimOptions(command, args->sim, {SimOption::Capacity, SimOption::Cache});
    command.get_option("--capacity")
        ->description("point tests per frame with coherence on (default: measured online)");
    return [args](Console& console) { return runError(*args, console); };
  };
  b.plot = [] {
    SvgPlotSpec spec;
    spec.title = "Frame time against error at rest";
    spec.xKey = "abs_gap_m";
    spec.yKey = "compute_p50_us";
    spec.seriesKey = "contact";
    spec.xLabel = "|gap| at rest, m (exact meshes, Embree)";
    spec.yLabel = "compute p50, us";
    spec.logX = true;
    spec.logY = true;
    return spec;
  }();
  return b;
}

}  // namespace voxhap::cli
