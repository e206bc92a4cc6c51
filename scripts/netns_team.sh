#!/bin/bash
# A robot per machine, on one machine: the base (ROS master, player, comm_broker, recorder) in one network
# namespace and each robot's front-end (with playback robot: and its trial_player) in its own, each with its own
# address on a bridge in the base's namespace (a veth per robot), each robot in its own mount namespace where the
# sequence's data is hidden (with playback robot: all but its own trial; and all of it from the base). The
# lockstep run's JRL is compared with cosmo_generate's, and the bytes each link carried are read from the veth
# counters.
#
#   scripts/netns_team.sh [--playback base,robot] [--simulate-config SIM.yaml | --sequence SEQ.yaml]
#                         [--odometry loam|reference] [--max-seconds S] [--comm wifi|proradio] [--work DIR]
#                         [--devel DIR] [--timeout S] [--no-compare] [--unreachable]
#
# --unreachable: one more run, the last robot's nodes registering an address the base cannot reach (ROS_IP set to
# an address of the robot that is not on the base's network): the player must stop it within its connect_timeout
# (8 s here), naming that robot's front-end, the address and ROS_IP ("unreachable" in the summary).
#
# Needs root, `ip netns` and `unshare` (util-linux); exits 77 with the reason when one is missing (a skip). Prints,
# per playback, the wall time, the bytes per second on each link and whether the JRL equals cosmo_generate's, and
# writes them to WORK/summary.json. Every process it starts runs inside its namespaces and is stopped by pid, and
# every namespace it made is deleted, also when it fails or is interrupted. Exit 0 when every JRL is identical.
set -uo pipefail

playbacks=base,robot
simulate_config=""
sequence=""
odometry=reference
max_seconds=0
comm=wifi
work=""
devel=""
timeout_s=900
compare=1
unreachable=0
here=$(cd "$(dirname "$0")/.." && pwd)

while [ $# -gt 0 ]; do
  case $1 in
    --playback) playbacks=$2; shift ;;
    --simulate-config) simulate_config=$2; shift ;;
    --sequence) sequence=$2; shift ;;
    --odometry) odometry=$2; shift ;;
    --max-seconds) max_seconds=$2; shift ;;
    --comm) comm=$2; shift ;;
    --work) work=$2; shift ;;
    --devel) devel=$2; shift ;;
    --timeout) timeout_s=$2; shift ;;
    --no-compare) compare=0 ;;
    --unreachable) unreachable=1 ;;
    -h|--help) sed -n 2,17p "$0"; exit 0 ;;
    *) echo "netns_team: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done

skip() { echo "SKIP: $*"; exit 77; }
[ "$(id -u)" = 0 ] || skip "needs root (network namespaces)"
command -v ip >/dev/null || skip "no 'ip' command (iproute2)"
command -v unshare >/dev/null || skip "no 'unshare' command (util-linux)"
probe_ns=cosmo_probe_$$
ip netns add "$probe_ns" 2>/dev/null || skip "'ip netns add' fails here (no CAP_SYS_ADMIN or no netns support)"
ip netns del "$probe_ns"

devel=${devel:-${COSMO_DEVEL:-$here/_build/devel}}
[ -f "$devel/setup.bash" ] || { echo "netns_team: no $devel/setup.bash: build first (scripts/setup.sh)" >&2; exit 2; }
export PATH=/usr/bin:$PATH
set +u
# shellcheck disable=SC1091
source "$devel/setup.bash"
set -u
lib=$devel/lib/cosmo
work=${work:-$(mktemp -d /tmp/cosmo_netns.XXXXXX)}
mkdir -p "$work"
work=$(cd "$work" && pwd)
export ROS_HOME=$work/ros_home ROS_LOG_DIR=$work/ros_log
unset ROS_HOSTNAME ROS_IP

# ---- the sequence and its data -------------------------------------------------------------------------------
if [ -z "$sequence" ]; then
  simulate_config=${simulate_config:-$here/test/rostest/sequence_sim.yaml}
  "$lib/cosmo_simulate" --config "$simulate_config" --out "$work/data" > "$work/simulate.log" 2>&1 ||
    { echo "netns_team: cosmo_simulate failed: $work/simulate.log" >&2; exit 1; }
  sequence=$(tail -n1 "$work/simulate.log")
fi
sequence=$(readlink -f "$sequence")
# robots, trial files (absolute) and the folders that hold them (hidden from the robots)
eval "$(/usr/bin/python3 - "$sequence" <<'EOF'
import os, sys, yaml
path = sys.argv[1]
cfg = yaml.safe_load(open(path))
root = os.path.dirname(path)
robots, files = [], {}
for t in cfg["trials"]:
    r = t["robot"]
    robots.append(r)
    fs = [os.path.realpath(os.path.join(root, t[k])) for k in ("bag", "reference") if t.get(k)]
    files[r] = fs
