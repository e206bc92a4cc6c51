#!/bin/bash
# A picture of a suite's report.html as a browser shows it: Debian's chromium, headless, one capture of the top of
# the page at the window size.
#
#   scripts/report_screenshot.sh REPORT.html OUT.png     e.g. out/ci_short/report.html docs/images/report.png
#
# Env: SIZE=W,H the window in CSS pixels (default 1400,1800). Needs chromium (apt-get install chromium); not a CI
# dependency: without it the script says so and exits 1.
set -eo pipefail
if [[ $# -ne 2 ]]; then
  echo "usage: scripts/report_screenshot.sh REPORT.html OUT.png" >&2
  exit 2
fi
[[ -f $1 ]] || { echo "report_screenshot: $1: no such file" >&2; exit 1; }
CHROMIUM=$(command -v chromium || command -v chromium-browser || true)
if [[ -z $CHROMIUM ]]; then
  echo "report_screenshot: chromium is not installed (apt-get install chromium); no screenshot taken" >&2
  exit 1
fi
REPORT=$(realpath "$1")
OUT=$(realpath -m "$2")
SIZE=${SIZE:-1400,1800}
PROFILE=$(mktemp -d /tmp/cosmo_report_screenshot.XXXXXX)
trap 'rm -rf "$PROFILE"' EXIT
flags=(--headless --disable-gpu --hide-scrollbars --no-first-run --user-data-dir="$PROFILE"
       --window-size="$SIZE" --screenshot="$OUT")
[[ $(id -u) -eq 0 ]] && flags+=(--no-sandbox)  # chromium refuses root without it
mkdir -p "$(dirname "$OUT")"
rm -f "$OUT"
"$CHROMIUM" "${flags[@]}" "file://$REPORT" > "$PROFILE/chromium.log" 2>&1 ||
  { tail -20 "$PROFILE/chromium.log" >&2; echo "report_screenshot: chromium failed" >&2; exit 1; }
[[ -s $OUT ]] || { tail -20 "$PROFILE/chromium.log" >&2; echo "report_screenshot: no $OUT written" >&2; exit 1; }
echo "report_screenshot: wrote $OUT ($(du -h "$OUT" | cut -f1))"
