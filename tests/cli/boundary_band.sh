# A block whose centre of mass is 1e-8 (of its size) past its support's
# corner tips; lp_solve used to certify it as stable within its tolerance
# while lp, lcp, lcp-reuse and lp-lcp said unstable. In the boundary band
# every method now gives the referee's verdict (docs/planning.md, "The
# boundary band"), in 2D and 3D, at sizes 1 and 1e6; 1e-6 past the corner
# and 1e-8 inside it stay exact.
. "$(dirname "$0")/lib.sh"

# corner FILE DIM OFFSET SIZE: a unit base box, a top box centred OFFSET past its right edge
corner() {
  python3 - "$@" <<'PY'
import json, sys
out, dim, d, sc = sys.argv[1], int(sys.argv[2]), float(sys.argv[3]), float(sys.argv[4])
if dim == 2:
    box = lambda x0, y0, x1, y1: [[x0 * sc, y0 * sc], [x1 * sc, y0 * sc], [x1 * sc, y1 * sc], [x0 * sc, y1 * sc]]
    bodies = [{"id": "base", "polygon": box(0, 0, 1, 1)}, {"id": "top", "polygon": box(0.5 + d, 1, 1.5 + d, 1.5)}]
else:
    bodies = [{"id": "base", "box": {"center": [0.5 * sc, 0.5 * sc, 0.5 * sc], "size": [sc, sc, sc]}},
              {"id": "top", "box": {"center": [(1 + d) * sc, 0.5 * sc, 1.25 * sc], "size": [sc, sc, 0.5 * sc]}}]
json.dump({"dimension": dim, "friction": 0.5, "bodies": bodies}, open(out, "w"))
PY
}

for sc in 1 1e6; do
  corner "$T/c2.json" 2 1e-8 "$sc"
  for m in lp lpsolve lcp lcp-reuse lp-lcp; do
    expect 1 "2D, size $sc, 1e-8 past the corner: $m unstable" -- "$CLI" check "$T/c2.json" --method "$m"
  done
  corner "$T/c3.json" 3 1e-8 "$sc"
  for m in lp lpsolve; do
    expect 1 "3D, size $sc, 1e-8 past the corner: $m unstable" -- "$CLI" check "$T/c3.json" --method "$m"
  done
done
"$CLI" check "$T/c2.json" --method lpsolve >"$T/out" 2>&1
contains "$T/out" "within tolerance of tipping" "lp_solve's claim is named as within tolerance of tipping"
for m in lp lpsolve lcp lp-lcp; do
  corner "$T/far.json" 2 1e-6 1
  expect 1 "1e-6 past the corner: $m unstable" -- "$CLI" check "$T/far.json" --method "$m"
  corner "$T/in.json" 2 -1e-8 1
  expect 0 "1e-8 inside the corner: $m stable" -- "$CLI" check "$T/in.json" --method "$m"
done
finish
