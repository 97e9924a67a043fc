#!/bin/bash
# The library keeps no mutable global state (a library called from
# threads): no object of its concept archives defines a writable variable
# (.data, .bss, common, thread-local) outside the justified list below.
# Constant tables live in .rodata / .data.rel.ro and are fine (a table of
# pointers needs both consts, `const char *const t[]`: an optimized build
# may place it read-only anyway, a debug build does not).
# Usage: globals.sh <build dir>
set -u
build=$1
# file:symbol, and why
allowed="
alloc.c:live        atomic count of live blocks (leak checks)
alloc.c:fail_after  thread-local failure hook (out-of-memory tests)
hook.c:hook_fn      thread-local verdict hook of the planner's tests
hook.c:hook_user    its argument, thread-local too
lcp_factor.c:klu_once  call_once flag: SuiteSparse's global allocator set once
lp_clp_lazy.c:clp_module  module record: an atomic pointer to the loaded entry points (core/module.h)
png_lazy.c:png_module     the same for the PNG writer's module
svg_lazy.c:svg_module     the same for the SVG import's module
mesh_lazy.c:mesh_module   the same for the mesh import's module
strong_lazy.c:cbc_module  the same for the strong-stability MIP's module (CBC)
"
found=$(for a in "$build"/libus_*.a; do objdump -t "$a"; done | awk '
  /^[^ ]+\.o:[ \t]+file format/ { f = $1; sub(/\.o:$/, "", f); next }
  /^[0-9a-f]+ / {
    sec = ""; name = $NF
    for (i = 2; i <= NF; i++) if ($i ~ /^(\.|\*COM\*)/) { sec = $i; break }
    if (name == sec || name ~ /^\./) next # section symbols
    if (name ~ /^__/) next                 # the compiler'"'"'s own (sanitizers: __odr_asan.*)
    if (sec ~ /^(\.data|\.bss|\.tdata|\.tbss|\*COM\*)(\.|$)/ && sec !~ /^\.data\.rel\.ro/)
      print f ":" name
  }' | sort -u)
n=$(ls "$build"/libus_*.a 2>/dev/null | wc -l)
fail=0
[ "$n" -lt 5 ] && { echo "only $n archives under $build"; fail=1; }
for g in $found; do
  if ! echo "$allowed" | awk '{print $1}' | grep -qx "$g"; then
    echo "writable global: $g"; fail=1
  fi
done
echo "$n archives, writable globals: $(echo $found)"
exit $fail
