#!/bin/bash
# Install what is missing (Debian packages, non-interactive, idempotent) and build cosmo into _build.
# Usage: scripts/setup.sh            (sudo is used when not root)
# Env:   JOBS=N parallel compile jobs (default: nproc); COSMO_SKIP_INSTALL=1 to skip the package step.
set -eo pipefail
cd "$(dirname "$0")/.."

if [ -z "$COSMO_SKIP_INSTALL" ]; then
  mapfile -t pkgs < <(grep -v '^\s*#' scripts/debian-packages.txt | grep -v '^\s*$')
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
export CCACHE_BASEDIR=$PWD CCACHE_NOHASHDIR=true
B=${COSMO_BUILD_DIR:-_build}
J=${JOBS:-$(nproc)}
mkdir -p "$B"
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCATKIN_ENABLE_TESTING=ON \
  -DPYTHON_EXECUTABLE=/usr/bin/python3 -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DCMAKE_CXX_COMPILER_LAUNCHER=ccache > "$B/cmake.log" 2>&1 || { cat "$B/cmake.log"; exit 1; }
targets="all"
[ -n "$COSMO_BUILD_TESTS" ] && targets="all tests"
# gcc 12 sporadically crashes (ICE) on ROS headers: retry once.
make -C "$B" -j"$J" $targets --no-print-directory || make -C "$B" -j"$J" $targets --no-print-directory
echo "[setup] built into $B"
