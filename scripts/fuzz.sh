#!/bin/bash
# Fuzz cosmo's readers of outside data with libFuzzer, ASan and UBSan (docs/fuzzing.md).
#
#   scripts/fuzz.sh [TARGET|all] [SECONDS]   a campaign: build, fuzz one target or each in turn for SECONDS (default
#                                            1800), then merge what it found into the kept corpus fuzz/corpus/<target>
#   scripts/fuzz.sh --ci [SECONDS]           CI (scripts/test.sh): build, replay every committed input of every target,
#                                            fuzz each for SECONDS in all (default 8); stops at the first finding
#   scripts/fuzz.sh --keep [TARGET|all]      only the merge of a campaign (e.g. after changing the budget)
#   scripts/fuzz.sh --list                   the targets
#
# Inputs of a target, all read at the start of every run (libFuzzer runs each once: a replay):
#   fuzz/seeds/<target>          valid inputs cut from the simulator's fixtures (cosmo_fuzz_seeds), and the
#                                repository files named in fuzz/seed_dirs.txt (copied into _build_fuzz/seeds/<target>)
#   fuzz/corpus/<target>         the kept corpus: what earlier campaigns found that adds coverage to the seeds,
#                                pruned with -merge=1 within a size budget (below); a campaign starts from it
#   fuzz/regressions/<target>    inputs that once crashed a reader (kept with the reader's fix)
# A campaign also resumes from its own working corpus _build_fuzz/corpus/<target> (kept on this machine only); CI
# fuzzes into a fresh _build_fuzz/ci_corpus/<target> and changes no committed file but fuzz/regressions.
#
# Kept corpus: after a campaign's run, the working and kept corpus (inputs up to COSMO_FUZZ_MAX_INPUT bytes, default
# 65536) are merged (-merge=1) over the seeds and regression inputs: what remains is the smallest set libFuzzer
# finds that adds their coverage, written to fuzz/corpus/<target> (named by content hash, so a rerun is stable).
# Over COSMO_FUZZ_BUDGET bytes per target (default 2097152) the largest inputs are left out, and the script says how
# many. Each campaign run appends "<date> <commit> <target> <seconds> <inputs> <exec/s> <findings> <kept files>
# <kept bytes>" to fuzz/campaigns.tsv (committed with the corpus: the cumulative count behind the kept corpus).
#
# An input that crashes, trips a sanitizer, runs out of memory or time is copied to fuzz/regressions/<target>/
# (commit it with the reader's fix: the gtest test/fuzz replays it in every build) and the script exits 1.
# Every run also appends "<target> <seconds> <inputs> <findings> <mode> <exec/s>" to _build_fuzz/runs.tsv.
# COSMO_FUZZ_JUNIT=FILE writes the runs as test cases (one per target) in JUnit XML (scripts/test.sh: counted by
# scripts/test_summary.py).
#
# Env: JOBS (build jobs, default nproc), COSMO_FUZZ_NICE (nice level of the runs, default 0; long campaigns on a
# shared machine: 19), COSMO_FUZZ_ARGS (more libFuzzer flags, e.g. -max_len=65536), COSMO_FUZZ_BUILD_DIR.
set -eo pipefail
cd "$(dirname "$0")/.."
ROOT=$PWD
B=${COSMO_FUZZ_BUILD_DIR:-_build_fuzz}
J=${JOBS:-$(nproc)}
MAX_INPUT=${COSMO_FUZZ_MAX_INPUT:-65536}
BUDGET=${COSMO_FUZZ_BUDGET:-2097152}
export PATH=/usr/bin:$PATH
stage_start=$(date +%s)

