# Hostile ids: escape sequences, newlines, bidi overrides, U+FFFE/U+FFFF.
# The terminal never receives ESC (or a raw newline inside a message) from
# an id; render writes XML that parses; invalid UTF-8 is refused with the
# file and line; messages cut long ids at a character boundary.
. "$(dirname "$0")/lib.sh"
body() { printf '{"id": "%s", "polygon": [[%s,%s],[%s,%s],[%s,%s],[%s,%s]]}' "$1" \
  "$2" "$3" "$(($2 + 1))" "$3" "$(($2 + 1))" "$(($3 + 1))" "$2" "$(($3 + 1))"; }
HOST='a\u001b[31mred\u001b]0;title\u0007\nfake line\uffff\ufffe\u202e\u0085'
{
  printf '{"friction": 0.5, "bodies": [\n'
  body 'caf\u00e9 <&>' 0 0; printf ',\n'
  body 'top\u001b[2J' 0 1; printf ',\n'
  body "$HOST" 5 1
  printf ']}\n'
} >"$T/ids.json"
esc=$(printf '\033')
no_esc() { # FILE DESCRIPTION
  if grep -q "$esc" "$1"; then bad "$2: ESC reached the terminal"; else ok "$2: no ESC"; fi
}
expect 1 "check (a floating body)" -- "$CLI" check "$T/ids.json"
no_esc "$T/out" "check stdout"
contains "$T/out" "'a\x1B[31mred" "check names the falling body, escaped"
no_esc "$T/err" "check stderr"
expect 1 "plan" -- "$CLI" plan "$T/ids.json" -o "$T/p.json"
no_esc "$T/out" "plan stdout"
expect 1 "verify of an unfinished plan" -- "$CLI" verify "$T/ids.json" "$T/p.json"
no_esc "$T/out" "verify stdout"
expect 0 "classify" -- "$CLI" classify "$T/ids.json"
no_esc "$T/out" "classify stdout"
expect 0 "render" -- "$CLI" render "$T/ids.json" -o "$T/ids.svg"
if command -v xmllint >/dev/null; then
  xmllint --noout "$T/ids.svg" 2>"$T/xml" && ok "render: xmllint parses the SVG" ||
    { bad "render: invalid XML"; head -5 "$T/xml"; }
else
  python3 -c 'import sys, xml.dom.minidom as m; m.parse(sys.argv[1])' "$T/ids.svg" 2>"$T/xml" &&
    ok "render: the SVG parses (python xml, no xmllint)" || { bad "render: invalid XML"; head -5 "$T/xml"; }
fi
no_esc "$T/ids.svg" "svg"

# a duplicate hostile id: the message is one line, escaped
{
  printf '{"bodies": [\n'; body "$HOST" 0 0; printf ',\n'; body "$HOST" 0 1; printf ']}\n'
} >"$T/dup.json"
expect 2 "duplicate hostile id" -- "$CLI" check "$T/dup.json"
no_esc "$T/err" "duplicate message"
[ "$(wc -l <"$T/err")" -eq 1 ] && ok "message is one line" || bad "message spans $(wc -l <"$T/err") lines"
contains "$T/err" 'a\x1B[31mred' "ESC shown as \\x1B"
contains "$T/err" '\x0Afake line\uFFFF\uFFFE\u202E\u0085' "newline, noncharacters, bidi, C1 escaped"

# a plan naming a hostile unknown id
printf '{"status": "found", "order": ["x\\u001b[2Jy"]}\n' >"$T/bad-plan.json"
expect 2 "verify: unknown hostile id" -- "$CLI" verify "$T/ids.json" "$T/bad-plan.json"
no_esc "$T/err" "verify stderr"
contains "$T/err" 'x\x1B[2Jy' "unknown id escaped"

# invalid UTF-8: refused with file and line
printf '{"bodies": [\n{"id": "b\377", "polygon": [[0,0],[1,0],[1,1],[0,1]]}]}\n' >"$T/utf.json"
expect 2 "invalid UTF-8 id" -- "$CLI" check "$T/utf.json"
contains "$T/err" "utf.json:2:" "names file and line"

# long ids: cut at a character boundary with an ellipsis, valid UTF-8
long=$(printf 'é%.0s' $(seq 1 100))
{ printf '{"bodies": [\n'; body "$long" 0 0; printf ',\n'; body "$long" 0 1; printf ']}\n'; } >"$T/long.json"
expect 2 "duplicate long id" -- "$CLI" check "$T/long.json"
contains "$T/err" 'éé...' "cut with an ellipsis"
if iconv -f UTF-8 -t UTF-8 "$T/err" >/dev/null 2>&1; then ok "message is valid UTF-8"; else
  bad "message cut inside a character"; fi
finish
