#!/usr/bin/env bash
# Voxhap set-up: installs the Debian 12 packages that are missing, configures and
# builds, then runs the demo or the whole test suite. Safe to run again: a second
# run installs nothing and rebuilds only what changed.
#
#   bash tools/setup.sh demo [ARGS…]   build (Release) and run `voxhap demo ARGS…`
#   bash tools/setup.sh test           check every source's formatting, build and run
#                                      every test in Release, then again under
#                                      AddressSanitizer + UBSan, and the threaded
#                                      ones under ThreadSanitizer
#   bash tools/setup.sh format         clang-format every source in place
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

packages=(
  build-essential cmake ninja-build pkg-config
  libglm-dev libtinygltf-dev nlohmann-json3-dev libcli11-dev libembree-dev libopenmesh-dev
  libglfw3-dev libgl-dev libepoxy-dev libhidapi-dev libusb-1.0-0-dev libpng-dev libxxhash-dev
  libasio-dev libprotobuf-dev protobuf-compiler python3-protobuf libsodium-dev
  libgtest-dev libgmock-dev libbenchmark-dev clang-format umockdev
  xvfb xauth xdotool libgl1-mesa-dri libimgui-dev libstb-dev
)

# the tests of code that runs on more than one thread, for the tsan preset
tsan_tests='^(HapticLoop|ControllerLink|ControllerCommand|FrontendServer|UdpRelay|RelayCommand|PeerSession|PeerCommand|JitterBuffer|FrameCodec|SpscQueue|LatestValue|TripleBuffer|SpaceMouseDevice|UsbHotplug|FrameClock|Realtime|FrameHelper|VoxelPager|Coherence\.AFrameHelper|PairCoherence\.AHelper|TangentPlaneForce\.ManyContacts|BenchCommand\.Latency)|^ProtocolPythonClient$'

say() { printf 'setup: %s\n' "$*" >&2; }

as_root() {
  if [ "$(id -u)" -eq 0 ]; then
    "$@"
  elif command -v sudo >/dev/null 2>&1; then
    sudo "$@"
  else
    say "need root to install packages: run as root or install sudo"
    exit 1
  fi
}

install_missing() {
  local missing=()
  for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    say "all ${#packages[@]} packages present"
    return
  fi
  say "installing ${missing[*]}"
  as_root apt-get update -qq
  as_root env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}"
}

# every C++ source of the project (tracked files in a clone, else all under the source dirs)
sources() {
  if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    git ls-files -- '*.cpp' '*.h'
  else
    find app haptics net render tests -name '*.cpp' -o -name '*.h'
  fi
}

# fails, naming the files, when one is not as .clang-format writes it
check_format() {
  local bad=()
  while IFS= read -r f; do
    clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
  done < <(sources)
  if [ ${#bad[@]} -gt 0 ]; then
    say "not formatted (run: bash tools/setup.sh format): ${bad[*]}"
    exit 1
  fi
  say "every source formatted"
}

# configure once per preset; later builds re-run CMake by themselves when needed; the
# targets after the preset, when given, are all that is built
build() {
  local preset=$1
  shift
  if [ ! -f "build/$preset/CMakeCache.txt" ]; then
    cmake --preset "$preset"
  fi
  if [ $# -gt 0 ]; then
    cmake --build --preset "$preset" -j "$(nproc)" --target "$@"
  else
    cmake --build --preset "$preset" -j "$(nproc)"
  fi
}

case "${1:-}" in
  demo)
    shift
    install_missing
    build release
    # without a display: no window, and the pictures drawn in a virtual one
    if [ -z "${DISPLAY:-}${WAYLAND_DISPLAY:-}" ] && command -v xvfb-run >/dev/null 2>&1; then
      exec xvfb-run -a build/release/app/voxhap demo --headless "$@"
    fi
    exec build/release/app/voxhap demo "$@"
    ;;
  format)
    install_missing
    sources | xargs clang-format -i
    say "formatted every source"
    ;;
  test)
    install_missing
    check_format
    build release
    ctest --preset release
    build asan
    ctest --preset asan
    # the threads of the haptic controller (haptic loop, comms, devices, front-end server)
    # again under ThreadSanitizer
    # (only what those tests run: the renderer's and the benches' programs are not built)
    build tsan voxhap voxhap_tests
    ctest --preset tsan -R "$tsan_tests"
    say "all tests passed (Release and ASan+UBSan; the controller's under TSan too)"
    ;;
  *)
    echo "usage: bash tools/setup.sh demo [ARGS...] | test | format" >&2
    exit 2
    ;;
esac
