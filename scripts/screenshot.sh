#!/bin/bash
# Reproduces docs/rviz.png: the built-in synthetic 3-robot sequence (config/sim/default.yaml) through
# `roslaunch cosmo sequence.launch rviz:=true odometry:=reference` on a virtual display (Xvfb), stopped after
# SECONDS of sequence time (lockstep: the same team state on any machine), then a capture of the whole screen.
#
#   scripts/screenshot.sh [OUT.png] [SECONDS]        defaults: docs/rviz.png, 150.1 (all three robots in view;
#                                                     wrong-place closures, labelled outliers, across the
#                                                     west block)
#
# Uses the workspace $COSMO_BUILD_DIR (default _build; build it first: scripts/setup.sh), its own ROS master on a
# free port (does not disturb a running roscore) and its own display; KEEP_LOGS=1 keeps the logs and the JRL.
# Needs xvfb and imagemagick (scripts/debian-packages.txt). The first run also generates the synthetic sequence
# (~5 GB cache, minutes); a run then takes 1-4 min (lockstep to 150 s, then 30 s for rviz to catch up).
set -eo pipefail
ROOT=$(cd "$(dirname "$0")/.." && pwd)
OUT=$(realpath -m "${1:-$ROOT/docs/rviz.png}")
SEQ_SECONDS=${2:-150.1}
BUILD=${COSMO_BUILD_DIR:-_build}
[[ $BUILD = /* ]] || BUILD=$ROOT/$BUILD
export PATH=/usr/bin:$PATH
export ROS_HOSTNAME=localhost
set +u
source "$BUILD/devel/setup.bash"
set -u

free_port() { /usr/bin/python3 -c 'import socket; s=socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])'; }
PORT=$(free_port)
export ROS_MASTER_URI=http://localhost:$PORT
WORK=$(mktemp -d /tmp/cosmo_screenshot.XXXXXX)
export ROS_LOG_DIR=$WORK/log

exec 3> "$WORK/display"
Xvfb -displayfd 3 -screen 0 1280x800x24 -nolisten tcp > "$WORK/xvfb.log" 2>&1 &
XVFB=$!
LAUNCH=
cleanup() {
  [[ -n $LAUNCH ]] && kill -INT "$LAUNCH" 2> /dev/null && wait "$LAUNCH" 2> /dev/null || true
  kill "$XVFB" 2> /dev/null || true
}
trap cleanup EXIT
for _ in $(seq 300); do [[ -s $WORK/display ]] && break; sleep 0.2; done
[[ -s $WORK/display ]] || { echo "screenshot: Xvfb did not start, see $WORK/xvfb.log"; exit 1; }
export DISPLAY=:$(head -n1 "$WORK/display")
echo "screenshot: display $DISPLAY, ROS master port $PORT, logs in $WORK"

# player_required:=false keeps rviz up (and the clock stopped) once the player is done at SEQ_SECONDS.
roslaunch -p "$PORT" cosmo sequence.launch rviz:=true odometry:=reference player_required:=false \
  max_seconds:="$SEQ_SECONDS" output_dir:="$WORK/out" > "$WORK/launch.log" 2>&1 &
LAUNCH=$!

# Wait for the player to finish (it logs "player: done" and exits; rviz stays up with the clock stopped).
until grep -q "player: done" "$WORK/launch.log" 2> /dev/null; do
  kill -0 "$LAUNCH" 2> /dev/null || { echo "screenshot: roslaunch ended early, see $WORK/launch.log"; exit 1; }
  sleep 2
done
grep -o "player: done.*" "$WORK/launch.log" | head -n1
sleep 30  # rviz (software OpenGL, slow under load) catches up with the last markers and scans
mkdir -p "$(dirname "$OUT")"
import -window root -depth 8 "png:$OUT"
echo "screenshot: wrote $OUT ($(du -h "$OUT" | cut -f1))"
[[ -n ${KEEP_LOGS:-} ]] || rm -rf "$WORK"
