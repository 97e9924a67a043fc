# The man page cannot drift from the tool: every command that
# `unstack --help` lists has its section (.SS) in docs/unstack.1, and every
# long option (and short alias) that `unstack CMD --help` prints appears in
# that command's section; generate's kinds in generate's. The page renders
# without groff warnings.
. "$(dirname "$0")/lib.sh"
MAN=$(dirname "$0")/../../docs/unstack.1
# the page as text: troff's \- and font escapes removed
sed 's/\\-/-/g; s/\\f[BIRP]//g; s/\\&//g' "$MAN" >"$T/man"
# section CMD: the lines of CMD's .SS section
section() { awk -v c="$1" '/^\.S[HS]/ {on = ($1 == ".SS" && $2 == c)} on' "$T/man"; }
# has FILE WORD: WORD appears in FILE as a whole word
has() { grep -qE -- "(^|[^A-Za-z0-9-])$2([^A-Za-z0-9-]|\$)" "$1"; }

"$CLI" --help >"$T/help" || bad "unstack --help"
cmds=$(sed -n '/^commands:/,/^$/p' "$T/help" | grep -oE '^  [a-z][a-z0-9-]*' | tr -d ' ')
[ "$(echo "$cmds" | wc -w)" -ge 8 ] && ok "unstack --help lists $(echo $cmds | wc -w) commands" ||
  bad "few commands in unstack --help: $cmds"
for w in $(grep -oE -- '--[a-z][a-z0-9-]*' "$T/help" | sort -u) --version; do
  has "$T/man" "$w" && ok "the page has $w" || bad "the page lacks $w"
done
for c in $cmds; do
  section "$c" >"$T/sec"
  if [ ! -s "$T/sec" ]; then bad "no section .SS $c"; continue; fi
  "$CLI" "$c" --help >"$T/chelp" 2>&1 || bad "$c --help"
  opts=$( (grep -oE -- '--[a-z][a-z0-9-]*' "$T/chelp"; grep -oE -- '^  -[a-z],' "$T/chelp" | tr -d ' ,') | sort -u)
  missing=""
  for o in $opts; do has "$T/sec" "$o" || missing="$missing $o"; done
  [ -z "$missing" ] && ok "$c: its $(echo $opts | wc -w) options are in its section" ||
    bad "$c: the page's section lacks$missing"
done
kinds=$(sed -n '/^  generate KIND/,/^  [a-z]/p' "$T/help" | grep -E '^ {10,}' | tr ',' ' ')
section generate >"$T/sec"
missing=""
for k in $kinds; do has "$T/sec" "$k" || missing="$missing $k"; done
[ -n "$kinds" ] && [ -z "$missing" ] && ok "generate: its $(echo $kinds | wc -w) kinds are in its section" ||
  bad "generate: kinds missing:$missing"
# groff (scripts/deps.sh: groff-base)
groff -man -Tutf8 -ww -z "$MAN" 2>"$T/groff" && [ ! -s "$T/groff" ] &&
  ok "groff renders the page without warnings" || { bad "groff warns or is missing"; head -5 "$T/groff"; }
finish
