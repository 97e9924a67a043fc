# unstack render: the format from --format or the output's extension (PNG
# files are PNG, SVG files XML), sizes, the title's status, and every error
# (bad --format, an extension that names no format, unwritable outputs, bad
# input, a PNG too large) is exit 2 with nothing written; a 3D structure
# as PNG and SVG, turned by --view, bad views refused.
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
expect 2 "3D --html" -- "$CLI" render "$T/p3.json" --html -o "$T/p3.html"
absent "$T/p3.html" "3D viewer"

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
finish
