#!/usr/bin/env bash
# omninav's one setup script: installs the Debian packages the project needs (only those
# missing), configures and builds, then optionally runs something.
#
#   scripts/setup.sh          install what is missing, configure, build
#   scripts/setup.sh demo     ... then run `omninav demo` on the built-in room
#   scripts/setup.sh test     ... then run the test suite (ctest)
#   scripts/setup.sh bench    ... then run the benchmarks
#
# Environment: BUILD_DIR (default build), BUILD_TYPE (Release), SANITIZE=1 for an
# AddressSanitizer + UndefinedBehaviorSanitizer build, CI=true turns warnings into errors.
# It is idempotent: run it again and it only rebuilds what changed.
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_dir=${BUILD_DIR:-$root/build}
build_type=${BUILD_TYPE:-Release}
action=${1:-build}
shift || true

packages=(
  build-essential cmake ninja-build pkg-config git
  libopencv-dev libfftw3-dev libeigen3-dev libceres-dev libboost-graph-dev
  libsqlite3-dev libyaml-cpp-dev libcli11-dev libgtest-dev libgmock-dev libbenchmark-dev
  libembree-dev libtinyobjloader-dev
)

install_missing_packages() {
  local missing=()
  for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return
  echo "setup: installing ${missing[*]}" >&2
  local sudo=()
  [ "$(id -u)" -ne 0 ] && sudo=(sudo)
  "${sudo[@]}" apt-get update -qq
  DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >&2
}

configure_and_build() {
  local options=(-DCMAKE_BUILD_TYPE="$build_type")
  [ "${CI:-}" = true ] && options+=(-DOMNINAV_WERROR=ON)
  [ "${SANITIZE:-0}" = 1 ] && options+=(-DOMNINAV_SANITIZE=ON)
  cmake -S "$root" -B "$build_dir" -G Ninja "${options[@]}" >/dev/null
  cmake --build "$build_dir" --parallel "$(nproc)"
}

install_missing_packages
configure_and_build

case "$action" in
  build) ;;
  demo) cd "$root" && exec "$build_dir/bin/omninav" demo "$@" ;;
  test) exec ctest --test-dir "$build_dir" --output-on-failure --parallel "$(nproc)" "$@" ;;
  bench)
    for program in "$build_dir"/bin/*_bench; do "$program" "$@"; done ;;
  *) echo "usage: scripts/setup.sh [build|demo|test|bench]" >&2; exit 2 ;;
esac
