#!/usr/bin/env bash
# omninav's one setup script: installs the Debian packages the project needs (only those
# missing), configures and builds, then optionally runs something.
#
#   scripts/setup.sh          install what is missing, configure, build
#   scripts/setup.sh demo     ... (only the program) then run `omninav demo` on the built-in room
#   scripts/setup.sh test     ... then run the test suite (ctest)
#   scripts/setup.sh bench    ... then run the benchmarks
#   scripts/setup.sh fuzz [s] builds the libFuzzer targets of tests/fuzz with clang, AddressSanitizer
#                             and UBSan in build-fuzz/ (FUZZ_BUILD_DIR), then runs each for s
#                             seconds (60) from its seed corpus; stops at the first finding
#
# Environment: BUILD_DIR (default build), BUILD_TYPE (Release), SANITIZE=1 for an
# AddressSanitizer + UndefinedBehaviorSanitizer build, CI=true turns warnings into errors (and
# makes `test` also run `fuzz 15`: each fuzz target for 15 seconds).
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
  libembree-dev libtinyobjloader-dev libfmt-dev nlohmann-json3-dev
  # bags: ROS 1 through librosbag and cv_bridge; ROS 2's MCAP chunks through zstd and lz4; the
  # Python ROS 1 packages write the test bags
  librosbag-dev libsensor-msgs-dev libnav-msgs-dev libgeometry-msgs-dev libcv-bridge-dev
  liblz4-dev libzstd-dev python3-rosbag python3-sensor-msgs python3-nav-msgs
  python3-geometry-msgs
  # the ROS 1 node (apps/omninav_ros) and its test: roscpp, the std_srvs and std_msgs headers,
  # a rosmaster, roslaunch and rospy to talk to it
  libroscpp-dev libstd-srvs-dev libstd-msgs-dev python3-rosmaster python3-roslaunch
  python3-rospy python3-std-srvs python3-std-msgs
  # the Python module, its tests and example, and `pip install --no-build-isolation .`
  pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib python3-pip
  python3-setuptools python3-wheel python3-venv
)

# clang and libFuzzer only for the fuzz action (and CI's test, which runs it).
if [ "$action" = fuzz ] || { [ "$action" = test ] && [ "${CI:-}" = true ]; }; then
  packages+=(clang libclang-rt-14-dev)
fi

install_missing_packages() {
  local missing=()
  for package in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" ||
      missing+=("$package")
  done
  [ ${#missing[@]} -eq 0 ] && return
  # apt's own output goes to a log: one line here, and the log's end and path if it fails.
  local log=${TMPDIR:-/tmp}/omninav-setup-apt.log
  echo "setup: installing ${#missing[@]} Debian packages (apt's log: $log)" >&2
  local sudo=()
  [ "$(id -u)" -ne 0 ] && sudo=(sudo)
  if ! { "${sudo[@]}" apt-get update -qq &&
         DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq \
           --no-install-recommends "${missing[@]}"; } > "$log" 2>&1; then
    tail -n 20 "$log" >&2
    echo "setup: installing the packages failed; apt's whole log: $log" >&2
    exit 1
  fi
  echo "setup: installed ${missing[*]}" >&2
}

# Configures, then builds the given targets (all when none): the demo needs only the program.
configure_and_build() {
  local options=(-DCMAKE_BUILD_TYPE="$build_type")
  [ "${CI:-}" = true ] && options+=(-DOMNINAV_WERROR=ON)
  [ "${SANITIZE:-0}" = 1 ] && options+=(-DOMNINAV_SANITIZE=ON)
  cmake -S "$root" -B "$build_dir" -G Ninja "${options[@]}" >/dev/null
  local targets=()
  for target in "$@"; do targets+=(--target "$target"); done
  cmake --build "$build_dir" --parallel "$(nproc)" "${targets[@]}"
}

# Builds the fuzz targets (tests/fuzz) in their own clang build and runs each for $1 seconds.
# A target's new inputs go to build-fuzz/corpus/<target>, so that the seeds in the repository
# stay the small hand-made ones; a finding is saved in build-fuzz/findings/ and stops the run.
run_fuzzers() {
  local seconds=${1:-60}
  local fuzz_dir=${FUZZ_BUILD_DIR:-$root/build-fuzz}
  local options=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DOMNINAV_FUZZ=ON -DOMNINAV_BUILD_TESTS=OFF
                 -DOMNINAV_BUILD_BENCHMARKS=OFF)
  [ "${CI:-}" = true ] && options+=(-DOMNINAV_WERROR=ON)
  CC=clang CXX=clang++ cmake -S "$root" -B "$fuzz_dir" -G Ninja "${options[@]}" >/dev/null
  cmake --build "$fuzz_dir" --target omninav_fuzzers --parallel "$(nproc)"
  mkdir -p "$fuzz_dir/findings"
  for source in "$root"/tests/fuzz/*_fuzz.cpp; do
    local target seeds corpus
    target=$(basename "$source" _fuzz.cpp)
    seeds=$root/tests/fuzz/corpus/$target
    corpus=$fuzz_dir/corpus/$target
    mkdir -p "$corpus"
    echo "fuzz: $target for ${seconds} s" >&2
    # -timeout: an input that takes 10 s is a hang; -rss_limit_mb: one that needs 2 GB, a leak
    # or a missing size check.
    "$fuzz_dir/bin/${target}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 \
      -print_final_stats=1 -artifact_prefix="$fuzz_dir/findings/${target}-" "$corpus" "$seeds"
  done
}

install_missing_packages
if [ "$action" = fuzz ]; then
  run_fuzzers "$@"
  exit
fi
if [ "$action" = demo ]; then configure_and_build omninav; else configure_and_build; fi

case "$action" in
  build) ;;
  demo) cd "$root" && exec "$build_dir/bin/omninav" demo "$@" ;;
  test)
    ctest --test-dir "$build_dir" --output-on-failure --parallel "$(nproc)" "$@"
    if [ "${CI:-}" = true ]; then run_fuzzers 15; fi ;;
  bench)
    for program in "$build_dir"/bin/*_bench; do "$program" "$@"; done ;;
  *) echo "usage: scripts/setup.sh [build|demo|test|bench|fuzz [seconds]]" >&2; exit 2 ;;
esac
