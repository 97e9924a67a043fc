# unstack import-mesh (docs/mesh.md): planar cases extruded into prisms
# (tests/cli/mesh_write.py) in every format give the planar answers
# (column: top-down; cantilever with counterweight: the cantilever first;
# arch: none; a slab leaning on a wall stands with friction 0.5 and falls
# with 0), verify accepts the plans; compounds, a --fixed ground slab, ids;
# every bad-file kind exits 2 naming the file and the object, writing
# nothing; and the executable maps Assimp only when a mesh is read.
. "$(dirname "$0")/lib.sh"
W="python3 $(dirname "$0")/mesh_write.py"
EX="$DATA/../../examples"

# order FILE: the plan's removal order as "a b c"
order() { sed -n 's/^ *"order": \[\(.*\)\],*$/\1/p' "$1" | tr -d '",'; }
position() { echo "$2" | tr ' ' '\n' | grep -nx -- "$1" | cut -d: -f1 | head -1; }
# plans NAME STRUCTURE WANT_EXIT: plan it (and verify a found plan)
plans() {
  expect "$3" "$1: plan exits $3" -- "$CLI" plan "$2" -o "$T/plan.json"
  [ "$3" -eq 0 ] && expect 0 "$1: verify accepts the plan" -- "$CLI" verify "$2" "$T/plan.json"
}

# --- column: every format, top-down (STL, PLY, OFF name nothing: shells STEM-k)
for fmt in obj stl stlb ply off gltf glb 3mf; do
  ext=$fmt up=z
  [ $fmt = stlb ] && ext=stl
  case $fmt in gltf | glb) up=y ;; esac
  $W "$DATA/column3.json" "$T/col.$ext" $fmt
  expect 0 "column ($fmt) imports" -- "$CLI" import-mesh "$T/col.$ext" --up $up -o "$T/col.json"
  contains "$T/out" "3 bodies (0 fixed" "column ($fmt): 3 bodies"
  plans "column ($fmt)" "$T/col.json" 0
  got=$(order "$T/plan.json")
  case $fmt in
    obj | gltf | glb) want="b3 b2 b1" ;;
    3mf) want="Object_3 Object_2 Object_1" ;; # Assimp 5.2 gives 3MF objects no names
    stl) want="planar-3 planar-2 planar-1" ;;  # the ASCII solid's name
    *) want="col-3 col-2 col-1" ;;
  esac
  [ "$got" = "$want" ] && ok "column ($fmt) comes apart top-down" || bad "column ($fmt) order '$got', wanted '$want'"
done
# y up: the same file turned, read with --up y; read as z-up it is a row lying down
$W "$DATA/column3.json" "$T/coly.obj" obj --up y
expect 0 "column (y-up OBJ) imports with --up y" -- "$CLI" import-mesh "$T/coly.obj" --up y -o "$T/coly.json"
plans "column (y-up)" "$T/coly.json" 0
[ "$(order "$T/plan.json")" = "b3 b2 b1" ] && ok "column (y-up) top-down" || bad "column (y-up) order '$(order "$T/plan.json")'"
expect 0 "column (y-up OBJ) read as z-up" -- "$CLI" import-mesh "$T/coly.obj" -o "$T/colz.json"
expect 0 "  lies on the ground: every block stands alone" -- "$CLI" plan "$T/colz.json" -o "$T/plan.json" --search dfs
# --scale: the same answers at another size
expect 0 "column scaled by 1000" -- "$CLI" import-mesh "$T/col.obj" --scale 1000 -o "$T/col1000.json"
contains "$T/col1000.json" "3000" "  coordinates scaled"
plans "column (scaled)" "$T/col1000.json" 0

# --- cantilever with counterweight: the cantilever L before its counterweight C
for fmt in obj objy gltf; do
  ext=obj up=z args=""
  [ $fmt = objy ] && up=y args="--up y"
  [ $fmt = gltf ] && ext=gltf up=y
  $W "$DATA/cantilever.json" "$T/cant.$ext" ${fmt%y} $args
  expect 0 "cantilever ($fmt) imports" -- "$CLI" import-mesh "$T/cant.$ext" --up $up --friction 0.5 -o "$T/cant.json"
  plans "cantilever ($fmt)" "$T/cant.json" 0
  got=$(order "$T/plan.json")
  l=$(position L "$got") c=$(position C "$got")
  if [ -n "$l" ] && [ -n "$c" ] && [ "$l" -lt "$c" ]; then ok "cantilever ($fmt) before counterweight: $got"
  else bad "cantilever ($fmt) order '$got'"; fi
done

