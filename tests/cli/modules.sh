# Start-up without the heavy libraries (docs/modules.md): check on a column,
# plan on the pyramid and its SVG picture map none of CLP (and its LAPACK/BLAS), cairo or
# libxml2 (ICU) - read from the dynamic loader's own log (LD_DEBUG=files), so
# relinking one of them into the executable fails here; the commands that
# need them (an LP without local tests, a PNG, an SVG import) do load their
# module, so the log is read right; and a copy of the executable without its
# modules still checks the column but refuses each of those commands with
# exit 2, naming the missing module, and writes nothing.
. "$(dirname "$0")/lib.sh"
HEAVY='libClp|libCoinUtils|liblapack|libopenblas|libblas|libcairo|libxml2|libicu|libX11|libfontconfig|libfreetype'
"$CLI" generate column --blocks 5 -o "$T/col5.json" >/dev/null || bad "generate column"
"$CLI" generate pyramid --rows 13 -o "$T/pyr.json" >/dev/null || bad "generate pyramid"

# loaded FILE: the shared objects the loader mapped (one name per line)
loaded() { grep -o 'file=[^ ]*' "$1" | sed 's/^file=//; s#.*/##' | sort -u; }
# light WHAT LOG: none of the heavy libraries in LOG
light() {
  local heavy
  heavy=$(loaded "$2" | grep -E "^($HEAVY)" | tr '\n' ' ')
  if [ -z "$heavy" ]; then ok "$1 loads no heavy library"; else bad "$1 loads $heavy"; fi
}
# loads WHAT LOG PATTERN: LOG shows a library matching PATTERN
loads() {
  if loaded "$2" | grep -qE "$3"; then ok "$1 loads $3"; else bad "$1 does not load $3"; fi
}
run_logged() { # LOG command...: the loader's log of one run in LOG
  local log=$1
  shift
  LD_DEBUG=files LD_DEBUG_OUTPUT="$log" "$@" >/dev/null 2>&1
  cat "$log".* >"$log" 2>/dev/null
}

run_logged "$T/check.log" "$CLI" check "$T/col5.json"
light "check col5" "$T/check.log"
loads "check col5 (the log is read)" "$T/check.log" '^libjansson'
run_logged "$T/plan.log" "$CLI" plan "$T/pyr.json" -o "$T/plan.json"
light "plan pyramid" "$T/plan.log"
[ -s "$T/plan.json" ] && ok "the pyramid's plan is written" || bad "no plan written"
run_logged "$T/lp.log" "$CLI" check "$T/pyr.json" --local off
loads "check --local off (an LP)" "$T/lp.log" '^(clp\.so|libClp)'
run_logged "$T/png.log" "$CLI" render "$T/col5.json" -o "$T/c.png"
loads "render PNG" "$T/png.log" '^(png\.so|libcairo)'
run_logged "$T/svgr.log" "$CLI" render "$T/pyr.json" --plan "$T/plan.json" -o "$T/p.svg"
light "render SVG with a plan" "$T/svgr.log"
run_logged "$T/imp.log" "$CLI" import-svg "$(dirname "$0")/../../examples/column.svg" -o "$T/imp.json"
loads "import-svg" "$T/imp.log" '^(svg\.so|libxml2)'

# a copy of the executable alone: no modules next to it
mkdir -p "$T/alone"
cp "$CLI" "$T/alone/unstack"
A=$T/alone/unstack
expect 0 "without modules: check col5" -- "$A" check "$T/col5.json"
expect 0 "without modules: plan pyramid" -- "$A" plan "$T/pyr.json" -o "$T/alone/p.json"
expect 2 "without modules: check --local off" -- "$A" check "$T/pyr.json" --local off
contains "$T/err" "module 'clp.so'" "the message names clp.so"
expect 2 "without modules: render PNG" -- "$A" render "$T/col5.json" -o "$T/alone/c.png"
contains "$T/err" "module 'png.so'" "the message names png.so"
[ -e "$T/alone/c.png" ] && bad "a PNG was written" || ok "no PNG written"
expect 2 "without modules: import-svg" -- "$A" import-svg "$(dirname "$0")/../../examples/column.svg" \
  -o "$T/alone/i.json"
contains "$T/err" "module 'svg.so'" "the message names svg.so"
[ -e "$T/alone/i.json" ] && bad "a structure was written" || ok "no structure written"
finish
