# The installed package (docs/install.md): `cmake --install` of this build
# into a temporary prefix, nothing outside it; the versioned library with
# its SONAME; examples/example_plan.c built against the prefix with
# pkg-config and cc, and with the CMake package (find_package(unstack)),
# both run; the installed `unstack` and the installed libunstack.so each
# load their modules (CLP, cairo's PNG) from the prefix. Reuses the built
# tree: nothing of the library is rebuilt.
. "$(dirname "$0")/lib.sh"
SRC=$(cd "$(dirname "$0")/../.." && pwd)
B=$(dirname "$CLI")
P=$T/prefix
CC=${CC:-cc}

# install, and once more staged under DESTDIR: the same files, all in P
if cmake --install "$B" --prefix "$P" >"$T/install.log" 2>&1; then ok "cmake --install"; else
  bad "cmake --install"; sed 's/^/    /' "$T/install.log" | tail -20; finish; exit 1
fi
DESTDIR=$T/stage cmake --install "$B" --prefix "$P" >"$T/stage.log" 2>&1 || bad "staged install"
(cd "$P" && find . ! -type d | sort) >"$T/files"
(cd "$T/stage" && find . ! -type d | sort) >"$T/staged"
outside=$(grep -v "^\.$P/" "$T/staged" | head -3)
[ -z "$outside" ] && ok "nothing installed outside the prefix" || bad "installed outside the prefix: $outside"
grep -q "^prefix=$P\$" "$T/stage$P"/lib/*/pkgconfig/unstack.pc && ok "a staged unstack.pc names the prefix" ||
  bad "a staged unstack.pc names another prefix"
sed "s#^\.$P/#./#" "$T/staged" | cmp -s - "$T/files" && ok "DESTDIR installs the same files" ||
  bad "DESTDIR installs other files"

# where things are: Debian's layout
pc=$(cd "$P" && ls lib/*/pkgconfig/unstack.pc 2>/dev/null)
[ -n "$pc" ] && ok "unstack.pc in lib/<multiarch>/pkgconfig ($pc)" || bad "no lib/<multiarch>/pkgconfig/unstack.pc"
export PKG_CONFIG_PATH=$P/${pc%/unstack.pc}
LIBDIR=$(pkg-config --variable=libdir unstack)
[ "$LIBDIR" = "$P/${pc%/pkgconfig/unstack.pc}" ] && ok "pkg-config's libdir is the prefix's" ||
  bad "pkg-config libdir $LIBDIR"
for f in bin/unstack include/unstack/unstack.h share/man/man1/unstack.1 \
         "${pc%/pkgconfig/unstack.pc}/cmake/unstack/unstackConfig.cmake" \
         "${pc%/pkgconfig/unstack.pc}/cmake/unstack/unstackConfigVersion.cmake"; do
  [ -f "$P/$f" ] && ok "installed $f" || bad "missing $f"
done
for m in clp png svg; do
  [ -f "$LIBDIR/unstack/$m.so" ] && ok "module $m.so in LIBDIR/unstack" || bad "no $LIBDIR/unstack/$m.so"
done
grep -qE '/(tests?|bench)/|/test_|fuzz' "$T/files" && bad "a test program was installed" ||
  ok "no test program installed"

# the versioned shared library: real file, SONAME link, namelink
real=$(cd "$LIBDIR" && ls libunstack.so.*.*.* 2>/dev/null)
[ -f "$LIBDIR/$real" ] && [ ! -L "$LIBDIR/$real" ] && ok "versioned library $real" || bad "no libunstack.so.X.Y.Z"
soname=$(objdump -p "$LIBDIR/$real" | awk '$1 == "SONAME" {print $2}')
[ "$soname" = libunstack.so.0 ] && ok "SONAME libunstack.so.0" || bad "SONAME '$soname'"
[ "$(readlink "$LIBDIR/libunstack.so.0")" = "$real" ] && ok "libunstack.so.0 -> $real" || bad "SONAME link"
[ "$(readlink "$LIBDIR/libunstack.so")" = libunstack.so.0 ] && ok "namelink libunstack.so" || bad "namelink"

# a sanitized build's library needs the sanitizer runtime in the program too
flags=""
objdump -p "$LIBDIR/$real" | grep -q 'NEEDED.*libasan' && flags="-fsanitize=address,undefined"

# from_prefix WHAT LOG LIB: the loader's LOG shows LIB initialized from the prefix
from_prefix() {
  if grep -q "calling init: $P/.*$3" "$2"; then ok "$1 loads $3 from the prefix"; else
    bad "$1: $3 not loaded from the prefix"; grep "calling init: .*$3" "$2" | head -3; fi
}
run_logged() { # LOG OUT command...: the loader's log of one run in LOG, stdout in OUT
  local log=$1 out=$2
  shift 2
  LD_DEBUG=libs LD_DEBUG_OUTPUT="$log" "$@" >"$out" 2>"$out.err"
  local rc=$?
  cat "$log".* >"$log" 2>/dev/null
  return $rc
}
# says WHAT OUT: example_plan's output says what the example is about
says() {
  contains "$2" "plan: found" "$1: a plan is found"
  contains "$2" "1. remove L" "$1: the plank goes first"
  contains "$2" "re-checked with lp_solve: valid" "$1: the plan re-checks"
}

