# A frictionless 1,256-block stack from an old stacker run whose tower
# tips at a waist (rows 0..65 of seed 1, 250 x 75, without the cantilever
# that balanced it): every method says unstable. CLP's barrier used to
# end "optimal" on it with a point 13 % of a block's weight x size off in
# torque, and the certificate check, measuring against the whole
# structure, let it pass as stable.
. "$(dirname "$0")/lib.sh"
for m in auto lp lpsolve; do
  expect 1 "near-infeasible stack, $m" -- "$CLI" check "$DATA/stacker_waist.json" --method "$m"
  contains "$T/out" "unstable" "$m: unstable"
done
expect 1 "near-infeasible stack, lp without local tests" -- "$CLI" check "$DATA/stacker_waist.json" --method lp --local off
