#!/bin/sh
# expect.sh ok|error REGEX -- COMMAND...
#   ok:    COMMAND exits 0 and its stdout matches REGEX (extended grep);
#   error: COMMAND exits with a status from 1 to 125 (an error, not a crash or a signal),
#          prints exactly one line on stderr, and that line matches REGEX.
mode=$1; regex=$2; shift 2
[ "$1" = "--" ] && shift
out=$(mktemp); err=$(mktemp)
trap 'rm -f "$out" "$err"' EXIT
"$@" >"$out" 2>"$err"
rc=$?
fail() { echo "FAIL: $*"; echo "--- stdout"; cat "$out"; echo "--- stderr"; cat "$err"; exit 1; }
case $mode in
  ok)
    [ $rc -eq 0 ] || fail "exit status $rc, expected 0"
    grep -Eq -- "$regex" "$out" || fail "stdout does not match /$regex/" ;;
  error)
    [ $rc -ge 1 ] && [ $rc -le 125 ] || fail "exit status $rc, expected an error status 1..125"
    [ "$(wc -l <"$err")" -eq 1 ] || fail "expected exactly one line on stderr"
    grep -Eq -- "$regex" "$err" || fail "stderr does not match /$regex/" ;;
  *) echo "usage: expect.sh ok|error REGEX -- COMMAND..."; exit 2 ;;
esac
cat "$out" "$err"
