#!/bin/bash
# Fuzz cosmo's readers of outside data with libFuzzer, ASan and UBSan (docs/fuzzing.md).
#
#   scripts/fuzz.sh [TARGET|all] [SECONDS]   build, then run one target or each in turn for SECONDS (default 60)
#   scripts/fuzz.sh --list                   the targets
#
# The targets are built with clang into _build_fuzz (COSMO_FUZZ_BUILD_DIR). Each keeps its corpus in
# _build_fuzz/corpus/<target> between runs (a later run resumes from it), seeded from fuzz/corpus/<target>, the
# repository files named in fuzz/seed_dirs.txt and fuzz/regressions/<target>. An input that crashes, trips a
# sanitizer, runs out of memory or time is copied to fuzz/regressions/<target>/ (commit it with the reader's fix:
# the gtest test/fuzz replays it in every build) and the script exits 1 after the other targets.
# Every run appends "<target> <seconds> <inputs executed> <crashes>" to _build_fuzz/runs.tsv and prints the totals.
# COSMO_FUZZ_JUNIT=FILE also writes the runs as test cases (one per target) in JUnit XML (scripts/test.sh: counted
# by scripts/test_summary.py).
#
# Env: JOBS (build jobs, default nproc), COSMO_FUZZ_NICE (nice level of the runs, default 0; long campaigns on a
# shared machine: 19), COSMO_FUZZ_ARGS (more libFuzzer flags, e.g. -max_len=65536).
set -eo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
B=${COSMO_FUZZ_BUILD_DIR:-_build_fuzz}
J=${JOBS:-$(nproc)}
export PATH=/usr/bin:$PATH

