#include "app/scene_source.h"

#include <chrono>
#include <cstdlib>

#include "haptics/core/error.h"
#include "haptics/scene/builtin/builtin_scenes.h"
#include "haptics/scene/gltf_loader.h"
#include "haptics/scene/gltf_writer.h"

namespace voxhap::cli {
namespace fs = std::filesystem;

namespace {

// Bump when the generators' output changes, so that stale cached scenes are not used.
constexpr int kGeneratedSceneVersion = 4;

bool isBuiltin(const std::string& name) {
  for (const std::string& builtin : builtinSceneNames()) {
    if (builtin == name) return true;
  }
  return false;
}

std::string builtinList() {
  std::string list;
  for (const std::string& name : builtinSceneNames()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

}  // namespace

fs::path userCacheDir() {
  if (const char* dir = std::getenv("VOXHAP_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "voxhap";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "voxhap";
  return fs::temp_directory_path() / "voxhap-cache";
}

fs::path resolveScenePath(const std::string& scene, std::uint64_t seed, Console& console) {
  std::error_code ec;
  if (fs::exists(scene, ec)) return scene;
  if (!isBuiltin(scene)) {
    throw Error(scene + ": no such file, nor a built-in scene (" + builtinList() + ")");
  }
  const fs::path asset = fs::path(VOXHAP_ASSET_DIR) / (scene + ".glb");
  if (scene != "landing-gear" && fs::exists(asset, ec)) return asset;

  const fs::path dir = userCacheDir() / "scenes";
  const fs::path cached =
      dir / (scene + "-seed" + std::to_string(seed) + "-v" + std::to_string(kGeneratedSceneVersion) + ".glb");
  if (fs::exists(cached, ec)) return cached;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir.string() + ": cannot create the scene cache folder: " + ec.message());
  const auto start = std::chrono::steady_clock::now();
  const Scene generated = makeBuiltinScene(scene, seed, console.progress("generating " + scene));
  writeGlbFile(generated, cached);
  console.note("generated " + scene + " in " + std::to_string(secondsSince(start)) + " s, cached as " +
               cached.string());
  return cached;
}

Scene loadScene(const std::string& scene, std::uint64_t seed, Console& console) {
  const fs::path path = resolveScenePath(scene, seed, console);
  const auto start = std::chrono::steady_clock::now();
  Scene loaded = loadGltfScene(path, console.progress("loading " + path.filename().string()));
  console.note("loaded " + path.string() + " in " + std::to_string(secondsSince(start)) + " s");
  constexpr std::size_t kWarningsShown = 10;
  const bool all = console.verbosity() == Verbosity::Verbose;
  for (std::size_t i = 0; i < loaded.warnings.size() && (all || i < kWarningsShown); ++i) {
    console.warning(loaded.warnings[i]);
  }
  if (!all && loaded.warnings.size() > kWarningsShown) {
    console.warning("… and " + std::to_string(loaded.warnings.size() - kWarningsShown) +
                    " more warnings (-v shows them all)");
  }
  return loaded;
}

}  // namespace voxhap::cli
