#!/usr/bin/env bash
# Lists the longest functions of the C++ code, longest first, as "lines  file:line  name".
# Universal Ctags parses the functions (its `end:` field gives the closing line); lambdas
# are counted inside the function that holds them, not on their own.
#
#   bash scripts/function_lengths.sh              # the ten longest in native/
#   bash scripts/function_lengths.sh 30 tests     # the thirty longest in tests/
#   MAX_LINES=120 bash scripts/function_lengths.sh  # exit 1 when one is longer than 120 lines
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
COUNT="${1:-10}"
DIR="${2:-native}"
cd "$ROOT"
listing=$(find "$DIR" -name '*.cpp' -o -name '*.hpp' | sort |
  ctags --c++-kinds=f --fields=+ne --sort=no -L - -o - |
  awk -F'\t' '$1 !~ /^__anon/ {
      line = ""; end = ""; scope = "";
      for (i = 4; i <= NF; i++) {
        if ($i ~ /^line:/) line = substr($i, 6);
        else if ($i ~ /^end:/) end = substr($i, 5);
        else if ($i ~ /^(class|struct|namespace):/) { split($i, kv, ":"); scope = substr($i, length(kv[1]) + 2) }
      }
      if (line != "" && end != "") {
        name = $1; sub(/^sheetgen::/, "", scope); sub(/^sheetgen$/, "", scope);
        gsub(/__anon[0-9a-f]+::/, "", scope);
        if (scope != "" && scope !~ /^__anon/) name = scope "::" name;
        printf "%5d  %s:%s  %s\n", end - line + 1, $2, line, name
      }
    }' | sort -rn)
echo "$listing" | head -n "$COUNT"
if [ -n "${MAX_LINES:-}" ]; then
  over=$(echo "$listing" | awk -v m="$MAX_LINES" '$1 > m' | wc -l)
  if [ "$over" -gt 0 ]; then echo "function_lengths: $over function(s) over $MAX_LINES lines" >&2; exit 1; fi
fi
