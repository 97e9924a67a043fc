# The installed Python package (docs/python.md): `cmake --install` of this
# build into a temporary prefix, then Debian's python3 in an empty
# environment with only PYTHONPATH=P/lib/python3/dist-packages imports
# unstack from the prefix, which finds the installed libunstack.so by its
# RUNPATH (no LD_LIBRARY_PATH), plans a generated pyramid (the CLP module
# loaded from the prefix too), loads a dict and reads a file. Skipped
# (with a line saying so) in builds without the package or with sanitizers.
. "$(dirname "$0")/lib.sh"
B=$(dirname "$CLI")
P=$T/prefix
ext=$(ls "$B"/python/unstack/_unstack*.so 2>/dev/null | head -1)
if [ -z "$ext" ] || ldd "$ext" | grep -q libasan; then
  echo "skipped: no Python package in $B, or a sanitizer build"; finish; exit 0
fi
if cmake --install "$B" --prefix "$P" >"$T/install.log" 2>&1; then ok "cmake --install"; else
  bad "cmake --install"; sed 's/^/    /' "$T/install.log" | tail -20; finish; exit 1
fi
SITE=$P/lib/python3/dist-packages
inst=$(ls "$SITE"/unstack/_unstack*.so 2>/dev/null | head -1)
[ -n "$inst" ] && [ -f "$SITE/unstack/__init__.py" ] && ok "package in lib/python3/dist-packages/unstack" ||
  bad "no package in $SITE/unstack"
readelf -d "$inst" | grep -q 'R.*PATH.*\$ORIGIN' && ok "the extension's RUNPATH is relative (\$ORIGIN)" ||
  bad "the extension's RUNPATH: $(readelf -d "$inst" | grep PATH)"
readelf -d "$inst" | grep PATH | grep -qF "$B" && bad "the installed extension points into the build tree" ||
  ok "nothing points into the build tree"

cat >"$T/session.py" <<'PY'
import sys, unstack
root = sys.argv[1]
assert unstack.__file__.startswith(root), unstack.__file__
s = unstack.generate("pyramid", rows=4)
p = s.plan(method="lp", certificates=True)
assert p.status == "found" and len(p.order) == len(s) == 10, p
assert p.order[0] == ["b10"] and p.verify()["ok"]
d = unstack.load({"bodies": [{"id": "a", "polygon": [[0, 0], [1, 0], [1, 1], [0, 1]]},
                             {"id": "b", "polygon": [[0.6, 1], [1.6, 1], [1.6, 2], [0.6, 2]]}]})
assert d.check().verdict == "unstable" and d.plan().status == "unstable"
c = unstack.load(sys.argv[2])
assert c.plan().order[0] == ["L"]
try:
    unstack.load({"bodies": 1})
except unstack.Error as e:
    assert e.code == "input"
else:
    raise SystemExit("no error")
assert unstack.generate("wall", rows=3, cols=3).check(method="lp", local=False).stable
# the library and the CLP module mapped are the prefix's, not the build's
import os
maps = [l.split()[-1] for l in open("/proc/self/maps") if "libunstack.so" in l or "/unstack/clp.so" in l]
real = os.path.realpath(root)
assert maps and all(os.path.realpath(m).startswith(real) for m in maps), maps
assert any(m.endswith("clp.so") for m in maps), maps
print("installed session ok:", unstack.__file__)
PY
expect 0 "python3 -c 'import unstack' with only PYTHONPATH" -- env -i PATH=/usr/bin:/bin \
  PYTHONPATH="$SITE" /usr/bin/python3 "$T/session.py" "$P" "$DATA/cantilever.json"
contains "$T/out" "installed session ok" "the session ran from the prefix"
finish
