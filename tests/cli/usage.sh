# Usage: --help everywhere, unknown commands and options, missing files.
. "$(dirname "$0")/lib.sh"
expect 0 "unstack --help" -- "$CLI" --help
for c in check plan verify render generate; do
  expect 0 "$c --help" -- "$CLI" $c --help
  contains "$T/out" "usage: unstack $c" "$c help text"
done
expect 2 "no command" -- "$CLI"
expect 2 "unknown command" -- "$CLI" frobnicate
expect 2 "check without file" -- "$CLI" check
expect 2 "missing file" -- "$CLI" check "$T/nope.json"
contains "$T/err" "nope.json" "names the missing file"
"$CLI" generate column --blocks 2 -o "$T/c.json" >/dev/null
expect 2 "unknown option" -- "$CLI" plan "$T/c.json" --frob
expect 2 "bad method" -- "$CLI" check "$T/c.json" --method simplex
expect 2 "bad number" -- "$CLI" plan "$T/c.json" --max-tests ten
expect 2 "non-finite tolerance" -- "$CLI" check "$T/c.json" --contact-tol nan
expect 2 "generate unknown kind" -- "$CLI" generate castle -o "$T/t.json"
expect 2 "generate bad size" -- "$CLI" generate column --blocks 0 -o "$T/z.json"
[ -e "$T/z.json" ] && bad "file written on error" || ok "no file written on error"
expect 2 "render needs -o" -- "$CLI" render "$T/c.json"
finish
