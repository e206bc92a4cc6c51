#!/bin/bash
# Install what is missing (Debian packages, non-interactive, idempotent), check that every tool the build and
# the scripts call is there, and build cosmo into _build.
# Usage: scripts/setup.sh            (sudo is used when not root)
# Env:   JOBS=N parallel compile jobs (default: nproc); COSMO_SKIP_INSTALL=1 to skip the package step.
set -eo pipefail
cd "$(dirname "$0")/.."

if [ -z "$COSMO_SKIP_INSTALL" ]; then
  mapfile -t pkgs < <(grep -v '^\s*#' scripts/debian-packages.txt | sed 's/#.*//; s/\s*$//' | grep -v '^\s*$')
  missing=()
  for p in "${pkgs[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "[setup] installing ${#missing[@]} Debian packages: ${missing[*]}"
    SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    export DEBIAN_FRONTEND=noninteractive
    $SUDO apt-get update -qq
    $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" > /tmp/cosmo-apt.log 2>&1 || {
      tail -30 /tmp/cosmo-apt.log; echo "[setup] apt-get install failed (log: /tmp/cosmo-apt.log)"; exit 1; }
  fi
fi

export PATH=/usr/bin:$PATH          # system python3 (catkin_pkg, rospkg) before any pyenv shim

# Every program the build, the tests and scripts/*.sh call, with the Debian package that provides it.
absent=()
require_tool() { command -v "$1" > /dev/null 2>&1 || absent+=("$1 (package $2)"); }
require_python() { /usr/bin/python3 -c "import $1" > /dev/null 2>&1 || absent+=("python module $1 (package $2)"); }
require_tool c++ g++;  require_tool make make;  require_tool cmake cmake;  require_tool ctest cmake
require_tool ccache ccache;  require_tool pkg-config pkg-config;  require_tool /usr/bin/python3 python3
require_tool roslaunch ros-core-dev;  require_tool rostest python3-rostest;  require_tool rosrun rosbash
require_tool Xvfb xvfb;  require_tool xauth xauth;  require_tool import imagemagick;  require_tool convert imagemagick
require_python catkin_pkg python3-catkin-pkg;  require_python rospkg python3-rospkg
require_python em python3-empy;  require_python yaml python3-yaml;  require_python nose python3-nose
require_python xml.etree.ElementTree python3
if [ ${#absent[@]} -gt 0 ]; then
  echo "[setup] missing after the package step (add the package to scripts/debian-packages.txt):"
  printf '  %s\n' "${absent[@]}"
  exit 1
fi

export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
B=${COSMO_BUILD_DIR:-_build}
J=${JOBS:-$(nproc)}
BUILD_TYPE=RelWithDebInfo
mkdir -p "$B"
# A cache is reused only when it comes from a configure that succeeded with the build type's flags: a failed
# configure (e.g. before a compiler was installed) leaves the flags of the build type empty, and cmake would
# keep them, building without optimisation.
if [ -f "$B/CMakeCache.txt" ] && { [ ! -f "$B/.cosmo-configured" ] ||
     ! grep -Eq "^CMAKE_CXX_FLAGS_$(echo $BUILD_TYPE | tr a-z A-Z):STRING=.+" "$B/CMakeCache.txt"; }; then
  echo "[setup] $B/CMakeCache.txt is from an incomplete configure: configuring afresh"
  rm -rf "$B/CMakeCache.txt" "$B/CMakeFiles"
fi
rm -f "$B/.cosmo-configured"
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=$BUILD_TYPE -DCATKIN_ENABLE_TESTING=ON \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache > "$B/cmake.log" 2>&1 || {
    cat "$B/cmake.log"; rm -rf "$B/CMakeCache.txt" "$B/CMakeFiles"; echo "[setup] cmake failed"; exit 1; }
touch "$B/.cosmo-configured"
targets="all"
[ -n "$COSMO_BUILD_TESTS" ] && targets="all tests"
# gcc 12 sporadically crashes (ICE) on ROS headers: retry once.
make -C "$B" -j"$J" $targets --no-print-directory || make -C "$B" -j"$J" $targets --no-print-directory
echo "[setup] built into $B"
