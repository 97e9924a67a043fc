# Messages that name the real cause: a plan for another structure names its
# first unknown id; a count beyond the generator's limit says the limit; a
# file starting with a UTF-8 byte order mark is read; an unknown enum word
# lists the words the tool accepts.
. "$(dirname "$0")/lib.sh"
"$CLI" generate column --blocks 3 -o "$T/c3.json" >/dev/null
"$CLI" generate pyramid --rows 3 -o "$T/p6.json" >/dev/null
"$CLI" plan "$T/p6.json" -o "$T/plan6.json" >/dev/null
expect 2 "verify a plan for another structure" -- "$CLI" verify "$T/c3.json" "$T/plan6.json"
contains "$T/err" "plan of another structure, not of $T/c3.json" "names both files (fingerprint)"
# without its fingerprint (an older file) the first unknown id says it
sed -i '/"fingerprint"/d' "$T/plan6.json"
expect 2 "verify an older plan for another structure" -- "$CLI" verify "$T/c3.json" "$T/plan6.json"
contains "$T/err" "unknown body id 'b" "names an unknown id"
contains "$T/err" "another structure" "suggests another structure"
if grep -q "more entries" "$T/err"; then bad "still says 'more entries'"; else ok "no 'more entries'"; fi
expect 2 "render with a plan for another structure" -- \
  "$CLI" render "$T/c3.json" --plan "$T/plan6.json" -o "$T/x.svg"
contains "$T/err" "unknown body id" "render: names the unknown id"

expect 2 "--blocks 2147483647" -- "$CLI" generate column --blocks 2147483647 -o "$T/big.json"
contains "$T/err" "limit of 10000000" "says the limit"
if grep -q "positive integer" "$T/err"; then bad "says 'positive integer'"; else ok "not 'positive integer'"; fi
expect 2 "--blocks 99999999999" -- "$CLI" generate column --blocks 99999999999 -o "$T/big.json"
contains "$T/err" "at most" "beyond int: says the bound"
expect 2 "--blocks 0" -- "$CLI" generate column --blocks 0 -o "$T/big.json"
contains "$T/err" "positive integer" "zero: positive integer"
[ -e "$T/big.json" ] && bad "file written" || ok "no file written"

printf '\357\273\277' >"$T/bom.json"
cat "$T/c3.json" >>"$T/bom.json"
expect 0 "check a file with a byte order mark" -- "$CLI" check "$T/bom.json"
printf '\357\273\277' >"$T/bomplan.json"
"$CLI" plan "$T/c3.json" -o "$T/plan3.json" >/dev/null
cat "$T/plan3.json" >>"$T/bomplan.json"
expect 0 "verify a plan with a byte order mark" -- "$CLI" verify "$T/c3.json" "$T/bomplan.json"

expect 2 "unknown method" -- "$CLI" check "$T/c3.json" --method simplex
contains "$T/err" "(lp, lpsolve, lcp, lcp-reuse, lp-lcp, auto)" "lists the methods"
expect 2 "unknown removal" -- "$CLI" plan "$T/c3.json" --removal sideways
contains "$T/err" "(any, up, free)" "lists the removals"
finish
