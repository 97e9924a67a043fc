# unstack render: the format from --format or the output's extension (PNG
# files are PNG, SVG files XML), sizes, the title's status, and every error
# (bad --format, an extension that names no format, unwritable outputs, bad
# input, a PNG too large) is exit 2 with nothing written; a 3D structure
# as PNG and SVG, turned by --view, bad views refused, labels of hidden
# bodies left out.
. "$(dirname "$0")/lib.sh"
"$CLI" generate column --blocks 3 -o "$T/c.json" >/dev/null || bad "generate column"
"$CLI" plan "$T/c.json" -o "$T/c-plan.json" >/dev/null || bad "plan column"
"$CLI" generate arch --voussoirs 7 -o "$T/arch.json" >/dev/null || bad "generate arch"
"$CLI" plan "$T/arch.json" -o "$T/arch-plan.json" >/dev/null
[ $? -eq 1 ] && ok "the arch has no plan" || bad "the arch has a plan"

is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ]; }
is_svg() { head -c 5 "$1" | grep -q '^<?xml'; }
# width and height of a PNG from its IHDR chunk (big-endian, bytes 16..23)
png_size() { od -An -tu1 -j16 -N8 "$1" | awk '{print $1*16777216+$2*65536+$3*256+$4 "x" $5*16777216+$6*65536+$7*256+$8}'; }
check_png() { if is_png "$1"; then ok "$2"; else bad "$2: not a PNG"; fi; }
check_svg() { if is_svg "$1"; then ok "$2"; else bad "$2: not an SVG"; fi; }
absent() { if [ -e "$1" ]; then bad "$2: $1 was written"; else ok "$2: nothing written"; fi; }

# the format from the extension, any case, or from --format
expect 0 "render -o x.png" -- "$CLI" render "$T/c.json" --plan "$T/c-plan.json" -o "$T/x.png"
check_png "$T/x.png" ".png is PNG"
expect 0 "render -o x.svg" -- "$CLI" render "$T/c.json" --plan "$T/c-plan.json" -o "$T/x.svg"
check_svg "$T/x.svg" ".svg is SVG"
expect 0 "render -o X.PNG" -- "$CLI" render "$T/c.json" -o "$T/X.PNG"
check_png "$T/X.PNG" ".PNG is PNG"
expect 0 "render --format png -o pic" -- "$CLI" render "$T/c.json" --format png -o "$T/pic"
check_png "$T/pic" "--format png without an extension"
expect 0 "render --format svg -o y.png" -- "$CLI" render "$T/c.json" --format svg -o "$T/y.png"
check_svg "$T/y.png" "--format wins over the extension"
expect 0 "render -o noext" -- "$CLI" render "$T/c.json" -o "$T/noext"
check_svg "$T/noext" "no extension: SVG"

# sizes
expect 0 "render --width 300 --height 200" -- "$CLI" render "$T/c.json" --width 300 --height 200 -o "$T/s.png"
[ "$(png_size "$T/s.png")" = 300x200 ] && ok "300 x 200 px" || bad "size $(png_size "$T/s.png")"
expect 0 "render --width 500" -- "$CLI" render "$T/c.json" -o "$T/w.png" --width 500
w=$(png_size "$T/w.png")
[ "${w%x*}" = 500 ] && [ "${w#*x}" -gt 500 ] && ok "500 px wide, taller than wide (a column)" || bad "size $w"
expect 2 "render --width 20000 to PNG" -- "$CLI" render "$T/c.json" --width 20000 -o "$T/big.png"
contains "$T/err" "16384" "the message names the limit"
absent "$T/big.png" "too wide"
expect 0 "the same width as SVG" -- "$CLI" render "$T/c.json" --width 20000 -o "$T/big.svg"
expect 2 "render --height 20" -- "$CLI" render "$T/c.json" --height 20 -o "$T/low.png"
contains "$T/err" "no room for the drawing" "too low: says so"
absent "$T/low.png" "too low"

# the title: file, bodies, status
contains "$T/x.svg" "c.json — 3 bodies, plan found, 3 steps" "title with the plan's status"
contains "$T/noext" "c.json — 3 bodies, stands" "title with the verdict without a plan"
expect 0 "render a none plan" -- "$CLI" render "$T/arch.json" --plan "$T/arch-plan.json" -o "$T/arch.svg"
contains "$T/arch.svg" "plan status none, 5 bodies cannot be removed" "title of a none plan"
contains "$T/arch.svg" 'fill="url(#blocked)"' "blocked bodies hatched"
expect 0 "render a none plan to PNG" -- "$CLI" render "$T/arch.json" --plan "$T/arch-plan.json" -o "$T/arch.png"
check_png "$T/arch.png" "none plan PNG"
expect 0 "render --title" -- "$CLI" render "$T/c.json" --title "my <column>" -o "$T/t.svg"
contains "$T/t.svg" "my &lt;column&gt;" "--title replaces the title, escaped"
expect 1 "render --forces, does not stand" -- "$CLI" render "$DATA/lean_wall_mu0.json" --forces -o "$T/f.png"
contains "$T/err" "does not stand" "says it does not stand"
check_png "$T/f.png" "picture written without forces"

