#!/bin/bash
# The ROS-free core on its own: configure core/ with plain CMake in an empty environment (no ROS setup sourced, no
# catkin on the path), build its libraries, programs and gtests, run the gtests. Fails when the configure looked at
# catkin or ROS. Prints "N passed, N failed" (scripts/test_summary.py).
# Env: JOBS=N parallel compile jobs (default: nproc); COSMO_CORE_BUILD_DIR (default: _build_core).
set -eo pipefail
cd "$(dirname "$0")/.."
B=${COSMO_CORE_BUILD_DIR:-_build_core}
J=${JOBS:-$(nproc)}
# The locale stays: ccache hashes LANG and LC_* (the compiler's messages depend on them), and the catkin build, which
# compiled every core source already, ran with them; without them not one of its objects would be reused.
clean_env=(env -i PATH=/usr/bin:/bin HOME="$HOME" CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=true
           ${CCACHE_DIR:+CCACHE_DIR=$CCACHE_DIR} ${LANG:+LANG=$LANG} ${LC_ALL:+LC_ALL=$LC_ALL}
           ${LC_CTYPE:+LC_CTYPE=$LC_CTYPE} ${LC_MESSAGES:+LC_MESSAGES=$LC_MESSAGES})
mkdir -p "$B"
"${clean_env[@]}" cmake -S core -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER_LAUNCHER=ccache \
  > "$B/cmake.log" 2>&1 || { cat "$B/cmake.log"; echo "[test_core] cmake failed"; exit 1; }
if grep -Eiq "catkin|/opt/ros|roscpp" "$B/CMakeCache.txt"; then
  grep -Ei "catkin|/opt/ros|roscpp" "$B/CMakeCache.txt" | head -5
  echo "[test_core] the core's configure found catkin or ROS"
  exit 1
fi
"${clean_env[@]}" make -C "$B" -j"$J" all tests --no-print-directory > "$B/make.log" 2>&1 ||
  { tail -40 "$B/make.log"; echo "[test_core] build failed"; exit 1; }
rm -rf "$B/test_results"
set +e
(cd "$B" && "${clean_env[@]}" ctest --output-on-failure -j"$J" --timeout 900) > "$B/ctest.log" 2>&1; rc_ctest=$?
grep -E "tests passed|Failed|\*\*\*" "$B/ctest.log" | tail -20
/usr/bin/python3 scripts/test_summary.py "$B/test_results"; rc_sum=$?
[ $rc_ctest -eq 0 ] && [ $rc_sum -eq 0 ]
