"""unstack: plan how to take a structure of rigid blocks apart (or build it)
so that it never collapses under gravity.

A thin layer over the C extension ``unstack._unstack``, which calls the
public API of libunstack.so (docs/python.md). Objects that own library
memory (Structure, Plan) free it on ``close()``, at the end of a ``with``
block, or when they are collected.

    >>> import unstack
    >>> s = unstack.generate("column", blocks=3)
    >>> s.check().stable
    True
    >>> s.plan().order
    [['b3'], ['b2'], ['b1']]
"""

import json
import os

from . import _unstack
from ._unstack import Error

__all__ = ["Error", "Structure", "CheckResult", "Plan", "load", "import_svg", "generate",
           "__version__"]
__version__ = _unstack.version
Error.code = "usage"  # errors raised by the library carry their own status name


def _alloc_live():
    """The library's live allocations (us_alloc_live): for leak checks."""
    return _unstack.alloc_live()


def _alloc_fail_after(n):
    """Tests only: after n more allocations of this thread every library
    allocation fails (n < 0: off); returns the live count."""
    return _unstack.alloc_fail_after(n)


def load(source, contact_tol=0.0):
    """A Structure from a structure file (a path) or from a dict in the JSON
    structure format (docs/format.md). Raises unstack.Error on bad input,
    with the library's message (file and line, or the body's id)."""
    if isinstance(source, Structure):
        raise Error("load: already a Structure")
    if isinstance(source, dict):
        try:
            text = json.dumps(source, allow_nan=False)
        except (TypeError, ValueError) as e:
            raise Error(f"load: the dict is not JSON: {e}") from None
        return Structure(_unstack.parse(text, "<dict>", float(contact_tol)))
    try:
        path = os.fspath(source)
    except TypeError:
        raise Error(f"load: needs a path or a dict, got {type(source).__name__}") from None
    if isinstance(path, bytes):
        path = os.fsdecode(path)
    return Structure(_unstack.read(path, float(contact_tol)))


def import_svg(path, friction=None, scale=1.0, ground=True):
    """A Structure from an SVG drawing, as `unstack import-svg` (docs/svg.md):
    friction (default: the drawing's data-friction, else 0.5), the drawing's
    scale (1:scale), ground (the drawing's lowest point supports it)."""
    mu = -1.0 if friction is None else float(friction)
    return Structure(_unstack.read_svg(os.fsdecode(os.fspath(path)), mu, float(scale), bool(ground)))


def generate(kind, **params):
    """A generated Structure: the kinds and parameters of `unstack generate`
    (column, pyramid, wall, arch, random, stacker, tower, pyramid3d, wall3d,
    dome, jenga, random3d), option names with '_' for '-', e.g.
    generate("wall", rows=4, cols=6, block_height=0.5); jenga's remove is a
    list of (level, position) pairs."""
    return Structure(_unstack.generate(kind, **params))


class _Owner:
    """Common close() / context manager of the objects holding a handle."""

    _h = None

    def close(self):
        """Free the library memory now (idempotent)."""
        if self._h is not None:
            self._h.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False