targets() { ls fuzz/targets/*.cpp | xargs -n1 basename | sed 's/\.cpp$//'; }
if [ "$1" = "--list" ]; then targets; exit 0; fi
TARGET=${1:-all}
SECONDS_EACH=${2:-60}
if [ "$TARGET" != all ] && [ ! -f "fuzz/targets/$TARGET.cpp" ]; then
  echo "fuzz.sh: no target '$TARGET' (scripts/fuzz.sh --list)"; exit 2
fi

# Build (clang, instrumented; ccache shares objects between checkouts as in scripts/setup.sh).
export CCACHE_BASEDIR=$ROOT CCACHE_NOHASHDIR=true
CXX=${COSMO_FUZZ_CXX:-clang++-14}
command -v "$CXX" > /dev/null || { echo "fuzz.sh: $CXX missing (packages clang-14 libclang-rt-14-dev)"; exit 1; }
mkdir -p "$B"
cmake -S fuzz -B "$B" -DCMAKE_CXX_COMPILER="$CXX" -DCMAKE_CXX_COMPILER_LAUNCHER=ccache > "$B/cmake.log" 2>&1 ||
  { cat "$B/cmake.log"; exit 1; }
build_start=$(date +%s)
make -C "$B" -j"$J" > "$B/build.log" 2>&1 || { tail -40 "$B/build.log"; echo "fuzz.sh: build failed"; exit 1; }
echo "[fuzz] built in $(( $(date +%s) - build_start )) s ($B)"

# The targets' input files go to a folder of their own in memory, removed however a run ends.
scratch_base=/dev/shm; [ -w "$scratch_base" ] || scratch_base=${TMPDIR:-/tmp}
export COSMO_FUZZ_SCRATCH; COSMO_FUZZ_SCRATCH=$(mktemp -d "$scratch_base/cosmo_fuzz.XXXXXX")
trap 'rm -rf "$COSMO_FUZZ_SCRATCH"' EXIT

export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export ASAN_SYMBOLIZER_PATH=${ASAN_SYMBOLIZER_PATH:-$(command -v llvm-symbolizer-14 || true)}

# Seed folders of a target: its committed corpus, the repository files of fuzz/seed_dirs.txt (copied, filtered
# by extension, into one folder), its regression inputs.
seed_dirs() {
  local t=$1
  local extra="$B/seeds/$t"
  rm -rf "$extra"; mkdir -p "$extra"
  awk -v t="$t" '$1 == t { for (i = 3; i <= NF; i++) print $2, $i }' fuzz/seed_dirs.txt |
    while read -r ext dir; do
      for f in "$dir"/*"$ext"; do [ -f "$f" ] && cp "$f" "$extra/$(echo "$dir" | tr / _)_$(basename "$f")"; done
    done
  for d in "fuzz/corpus/$t" "$extra" "fuzz/regressions/$t"; do [ -d "$d" ] && echo "$d"; done
}

status=0
cases=""
run_target() {
  local t=$1
  local corpus="$B/corpus/$t" art="$B/artifacts/$t/" log="$B/logs/$t.log"
  mkdir -p "$corpus" "$art" "$B/logs"
  local start; start=$(date +%s)
  set +e
  # shellcheck disable=SC2046,SC2086
  nice -n "${COSMO_FUZZ_NICE:-0}" "$B/fuzz_$t" -max_total_time="$SECONDS_EACH" -timeout=20 -rss_limit_mb=2560 \
    -print_final_stats=1 -artifact_prefix="$art" $COSMO_FUZZ_ARGS "$corpus" $(seed_dirs "$t") > "$log" 2>&1
  local rc=$?
  set -e
  local secs=$(( $(date +%s) - start ))
  local execs; execs=$(awk '/stat::number_of_executed_units/ { print $2 }' "$log" | tail -1)
  local found=0
  for f in "$art"*; do
    [ -f "$f" ] || continue
    # libFuzzer keeps an input that took over 10 s as slow-unit-*: a report, not a failure (a loaded or niced run
    # makes any input slow); an input over -timeout=20 is a timeout-* finding.
    if [[ $(basename "$f") == slow-unit-* ]]; then
      echo "[fuzz] $t: slow input $(basename "$f") (over 10 s at this load; not a finding)"; rm -f "$f"; continue
    fi
    found=$((found + 1))
    mkdir -p "fuzz/regressions/$t"
    cp "$f" "fuzz/regressions/$t/$(basename "$f")"
    echo "[fuzz] $t: FINDING $(basename "$f") -> fuzz/regressions/$t/ (log: $log)"
    rm -f "$f"
  done
  if [ $rc -ne 0 ] && [ $found -eq 0 ]; then
    echo "[fuzz] $t: libFuzzer exited $rc without an input (log: $log)"; tail -20 "$log"; found=1
  fi
  [ $found -gt 0 ] && { status=1; grep -E "ERROR: |SUMMARY: |runtime error|terminate called|what\(\)" "$log" | head -8; }
  printf '%s\t%s\t%s\t%s\n' "$t" "$secs" "${execs:-0}" "$found" >> "$B/runs.tsv"
  local failure=""
  [ $found -gt 0 ] && failure="<failure message=\"$found findings, inputs in fuzz/regressions/$t, log $log\"/>"
  cases+="  <testcase classname=\"fuzz\" name=\"$t\" time=\"$secs\">$failure</testcase>"$'\n'
  echo "[fuzz] $t: ${execs:-0} inputs in $secs s, corpus $(ls "$corpus" | wc -l) files, $found findings"
}

if [ "$TARGET" = all ]; then
  for t in $(targets); do run_target "$t"; done
else
  run_target "$TARGET"
fi
if [ -n "$COSMO_FUZZ_JUNIT" ]; then
  mkdir -p "$(dirname "$COSMO_FUZZ_JUNIT")"
  printf '<?xml version="1.0"?>\n<testsuite name="fuzz">\n%s</testsuite>\n' "$cases" > "$COSMO_FUZZ_JUNIT"
fi
echo "[fuzz] totals over every run kept in $B/runs.tsv (target, seconds, inputs, findings):"
awk -F'\t' '{ s[$1] += $2; n[$1] += $3; f[$1] += $4 } END { for (t in s) printf "  %-20s %8d s %12d inputs %3d findings\n", t, s[t], n[t], f[t] }' \
  "$B/runs.tsv" | sort
exit $status
