#!/usr/bin/env bash
# Source check (a ctest): no function in master/, slave/, common/ or tools/ under ROOT (default: the
# repository) is longer than MAX lines (default 80), as Universal Ctags measures it (from the
# line of its name to its `end:` line). Lambdas count in the function that holds them.
# The one allowed exception is the reference integrator's multiple_scattering (its comment says why).
#   scripts/check_function_length.sh [ROOT] [MAX]
set -euo pipefail
root="${1:-$(dirname "$0")/..}"
max="${2:-80}"
cd "$root"
command -v ctags >/dev/null || { echo "check_function_length: ctags missing (scripts/setup.sh installs universal-ctags)" >&2; exit 2; }
dirs=()
for d in master slave common tools; do [ -d "$d" ] && dirs+=("$d"); done
[ ${#dirs[@]} -gt 0 ] || { echo "check_function_length: no source folders under $PWD" >&2; exit 2; }
long="$(ctags -R --languages=C++ --kinds-C++=f --fields=+ne -x --_xformat='%{end} %{line} %N %F' "${dirs[@]}" |
  awk -v max="$max" '$1 ~ /^[0-9]+$/ { n = $1 - $2 + 1; if (n > max) printf "%s:%s: %s is %d lines\n", $4, $2, $3, n }' |
  grep -v '^common/atmosphere/reference_integrator.cpp:[0-9]*: multiple_scattering ' || true)"
if [ -n "$long" ]; then
  echo "$long" >&2
  echo "check_function_length: functions over $max lines (split them into named steps)" >&2
  exit 1
fi
echo "check_function_length: every function in ${dirs[*]} is at most $max lines"