class Structure(_Owner):
    """A finalized structure: bodies, contacts, materials (read-only)."""

    def __init__(self, handle):
        self._h = handle

    @property
    def dim(self):
        return self._h.dim

    @property
    def ids(self):
        """Body ids in file order."""
        return self._h.ids

    @property
    def fixed(self):
        """Ids of the fixed bodies (never removed)."""
        return self._h.fixed

    @property
    def bodies(self):
        """One dict per body: id, fixed, mass (None when fixed), com."""
        return self._h.bodies

    @property
    def contacts(self):
        """One dict per contact: a, b (ids, "ground"), point, normal (from a
        into b), mu."""
        return self._h.contacts

    @property
    def ncontacts(self):
        return self._h.ncontacts

    @property
    def fingerprint(self):
        """The structure's fingerprint ("fnv1a64:..."), as plan files name it."""
        return self._h.fingerprint

    @property
    def closed(self):
        return self._h.closed

    def __len__(self):
        return len(self._h)

    def __repr__(self):
        if self.closed:
            return "<unstack.Structure closed>"
        return f"<unstack.Structure {self.dim}D, {len(self)} bodies, {self.ncontacts} contacts>"

    def write(self, path):
        """Write the structure file (atomically: nothing on error)."""
        self._h.write(os.fsdecode(os.fspath(path)))

    def to_dict(self):
        """The structure in the JSON structure format, as a dict."""
        import tempfile  # here: it costs import time most sessions never need

        fd, path = tempfile.mkstemp(prefix="unstack-", suffix=".json")
        os.close(fd)
        try:
            self._h.write(path)
            with open(path, encoding="utf-8") as f:
                return json.load(f)
        finally:
            os.unlink(path)

    def render(self, path, plan=None, forces=False, title=None):
        """Draw the structure, and a plan of it when given: .svg or .png
        (docs/render.md; the plan's order numbered, a none plan's build and
        blocked bodies), or .html, the interactive viewer (docs/viewer.md;
        2D; the forces of every step when the plan was made with
        certificates=True). forces=True draws in a picture the full
        structure's forces of such a plan. Written atomically."""
        h = None if plan is None else plan._h
        _unstack.render(self._h, os.fsdecode(os.fspath(path)), h, bool(forces), title)

    def check(self, method="auto", **settings):
        """Does the whole structure stand? Keywords: method (auto, lp,
        lpsolve, lcp, lcp-reuse, lp-lcp), local (True/False), time_limit
        (seconds), cert_tol, max_pivots."""
        return CheckResult(_unstack.check(self._h, method=method, **settings))

    def plan(self, method="auto", **settings):
        """Plan a removal order (or, with hands, an assembly). Keywords as
        `unstack plan`'s options: method, search (assemble, dfs, bfs,
        random), hands (int or "auto"), max_group (int or "auto"),
        time_limit, direction (down, up), order (highest, lowest, input),
        removal (any, up, free), rules, seed, max_tests, exact_tests,
        certificates (bool), local, cert_tol, max_pivots."""
        handle, data = _unstack.plan(self._h, method=method, **settings)
        return Plan(handle, data)


class CheckResult:
    """The verdict of one stability test of the whole structure.

    stable, verdict ("stable", "unstable", "undecided"); forces (stable: one
    dict per active contact with a, b, point, normal, normal_force,
    tangential and the friction vector), certificate (its independent
    re-check); mechanism (unstable, when known: moving bodies and
    velocities), unstable_body; note, method, stats."""

    def __init__(self, data):
        self._d = data
        for k, v in data.items():
            setattr(self, k, v)
        self.stable = data["verdict"] == "stable"

    def to_dict(self):
        return dict(self._d)

    def __bool__(self):
        return self.stable

    def __repr__(self):
        return f"<unstack.CheckResult {self.verdict}>"


class Plan(_Owner):
    """A plan: status ("found", "none", "unstable", "limit", "undecided"),
    order (a list of steps, each a list of body ids, in removal order),
    actions (hands plans: (verb, id) pairs in assembly order, else None),
    blocked and build (status none), hands, hands_lower, max_group, note,
    stats (dict). write(path) writes the plan file; verify() re-checks it."""

    def __init__(self, handle, data):
        self._h = handle
        self._d = data
        for k, v in data.items():
            setattr(self, k, v)

    @property
    def found(self):
        return self.status == "found"

    def write(self, path):
        """Write the plan file (docs/format.md), atomically."""
        self._h.write(os.fsdecode(os.fspath(path)))

    def verify(self):
        """Re-check every step (or action) with fresh stability tests whose
        certificates are re-checked; a dict with ok, failed_step, ..."""
        return self._h.verify()

    def certificates(self):
        """With certificates=True: the forces of the structure before every
        step (the last, the empty structure), else None."""
        return self._h.certificates()

    def to_dict(self):
        return dict(self._d)

    def __repr__(self):
        return f"<unstack.Plan {self.status}, {len(self.order)} steps>"
