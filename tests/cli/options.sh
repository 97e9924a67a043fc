# Option tables (tools/optable.h): every option --help lists is accepted,
# typos get the nearest name, check --stats, and the progress line on a
# terminal (through a pseudo-terminal made by script(1)).
. "$(dirname "$0")/lib.sh"
"$CLI" generate column --blocks 3 -o "$T/c.json" >/dev/null

# Each option in a command's help is one the parser knows: given with a
# value (or with "x" as the file for a flag), it is never "unknown".
for c in check plan verify render count classify import-svg generate; do
  "$CLI" $c --help >"$T/help"
  opts=$(sed -n 's/^  \(-[a-z], \)\{0,1\}\(--[a-z0-9-]*\).*/\2/p' "$T/help")
  n=0
  for o in $opts; do
    n=$((n + 1))
    if [ $c = generate ]; then "$CLI" generate column $o 1 --help >/dev/null 2>"$T/err"
    else "$CLI" $c $o x --help >/dev/null 2>"$T/err"; fi
    grep -qF "unknown option '$o'" "$T/err" && bad "$c: --help lists $o, the parser refuses it"
  done
  [ $n -ge 1 ] && ok "$c: the $n options of --help are accepted" || bad "$c: no option in --help"
done

# The top-level help lists every kind generate takes, and render's formats.
"$CLI" --help >"$T/top"
"$CLI" generate castle -o "$T/x.json" 2>"$T/kinds"
kinds=$(sed -n "s/.*unknown kind 'castle' (\([^)]*\)).*/\1/p" "$T/kinds" | tr -d ,)
missing=""
for k in $kinds; do grep -qw -- "$k" "$T/top" || missing="$missing $k"; done
[ -n "$kinds" ] && [ -z "$missing" ] && ok "top-level help lists the $(echo $kinds | wc -w) kinds" ||
  bad "top-level help misses kinds:$missing"
contains "$T/top" "SVG, PNG or an HTML viewer" "top-level help: render's formats"

# Did you mean: commands, options, enum words, generate kinds.
expect 2 "typo in a command" -- "$CLI" chekc "$T/c.json"
contains "$T/err" "did you mean 'check'" "suggests check"
expect 2 "typo in an option" -- "$CLI" plan "$T/c.json" --metod lp
contains "$T/err" "unknown option '--metod' (did you mean --method?)" "suggests --method"
expect 2 "swapped letters" -- "$CLI" render "$T/c.json" -o "$T/c.svg" --froces
contains "$T/err" "did you mean --forces?" "suggests --forces"
expect 2 "typo in a method" -- "$CLI" check "$T/c.json" --method lpsolv
contains "$T/err" "unknown method 'lpsolv'" "names the bad method"
contains "$T/err" "did you mean 'lpsolve'?" "suggests lpsolve"
expect 2 "typo in a search" -- "$CLI" plan "$T/c.json" --search asemble
contains "$T/err" "did you mean 'assemble'?" "suggests assemble"
expect 2 "typo in a kind" -- "$CLI" generate pyramd -o "$T/p.json"
contains "$T/err" "did you mean 'pyramid'?" "suggests pyramid"
expect 2 "far from every option" -- "$CLI" plan "$T/c.json" --zzzzzzzz
grep -q "did you mean" "$T/err" && bad "no suggestion when nothing is near" || ok "no suggestion when nothing is near"
expect 2 "value errors keep their message" -- "$CLI" plan "$T/c.json" --max-group 65
contains "$T/err" "--max-group needs 'auto' or an integer from 1 to 64, got '65'" "max-group message"
expect 2 "generate: too large" -- "$CLI" generate column --blocks 99999999999 -o "$T/z.json"
contains "$T/err" "--blocks: 99999999999 is too large" "too-large message"

# --name=value is the same as --name value; a flag takes no value.
expect 0 "--method=lpsolve" -- "$CLI" check "$T/c.json" --method=lpsolve
contains "$T/out" "stable" "the value after = is used"
expect 2 "--method=bad" -- "$CLI" check "$T/c.json" --method=simplex
contains "$T/err" "unknown method 'simplex'" "the value after = is checked"
expect 2 "a flag with a value" -- "$CLI" check "$T/c.json" --forces=yes
contains "$T/err" "option --forces takes no value" "flag value refused"
expect 2 "typo with =" -- "$CLI" check "$T/c.json" --metod=lp
contains "$T/err" "did you mean --method?" "suggests --method for --metod=lp"

# check --stats: tests, time, solver, local tests.
expect 0 "check --stats" -- "$CLI" check "$T/c.json" --stats
contains "$T/out" "statistics:" "check prints statistics"
contains "$T/out" "tests 1, method " "one test, and the method used"
contains "$T/out" "in solver" "solver time"
contains "$T/out" "LCP pivots" "solver counters"
contains "$T/out" "local tests:" "local-test statistics"

# The progress line needs a terminal on stderr: script(1) gives one.
if command -v script >/dev/null && script -qec true /dev/null >/dev/null 2>&1; then
  "$CLI" generate pyramid --rows 8 -o "$T/p.json" >/dev/null
  "$CLI" plan "$T/p.json" -o "$T/p.plan.json" >/dev/null
  # a DFS that takes the wrong body first: many reports, removals up and down
  script -qec "'$CLI' plan '$T/p.json' --search dfs --rules none --order lowest --method lpsolve --max-tests 800" /dev/null \
    </dev/null >"$T/tty" 2>&1
  tr '\r' '\n' <"$T/tty" | grep -a "bodies removed" >"$T/lines"
  if grep -aqE '^plan: [0-9]+/36 bodies removed \([0-9]+%\), [0-9]+ tests' "$T/lines"; then
    ok "plan: progress with total and percentage"
  else bad "plan: no progress line"; sed 's/^/    /' "$T/tty" | head -5; fi
  sed -n 's/^plan: \([0-9]*\)\/.*/\1/p' "$T/lines" | sort -n -c 2>/dev/null &&
    ok "plan: the body count never goes down" || bad "plan: the body count goes down"
  script -qec "'$CLI' verify '$T/p.json' '$T/p.plan.json'" /dev/null </dev/null >"$T/tty" 2>&1
  tr '\r' '\n' <"$T/tty" | grep -aqE '^verify: [0-9]+/36 steps checked \([0-9]+%\)' &&
    ok "verify: progress with total and percentage" || bad "verify: no progress line"
else
  ok "no script(1): progress line not tested"
fi
finish
