#!/bin/bash
# Set up (scripts/setup.sh) and run the main job: the built-in synthetic 3-robot sequence end to end through
# `roslaunch cosmo sequence.launch`, writing <name>_<comm>.jrl and its statistics into ./out (or output_dir:=...).
# Extra arguments go to roslaunch, e.g.  scripts/run.sh comm:=proradio rviz:=true
# Exits non-zero unless the player finished the sequence: roslaunch itself exits 0 even when its required player
# stopped the run (a node died or never connected), so the player's status file decides.
set -eo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
export PATH=/usr/bin:$PATH
export ROS_HOSTNAME=${ROS_HOSTNAME:-localhost}
set +u
source _build/devel/setup.bash
mkdir -p out
status=$(mktemp)
trap 'rm -f "$status"' EXIT
roslaunch cosmo sequence.launch output_dir:="$PWD/out" status_file:="$status" "$@" || exit
result=$(cat "$status")
if [ "$result" != "done" ]; then
  echo "run.sh: the run did not finish: ${result:-the player did not end by itself}" >&2
  exit 1
fi
