# render --html (docs/viewer.md): the page is written for a plan with or
# without certificates and for a structure alone; an output name ending in
# .html chooses it; an order that verify rejects is written and exits 1;
# bad input (another structure's plan, tampered certificates, a bad 3D
# file or view) exits 2 and leaves the output as it was; 3D structures and
# plans (with certificates, hands, an invalid order) give a 3D page. The page itself is tested in a
# browser (ctest browser.viewer) and its data by test_render_html.
. "$(dirname "$0")/lib.sh"
# absent FILE DESCRIPTION
absent() { if [ -e "$1" ]; then bad "$2: $1 was written"; else ok "$2: nothing written"; fi; }
page_has() { contains "$1" "$2" "$3"; }

"$CLI" generate pyramid --rows 4 -o "$T/p.json" >/dev/null
"$CLI" plan "$T/p.json" --certificates -o "$T/plan.json" >/dev/null
"$CLI" plan "$T/p.json" -o "$T/plain.json" >/dev/null
"$CLI" generate tower --blocks 3 -o "$T/p3.json" >/dev/null
expect 0 "render --html with certificates" -- "$CLI" render "$T/p.json" --plan "$T/plan.json" --html -o "$T/a.html"
page_has "$T/a.html" '"forces":[' "the page holds the plan's forces"
page_has "$T/a.html" '"verify":{"ok":true' "the page holds verify's report"
expect 0 "an output ending in .html chooses the viewer" -- "$CLI" render "$T/p.json" --plan "$T/plain.json" -o "$T/b.html"
page_has "$T/b.html" '<!DOCTYPE html>' "the page is HTML"
page_has "$T/b.html" '"forces":null' "a plan without certificates has no forces"
expect 0 "the structure alone" -- "$CLI" render "$T/p.json" -o "$T/c.html"
page_has "$T/c.html" '"status":null' "no plan, no status"
# (the SVG namespace http://www.w3.org/2000/svg is a name, not a load)
if grep -qiE "<script[^>]+src=|<link|(src|href)=.?https?:|url\\(.?https?:|@import|fetch\\(|XMLHttpRequest" \
   "$T/a.html"; then bad "the page loads nothing from outside"
else ok "the page loads nothing from outside"; fi

# an order verify rejects: the column from the bottom up
"$CLI" generate column --blocks 3 -o "$T/col.json" >/dev/null
ids=$(grep -o '"id": "[^"]*"' "$T/col.json" | cut -d'"' -f4)
set -- $ids
printf '{"status": "found", "order": ["%s", "%s", "%s"]}\n' "$1" "$2" "$3" >"$T/bad-plan.json"
expect 1 "an invalid order: written, exit 1" -- "$CLI" render "$T/col.json" --plan "$T/bad-plan.json" -o "$T/d.html"
page_has "$T/d.html" '"failed_step":0' "the page names the failing step"
contains "$T/err" "invalid" "stderr says the order is invalid"

# certificates edited in the file: the page re-checks them itself and
# flags the edited step (the order stays valid: verify re-solves it)
sed -E '0,/"force": \[[^,]*,/s//"force": [-1000,/' "$T/plan.json" >"$T/neg.json"
expect 0 "a negative normal force in the file: written" -- "$CLI" render "$T/p.json" --plan "$T/neg.json" -o "$T/neg.html"
if grep -A1 -F '"certs":[' "$T/neg.html" | tail -1 | grep -qF '{"ok":false'; then
  ok "the page flags the first step, whose force was made negative"
else bad "the page flags the first step, whose force was made negative"; fi
n=$(grep -o '{"ok":false' "$T/neg.html" | wc -l)
[ "$n" -eq 1 ] && ok "only that step is flagged" || bad "only that step is flagged: $n flagged"
sed -E '0,/"force": \[[^,]*,/s//"force": [1e308,/' "$T/plan.json" >"$T/huge.json"
expect 0 "a 1e308 force in the file: written" -- "$CLI" render "$T/p.json" --plan "$T/huge.json" -o "$T/huge.html"
page_has "$T/huge.html" '{"ok":false' "the page flags the step with a 1e308 force"
page_has "$T/plan.json" '"check": {"ok": true' "the untouched plan's steps pass"
if grep -q '{"ok":false' "$T/a.html"; then bad "the untouched plan's page flags nothing"
else ok "the untouched plan's page flags nothing"; fi

