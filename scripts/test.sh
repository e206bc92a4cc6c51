#!/bin/bash
# Set up (scripts/setup.sh), build every test and run them: the core's gtests in the core's own build without ROS
# (scripts/test_core.sh), the gtests that use ROS and the rostests in the catkin build, then each fuzz target briefly
# (scripts/fuzz.sh --ci; COSMO_SKIP_FUZZ=1 skips it, COSMO_CI_FUZZ_SECONDS sets its seconds per target, default 8).
# Prints one line per failing test case and ends with "N passed, N failed"; exits non-zero on any failure,
# crash, hang (ctest / rostest time limits) or when no test ran.
set -eo pipefail
cd "$(dirname "$0")/.."
COSMO_BUILD_TESTS=1 scripts/setup.sh
export PATH=/usr/bin:$PATH
B=${COSMO_BUILD_DIR:-_build}
J=${JOBS:-$(nproc)}
export ROS_HOSTNAME=localhost ROS_HOME=$PWD/$B/ros_home ROS_LOG_DIR=$PWD/$B/ros_log
set +e
rm -rf "$B/test_results"
C=${COSMO_CORE_BUILD_DIR:-_build_core}
echo "[test] the core on its own (plain CMake, no ROS): scripts/test_core.sh"
COSMO_CORE_BUILD_DIR=$C JOBS=$J scripts/test_core.sh; rc_core=$?
echo "[test] the ROS gtests and the rostests (catkin build $B)"
(cd "$B" && ctest --output-on-failure -j"$J" --timeout 900); rc_ctest=$?
# The fuzz targets (docs/fuzzing.md): built with clang into _build_fuzz; every committed input (seeds, kept corpus,
# regression inputs) replayed, then each target fuzzed for a few seconds; the first input that crashes a reader is
# kept in fuzz/regressions/<target>/ and counts as a failed case.
rc_fuzz=0
if [ -z "$COSMO_SKIP_FUZZ" ]; then
  COSMO_FUZZ_JUNIT="$B/test_results/fuzz/fuzz.xml" scripts/fuzz.sh --ci "${COSMO_CI_FUZZ_SECONDS:-8}"; rc_fuzz=$?
fi
echo "[test] all of it:"
/usr/bin/python3 scripts/test_summary.py "$C/test_results" "$B/test_results"; rc_sum=$?
[ $rc_core -eq 0 ] && [ $rc_ctest -eq 0 ] && [ $rc_sum -eq 0 ] && [ $rc_fuzz -eq 0 ]
