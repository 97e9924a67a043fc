# Every bad input gives exit 2, a message naming the file and the fault,
# and no output file.
. "$(dirname "$0")/lib.sh"
list="$DATA/bad/README"
[ -f "$list" ] || { bad "no $list"; finish; exit 1; }
n=0
while IFS=$'\t' read -r file frag; do
  case "$file" in ''|'#'*) continue ;; esac
  n=$((n + 1))
  expect 2 "check $file" -- "$CLI" check "$DATA/bad/$file"
  contains "$T/err" "$file" "$file: message names the file"
  contains "$T/err" "$frag" "$file: message says '$frag'"
  expect 2 "plan $file" -- "$CLI" plan "$DATA/bad/$file" -o "$T/out-$n.json"
  [ -e "$T/out-$n.json" ] && bad "$file: plan file written" || ok "$file: no plan file"
  expect 2 "render $file" -- "$CLI" render "$DATA/bad/$file" -o "$T/out-$n.svg"
  [ -e "$T/out-$n.svg" ] && bad "$file: svg written" || ok "$file: no svg"
done <"$list"
[ "$n" -ge 10 ] && ok "$n bad inputs tried" || bad "only $n bad inputs listed"
leftover=$(ls "$T" | grep -c '\.tmp\.' || true)
[ "$leftover" -eq 0 ] && ok "no temporary files left" || bad "$leftover temporary files left"
finish
