#!/usr/bin/env bash
# Source check (a ctest): every C++ file under ROOT (default: the repository) is formatted as
# ROOT/.clang-format says, with Debian's clang-format 14. Names each file that is not, and how to fix it.
#   scripts/check_format.sh [ROOT]
set -euo pipefail
root="${1:-$(dirname "$0")/..}"
cd "$root"
command -v clang-format >/dev/null || { echo "check_format: clang-format missing (scripts/setup.sh installs it)" >&2; exit 2; }
mapfile -t files < <(find master slave common tools tests benchmarks fuzz -type f \( -name '*.cpp' -o -name '*.hpp' \) 2>/dev/null | sort)
[ ${#files[@]} -gt 0 ] || { echo "check_format: no C++ files under $PWD" >&2; exit 2; }
# One clang-format per file, as many at once as there are cores; each names itself when it fails.
mapfile -t bad < <(printf '%s\0' "${files[@]}" |
  xargs -0 -P "$(nproc)" -n 1 sh -c 'clang-format --style=file --dry-run --Werror "$1" >/dev/null 2>&1 || echo "$1"' _ |
  sort)
if [ ${#bad[@]} -gt 0 ]; then
  printf 'check_format: not formatted: %s\n' "${bad[@]}" >&2
  echo "check_format: ${#bad[@]} of ${#files[@]} files; fix with: clang-format -i FILE..." >&2
  exit 1
fi
echo "check_format: ${#files[@]} files formatted"
