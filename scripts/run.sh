#!/bin/bash
# Set up (scripts/setup.sh) and run the main job: the built-in synthetic 3-robot sequence end to end through
# `roslaunch cosmo sequence.launch`, writing <name>_<comm>.jrl and its statistics into ./out (or output_dir:=...).
# Extra arguments go to roslaunch, e.g.  scripts/run.sh comm:=proradio rviz:=true
set -eo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
export PATH=/usr/bin:$PATH
export ROS_HOSTNAME=${ROS_HOSTNAME:-localhost}
set +u
source _build/devel/setup.bash
mkdir -p out
exec roslaunch cosmo sequence.launch output_dir:="$PWD/out" "$@"