# forces: a representative set per step, certified in the page
expect 0 "--force-set margin with a plan" -- "$CLI" render "$T/p.json" --plan "$T/plan.json" --force-set margin --html -o "$T/m.html"
page_has "$T/m.html" '"force_set":"margin"' "the page names the force set"
if grep -q '{"ok":false' "$T/m.html"; then bad "the margin forces pass the re-check"
else ok "the margin forces pass the re-check"; fi
expect 0 "an SVG of margin resultants" -- "$CLI" render "$T/p.json" --forces resultants --force-set margin -o "$T/m.svg"
contains "$T/m.svg" "the largest smallest normal force" "the legend names the margin set"
contains "$T/m.svg" "per touching pair" "the legend says resultants"
expect 0 "min-norm forces in SVG" -- "$CLI" render "$T/p.json" --forces --force-set min-norm -o "$T/n.svg"
contains "$T/n.svg" "the least sum of squares" "the legend names the min-norm set"
expect 0 "a 3D PNG of margin forces" -- "$CLI" render "$T/p3.json" --forces --force-set margin -o "$T/m3.png"
expect 2 "an unknown --force-set" -- "$CLI" render "$T/p.json" --forces --force-set best -o "$T/x.svg"
contains "$T/err" "margin" "the message lists the sets"

# a none plan: the page takes apart the buildable part
"$CLI" generate arch --voussoirs 7 --loose 30 -o "$T/arch.json" >/dev/null
"$CLI" plan "$T/arch.json" -o "$T/arch-plan.json" >/dev/null
expect 0 "a none plan" -- "$CLI" render "$T/arch.json" --plan "$T/arch-plan.json" -o "$T/arch.html"
if grep -q '"steps":\[\]' "$T/arch.html"; then bad "a none plan has steps"; else ok "a none plan has steps"; fi

# bad input: exit 2, the old output kept
echo old >"$T/keep.html"
expect 2 "a plan for another structure" -- "$CLI" render "$T/col.json" --plan "$T/plan.json" -o "$T/keep.html"
page_has "$T/keep.html" old "the old output is kept"
sed 's/"point": \[/"point": [7/' "$T/plan.json" >"$T/tampered.json"
expect 2 "a certificate at a point the structure has no contact" -- "$CLI" render "$T/p.json" --plan "$T/tampered.json" -o "$T/e.html"
contains "$T/err" "steps[0].certificate.contacts[0]" "the message names the JSON path"
absent "$T/e.html" "tampered certificates"

# 3D: the page is written with the structure's parts, the plan and its
# forces, self-contained; a 3D plan with hands; an order verify rejects
"$CLI" generate pyramid3d --rows 3 -o "$T/q.json" >/dev/null
"$CLI" plan "$T/q.json" --certificates -o "$T/q-plan.json" >/dev/null
expect 0 "3D: render --html with certificates" -- "$CLI" render "$T/q.json" --plan "$T/q-plan.json" --html -o "$T/q.html"
page_has "$T/q.html" '"dim":3' "the 3D page says its dimension"
page_has "$T/q.html" '"parts":[{"v":[' "the 3D page holds the bodies' parts"
page_has "$T/q.html" '"forces":[' "the 3D page holds the plan's forces"
page_has "$T/q.html" '"verify":{"ok":true' "the 3D page holds verify's report"
page_has "$T/q.html" 'function view3' "the 3D page carries the 3D view"
if grep -q 'function view3' "$T/a.html"; then bad "a 2D page does not carry the 3D view"
else ok "a 2D page does not carry the 3D view"; fi
nb=$(grep -o '"id":' "$T/q.html" | wc -l)
[ "$nb" -eq 14 ] && ok "the 3D page has the 14 bodies" || bad "the 3D page has the 14 bodies: $nb"
# no http(s) URL at all but the SVG namespace (a name, not a load)
if grep -oiE "https?://[^\"' )]*" "$T/q.html" | grep -qv '^http://www.w3.org/2000/svg$' ||
   grep -qiE "<script[^>]+src=|<link|@import|fetch\(|XMLHttpRequest" "$T/q.html"; then
  bad "the 3D page loads nothing from outside"
