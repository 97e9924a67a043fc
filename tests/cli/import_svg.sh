# unstack import-svg: the source's Figure 1 trio drawn as SVG imports and
# plans as a user expects (column: top-down; cantilever: the cantilever
# before its counterweight; arch: none), the Inkscape drawing imports with
# its layers and transforms, and bad drawings exit 2 with nothing written.
. "$(dirname "$0")/lib.sh"
EX="$DATA/../../examples"

# order FILE: the plan's removal order as "a b c" (one line of the plan file)
order() { sed -n 's/^ *"order": \[\(.*\)\],*$/\1/p' "$1" | tr -d '",'; }
# position ID in an order string: 1-based, 0 when absent
position() { echo "$2" | tr ' ' '\n' | grep -nx -- "$1" | cut -d: -f1 | head -1; }

# --- column: top-down
expect 0 "column imports" -- "$CLI" import-svg "$EX/column.svg" -o "$T/column.json"
contains "$T/out" "3 bodies (0 fixed)" "column: 3 bodies"
contains "$T/err" "column.svg:12: <text>: skipped" "column: the label is skipped with its line"
expect 0 "column plans" -- "$CLI" plan "$T/column.json" -o "$T/column-plan.json"
got=$(order "$T/column-plan.json")
[ "$got" = "top middle base" ] && ok "column comes apart top-down" || bad "column order '$got'"
expect 0 "column plan verifies" -- "$CLI" verify "$T/column.json" "$T/column-plan.json"

# --- cantilever: the cantilevered block before its counterweight, with every search
expect 0 "cantilever imports" -- "$CLI" import-svg "$EX/cantilever.svg" -o "$T/cant.json"
for search in assemble dfs bfs; do
  expect 0 "cantilever plans ($search)" -- "$CLI" plan "$T/cant.json" --search $search -o "$T/cant-plan.json"
  got=$(order "$T/cant-plan.json")
  c=$(position cantilever "$got") w=$(position counterweight "$got")
  if [ -n "$c" ] && [ -n "$w" ] && [ "$c" -lt "$w" ]; then ok "cantilever before counterweight ($search: $got)"
  else bad "cantilever order ($search): '$got'"; fi
  expect 0 "cantilever plan verifies ($search)" -- "$CLI" verify "$T/cant.json" "$T/cant-plan.json"
done
# the highest-first order (counterweight first) is refused by verify
sed 's/^ *"order": \[.*\]/  "order": ["counterweight", "cantilever", "block", "pier"]/' "$T/cant-plan.json" >"$T/wrong.json"
expect 1 "counterweight first fails verify" -- "$CLI" verify "$T/cant.json" "$T/wrong.json"

# --- arch: no block can be removed alone
expect 0 "arch imports" -- "$CLI" import-svg "$EX/arch.svg" -o "$T/arch.json"
contains "$T/out" "9 bodies (2 fixed)" "arch: seven voussoirs and two fixed piers"
expect 1 "arch: no plan" -- "$CLI" plan "$T/arch.json" -o "$T/arch-plan.json"
contains "$T/arch-plan.json" '"status": "none"' "arch: status none"
expect 0 "arch stands" -- "$CLI" check "$T/arch.json"

# --- the Inkscape drawing: mm units, layers, transforms, relative path, arc
expect 0 "inkscape drawing imports" -- "$CLI" import-svg "$EX/inkscape_trilithon.svg" --unit mm -o "$T/tri.json"
contains "$T/out" "6 bodies (1 fixed)" "inkscape: 6 bodies, the plinth fixed"
contains "$T/err" "<g id='layer3'>: skipped (display: none)" "inkscape: hidden layer skipped"
contains "$T/tri.json" '"polygon": [[108, 50], [108, 5], [120, 5], [120, 50]]' "inkscape: relative path in mm"
expect 0 "inkscape drawing plans" -- "$CLI" plan "$T/tri.json" -o "$T/tri-plan.json"
got=$(order "$T/tri-plan.json")
[ "$(position finial "$got")" = 1 ] && ok "finial first ($got)" || bad "trilithon order '$got'"
expect 0 "quiet: no warnings" -- "$CLI" import-svg "$EX/inkscape_trilithon.svg" -q -o "$T/tri2.json"
[ -s "$T/err" ] && bad "warnings printed with -q" || ok "no warnings with -q"