# 3D: an axonometric picture; --view turns it; bad views are usage errors
"$CLI" generate pyramid3d --rows 3 -o "$T/p3.json" >/dev/null || bad "generate pyramid3d"
"$CLI" plan "$T/p3.json" -o "$T/p3-plan.json" >/dev/null || bad "plan pyramid3d"
expect 0 "render 3D to PNG" -- "$CLI" render "$T/p3.json" --plan "$T/p3-plan.json" --forces -o "$T/p3.png"
check_png "$T/p3.png" "3D PNG"
expect 0 "render 3D to SVG" -- "$CLI" render "$T/p3.json" --plan "$T/p3-plan.json" -o "$T/p3.svg"
check_svg "$T/p3.svg" "3D SVG"
contains "$T/p3.svg" "p3.json — 14 bodies, plan found, 14 steps" "3D title with the plan's status"
contains "$T/p3.svg" '<g class="grid"' "3D ground grid"
expect 0 "render 3D --view 120,50" -- "$CLI" render "$T/p3.json" --plan "$T/p3-plan.json" --view 120,50 -o "$T/p3b.png"
cmp -s "$T/p3.png" "$T/p3b.png" && bad "--view changed nothing" || ok "--view changes the picture"
for v in 35 35,91 a,b 35,25x ,25; do
  expect 2 "--view $v" -- "$CLI" render "$T/p3.json" --view "$v" -o "$T/v.png"
  absent "$T/v.png" "bad --view $v"
done
contains "$T/err" "--view needs AZ,EL" "names the option"
expect 0 "3D --html (the 3D viewer, tests/cli/render_html.sh)" -- "$CLI" render "$T/p3.json" --html -o "$T/p3.html"