targets() { for f in fuzz/targets/*.cpp; do basename "$f" .cpp; done; }
MODE=campaign
case "$1" in
  --list) targets; exit 0 ;;
  --ci) MODE=ci; TARGET=all; SECONDS_EACH=${2:-8} ;;
  --keep) MODE=keep; TARGET=${2:-all} ;;
  -*) echo "fuzz.sh: unknown option '$1' (see the head of scripts/fuzz.sh)"; exit 2 ;;
  *) TARGET=${1:-all}; SECONDS_EACH=${2:-1800} ;;
esac
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
FLAGS=(-timeout=20 -rss_limit_mb=2560)

# The committed input folders of a target, besides its kept corpus: its seeds, the repository files of
# fuzz/seed_dirs.txt (copied, filtered by extension, into one folder), its regression inputs.
seed_dirs() {
  local t=$1
  local extra="$B/seeds/$t"
  rm -rf "$extra"; mkdir -p "$extra"
  awk -v t="$t" '$1 == t { for (i = 3; i <= NF; i++) print $2, $i }' fuzz/seed_dirs.txt |
    while read -r ext dir; do
      for f in "$dir"/*"$ext"; do [ -f "$f" ] && cp "$f" "$extra/$(echo "$dir" | tr / _)_$(basename "$f")"; done
    done
  for d in "fuzz/seeds/$t" "$extra" "fuzz/regressions/$t"; do [ -d "$d" ] && echo "$d"; done
}
files_in() { find "$@" -maxdepth 1 -type f 2> /dev/null | wc -l; }
bytes_in() { find "$@" -maxdepth 1 -type f -printf '%s\n' 2> /dev/null | awk '{ s += $1 } END { print s + 0 }'; }

# Merges the working corpus and the kept one into fuzz/corpus/<target> (see the head of this file).
keep_corpus() {
  local t=$1
  local kept="fuzz/corpus/$t" out="$B/merge/$t" in="$B/merge_in/$t" log="$B/logs/$t.merge.log"
  rm -rf "$out" "$in"; mkdir -p "$out" "$in" "$kept"
  # The seeds and regression inputs first, as the coverage already had; removed after the merge.
  local d
  for d in $(seed_dirs "$t"); do find "$d" -maxdepth 1 -type f -exec cp -t "$out" {} +; done
  local had; had=$(files_in "$out")
  find "$out" -maxdepth 1 -type f -printf '%f\n' | sort > "$B/merge/$t.had"
  for d in "$B/corpus/$t" "$kept"; do  # one cp per folder: an input in both has one name (its hash)
    find "$d" -maxdepth 1 -type f -size -$((MAX_INPUT + 1))c -exec cp -t "$in" {} +
  done
  local candidates; candidates=$(files_in "$in")
  # shellcheck disable=SC2086
  nice -n "${COSMO_FUZZ_NICE:-0}" "$B/fuzz_$t" -merge=1 "${FLAGS[@]}" $COSMO_FUZZ_ARGS "$out" "$in" > "$log" 2>&1 ||
    { tail -20 "$log"; echo "[fuzz] $t: merge failed (log: $log); fuzz/corpus/$t unchanged"; return 1; }
  (cd "$out" && xargs -r rm -f < "../$t.had")
  # Within the budget: the smallest inputs first (the merge prefers them too).
  local total=0 dropped=0 size name
  while read -r size name; do
    if [ $((total + size)) -gt "$BUDGET" ]; then rm -f "$out/$name"; dropped=$((dropped + 1)); else total=$((total + size)); fi
  done < <(find "$out" -maxdepth 1 -type f -printf '%s %f\n' | sort -n -k1,1 -k2,2)
  find "$kept" -maxdepth 1 -type f -delete
  find "$out" -maxdepth 1 -type f -exec cp -t "$kept" {} +
  KEPT_FILES=$(files_in "$kept"); KEPT_BYTES=$(bytes_in "$kept")
  local over=""
  [ "$dropped" -gt 0 ] && over="; $dropped left out over the budget of $BUDGET bytes"
  echo "[fuzz] $t: kept corpus fuzz/corpus/$t: $KEPT_FILES files, $KEPT_BYTES bytes (merged from $candidates inputs" \
       "over $had seeds and regression inputs$over)"
}

status=0
cases=""
run_target() {
  local t=$1
  local corpus="$B/corpus/$t" art="$B/artifacts/$t/" log="$B/logs/$t.log"
  if [ "$MODE" = ci ]; then corpus="$B/ci_corpus/$t"; rm -rf "$corpus"; fi
  mkdir -p "$corpus" "$art" "$B/logs"
  local start; start=$(date +%s)
  set +e
  # The first folder receives what the run finds; every other one is read (and each input run once) at the start.
  # shellcheck disable=SC2046,SC2086
  nice -n "${COSMO_FUZZ_NICE:-0}" "$B/fuzz_$t" -max_total_time="$SECONDS_EACH" "${FLAGS[@]}" -print_final_stats=1 \
    -artifact_prefix="$art" $COSMO_FUZZ_ARGS "$corpus" $([ -d "fuzz/corpus/$t" ] && echo "fuzz/corpus/$t") \
    $(seed_dirs "$t") > "$log" 2>&1
  local rc=$?
  set -e
  local secs=$(( $(date +%s) - start ))
  local execs rate replayed
  execs=$(awk '/stat::number_of_executed_units/ { print $2 }' "$log" | tail -1)
  rate=$(awk '/stat::average_exec_per_sec/ { print $2 }' "$log" | tail -1)
  replayed=$(grep -oE 'INFO: seed corpus: files: [0-9]+' "$log" | awk '{ print $NF }' | tail -1)
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
  printf '%s\t%s\t%s\t%s\t%s\t%s\n' "$t" "$secs" "${execs:-0}" "$found" "$MODE" "${rate:-0}" >> "$B/runs.tsv"
  local failure=""
  [ $found -gt 0 ] && failure="<failure message=\"$found findings, inputs in fuzz/regressions/$t, log $log\"/>"
  cases+="  <testcase classname=\"fuzz\" name=\"$t\" time=\"$secs\">$failure</testcase>"$'\n'
  echo "[fuzz] $t: ${execs:-0} inputs in $secs s (${rate:-0} exec/s), ${replayed:-?} committed inputs replayed," \
       "$found findings"
  if [ "$MODE" = campaign ]; then
    KEPT_FILES=$(files_in "fuzz/corpus/$t"); KEPT_BYTES=$(bytes_in "fuzz/corpus/$t")
    keep_corpus "$t" || status=1
    printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$(date -u +%Y-%m-%d)" "$(git rev-parse --short HEAD 2> /dev/null || echo -)" \
      "$t" "$secs" "${execs:-0}" "${rate:-0}" "$found" "$KEPT_FILES" "$KEPT_BYTES" >> fuzz/campaigns.tsv
  fi
  return $found
}

for t in $( [ "$TARGET" = all ] && targets || echo "$TARGET"); do
  if [ "$MODE" = keep ]; then mkdir -p "$B/corpus/$t" "$B/logs"; keep_corpus "$t" || status=1; continue; fi
  if ! run_target "$t" && [ "$MODE" = ci ]; then echo "[fuzz] stopped at the first finding"; break; fi
done
if [ -n "$COSMO_FUZZ_JUNIT" ]; then
  mkdir -p "$(dirname "$COSMO_FUZZ_JUNIT")"
  printf '<?xml version="1.0"?>\n<testsuite name="fuzz">\n%s</testsuite>\n' "$cases" > "$COSMO_FUZZ_JUNIT"
fi
if [ "$MODE" = campaign ]; then
  echo "[fuzz] cumulative over the kept corpus (fuzz/campaigns.tsv: target, seconds, inputs, findings):"
  awk -F'\t' '!/^#/ { s[$3] += $4; n[$3] += $5; f[$3] += $7 } END { for (t in s) printf "  %-20s %8d s %12d inputs %3d findings\n", t, s[t], n[t], f[t] }' \
    fuzz/campaigns.tsv | sort
fi
echo "[fuzz] $MODE stage: $(( $(date +%s) - stage_start )) s in all"
exit $status
