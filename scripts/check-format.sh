#!/usr/bin/env bash
# Checks that the C++ files follow .clang-format; names each file that does not and exits 1.
# Usage: scripts/check-format.sh [--fix]   (--fix: rewrite them in place instead)
# Run by ctest as format_check; clang-format comes from scripts/install-deps.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
clang_format="${CLANG_FORMAT:-clang-format}"
mapfile -t files < <(find src apps tests bench examples -name '*.cpp' -o -name '*.hpp' 2>/dev/null | sort)
if [ "${1:-}" = "--fix" ]; then
  "$clang_format" -i --style=file "${files[@]}"
  exit 0
elif [ $# -gt 0 ]; then
  echo "check-format: unknown argument '$1' (the only option is --fix)" >&2
  exit 2
fi
bad=0
for f in "${files[@]}"; do
  if ! "$clang_format" --style=file --dry-run --Werror "$f" > /dev/null 2>&1; then
    echo "$f: not in .clang-format's layout (scripts/check-format.sh --fix rewrites it)"
    bad=1
  fi
done
exit $bad