# --- arch (examples/arch.svg, piers fixed by --fixed): none
"$CLI" import-svg "$EX/arch.svg" -o "$T/arch2d.json" >/dev/null
for fmt in obj stl; do
  $W "$T/arch2d.json" "$T/arch.$fmt" $fmt --depth 0.02
  # STL names nothing: the piers are the file's shells 1 and 2 (its solid's name: planar-1, -2)
  pat='pier-*'
  [ $fmt = stl ] && pat='planar-[12]'
  expect 0 "arch ($fmt) imports" -- "$CLI" import-mesh "$T/arch.$fmt" --scale 10 --fixed "$pat" -o "$T/arch.json"
  contains "$T/out" "9 bodies (2 fixed" "arch ($fmt): 9 bodies, 2 fixed"
  plans "arch ($fmt)" "$T/arch.json" 1
  contains "$T/plan.json" '"status": "none"' "arch ($fmt): status none"
done

# --- friction changes the answer: a slab leaning on a fixed wall
$W "$DATA/lean_wall.json" "$T/lean.obj" obj
expect 0 "lean wall imports (mu 0.5)" -- "$CLI" import-mesh "$T/lean.obj" --fixed wall --friction 0.5 -o "$T/lean5.json"
expect 0 "  stands with friction 0.5" -- "$CLI" check "$T/lean5.json"
expect 0 "lean wall imports (mu 0)" -- "$CLI" import-mesh "$T/lean.obj" --fixed wall --friction 0 -o "$T/lean0.json"
expect 1 "  falls without friction" -- "$CLI" check "$T/lean0.json"

# --- a compound: b1 and b2 as two groups (OBJ) / primitives (glTF) / shells (3MF) of one object
for fmt in obj gltf 3mf; do
  up=z
  [ $fmt = gltf ] && up=y
  $W "$DATA/column3.json" "$T/pair.$fmt" $fmt --compound pair=b1,b2
  expect 0 "compound ($fmt) imports" -- "$CLI" import-mesh "$T/pair.$fmt" --up $up -o "$T/pair.json"
  contains "$T/out" "2 bodies (0 fixed, 1 compound" "compound ($fmt): 2 bodies, one of them compound"
  contains "$T/pair.json" '"parts"' "compound ($fmt): written with parts"
  plans "compound ($fmt)" "$T/pair.json" 0
done
[ "$(order "$T/plan.json")" = "Object_2 Object_1" ] && ok "compound: the top block first" || bad "compound order '$(order "$T/plan.json")'"

# --- a --fixed ground slab under the column
cat >"$T/slab2d.json" <<'EOF'
{"bodies": [{"id": "ground_slab", "polygon": [[-1, 0], [2, 0], [2, 0.5], [-1, 0.5]]},
            {"id": "b1", "polygon": [[0, 0.5], [1, 0.5], [1, 1.5], [0, 1.5]]},
            {"id": "b2", "polygon": [[0, 1.5], [1, 1.5], [1, 2.5], [0, 2.5]]}]}
EOF
$W "$T/slab2d.json" "$T/slab.obj" obj
expect 0 "slab imports with --fixed 'ground*'" -- "$CLI" import-mesh "$T/slab.obj" --fixed 'ground*' -o "$T/slab.json"
contains "$T/out" "3 bodies (1 fixed" "slab: one fixed body"
contains "$T/slab.json" '"fixed": true' "slab: written fixed"
plans "slab" "$T/slab.json" 0
[ "$(order "$T/plan.json")" = "b2 b1" ] && ok "slab stays, column top-down" || bad "slab order '$(order "$T/plan.json")'"
expect 0 "without a ground the fixed slab holds" -- "$CLI" import-mesh "$T/slab.obj" --fixed 'ground*' --no-ground -o "$T/slab.json"
plans "slab without ground" "$T/slab.json" 0

# --- ids: a malformed UTF-8 byte, repeats and "ground"
tet() { # tet NAME DX: a tetrahedron at x = DX (vertices numbered from 4 * (NAME's index) + 1)
  echo "o $1"; echo "v $2 0 0"; echo "v $(($2 + 1)) 0 0"; echo "v $2 1 0"; echo "v $2 0 1"
  local b=$3
  echo "f $b $((b + 2)) $((b + 1))"; echo "f $b $((b + 1)) $((b + 3))"
  echo "f $b $((b + 3)) $((b + 2))"; echo "f $((b + 1)) $((b + 2)) $((b + 3))"
}
{ tet $'bad\xffname' 0 1; tet ground 2 5; tet ground-2 4 9; tet x 6 13; tet x 8 17
  tet "block 1" 10 21; tet "block 2" 12 25; } >"$T/names.obj"
expect 0 "names import" -- "$CLI" import-mesh "$T/names.obj" -o "$T/names.json"
for id in bad_name ground-2 ground-2-2 x block_1 block_2; do contains "$T/names.json" "\"id\": \"$id\"" "id $id"; done
contains "$T/out" "5 ids renamed" "names: 5 renamed"
contains "$T/out" "6 bodies (0 fixed, 1 compound" "names: an OBJ o given twice is one object"