print("robots=(%s)" % " ".join(robots))
for r in robots:
    print("files_%s=(%s)" % (r, " ".join("'%s'" % f for f in files[r])))
dirs = sorted({os.path.dirname(f) for fs in files.values() for f in fs} | {os.path.dirname(os.path.realpath(path))})
print("data_dirs=(%s)" % " ".join("'%s'" % d for d in dirs))
print("seq_name=%s" % cfg["name"])
EOF
)"
[ ${#robots[@]} -gt 0 ] || { echo "netns_team: no robots in $sequence" >&2; exit 1; }
all_files=()
for r in "${robots[@]}"; do eval "all_files+=(\"\${files_$r[@]}\")"; done
data_dirs+=("$(dirname "$sequence")")
# the base's and each robot's copy of the config (the original may be a link into a hidden folder); the trials'
# paths resolve against the original folder (data_root), hidden or not
mkdir -p "$work/view"
cp -L "$sequence" "$work/view/sequence.yaml"
data_root=$(dirname "$sequence")

# ---- namespaces: a bridge in the base's, a veth per robot ----------------------------------------------------
tag=nt$$
ns_base=cosmo_${tag}_base
# namespaces of an earlier run of this script that was killed before it could clean up (its pid is gone): their
# processes are stopped and the namespaces deleted
for ns in $(ip netns list | grep -o '^cosmo_nt[0-9]*_[a-z]*'); do
  owner=${ns#cosmo_nt}; owner=${owner%%_*}
  kill -0 "$owner" 2>/dev/null && continue
  for p in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$p" 2>/dev/null; done
  ip netns del "$ns" 2>/dev/null && echo "netns_team: deleted $ns, left by a run that was killed"
done
subnet=10.213.0
master_ip=$subnet.1
port=11311
export ROS_MASTER_URI=http://$master_ip:$port
namespaces=()
pids=()

cleanup() {
  local rc=$?
  trap - EXIT INT TERM
  for p in "${pids[@]}"; do kill -INT -- "-$p" 2>/dev/null; done
  sleep 2
  for ns in "${namespaces[@]}"; do
    for p in $(ip netns pids "$ns" 2>/dev/null); do kill -KILL "$p" 2>/dev/null; done
  done
  for ns in "${namespaces[@]}"; do ip netns del "$ns" 2>/dev/null; done
  exit $rc
}
trap cleanup EXIT
trap 'exit 130' INT TERM

ip netns add "$ns_base" && namespaces+=("$ns_base")
ip -n "$ns_base" link set lo up
ip -n "$ns_base" link add br0 type bridge
ip -n "$ns_base" addr add "$master_ip/24" dev br0
ip -n "$ns_base" link set br0 up
declare -A robot_ip robot_ns
i=10
for r in "${robots[@]}"; do
  ns=cosmo_${tag}_$r
  ip netns add "$ns" && namespaces+=("$ns")
  ip -n "$ns" link set lo up
  ip link add "link_$r" netns "$ns_base" type veth peer name eth0 netns "$ns"
  ip -n "$ns_base" link set "link_$r" master br0
  ip -n "$ns_base" link set "link_$r" up
  robot_ip[$r]=$subnet.$i
  robot_ns[$r]=$ns
  ip -n "$ns" addr add "${robot_ip[$r]}/24" dev eth0
  ip -n "$ns" link set eth0 up
  i=$((i + 1))
done

# ns_exec NS ADDR KEEP CMD...: CMD in namespace NS with ROS_IP ADDR, in its own mount namespace where every data
# folder is hidden (an empty tmpfs over it) except the files listed in KEEP (space-separated).
ns_exec() {
  local ns=$1 addr=$2 keep=$3
  shift 3
  ip netns exec "$ns" unshare --mount --propagation private /bin/bash -c '
    keep=$1; shift; vis=$(mktemp -d /tmp/cosmo_netns_keep.XXXXXX); n=0
    for f in $keep; do n=$((n + 1)); touch "$vis/$n"; mount --bind "$f" "$vis/$n" || exit 1; done
    for d in $DATA_DIRS; do mount -t tmpfs -o size=1m cosmo_hidden "$d" || exit 1; done
    n=0
    for f in $keep; do n=$((n + 1)); mkdir -p "$(dirname "$f")"; touch "$f"; mount --bind "$vis/$n" "$f" || exit 1; done
    exec "$@"' ns_exec "$keep" env ROS_IP="$addr" "$@"
}
export -f ns_exec

# in_ns NS ADDR KEEP LOG CMD...: ns_exec in the background, in its own process group (its pid in $last_pid).
in_ns() {
  local log=$4
  setsid /bin/bash -c 'ns_exec "$@"' in_ns "$1" "$2" "$3" "${@:5}" > "$log" 2>&1 &
  last_pid=$!
  pids+=("$last_pid")
}

# The files NS sees of the trials: "visible" or "hidden" per file, for the check below.
seen_in_ns() {
  ns_exec "$1" 0.0.0.0 "$2" /bin/bash -c 'for f in "$@"; do [ -r "$f" ] && echo visible || echo hidden; done' seen \
    "${all_files[@]}"
}
export DATA_DIRS="${data_dirs[*]}"

ip netns exec "$ns_base" env ROS_IP=$master_ip setsid roscore -p $port > "$work/roscore.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  ip netns exec "$ns_base" env ROS_IP=$master_ip rosparam get /rosdistro >/dev/null 2>&1 && break
  sleep 0.2
done
ip netns exec "$ns_base" env ROS_IP=$master_ip rosparam get /rosdistro >/dev/null 2>&1 ||
  { echo "netns_team: the master did not start: $work/roscore.log" >&2; exit 1; }

counters() {  # "<robot> <rx> <tx>" per link, seen from the base: rx = robot -> base, tx = base -> robot
  for r in "${robots[@]}"; do
    echo "$r $(ip netns exec "$ns_base" cat /sys/class/net/link_$r/statistics/rx_bytes) \
$(ip netns exec "$ns_base" cat /sys/class/net/link_$r/statistics/tx_bytes)"
  done
}

# the offline run to compare with, beside the first launch run (it is needed only when that one ends)
offline_jrl=""
offline_pid=""
if [ $compare = 1 ]; then
  args=(--comm "$comm" --out "$work/offline" --quiet)
  [ "$odometry" = reference ] && args+=(--odometry reference)
  [ "$max_seconds" != 0 ] && args+=(--max-seconds "$max_seconds")
  setsid "$lib/cosmo_generate" "$sequence" --data-root "$data_root" "${args[@]}" > "$work/offline.log" 2>&1 &
  offline_pid=$!
  pids+=("$offline_pid")
  offline_jrl=$work/offline/${seq_name}_$comm.jrl
fi
offline_done() {  # waits for the offline run once; exits when it failed
  [ -n "$offline_pid" ] || return 0
  wait "$offline_pid" || { echo "netns_team: cosmo_generate failed: $work/offline.log" >&2; exit 1; }
  offline_pid=""
}

summary="{"
failed=0
for playback in ${playbacks//,/ }; do
  out=$work/$playback
  rm -rf "$out"; mkdir -p "$out"
  ip netns exec "$ns_base" env ROS_IP=$master_ip rosparam delete /player >/dev/null 2>&1
  base_keep=""
  [ "$playback" = base ] && for r in "${robots[@]}"; do eval "base_keep+=\" \${files_$r[*]}\""; done
  # what each machine sees of the data: the base all of it (playback base) or none; each robot its own trial
  # (playback robot) or none
  expected=$(for f in "${all_files[@]}"; do [ -n "$base_keep" ] && echo visible || echo hidden; done)
  [ "$(seen_in_ns "$ns_base" "$base_keep")" = "$expected" ] ||
    { echo "netns_team: the base does not see the data it should (playback $playback)" >&2; exit 1; }
  robot_pids=()
  for r in "${robots[@]}"; do
    keep=""
    robot_args=(robot:="$r" lockstep:=true odometry:="$odometry")
    if [ "$playback" = robot ]; then
      eval "keep=\"\${files_$r[*]}\""
      robot_args+=(playback:=robot sequence:="$work/view/sequence.yaml" data_root:="$data_root")
    fi
    expected=$(for f in "${all_files[@]}"; do [[ " $keep " == *" $f "* ]] && echo visible || echo hidden; done)
    [ "$(seen_in_ns "${robot_ns[$r]}" "$keep")" = "$expected" ] ||
      { echo "netns_team: robot $r does not see the data it should (playback $playback)" >&2; exit 1; }
    in_ns "${robot_ns[$r]}" "${robot_ip[$r]}" "$keep" "$out/robot_$r.log" roslaunch cosmo robot.launch "${robot_args[@]}"
    robot_pids+=("$last_pid")
  done
  before=$(counters)
  start=$(date +%s.%N)
  in_ns "$ns_base" "$master_ip" "$base_keep" "$out/base.log" timeout "$timeout_s" roslaunch cosmo sequence.launch \
    frontends:=false playback:="$playback" sequence:="$work/view/sequence.yaml" data_root:="$data_root" \
    name:="$seq_name" comm:="$comm" odometry:="$odometry" max_seconds:="$max_seconds" output_dir:="$out" \
    status_file:="$out/status"
  base_pid=$last_pid
  wait "$base_pid"; base_rc=$?
  # roslaunch exits 0 whatever its nodes did: the player writes how the run ended
  status=$(head -n1 "$out/status" 2>/dev/null || echo "no status (the player did not end)")
  [ "$status" = done ] || [ $base_rc != 0 ] || base_rc=1
  wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
  after=$(counters)
  for p in "${robot_pids[@]}"; do kill -INT -- "-$p" 2>/dev/null; done
  for p in "${robot_pids[@]}"; do wait "$p" 2>/dev/null; done
  jrl=$out/${seq_name}_$comm.jrl
  identical=null
  offline_done
  if [ -n "$offline_jrl" ]; then
    if [ -f "$jrl" ] && cmp -s "$jrl" "$offline_jrl"; then identical=true; else identical=false; failed=1; fi
  fi
  [ $base_rc = 0 ] || failed=1
  echo "== playback $playback: the player's run: $status, $wall s wall, JRL identical to cosmo_generate's: $identical"
  links=""
  while read -r r rx0 tx0; do
    read -r _ rx1 tx1 <<< "$(echo "$after" | grep "^$r ")"
    up=$((rx1 - rx0)); down=$((tx1 - tx0))
    awk -v r="$r" -v d="$down" -v u="$up" -v w="$wall" 'BEGIN {
      printf "   link %s: base -> robot %12d B (%9.0f B/s), robot -> base %12d B (%9.0f B/s)\n", r, d, d / w, u, u / w }'
    links+="\"$r\": {\"base_to_robot_bytes\": $down, \"robot_to_base_bytes\": $up},"
  done <<< "$before"
  summary+="\"$playback\": {\"exit\": $base_rc, \"wall_s\": $wall, \"identical\": $identical, \"links\": {${links%,}}},"
  [ "$identical" = false ] && echo "   JRL differs: $jrl vs $offline_jrl (logs in $out)"
  [ $base_rc = 0 ] || echo "   the run failed ($status): $out/base.log"
done

# one robot not reachable back: its nodes register an address the base has no route to (a wrong ROS_IP)
if [ $unreachable = 1 ]; then
  out=$work/unreachable
  rm -rf "$out"; mkdir -p "$out"
  ip netns exec "$ns_base" env ROS_IP=$master_ip rosparam delete /player >/dev/null 2>&1
  base_keep=""
  for r in "${robots[@]}"; do eval "base_keep+=\" \${files_$r[*]}\""; done
  last=${robots[-1]}
  wrong_ip=10.214.0.99  # the robot has it (its own roslaunch checks that it reaches itself), the base no route to it
  ip -n "${robot_ns[$last]}" addr add "$wrong_ip/32" dev lo
  robot_pids=()
  for r in "${robots[@]}"; do
    addr=${robot_ip[$r]}
    [ "$r" = "$last" ] && addr=$wrong_ip
    in_ns "${robot_ns[$r]}" "$addr" "" "$out/robot_$r.log" roslaunch cosmo robot.launch robot:="$r" lockstep:=true \
      odometry:="$odometry"
    robot_pids+=("$last_pid")
  done
  start=$(date +%s.%N)
  in_ns "$ns_base" "$master_ip" "$base_keep" "$out/base.log" timeout 120 roslaunch cosmo sequence.launch \
    frontends:=false sequence:="$work/view/sequence.yaml" data_root:="$data_root" name:="$seq_name" comm:="$comm" \
    odometry:="$odometry" max_seconds:="$max_seconds" output_dir:="$out" status_file:="$out/status" connect_timeout:=8
  wait "$last_pid"
  wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
  for p in "${robot_pids[@]}"; do kill -INT -- "-$p" 2>/dev/null; done
  for p in "${robot_pids[@]}"; do wait "$p" 2>/dev/null; done
  status=$(head -n1 "$out/status" 2>/dev/null || echo "no status (the player did not end)")
  echo "== robot $last registering $wrong_ip: $wall s wall, the player's run: $status"
  named=false
  [[ "$status" == stopped:*"/$last/frontend"*"$wrong_ip"* ]] && named=true
  [ $named = true ] || { failed=1; echo "   not stopped naming /$last/frontend and $wrong_ip: $out/base.log"; }
  status_json=$(/usr/bin/python3 -c 'import json, sys; print(json.dumps(sys.argv[1]))' "$status")
  summary+="\"unreachable\": {\"robot\": \"$last\", \"address\": \"$wrong_ip\", \"wall_s\": $wall, \"named\": $named, \"status\": $status_json},"
fi
echo "${summary%,}}" > "$work/summary.json"
echo "summary: $work/summary.json"
exit $failed
