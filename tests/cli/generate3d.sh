# The 3D generators end to end: each kind writes a 3D structure file with
# the expected body count; bad 3D settings are usage errors that write
# nothing. (Reading the files back, their contacts and mass properties:
# tests/test_gen3d.c.)
. "$(dirname "$0")/lib.sh"
expect 0 "tower" -- "$CLI" generate tower --blocks 6 --jitter 20 --seed 3 -o "$T/tower.json"
contains "$T/out" "6 bodies" "tower: 6 bodies"
contains "$T/tower.json" '"dimension": 3' "tower: a 3D file"
expect 0 "pyramid3d" -- "$CLI" generate pyramid3d --rows 4 -o "$T/p.json"
contains "$T/out" "30 bodies" "pyramid3d: 4 courses are 16 + 9 + 4 + 1 boxes"
expect 0 "wall3d" -- "$CLI" generate wall3d --rows 4 --cols 5 --thickness 0.3 -o "$T/w.json"
contains "$T/out" "22 bodies" "wall3d: 2 x 5 + 2 x 6 bricks"
expect 2 "tower: negative jitter" -- "$CLI" generate tower --jitter -1 -o "$T/bad1.json"
contains "$T/err" "jitter" "message names the jitter"
expect 2 "pyramid3d: zero depth" -- "$CLI" generate pyramid3d --block-depth 0 -o "$T/bad2.json"
contains "$T/err" "block depth" "message names the block depth"
[ -e "$T/bad1.json" ] || [ -e "$T/bad2.json" ] && bad "file written on error" || ok "no file written on error"
finish