else ok "the 3D page loads nothing from outside"; fi
expect 0 "3D: --view sets the first view" -- "$CLI" render "$T/q.json" --view 120,40 --html -o "$T/q2.html"
page_has "$T/q2.html" '"view":[120,40]' "the page holds the view"
sed -E '0,/"force": \[[^,]*,/s//"force": [-1000,/' "$T/q-plan.json" >"$T/q-neg.json"
expect 0 "3D: a negative normal force in the file: written" -- "$CLI" render "$T/q.json" --plan "$T/q-neg.json" -o "$T/q-neg.html"
n=$(grep -o '{"ok":false' "$T/q-neg.html" | wc -l)
[ "$n" -eq 1 ] && ok "3D: only the edited step is flagged" || bad "3D: only the edited step is flagged: $n flagged"
"$CLI" plan "$T/q.json" --hands auto -o "$T/q-hands.json" >/dev/null
expect 0 "3D: a plan with hands" -- "$CLI" render "$T/q.json" --plan "$T/q-hands.json" -o "$T/q-hands.html"
page_has "$T/q-hands.html" '"actions":[["place"' "the 3D page holds the actions"
"$CLI" generate tower --blocks 3 -o "$T/t3.json" >/dev/null
ids=$(grep -o '"id": "[^"]*"' "$T/t3.json" | cut -d'"' -f4)
set -- $ids
printf '{"status": "found", "order": ["%s", "%s", "%s"]}\n' "$1" "$2" "$3" >"$T/t3-bad.json"
expect 1 "3D: an invalid order: written, exit 1" -- "$CLI" render "$T/t3.json" --plan "$T/t3-bad.json" -o "$T/t3.html"
page_has "$T/t3.html" '"failed_step":0' "the 3D page names the failing step"
"$CLI" generate dome --courses 3 --segments 6 -o "$T/dome.json" >/dev/null
"$CLI" plan "$T/dome.json" -o "$T/dome-plan.json" >/dev/null 2>&1
expect 0 "3D: a dome's plan" -- "$CLI" render "$T/dome.json" --plan "$T/dome-plan.json" -o "$T/dome.html"

# 3D bad input: exit 2, nothing written
expect 2 "3D: a 2D plan on a 3D structure" -- "$CLI" render "$T/q.json" --plan "$T/plan.json" -o "$T/f.html"
absent "$T/f.html" "3D with another structure's plan"
sed 's/"point": \[/"point": [7/' "$T/q-plan.json" >"$T/q-tampered.json"
expect 2 "3D: a certificate at a point the structure has no contact" -- "$CLI" render "$T/q.json" --plan "$T/q-tampered.json" -o "$T/f.html"
contains "$T/err" "steps[0].certificate.contacts[0]" "the message names the JSON path"
absent "$T/f.html" "3D tampered certificates"
sed -E '0,/"vertices": \[\[0, 0, 0\]/s//"vertices": [[0, 0]/' "$T/q.json" >"$T/q-bad.json"
expect 2 "3D: a vertex with two coordinates" -- "$CLI" render "$T/q-bad.json" --html -o "$T/f.html"
contains "$T/err" "q-bad.json" "the message names the file"
absent "$T/f.html" "3D bad structure"
expect 2 "3D: --view past the pole" -- "$CLI" render "$T/q.json" --view 35,95 --html -o "$T/f.html"
absent "$T/f.html" "3D bad view"
finish
