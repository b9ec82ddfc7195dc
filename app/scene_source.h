#pragma once
/// Turns a SCENE argument (a glTF file or a built-in scene name) into a loaded
/// Scene, generating and caching built-in scenes as needed.

#include <cstdint>
#include <filesystem>
#include <string>

#include "app/cli/console.h"
#include "haptics/scene/scene.h"

namespace voxhap::cli {

/// The scene `voxhap demo` runs when given none.
inline constexpr const char* kDefaultSceneName = "landing-gear";
/// Seed of the built-in landing gear unless --seed says otherwise.
inline constexpr std::uint64_t kDefaultSeed = 1;

/// Voxhap's cache folder: $VOXHAP_CACHE_DIR, else $XDG_CACHE_HOME/voxhap, else
/// ~/.cache/voxhap. Not created here.
std::filesystem::path userCacheDir();

/// The file behind a SCENE argument: an existing file as it is; a built-in name as
/// the committed asset (small scenes) or the cached generated file, generated now
/// (with a progress bar) when absent. Throws voxhap::Error for anything else.
std::filesystem::path resolveScenePath(const std::string& scene, std::uint64_t seed, Console& console);

/// Resolves and loads a SCENE argument, printing the loader's warnings.
Scene loadScene(const std::string& scene, std::uint64_t seed, Console& console);

}  // namespace voxhap::cli
