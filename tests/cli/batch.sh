# unstack batch (docs/batch.md) and generate --count: one line per input in
# input order, error lines carrying the single command's message, statuses
# equal to the single commands', the same lines whatever --jobs and over
# MPI ranks, --resume after a cut output, directory and stdin inputs.
# Nothing here depends on timing: the "time" field is dropped before
# comparing.
. "$(dirname "$0")/lib.sh"

notime() { sed 's/,"time":[0-9.e+-]*//' "$@"; }
# same FILE1 FILE2 DESCRIPTION: equal once the times are dropped
same() {
  if cmp -s <(notime "$1") <(notime "$2"); then ok "$3"; else
    bad "$3"; diff <(notime "$1") <(notime "$2") | head -10 | sed 's/^/    /'; fi
}
# field LINE NAME: the value of a top-level string or number field
field() { printf '%s\n' "$1" | sed -n "s/.*\"$2\":\"\{0,1\}\([^\",}]*\).*/\1/p"; }

# --- generate --count: consecutive seeds, names that sort as seeds
D=$T/set
expect 0 "generate --count 12" -- "$CLI" generate random --rows 5 --width 4 --count 12 --seed 3 -o "$D/"
contains "$T/out" "wrote 12 structures" "generate --count says how many"
n=$(ls "$D" | wc -l)
[ "$n" -eq 12 ] && ok "12 files written" || bad "12 files written (got $n)"
[ -f "$D/random-03.json" ] && [ -f "$D/random-14.json" ] && ok "seeds 3..14, zero-padded" \
  || bad "seeds 3..14, zero-padded: $(ls "$D" | head -3 | tr '\n' ' ')"
"$CLI" generate random --rows 5 --width 4 --seed 9 -o "$T/seed9.json" >/dev/null
cmp -s "$T/seed9.json" "$D/random-09.json" && ok "file of seed 9 = generate --seed 9" \
  || bad "file of seed 9 = generate --seed 9"
expect 0 "generate stacker --count 4" -- "$CLI" generate stacker --rows 5 --width 6 --count 4 -o "$D"
"$CLI" generate arch --voussoirs 9 --radius 3 --thickness 0.6 -o "$D/arch.json" >/dev/null
cp "$DATA/greedy_stuck.json" "$DATA/column3.json" "$D/"
expect 2 "generate --count into a file is refused" -- "$CLI" generate column --count 2 -o "$T/seed9.json"