# --- bad files: exit 2, the file and the object named, nothing written
# refuse NAME FILE TEXT...: import exits 2, the message holds FILE and each TEXT, no output
refuse() {
  local what=$1 file=$2
  shift 2
  rm -f "$T/bad.json"
  expect 2 "$what: exit 2" -- "$CLI" import-mesh "$file" -o "$T/bad.json"
  contains "$T/err" "$file" "$what: names the file"
  for t in "$@"; do contains "$T/err" "$t" "$what: says '$t'"; done
  [ ! -e "$T/bad.json" ] && ok "$what: nothing written" || bad "$what: an output was written"
}
{ tet A 0 1; tet B 2 5; } >"$T/good.obj"
sed 's/^v 2 0 0$/v nan 0 0/' "$T/good.obj" >"$T/nan.obj"
refuse "NaN" "$T/nan.obj" "object 'B'" "non-finite"
sed 's/^v 2 0 1$/v 2 0 1e999/' "$T/good.obj" >"$T/inf.obj"
refuse "infinite" "$T/inf.obj" "object 'B'" "non-finite"
sed 's/^v 3 0 0$/v 2 0.5 0/' "$T/good.obj" >"$T/flat.obj" # a face of B with 3 points on a line
refuse "degenerate face" "$T/flat.obj" "object 'B'" "degenerate"
sed '$d' "$T/good.obj" >"$T/open.obj"
refuse "open mesh" "$T/open.obj" "object 'B'" "open mesh"
{ tet A 0 1; echo "o B"; echo "v 0.1 0.1 0.1"; echo "v 1.1 0.1 0.1"; echo "v 0.1 1.1 0.1"; echo "v 0.1 0.1 1.1"
  echo "f 5 7 6"; echo "f 5 6 8"; echo "f 5 8 7"; echo "f 6 7 8"; } >"$T/overlap.obj"
refuse "overlapping bodies" "$T/overlap.obj" "'A'" "'B'" "overlap"
cat >"$T/ell2d.json" <<'EOF'
{"bodies": [{"id": "ell", "polygon": [[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]]}]}
EOF
$W "$T/ell2d.json" "$T/ell.obj" obj
refuse "non-convex" "$T/ell.obj" "object 'ell'" "not convex" "convex parts"
echo "this is not a mesh" >"$T/garbage.obj"
refuse "garbage OBJ" "$T/garbage.obj" "garbage.obj:1: not an OBJ statement: 'this'"
printf 'o A\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n' >"$T/index.obj"
refuse "OBJ face past the vertices" "$T/index.obj" "index.obj:5:" "no such vertex"
echo "solid x" >"$T/garbage.stl"
refuse "garbage STL" "$T/garbage.stl" "cannot read"
echo "x" >"$T/mesh.xyz1"
refuse "unknown format" "$T/mesh.xyz1" "cannot read"
refuse "missing file" "$T/nope.obj" "cannot open"
# a limit already past when the file is read (1 ns): exit 3, nothing written, whatever the timing
rm -f "$T/bad.json"
expect 3 "--time-limit past: exit 3" -- "$CLI" import-mesh "$T/good.obj" --time-limit 1e-9 -o "$T/bad.json"
contains "$T/out" "undecided" "  says undecided"
[ ! -e "$T/bad.json" ] && ok "  nothing written" || bad "  an output was written"
expect 0 "--density" -- "$CLI" import-mesh "$T/good.obj" --density 2.5 -o "$T/dens.json"
[ "$(grep -c '"density": 2.5' "$T/dens.json")" = 2 ] && ok "  every body's density" || bad "  densities not written"
expect 2 "bad --up" -- "$CLI" import-mesh "$T/good.obj" --up x -o "$T/bad.json"
expect 2 "bad --scale" -- "$CLI" import-mesh "$T/good.obj" --scale 0 -o "$T/bad.json"
expect 2 "no output" -- "$CLI" import-mesh "$T/good.obj"

# --- the module: check maps no Assimp, import-mesh does; without it, exit 2 naming it
LD_DEBUG=files "$CLI" check "$T/col.json" >/dev/null 2>"$T/ld"
! grep -q "libassimp" "$T/ld" && ok "check maps no Assimp" || bad "check loaded libassimp"
LD_DEBUG=files "$CLI" import-mesh "$T/col.obj" -o "$T/m.json" >/dev/null 2>"$T/ld"
grep -q "libassimp" "$T/ld" && ok "import-mesh maps Assimp (the log is read right)" || bad "no libassimp in the loader's log"
mkdir -p "$T/bare" && cp "$CLI" "$T/bare/unstack"
rm -f "$T/bad.json"
expect 2 "without its modules: exit 2" -- "$T/bare/unstack" import-mesh "$T/col.obj" -o "$T/bad.json"
contains "$T/err" "mesh.so" "  names the module"
[ ! -e "$T/bad.json" ] && ok "  nothing written" || bad "  an output was written"
finish
