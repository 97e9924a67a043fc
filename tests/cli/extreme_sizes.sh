# Extreme sizes get their true reason (issue 24, point 5): exit 2 naming
# the body and saying overflow or underflow, never "lie in one plane" or
# "must not be zero"; sizes the doubles can carry are accepted.
. "$(dirname "$0")/lib.sh"
cube() { echo "{\"dimension\": 3, \"bodies\": [{\"id\": \"c\", \"box\": {\"center\": [0, 0, $2], \"size\": [$1, $1, $1]}}]}" >"$T/c.json"; }
cube 1e101 5e100
expect 2 "cube of side 1e101" -- "$CLI" check "$T/c.json"
contains "$T/err" "body 'c': coordinates too large, the inertia overflows" "1e101: the inertia overflows"
cube 1e-100 5e-101
expect 0 "cube of side 1e-100" -- "$CLI" check "$T/c.json"
cube 1e-300 5e-301
expect 2 "cube of side 1e-300" -- "$CLI" check "$T/c.json"
contains "$T/err" "body 'c': coordinates too small, the volume underflows" "1e-300: the volume underflows"
echo '{"bodies": [{"id": "s", "polygon": [[0, 0], [1e-300, 0], [1e-300, 1e-300], [0, 1e-300]]}]}' >"$T/s.json"
expect 2 "square of side 1e-300" -- "$CLI" check "$T/s.json"
contains "$T/err" "body 's': coordinates too small, the area underflows" "2D 1e-300: the area underflows"
echo '{"dimension": 3, "bodies": [{"id": "q", "box": {"center": [0, 0, 0.5], "size": [1, 1, 1], "rotation": [1e308, 1e308, 0, 0]}}]}' >"$T/q.json"
expect 0 "quaternion [1e308, 1e308, 0, 0] is normalized" -- "$CLI" check "$T/q.json"
echo '{"dimension": 3, "gravity": [0, 0, 0], "bodies": [{"id": "g", "box": {"center": [0, 0, 0.5], "size": [1, 1, 1]}}]}' >"$T/g.json"
expect 2 "3D zero gravity" -- "$CLI" check "$T/g.json"
contains "$T/err" "e.g. [0, 0, -9.81]" "3D zero gravity: a 3D example"
finish