# --- three broken files: malformed JSON, an unknown id, a non-finite number
B=$T/broken
mkdir -p "$B"
cp "$DATA/bad/malformed.json" "$DATA/bad/unknown_contact_id.json" "$DATA/bad/nan.json" "$B/"
{ printf '%s\n' "$D"/*.json | LC_ALL=C sort; printf '%s\n' "$B"/*.json | LC_ALL=C sort; } >"$T/list"
N=$(wc -l <"$T/list")

# --- one line per input, in input order; exit 1: some input failed
expect 1 "batch with broken files exits 1" -- "$CLI" batch "$D" "$B" -o "$T/j2.jsonl" --jobs 2
contains "$T/out" "3 errors" "summary counts the errors"
lines=$(wc -l <"$T/j2.jsonl")
[ "$lines" -eq "$N" ] && ok "one line per input ($N)" || bad "one line per input ($lines, wanted $N)"
files=$(sed 's/^{"file":"\([^"]*\)".*/\1/' "$T/j2.jsonl")
[ "$files" = "$(cat "$T/list")" ] && ok "lines in input order (directories sorted)" \
  || bad "lines in input order"
for f in "$B"/*.json; do
  want=$("$CLI" plan "$f" 2>&1 >/dev/null)
  line=$(grep -F "\"file\":\"$f\"" "$T/j2.jsonl")
  got=$(printf '%s\n' "$line" | python3 -c 'import json,sys; print(json.loads(sys.stdin.read())["error"])')
  [ -n "$want" ] && [ "$got" = "$want" ] && ok "error line of $(basename "$f") = plan's message" \
    || bad "error line of $(basename "$f"): '$got' vs '$want'"
done
errs=$(grep -c '"error"' "$T/j2.jsonl")
[ "$errs" -eq 3 ] && ok "exactly the 3 broken files give error lines" || bad "error lines: $errs"

# --- statuses (and exit codes, tests, orders) equal to unstack plan alone
k=0
for f in "$D/random-04.json" "$D/random-11.json" "$D/arch.json" "$D/greedy_stuck.json" \
         "$D/stacker-2.json" "$D/column3.json"; do
  "$CLI" plan "$f" --print >"$T/single"
  code=$?
  status=$(head -1 "$T/single" | sed 's/[:,].*//')
  line=$(grep -F "\"file\":\"$f\"" "$T/j2.jsonl")
  [ "$(field "$line" status)" = "$status" ] && [ "$(field "$line" exit)" = "$code" ] \
    && ok "$(basename "$f"): $status (exit $code) as plan alone" \
    || bad "$(basename "$f"): batch '$line' vs plan '$status' exit $code"
  if [ "$status" = found ]; then
    want=$(tail -n +2 "$T/single" | cut -f2- | tr '\t' ',' | sed 's/[^,][^,]*/"&"/g; s/^/[/; s/$/]/' | paste -sd, -)
    printf '%s\n' "$line" | grep -qF "\"order\":[$want]" && ok "$(basename "$f"): same order as plan --print" \
      || bad "$(basename "$f"): order differs from plan --print ($want)"
  fi
  k=$((k + 1))
done
grep -q '"status":"none"' "$T/j2.jsonl" && grep -q '"status":"found"' "$T/j2.jsonl" \
  && ok "the set has found and none statuses" || bad "the set should mix found and none"

# --- --jobs 1 and 2: identical lines, times aside
"$CLI" batch "$D" "$B" -o "$T/j1.jsonl" --jobs 1 >/dev/null
same "$T/j1.jsonl" "$T/j2.jsonl" "--jobs 1 and --jobs 2 give identical lines"

# --- inputs: stdin, mixed with a file
cut -c1- "$T/list" | "$CLI" batch - -o "$T/stdin.jsonl" --jobs 2 >/dev/null
same "$T/stdin.jsonl" "$T/j2.jsonl" "paths on stdin give the same lines"
expect 2 "'-' twice is refused" -- "$CLI" batch - - -o "$T/x.jsonl"

# --- --resume after a cut output: nothing lost, nothing repeated
head -c "$(( $(head -n 7 "$T/j2.jsonl" | wc -c) + 25 ))" "$T/j2.jsonl" >"$T/cut.jsonl"
"$CLI" batch "$D" "$B" -o "$T/cut.jsonl" --resume --jobs 2 >"$T/resume.out"
contains "$T/resume.out" "7 kept" "resume keeps the 7 whole lines"
same "$T/cut.jsonl" "$T/j2.jsonl" "resumed output = a whole run (cut line redone, none repeated)"
"$CLI" batch "$D" "$B" -o "$T/cut.jsonl" --resume >"$T/resume2.out"
contains "$T/resume2.out" "0 answered now" "a finished output is left as it is"
same "$T/cut.jsonl" "$T/j2.jsonl" "and unchanged"

# a batch killed at any moment, then resumed: the same lines (whenever the
# kill lands, even after the end)
"$CLI" batch "$D" "$B" -o "$T/killed.jsonl" --jobs 2 >/dev/null 2>&1 &
pid=$!
sleep 0.05
kill -9 "$pid" 2>/dev/null
wait "$pid" 2>/dev/null
"$CLI" batch "$D" "$B" -o "$T/killed.jsonl" --resume --jobs 2 >/dev/null
same "$T/killed.jsonl" "$T/j2.jsonl" "killed with SIGKILL, then --resume: no line lost or repeated"

# an empty directory, an empty output resumed: no lines, no error
mkdir -p "$T/empty"
: >"$T/empty.jsonl"
expect 0 "an empty directory, --resume on an empty OUT" -- "$CLI" batch "$T/empty" -o "$T/empty.jsonl" --resume
[ ! -s "$T/empty.jsonl" ] && ok "no lines for no inputs" || bad "lines written for no inputs"

# --- check and classify: the single commands' verdicts
"$CLI" batch "$D" -o "$T/check.jsonl" --task check --method lpsolve >/dev/null
for f in "$D/arch.json" "$D/random-05.json"; do
  "$CLI" check "$f" --method lpsolve >"$T/single"
  code=$?
  line=$(grep -F "\"file\":\"$f\"" "$T/check.jsonl")
  [ "$(field "$line" verdict)" = "$(sed 's/:.*//;q' "$T/single")" ] && [ "$(field "$line" exit)" = "$code" ] \
    && ok "check $(basename "$f"): verdict as check alone" || bad "check $(basename "$f"): $line"
done
"$CLI" batch "$D/column3.json" "$D/greedy_stuck.json" -o "$T/classify.jsonl" --task classify >/dev/null
grep -q '"file":"[^"]*column3.json","status":"classified".*"stands":true' "$T/classify.jsonl" \
  && ok "classify column3: stands" || bad "classify: $(head -1 "$T/classify.jsonl")"

# --- usage errors write nothing
expect 2 "no output" -- "$CLI" batch "$D"
expect 2 "unknown task" -- "$CLI" batch "$D" --task plot -o "$T/u.jsonl"
expect 2 "a plan option with a bad value" -- "$CLI" batch "$D" --max-group 99 -o "$T/u.jsonl"
expect 2 "plan's own output options are not batch's" -- "$CLI" batch "$D" --print -o "$T/u.jsonl"
expect 2 "output = an input" -- "$CLI" batch "$D" -o "$D/random-03.json"
[ ! -e "$T/u.jsonl" ] && ok "usage errors write no output file" || bad "u.jsonl written"

# --- libmpi is never linked: only batch under a launcher loads modules/mpi.so
if ldd "$CLI" | grep -q libmpi; then bad "unstack links libmpi"; else ok "unstack does not link libmpi"; fi

# --- MPI: mpirun -n 2 gives the same lines (when this build has MPI)
if "$CLI" --version | grep -q '^mpi: yes' && command -v mpirun >/dev/null; then
  asroot=""
  [ "$(id -u)" -eq 0 ] && asroot=--allow-run-as-root
  ASAN_OPTIONS=detect_leaks=0 OMPI_MCA_plm_rsh_agent= mpirun -n 2 $asroot --oversubscribe \
    "$CLI" batch "$D" "$B" -o "$T/mpi.jsonl" >"$T/mpi.out" 2>&1
  code=$?
  [ "$code" -eq 1 ] && ok "mpirun -n 2: exit 1 (broken files)" || { bad "mpirun -n 2: exit $code"; head "$T/mpi.out"; }
  contains "$T/mpi.out" "2 MPI ranks" "mpirun -n 2 ran over the ranks"
  same "$T/mpi.jsonl" "$T/j2.jsonl" "mpirun -n 2: the same lines as a local run"
else
  ok "mpirun (skipped: $("$CLI" --version | grep '^mpi'))"
fi
finish