# --- a thin plank on the ground (2000 x 1 px): snapping keeps its height
printf '%s\n' "<svg xmlns='http://www.w3.org/2000/svg' width='2000' height='100'>" \
  "<rect id='plank' x='0' y='99' width='2000' height='1'/></svg>" >"$T/plank.svg"
for snap in "" "--snap 5"; do
  expect 0 "plank imports ${snap:-(default snap)}" -- "$CLI" import-svg "$T/plank.svg" $snap --unit px -o "$T/plank.json"
  contains "$T/plank.json" '[[0, 1], [0, 0], [2000, 0], [2000, 1]]' "plank keeps its height ${snap:-(default snap)}"
  expect 0 "plank stands ${snap:-(default snap)}" -- "$CLI" check "$T/plank.json"
  contains "$T/out" "stable: 1 bodies" "plank: stable ${snap:-(default snap)}"
done

# --- options
printf '%s\n' "<svg xmlns='http://www.w3.org/2000/svg' width='100mm' height='50mm' viewBox='0 0 200 100'>" \
  "<rect id='a' x='0' y='80' width='20' height='20'/></svg>" >"$T/unit.svg"
expect 0 "--unit cm" -- "$CLI" import-svg "$T/unit.svg" --unit cm -o "$T/u.json"
contains "$T/u.json" '[[0, 1], [0, 0], [1, 0], [1, 1]]' "--unit cm: 20 units of 0.5 mm = 1 cm"
expect 0 "--ground-at" -- "$CLI" import-svg "$T/unit.svg" --unit user --ground-at 110 -o "$T/g.json"
contains "$T/g.json" '[[0, 30], [0, 10], [20, 10], [20, 30]]' "--ground-at 110: 10 units above the ground"
expect 0 "--scale" -- "$CLI" import-svg "$T/unit.svg" --unit mm --scale 100 -o "$T/s.json"
contains "$T/s.json" '[[0, 1000], [0, 0], [1000, 0], [1000, 1000]]' "--scale 100: a drawing at 1:100"
expect 0 "help" -- "$CLI" import-svg --help
contains "$T/out" "--snap TOL" "help names --snap"
expect 0 "listed in the command list" -- "$CLI" --help
contains "$T/out" "import-svg" "unstack --help lists import-svg"

