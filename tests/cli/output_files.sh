# -o never destroys what it names: devices and FIFOs are written through,
# symlinks followed, hard links kept, read-only files and inputs refused
# (exit 2, nothing planned), unwritable locations refused before planning.
. "$(dirname "$0")/lib.sh"
S="$T/s.json"
"$CLI" generate column --blocks 3 -o "$S" >/dev/null || bad "generate"
lines() { grep -c '"id"' "$1" 2>/dev/null || echo 0; }

# a FIFO with a reader gets the file, and stays a FIFO
mkfifo "$T/fifo"
cat "$T/fifo" >"$T/fifo.out" &
reader=$!
expect 0 "generate -o FIFO" -- "$CLI" generate column --blocks 2 -o "$T/fifo"
wait "$reader"
[ -p "$T/fifo" ] && ok "FIFO is still a FIFO" || bad "FIFO replaced"
[ "$(lines "$T/fifo.out")" -eq 2 ] && ok "reader got the structure" || bad "reader got $(lines "$T/fifo.out") ids"

# a symlink: the target gets the content, the link stays a link
"$CLI" generate column --blocks 2 -o "$T/target.json" >/dev/null
ln -s target.json "$T/link.json"
expect 0 "generate -o symlink" -- "$CLI" generate column --blocks 4 -o "$T/link.json"
[ -L "$T/link.json" ] && ok "symlink is still a symlink" || bad "symlink replaced"
[ "$(lines "$T/target.json")" -eq 4 ] && ok "symlink target rewritten" || bad "target not rewritten"

# a hard link: written in place, both names see the new content
"$CLI" generate column --blocks 2 -o "$T/h1.json" >/dev/null
ln "$T/h1.json" "$T/h2.json"
expect 0 "generate -o hard link" -- "$CLI" generate column --blocks 5 -o "$T/h2.json"
[ "$(stat -c %h "$T/h1.json")" -eq 2 ] && ok "hard link kept" || bad "hard link broken"
[ "$(lines "$T/h1.json")" -eq 5 ] && ok "other name sees the content" || bad "other name unchanged"

# mode kept on replacement
"$CLI" generate column --blocks 2 -o "$T/m.json" >/dev/null
chmod 640 "$T/m.json"
expect 0 "plan -o existing 0640 file" -- "$CLI" plan "$S" -o "$T/m.json"
[ "$(stat -c %a "$T/m.json")" = 640 ] && ok "mode 640 kept" || bad "mode now $(stat -c %a "$T/m.json")"

# a read-only file is refused, also as root (mode bits, not access(2))
"$CLI" generate column --blocks 2 -o "$T/ro.json" >/dev/null
chmod 444 "$T/ro.json"
expect 2 "generate -o read-only file" -- "$CLI" generate column --blocks 3 -o "$T/ro.json"
contains "$T/err" "not writable" "read-only: says not writable"
[ "$(lines "$T/ro.json")" -eq 2 ] && ok "read-only file unchanged" || bad "read-only file changed"
expect 2 "plan -o read-only file" -- "$CLI" plan "$S" -o "$T/ro.json"
expect 2 "plan (missing FILE) -o read-only file" -- "$CLI" plan "$T/missing.json" -o "$T/ro.json"
contains "$T/err" "not writable" "the output is refused before the input is read"

# /dev/null when writable: written through, still a character device
if [ -w /dev/null ]; then
  expect 0 "generate -o /dev/null" -- "$CLI" generate column --blocks 2 -o /dev/null
  [ -c /dev/null ] && ok "/dev/null is still a device" || bad "/dev/null replaced"
fi

# /dev/stdout: to a pipe, and to a redirected file (not truncated under the
# shell's own output: the structure, then the summary line)
"$CLI" generate column --blocks 2 -o /dev/stdout | cat >"$T/piped.txt"
[ "$(lines "$T/piped.txt")" -eq 2 ] && ok "-o /dev/stdout into a pipe" || bad "pipe got $(lines "$T/piped.txt") ids"
"$CLI" generate column --blocks 2 -o /dev/stdout >"$T/redir.txt"
[ "$(lines "$T/redir.txt")" -eq 2 ] && head -1 "$T/redir.txt" | grep -q '^{' &&
  tail -1 "$T/redir.txt" | grep -q '^wrote' && ok "-o /dev/stdout redirected to a file" ||
  { bad "-o /dev/stdout > file"; sed 's/^/    /' "$T/redir.txt" | head -5; }

# an output that is an input, by any name: refused, input unchanged
before=$(cksum <"$S")
ln -s s.json "$T/s-link.json"
ln "$S" "$T/s-hard.json"
for o in "$S" "$T/./s.json" "$T/s-link.json" "$T/s-hard.json"; do
  expect 2 "plan s.json -o ${o#"$T"/}" -- "$CLI" plan "$S" -o "$o"
  contains "$T/err" "output would overwrite input" "plan -o ${o#"$T"/}: names the clash"
done
(cd "$T" && "$CLI" plan s.json -o ./s.json >"$T/out" 2>"$T/err")
[ $? -eq 2 ] && ok "plan s.json -o ./s.json (relative)" || bad "relative clash not refused"
contains "$T/err" "output would overwrite input s.json" "relative: message names s.json"
"$CLI" plan "$S" -o "$T/p.json" >/dev/null
pbefore=$(cksum <"$T/p.json")
expect 2 "render --plan p.json -o p.json" -- "$CLI" render "$S" --plan "$T/p.json" -o "$T/p.json"
contains "$T/err" "output would overwrite input" "render: names the clash"
expect 2 "render s.json -o s.json" -- "$CLI" render "$S" -o "$S"
[ "$(cksum <"$S")" = "$before" ] && ok "input unchanged" || bad "input changed"
[ "$(cksum <"$T/p.json")" = "$pbefore" ] && ok "plan input unchanged" || bad "plan input changed"

# unwritable locations fail at once, before loading or planning
expect 2 "plan -o /nonexistent/x.json" -- "$CLI" plan "$S" -o /nonexistent/x.json
contains "$T/err" "cannot write in directory /nonexistent" "names the missing directory"
[ -s "$T/out" ] && bad "plan printed a summary" || ok "no planning before the refusal"
expect 2 "plan of a missing FILE -o bad dir: the output is checked first" -- \
  "$CLI" plan "$T/missing.json" -o /nonexistent/x.json
contains "$T/err" "/nonexistent" "output checked before the input is read"
expect 2 "render -o /nonexistent/x.svg" -- "$CLI" render "$S" -o /nonexistent/x.svg
expect 2 "generate -o /nonexistent/x.json" -- "$CLI" generate column -o /nonexistent/x.json
expect 2 "generate -o a directory" -- "$CLI" generate column -o "$T"
contains "$T/err" "is a directory" "directory: says so"
expect 2 "plan -o under a regular file" -- "$CLI" plan "$S" -o "$S/x.json"

leftover=$(ls "$T" | grep -c '\.tmp\.' || true)
[ "$leftover" -eq 0 ] && ok "no temporary files left" || bad "$leftover temporary files left"
finish
