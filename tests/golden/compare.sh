#!/usr/bin/env bash
# Golden comparison: run the golden commands on TREE and diff them against the baseline.
#   python3 tests/golden/run.py OLD_TREE $GOLDEN/before     # once: the baseline
#   bash tests/golden/compare.sh TREE
# GOLDEN (default /tmp/dyade-golden) holds the runs. Writes $GOLDEN/after-$(basename TREE)
# (emptied first), compares it with $GOLDEN/before, prints the number of files compared
# and every file that differs or exists on one side only. Exit status 0: byte-identical;
# 1: differences (diff -r $GOLDEN/before $GOLDEN/after-NAME); 2: usage or run error.
# The same interpreter must make both runs ($GOLDEN/venv/bin/python where it exists).
set -uo pipefail
if [ $# -ne 1 ] || [ ! -d "$1" ]; then
    echo "usage: bash $0 TREE   (a dyade checkout: TREE/dyade, TREE/mechanisms)" >&2
    exit 2
fi
HERE=${GOLDEN:-/tmp/dyade-golden}
SCRIPT=$(cd "$(dirname "$0")" && pwd)
TREE=$(cd "$1" && pwd)
BEFORE=$HERE/before
AFTER=$HERE/after-$(basename "$TREE")
if [ "$AFTER" = "$BEFORE" ] || [ "$AFTER" = "$HERE/before2" ]; then
    echo "refusing to overwrite $AFTER" >&2; exit 2
fi
[ -d "$BEFORE" ] || { echo "no baseline run in $BEFORE" >&2; exit 2; }
PY=$HERE/venv/bin/python
[ -x "$PY" ] || PY=python3
GOLDEN_NO_VENV=1 "$PY" "$SCRIPT/run.py" "$TREE" "$AFTER" || { echo "golden run failed" >&2; exit 2; }

cd "$BEFORE" && find . -type f | sort > /tmp/golden-cmp-before.$$
cd "$AFTER" && find . -type f | sort > /tmp/golden-cmp-after.$$
compared=$(sort -u /tmp/golden-cmp-before.$$ /tmp/golden-cmp-after.$$ | wc -l)
only_before=$(comm -23 /tmp/golden-cmp-before.$$ /tmp/golden-cmp-after.$$)
only_after=$(comm -13 /tmp/golden-cmp-before.$$ /tmp/golden-cmp-after.$$)
changed=$(comm -12 /tmp/golden-cmp-before.$$ /tmp/golden-cmp-after.$$ | while read -r f; do
    cmp -s "$BEFORE/$f" "$AFTER/$f" || echo "$f"; done)
rm -f /tmp/golden-cmp-before.$$ /tmp/golden-cmp-after.$$
count() { [ -z "$1" ] && echo 0 || printf '%s\n' "$1" | wc -l; }
n_changed=$(count "$changed"); n_before=$(count "$only_before"); n_after=$(count "$only_after")
differing=$((n_changed + n_before + n_after))
echo "golden compare: $TREE vs baseline"
echo "  files compared: $compared   files differing: $differing" \
     "(changed $n_changed, only in before $n_before, only in after $n_after)"
[ -n "$changed" ] && printf '%s\n' "$changed" | sed 's|^\./|  changed: |'
[ -n "$only_before" ] && printf '%s\n' "$only_before" | sed 's|^\./|  only in before: |'
[ -n "$only_after" ] && printf '%s\n' "$only_after" | sed 's|^\./|  only in after: |'
if [ "$differing" -eq 0 ]; then
    echo "  IDENTICAL"
    exit 0
fi
echo "  details: diff -r $BEFORE $AFTER"
exit 1
