#!/bin/bash
# Format C++ sources with clang-format and the project's .clang-format (Debian's clang-format package).
#   scripts/format.sh                 format every tracked .cpp / .hpp in place
#   scripts/format.sh --check [FILE...]  list the files that differ from the style (exit 1 if any)
#   scripts/format.sh FILE...         format the given files
set -eo pipefail
cd "$(dirname "$0")/.."
command -v clang-format > /dev/null || { echo "format: clang-format not found (apt-get install clang-format)"; exit 2; }
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
if [ $# -gt 0 ]; then files=("$@"); else
  mapfile -t files < <(git ls-files '*.cpp' '*.hpp' | while read -r f; do [ -f "$f" ] && echo "$f"; done); fi
if [ $check -eq 0 ]; then
  clang-format -i --style=file "${files[@]}"
  exit 0
fi
bad=0
for f in "${files[@]}"; do
  if ! clang-format --style=file "$f" | cmp -s - "$f"; then echo "$f"; bad=$((bad + 1)); fi
done
echo "format: $bad of ${#files[@]} files differ from .clang-format"
[ $bad -eq 0 ]
