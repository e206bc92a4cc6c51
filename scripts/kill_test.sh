#!/bin/bash
# The kill tests of docs/benchmarks.md: one sequence.launch run in which nodes are SIGKILLed at given moments, and
# what was written. The CI sequence (test/rostest/sequence_sim.yaml), reference odometry, 40 s of sequence time,
# on its own master.
#   scripts/kill_test.sh MODE NODE@SECONDS [NODE@SECONDS ...] [-- roslaunch args]
#     MODE      lockstep | realtime
#     NODE      a node name: recorder, comm_broker, player, team_launcher, b/frontend, ...
#     SECONDS   wall seconds after the player published its first scan
# Prints the player's status, the dataset's completeness, sessions, restarts and bridges (<name>.recorder.yaml), each
# front-end's count of measurements sent and not acknowledged, and in lockstep whether the JRL is byte-identical to
# cosmo_generate's for the same settings (the uninterrupted run's). Writes into $OUT (default /tmp/cosmo_kill_test).
# Run after a build (source _build/devel/setup.bash is done here); ROS_MASTER_URI's port: $PORT (default 11399).
set -eo pipefail
cd "$(dirname "$0")/.."
mode=$1; shift || true
[[ "$mode" == lockstep || "$mode" == realtime ]] || { sed -n 2,13p "$0"; exit 2; }
kills=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do kills+=("$1"); shift; done
[ "${1:-}" == "--" ] && shift
OUT=${OUT:-/tmp/cosmo_kill_test}
PORT=${PORT:-11399}
export PATH=/usr/bin:$PATH ROS_HOSTNAME=localhost
set +u
source _build/devel/setup.bash
set -u
export ROS_MASTER_URI=http://localhost:$PORT
rm -rf "$OUT" && mkdir -p "$OUT"
roscore -p "$PORT" > "$OUT/roscore.log" 2>&1 & core=$!
trap 'kill -INT $core 2>/dev/null; wait $core 2>/dev/null || true' EXIT
until rosparam get /rosdistro > /dev/null 2>&1; do sleep 0.2; done
sim=$PWD/test/rostest/sequence_sim.yaml
roslaunch cosmo sequence.launch simulate_config:="$sim" simulate_out:="$OUT/sequence" name:=rostest_r3 mode:="$mode" \
  odometry:=reference max_seconds:=40 output_dir:="$OUT" status_file:="$OUT/status" "$@" > "$OUT/launch.log" 2>&1 &
launch=$!
pid_of() {  # the process of a node, by its XML-RPC API (as rosnode does)
  python3 -c "
import os, sys, xmlrpc.client
code, _, uri = xmlrpc.client.ServerProxy(os.environ['ROS_MASTER_URI']).lookupNode('/kill_test', sys.argv[1])
print(xmlrpc.client.ServerProxy(uri).getPid('/kill_test')[2] if code == 1 else '')" "/$1" 2>/dev/null || true
}
timeout 600 rostopic echo -n1 /player/progress > /dev/null 2>&1 & first=$!
while kill -0 $first 2>/dev/null && kill -0 $launch 2>/dev/null; do sleep 0.2; done  # the first scan, or the end
kill $first 2>/dev/null || true
start=$(date +%s.%N)
for k in "${kills[@]}"; do
  node=${k%@*} at=${k#*@}
  sleep "$(python3 -c "print(max(0.0, $start + $at - $(date +%s.%N)))")"
  pid=$(pid_of "$node")
  if [ -n "$pid" ]; then
    kill -9 "$pid" && echo "SIGKILL /$node (pid $pid) at $(python3 -c "print(round($(date +%s.%N) - $start, 1))") s"
  else
    echo "/$node is not running at $at s"
  fi
done
stopped=$(date +%s.%N)
wait $launch || true
echo "launch ended $(python3 -c "print(round($(date +%s.%N) - $stopped, 1))") s after the last kill"
echo "player status: $(cat "$OUT/status" 2>/dev/null || echo '(none: the player did not end by itself)')"
yaml=$OUT/rostest_r3_wifi.recorder.yaml
grep -E "^(complete|incomplete|recorder_sessions|frontend_restarts|scans_skipped|entries|keyframes_pending|loop_closures_pending):|robot: " "$yaml" || echo "no $yaml"
grep -a "measurements sent" "$OUT/launch.log" | sed 's/^/  /' || true
grep -a "recorder: wrote" "$OUT/launch.log" | tail -1 | sed 's/\x1b\[[0-9;]*m//g' || true
if [ "$mode" == lockstep ]; then
  sequence=$(ls "$OUT"/sequence/*.yaml | head -1)
  cosmo_generate "$sequence" --comm wifi --config-dir config --noise-models config/noise_models/synthetic.yaml \
    --odometry reference --max-seconds 40 --out "$OUT/offline" --quiet > "$OUT/offline.log" 2>&1
  if cmp "$OUT/rostest_r3_wifi.jrl" "$OUT/offline/$(basename "$sequence" .yaml)_wifi.jrl"; then
    echo "JRL byte-identical to the uninterrupted run (cosmo_generate)"
  else
    echo "JRL differs from the uninterrupted run (cosmo_generate)"
  fi
fi