# --- bad input: exit 2, a message with file, line and element, nothing written
bad_svg() { # NAME TEXT FRAGMENT
  printf '%s\n' "$2" >"$T/$1.svg"
  expect 2 "$1: exit 2" -- "$CLI" import-svg "$T/$1.svg" -o "$T/$1.json"
  contains "$T/err" "$3" "$1: says '$3'"
  [ -e "$T/$1.json" ] && bad "$1: output written" || ok "$1: nothing written"
}
bad_svg malformed "<svg xmlns='http://www.w3.org/2000/svg'>
<rect width='1' height=1/></svg>" "malformed.svg:2: malformed XML"
bad_svg command "<svg xmlns='http://www.w3.org/2000/svg'>
<path id='p' d='M 0 0 L 1 0 K 1 1 Z'/></svg>" "command.svg:2: <path id='p'>: path data: unknown command 'K'"
bad_svg overlap "<svg xmlns='http://www.w3.org/2000/svg'>
<rect id='left' width='10' height='10'/>
<rect id='right' x='5' width='10' height='10'/></svg>" "bodies 'left' and 'right' overlap"
bad_svg degenerate "<svg xmlns='http://www.w3.org/2000/svg'>
<polygon id='line' points='0,0 5,5 10,10'/></svg>" "degenerate.svg:2: <polygon id='line'>: degenerate shape"
bad_svg infinite "<svg xmlns='http://www.w3.org/2000/svg'>
<rect width='1e999' height='1'/></svg>" "infinite.svg:2: <rect>: width is not finite"
bad_svg overflow "<svg xmlns='http://www.w3.org/2000/svg'>
<rect x='1e308' width='1' height='1' transform='scale(10)'/></svg>" "overflow.svg:2: <rect>: a coordinate overflows"
bad_svg huge "<svg xmlns='http://www.w3.org/2000/svg'>
<rect width='1e200' height='1e200'/></svg>" "huge.svg:2: <rect>: coordinates too large: the shape's area or inertia overflows"
bad_svg empty "<svg xmlns='http://www.w3.org/2000/svg'><text>hello</text></svg>" "no shapes to import"
# entity bombs (issue 24): one 20 kB entity 6,000 times in a class (38 kB of
# file, 120 MB expanded) and 35,000 times (160 kB), refused before any
# expansion; under a memory cap where the build allows one (not ASan)
bomb() { # NAME REFS
  { printf "<?xml version='1.0'?>\n<!DOCTYPE svg [<!ENTITY e '"; head -c 20000 /dev/zero | tr '\0' x
    printf "'>]>\n<svg xmlns='http://www.w3.org/2000/svg'>\n<g>\n<rect id='r' class='"
    yes '&e;' | head -n "$2" | tr '\n' ' '; printf "' width='10' height='10'/></g></svg>\n"; } >"$T/$1.svg"
}
capped() { bash -c "$cap; exec \"\$0\" \"\$@\"" "$@"; }
cap="ulimit -v 250000"
capped "$CLI" import-svg "$EX/column.svg" -q -o "$T/capped.json" >/dev/null 2>&1 || cap=true
[ "$cap" = true ] && echo "(no memory cap in this build)"
for b in "bomb38 6000" "bomb160 35000"; do
  set -- $b
  bomb "$1" "$2"
  expect 2 "$1: exit 2" -- capped "$CLI" import-svg "$T/$1.svg" -o "$T/$1.json"
  contains "$T/err" "$1.svg:5: <rect id='r'>: attribute 'class': entity references expand past" "$1: says where and why"
  [ -e "$T/$1.json" ] && bad "$1: output written" || ok "$1: nothing written"
done
# over 64 MiB: refused before it is read (a sparse file)
truncate -s 65M "$T/huge65.svg"
expect 2 "65 MiB drawing: exit 2" -- "$CLI" import-svg "$T/huge65.svg" -o "$T/huge65.json"
contains "$T/err" "huge65.svg: too large (68157440 bytes): the import reads at most 64 MiB" "65 MiB drawing: says why"
laughs="<!ENTITY l0 'lol'>"
for i in 1 2 3 4 5 6 7 8 9; do laughs="$laughs<!ENTITY l$i '$(printf "&l$((i - 1));%.0s" 1 2 3 4 5 6 7 8 9 10)'>"; done
bad_svg laughs "<!DOCTYPE svg [$laughs]>
<svg xmlns='http://www.w3.org/2000/svg'><rect class='&l9;' width='1' height='1'/></svg>" "entities that expand too much"
# an existing output stays as it was
echo keep >"$T/kept.json"
expect 2 "bad drawing over an existing file" -- "$CLI" import-svg "$T/overlap.svg" -o "$T/kept.json"
[ "$(cat "$T/kept.json")" = keep ] && ok "existing output untouched" || bad "existing output changed"
expect 2 "output is the input" -- "$CLI" import-svg "$T/unit.svg" -o "$T/unit.svg"
expect 2 "missing drawing" -- "$CLI" import-svg "$T/none.svg" -o "$T/none.json"
[ -e "$T/none.json" ] && bad "missing drawing: output written" || ok "missing drawing: nothing written"
expect 2 "bad unit" -- "$CLI" import-svg "$T/unit.svg" --unit furlong -o "$T/x.json"
expect 2 "negative snap" -- "$CLI" import-svg "$T/unit.svg" --snap -1 -o "$T/x.json"
expect 2 "no output" -- "$CLI" import-svg "$T/unit.svg"
leftover=$(ls "$T" | grep -c '\.tmp\.' || true)
[ "$leftover" -eq 0 ] && ok "no temporary files left" || bad "$leftover temporary files left"
finish
