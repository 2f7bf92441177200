#!/usr/bin/env bash
# The source checks fail where they should: a scratch tree with one badly formatted file and one
# 81-line function must be refused by scripts/check_format.sh and scripts/check_function_length.sh,
# and the same tree mended must pass.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/common"
cp "$here/.clang-format" "$tmp/"
{
  echo "int long_function() {"
  echo "    int x = 0;"
  for i in $(seq 1 78); do echo "    x += $i;"; done
  echo "}"
} > "$tmp/common/long.cpp"   # 81 lines from name to end
printf 'int  badly ( int a ){return a;}\n' > "$tmp/common/bad.cpp"
fail() { echo "test_source_checks: $*" >&2; exit 1; }

if bash "$here/scripts/check_format.sh" "$tmp" 2>"$tmp/fmt.err"; then fail "check_format accepted common/bad.cpp"; fi
grep -q 'common/bad.cpp' "$tmp/fmt.err" || fail "check_format did not name common/bad.cpp: $(cat "$tmp/fmt.err")"
grep -q 'common/long.cpp' "$tmp/fmt.err" && fail "check_format named the well-formatted common/long.cpp"
if bash "$here/scripts/check_function_length.sh" "$tmp" 2>"$tmp/len.err"; then fail "check_function_length accepted an 81-line function"; fi
grep -q 'common/long.cpp:1: long_function is 81 lines' "$tmp/len.err" || fail "unexpected report: $(cat "$tmp/len.err")"

sed -i '/x += 78;/d' "$tmp/common/long.cpp"   # 80 lines: allowed
clang-format -i "$tmp/common/bad.cpp"
bash "$here/scripts/check_function_length.sh" "$tmp" >/dev/null || fail "check_function_length refused an 80-line function"
bash "$here/scripts/check_format.sh" "$tmp" >/dev/null || fail "check_format refused a formatted tree"
echo "test_source_checks: both checks refuse the violations and accept the mended tree"
