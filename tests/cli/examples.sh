# The hand-made example structures: verdicts a user expects.
. "$(dirname "$0")/lib.sh"
expect 0 "column3 plan" -- "$CLI" plan "$DATA/column3.json" -o "$T/p.json"
expect 0 "cantilever plan found" -- "$CLI" plan "$DATA/cantilever.json" --stats -o "$T/cant.json"
expect 0 "cantilever plan verifies" -- "$CLI" verify "$DATA/cantilever.json" "$T/cant.json"
expect 1 "leaning slabs: no order" -- "$CLI" plan "$DATA/leaning.json" -o "$T/lean.json"
contains "$T/lean.json" '"none"' "leaning: status none"
expect 0 "slab on a wall stands with friction" -- "$CLI" check "$DATA/lean_wall.json"
expect 1 "slab on a wall falls without friction" -- "$CLI" check "$DATA/lean_wall_mu0.json"
expect 0 "explicit contacts stand" -- "$CLI" check "$DATA/explicit.json"
expect 0 "explicit contacts plan" -- "$CLI" plan "$DATA/explicit.json" -o "$T/ex.json"
for m in lp lpsolve lcp lcp-reuse lp-lcp; do
  expect 0 "cantilever with $m" -- "$CLI" plan "$DATA/cantilever.json" --method $m
  expect 1 "leaning with $m" -- "$CLI" plan "$DATA/leaning.json" --method $m
done
# the Python session (examples/plan.py) with the build tree's package, when
# built; not in sanitizer builds (python.pytest runs the package there)
py=$(dirname "$CLI")/python
ext=$(ls "$py"/unstack/_unstack*.so 2>/dev/null | head -1)
if [ -n "$ext" ] && ! ldd "$ext" | grep -q libasan; then
  expect 0 "examples/plan.py session" -- env PYTHONPATH="$py" /usr/bin/python3 \
    "$(dirname "$0")/../../examples/plan.py" "$T"
  contains "$T/out" "all as expected" "examples/plan.py: known answers"
fi
finish