# the pkg-config way
if $CC -std=c17 -Wall -Wextra -Werror $flags -o "$T/ex_pc" "$SRC/examples/example_plan.c" \
     $(pkg-config --cflags --libs unstack) -Wl,-rpath,"$LIBDIR" 2>"$T/cc.err"; then
  ok "example_plan builds with pkg-config"
  run_logged "$T/pc.log" "$T/pc.out" "$T/ex_pc" && ok "example_plan (pkg-config) exits 0" ||
    bad "example_plan (pkg-config) failed"
  says "pkg-config build" "$T/pc.out"
  from_prefix "example_plan (pkg-config)" "$T/pc.log" "libunstack.so.0"
else bad "example_plan does not build with pkg-config"; sed 's/^/    /' "$T/cc.err" | head; fi

# the CMake package: a fresh configure of examples/ against the prefix
if cmake -S "$SRC/examples" -B "$T/exb" -DCMAKE_PREFIX_PATH="$P" -DCMAKE_C_FLAGS="$flags" \
     -DCMAKE_EXE_LINKER_FLAGS="$flags" >"$T/cm.log" 2>&1 && cmake --build "$T/exb" >>"$T/cm.log" 2>&1; then
  ok "examples/ build with find_package(unstack)"
  run_logged "$T/cm.rlog" "$T/cm.out" "$T/exb/example_plan" && ok "example_plan (CMake) exits 0" ||
    bad "example_plan (CMake) failed"
  says "CMake build" "$T/cm.out"
  from_prefix "example_plan (CMake)" "$T/cm.rlog" "libunstack.so.0"
else bad "examples/ do not build with the CMake package"; sed 's/^/    /' "$T/cm.log" | tail -15; fi

# the installed library finds its module: an LP without local tests needs CLP
cat >"$T/lp.c" <<'C'
#include <stdio.h>
#include "unstack/unstack.h"
int main(void) { /* two boxes stacked: a CLP test on the whole structure */
  us_Error err;
  us_error_clear(&err);
  us_Structure *s = us_structure_new(2);
  double a[8] = {0, 0, 1, 0, 1, 1, 0, 1}, b[8] = {0, 1, 1, 1, 1, 2, 0, 2};
  us_BodyDef da = {.id = "a", .nvert = 4, .xy = a, .density = 1, .friction = -1};
  us_BodyDef db = {.id = "b", .nvert = 4, .xy = b, .density = 1, .friction = -1};
  us_StabilitySettings set = us_stability_default_settings();
  set.method = US_METHOD_LP;
  set.local = -1;
  us_StabilityResult res;
  us_stability_result_init(&res);
  us_Stability *w = NULL;
  int ok = s && us_structure_add_body(s, &da, &err) >= 0 && us_structure_add_body(s, &db, &err) >= 0 &&
           us_structure_finalize(s, &err) == US_OK && (w = us_stability_new(s, &set, &err)) &&
           us_stability_test_full(w, &res, &err) == US_OK;
  printf("%s\n", ok ? us_verdict_name(res.verdict) : err.msg);
  us_stability_result_free(&res);
  us_stability_free(w);
  us_structure_free(s);
  return ok ? 0 : 2;
}
C
if $CC -std=c17 -Wall -Wextra -Werror $flags -o "$T/lp" "$T/lp.c" $(pkg-config --cflags --libs unstack) \
     -Wl,-rpath,"$LIBDIR" 2>"$T/cc.err"; then
  run_logged "$T/lp.log" "$T/lp.out" "$T/lp" && ok "a CLP test through the installed library" ||
    { bad "a CLP test through the installed library"; sed 's/^/    /' "$T/lp.out" "$T/lp.out.err"; }
  contains "$T/lp.out" "stable" "two stacked boxes stand"
  from_prefix "the installed library" "$T/lp.log" "unstack/clp.so"
else bad "the CLP program does not build"; sed 's/^/    /' "$T/cc.err" | head; fi

# the installed tool: a plan on CLP and a PNG, modules from the prefix
U=$P/bin/unstack
expect 0 "installed unstack --version" -- "$U" --version
contains "$T/out" "unstack " "--version answers"
"$U" generate pyramid --rows 4 -o "$T/pyr.json" >/dev/null || bad "installed generate"
run_logged "$T/plan.log" "$T/plan.out" "$U" plan "$T/pyr.json" --method lp --local off -o "$T/plan.json" &&
  ok "installed plan --method lp --local off" || bad "installed plan --method lp"
contains "$T/plan.json" '"found"' "the installed tool's plan is found"
from_prefix "installed plan --method lp" "$T/plan.log" "unstack/clp.so"
run_logged "$T/png.log" "$T/png.out" "$U" render "$T/pyr.json" --plan "$T/plan.json" -o "$T/pyr.png" &&
  ok "installed render PNG" || bad "installed render PNG"
[ "$(head -c 8 "$T/pyr.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] && ok "a PNG is written" ||
  bad "no PNG written"
from_prefix "installed render PNG" "$T/png.log" "unstack/png.so"
finish
