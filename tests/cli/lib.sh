# Helpers for the CLI tests: each test script sources this file and is run
# by ctest as `bash script.sh CLI DATA_DIR`. Prints one line per check and
# "N passed, N failed" at the end; exits non-zero on any failure.
CLI=$1
DATA=$2
T=$(mktemp -d)
trap 'rm -rf "$T"' EXIT
pass=0
fail=0
ok() { pass=$((pass + 1)); echo "ok   $*"; }
bad() { fail=$((fail + 1)); echo "FAIL $*"; }
# expect CODE DESCRIPTION -- command...: run, compare the exit code
expect() {
  local want=$1 what=$2
  shift 3
  "$@" >"$T/out" 2>"$T/err"
  local got=$?
  if [ "$got" -eq "$want" ]; then ok "$what"; else
    bad "$what (exit $got, wanted $want)"; sed 's/^/    /' "$T/out" "$T/err" | head -20
  fi
}
# contains FILE TEXT DESCRIPTION
contains() {
  if grep -qF -- "$2" "$1"; then ok "$3"; else bad "$3 ('$2' not in output)"; sed 's/^/    /' "$1" | head -10; fi
}
finish() {
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