# errors: exit 2, nothing written
expect 2 "--format gif" -- "$CLI" render "$T/c.json" --format gif -o "$T/g.png"
contains "$T/err" "unknown --format 'gif'" "names the bad format"
absent "$T/g.png" "bad --format"
expect 2 "-o x.jpg" -- "$CLI" render "$T/c.json" -o "$T/x.jpg"
contains "$T/err" "cannot tell the picture format" "says the extension names no format"
absent "$T/x.jpg" "unknown extension"
expect 2 "-o into a missing directory" -- "$CLI" render "$T/c.json" -o "$T/nodir/x.png"
absent "$T/nodir/x.png" "missing directory"
printf old >"$T/ro.png"
chmod 444 "$T/ro.png"
expect 2 "-o a read-only file" -- "$CLI" render "$T/c.json" -o "$T/ro.png"
[ "$(cat "$T/ro.png")" = old ] && ok "read-only file unchanged" || bad "read-only file changed"
printf '{"bodies": [' >"$T/broken.json"
expect 2 "bad input" -- "$CLI" render "$T/broken.json" -o "$T/broken.png"
absent "$T/broken.png" "bad input"
expect 2 "a plan of another structure" -- "$CLI" render "$T/c.json" --plan "$T/arch-plan.json" -o "$T/other.png"
absent "$T/other.png" "plan of another structure"
printf old >"$T/keep.png"
expect 2 "bad plan over an existing file" -- "$CLI" render "$T/c.json" --plan "$T/arch-plan.json" -o "$T/keep.png"
[ "$(cat "$T/keep.png")" = old ] && ok "existing file unchanged" || bad "existing file changed"
# another structure's plan with the same ids: refused by its fingerprint,
# both files named, nothing written (render and verify)
"$CLI" generate pyramid --rows 13 -o "$T/pyr.json" >/dev/null || bad "generate pyramid"
"$CLI" generate arch --voussoirs 12 -o "$T/a12.json" >/dev/null || bad "generate arch 12"
"$CLI" plan "$T/a12.json" -o "$T/a12-plan.json" >/dev/null
"$CLI" plan "$T/pyr.json" -o "$T/pyr-plan.json" >/dev/null || bad "plan pyramid"
contains "$T/pyr-plan.json" '"fingerprint": "fnv1a64:' "plan files carry a fingerprint"
expect 2 "render: the arch's plan on the pyramid" -- "$CLI" render "$T/pyr.json" --plan "$T/a12-plan.json" -o "$T/pa.svg"
contains "$T/err" "a12-plan.json is a plan of another structure, not of $T/pyr.json" "render names both files"
absent "$T/pa.svg" "another structure's plan"
expect 2 "verify: the arch's plan on the pyramid" -- "$CLI" verify "$T/pyr.json" "$T/a12-plan.json"
contains "$T/err" "fingerprints differ" "verify names the fingerprints"
# an older plan (no fingerprint) is read, with a note; an order verify
# rejects is drawn with its failing step and the falling body, exit 1
sed -e '/"fingerprint"/d' "$T/c-plan.json" >"$T/old-plan.json"
expect 0 "a plan without a fingerprint" -- "$CLI" render "$T/c.json" --plan "$T/old-plan.json" -o "$T/old.svg"
contains "$T/err" "has no fingerprint" "a note on the missing fingerprint"
printf '{"status": "found", "order": ["b1", "b2", "b3"]}' >"$T/wrong.json"
expect 1 "render an invalid order" -- "$CLI" render "$T/c.json" --plan "$T/wrong.json" -o "$T/wrong.svg"
contains "$T/err" "the order is invalid" "says the order is invalid"
contains "$T/wrong.svg" "the plan fails at step 1 of 3" "title names the failing step"
contains "$T/wrong.svg" 'class="failing-step"' "the failing step's body marked"
contains "$T/wrong.svg" 'class="falls"' "the falling body marked"
expect 1 "render an invalid order to PNG" -- "$CLI" render "$T/c.json" --plan "$T/wrong.json" -o "$T/wrong.png"
check_png "$T/wrong.png" "invalid order PNG"
# labels by id, step or none
expect 0 "--labels ids" -- "$CLI" render "$T/c.json" --plan "$T/c-plan.json" --labels ids -o "$T/ids.svg"
contains "$T/ids.svg" ">b2</text>" "ids as labels"
expect 0 "--labels steps" -- "$CLI" render "$T/c.json" --plan "$T/c-plan.json" --labels steps -o "$T/steps.svg"
contains "$T/steps.svg" ">3</text>" "steps as labels"
grep -q ">b2</text>" "$T/steps.svg" && bad "--labels steps writes ids" || ok "--labels steps writes no ids"
expect 0 "--labels none" -- "$CLI" render "$T/c.json" --plan "$T/c-plan.json" --labels none -o "$T/nol.svg"
grep -q ">3</text>\|>b2</text>" "$T/nol.svg" && bad "--labels none writes labels" || ok "--labels none: no labels"
expect 2 "--labels steps without a plan" -- "$CLI" render "$T/c.json" --labels steps -o "$T/x2.svg"
expect 2 "--labels bad" -- "$CLI" render "$T/c.json" --labels nope -o "$T/x2.svg"
expect 0 "3D --labels ids to PNG" -- "$CLI" render "$T/p3.json" --plan "$T/p3-plan.json" --labels ids -o "$T/p3i.png"
# 3D labels only where seen: the bottom course's middle box b5 is covered on
# every side (neighbours and the course above), the top box b14 is not
expect 0 "3D --labels ids to SVG" -- "$CLI" render "$T/p3.json" --labels ids -o "$T/p3i.svg"
grep -q ">b5</text>" "$T/p3i.svg" && bad "the hidden box's label is drawn" || ok "no label on the hidden box"
contains "$T/p3i.svg" ">b14</text>" "the top box's label"
# an unstable structure: the falling body and the mechanism
printf '{"bodies": [{"id": "base", "polygon": [[0,0],[1,0],[1,1],[0,1]]}, {"id": "top", "polygon": [[0.6,1],[1.8,1],[1.8,1.4],[0.6,1.4]]}]}' >"$T/tip.json"
expect 0 "render an unstable structure" -- "$CLI" render "$T/tip.json" -o "$T/tip.svg"
contains "$T/tip.svg" '<g class="falls"><title>top</title>' "the falling body marked"
contains "$T/tip.svg" 'class="mechanism"' "the mechanism drawn"
contains "$T/tip.svg" 'class="ghost"' "the ghost drawn"
expect 1 "--forces on an unstable structure" -- "$CLI" render "$T/tip.json" --forces -o "$T/tipf.png"
check_png "$T/tipf.png" "unstable PNG"
# a none plan numbers its buildable part in build order
contains "$T/arch.svg" "placed first" "none plan: the build order's ramp"
contains "$T/arch.svg" ">1</text>" "none plan: the buildable part numbered"
# plan --print and -o -
"$CLI" plan "$T/c.json" --print >"$T/print.txt" || bad "plan --print"
[ "$(sed -n 2p "$T/print.txt")" = "$(printf '1\tb3')" ] && ok "--print: step 1 removes b3" || bad "--print: $(sed -n 2p "$T/print.txt")"
[ "$(grep -c "$(printf '\t')" "$T/print.txt")" -eq 3 ] && ok "--print: one line per step" || bad "--print: lines"
"$CLI" plan "$T/c.json" -o - >"$T/stdout.json" 2>"$T/stderr.txt" || bad "plan -o -"
"$CLI" verify "$T/c.json" "$T/stdout.json" >/dev/null && ok "-o -: a plan verify reads" || bad "-o -: not a plan"
contains "$T/stderr.txt" "found: 3 removals" "-o -: the summary on stderr"
expect 2 "--print with -o -" -- "$CLI" plan "$T/c.json" --print -o -
finish
