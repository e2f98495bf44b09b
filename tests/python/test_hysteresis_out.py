"""Hysteresis.forces / displacements with out= (issue 14, item 6): the result written into
a caller's array equals the allocating call bit for bit (same C++ loop, same doubles),
for contiguous and strided outputs, in place and with overlapping views; a wrong `out`
is an InvalidInput naming `out`, what it got and what is allowed.

References: the allocating call on the same state (itself tested against closed forms in
test_rough_flat.py); the Jenkins element (k = 2, F = 1) and the Fig. 4.4 rough flat
(beta = 0.04, psi = 0.5, nu = 0.3, P* = 1e-3) as backbones."""
import signal
import sys

import numpy as np
import pytest

import asperity


def jenkins_with_reversals():
    h = asperity.Hysteresis(asperity.JenkinsBackbone(2.0, 1.0))
    for x in (1.0, -0.25, 0.1):
        h.update(x)
    assert len(h.reversals) == 2  # a non-empty stack: the histories below close loops
    return h


def rough_flat_with_reversals(memory="masing"):
    flat = asperity.RoughFlat("bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
    h = asperity.Hysteresis(flat.backbone(flat.separation_star(1e-3)), memory=memory)
    for x in (0.5, -0.2, 0.3, 0.1):
        h.update(x)
    return h


def history(n, seed=3):
    """A path with many reversals and jumps across remembered points."""
    rng = np.random.default_rng(seed)
    return np.cumsum(rng.normal(0.0, 0.15, n)) % 1.2 - 0.6


def snapshot(h):
    return h.x, h.Q, h.reversals


# n = 1 (the peek path), 2-8 (small, GIL held), 1023 and 5000 (either side of where the
# loop releases the GIL).
@pytest.mark.parametrize("n", [0, 1, 2, 8, 1023, 5000])
@pytest.mark.parametrize("make", [jenkins_with_reversals, rough_flat_with_reversals,
                                  lambda: rough_flat_with_reversals("reset_at_reversal")])
def test_out_equals_the_allocating_call(make, n):
    h = make()
    before = snapshot(h)
    x = history(n)
    expected = h.forces(x)
    # The reference: update() one point at a time on a replay of the same state (forces
    # runs Hysteresis::update_strided; the same doubles, bit for bit).
    replay = make()
    np.testing.assert_array_equal(expected, np.array([replay.update(v) for v in x]))
    out = np.full(n, np.nan)
    assert h.forces(x, out=out) is out
    np.testing.assert_array_equal(out, expected)
    # A strided output (every third element of a larger array) and a strided input.
    big = np.full(3 * n, -7.0)
    assert h.forces(x, out=big[::3]) is not None
    np.testing.assert_array_equal(big[::3], expected)
    np.testing.assert_array_equal(big[1::3], -7.0)  # nothing written between
    wide = np.repeat(x, 2)
    np.testing.assert_array_equal(h.forces(wide[::2], out=np.empty(n)), expected)
    # Any sequence as input (through numpy.asarray), into out.
    np.testing.assert_array_equal(h.forces(list(x), out=np.empty(n)), expected)
    assert snapshot(h) == before
    # The inverse, on the forces of a smaller history (reachable under force control).
    q = h.forces(0.2 * x)
    back = h.displacements(q)
    into = np.full(n, np.nan)
    assert h.displacements(q, out=into) is into
    np.testing.assert_array_equal(into, back)
    assert snapshot(h) == before


# forces() evaluates the leading points that continue the current branch on the state
# itself (Hysteresis::peek_strided) and the rest on a copy restarted at the last of them:
# histories that continue for 0, 1, 2 or 5 points, then turn (and turn again), into a new
# array, into out and in place (where the restart point is overwritten, so the copy takes
# every point), against update() one point at a time on a replay.
@pytest.mark.parametrize("lead", [0, 1, 2, 5])
@pytest.mark.parametrize("make, direction", [(jenkins_with_reversals, 1.0),
                                             (rough_flat_with_reversals, -1.0)])
def test_a_history_continuing_the_branch_then_turning(make, direction, lead):
    h = make()
    x0 = h.x
    up = [x0 + direction * 0.01 * (i + 1) for i in range(lead)]
    top = up[-1] if up else x0
    back = [top - direction * 0.05 * j for j in range(1, 5)]
    x = np.array(up + back + [back[-1] + direction * 0.02 * j for j in range(1, 4)])
    replay = make()
    expected = np.array([replay.update(v) for v in x])
    before = snapshot(h)
    np.testing.assert_array_equal(h.forces(x), expected)
    np.testing.assert_array_equal(h.forces(x, out=np.empty(len(x))), expected)
    y = x.copy()
    np.testing.assert_array_equal(h.forces(y, out=y), expected)
    # Only continuing points: no copy at all.
    if lead:
        np.testing.assert_array_equal(h.forces(np.array(up)), expected[:lead])
    assert snapshot(h) == before


def test_prefix_of_a_long_history_equals_the_short_call():
    # The loop with the GIL released (5000 points) and held (1000) compute the same
    # thing: forces(x)[:m] == forces(x[:m]).
    h = rough_flat_with_reversals()
    x = history(5000)
    np.testing.assert_array_equal(h.forces(x)[:1000], h.forces(x[:1000]))
    np.testing.assert_array_equal(h.forces(x, out=np.empty(5000))[:7], h.forces(x[:7]))


@pytest.mark.parametrize("n", [1, 8, 3000])
def test_out_aliasing_the_input(n):
    h = jenkins_with_reversals()
    x = history(n, seed=11) * 2.0  # beyond the slip displacement: gross slip and loops
    expected = h.forces(x)
    # In place: out is x itself (each point is read before its force is written).
    y = x.copy()
    assert h.forces(y, out=y) is y
    np.testing.assert_array_equal(y, expected)
    if n > 1:
        # Overlapping but shifted views: writing out[k] would overwrite x[k + 1] before it
        # is read, so the history is copied first.
        buf = np.empty(n + 1)
        buf[:n] = x
        np.testing.assert_array_equal(h.forces(buf[:n], out=buf[1:]), expected)
        buf[1:] = x
        np.testing.assert_array_equal(h.forces(buf[1:], out=buf[:n]), expected)
        # Reversed view of the same memory.
        z = x.copy()
        np.testing.assert_array_equal(h.forces(z, out=z[::-1]), expected)
    # Displacements in place (within partial slip of the Jenkins element: |Q - Q_r| < 2F).
    q = np.clip(expected, -0.9, 0.9) * 0.5
    back = h.displacements(q)
    p = q.copy()
    np.testing.assert_array_equal(h.displacements(p, out=p), back)


@pytest.mark.parametrize("bad, got", [
    (np.empty(3), r"got a numpy\.float64 array of shape \(3,\)"),
    (np.empty(4, dtype=np.float32), r"got a numpy\.float32 array of shape \(4,\)"),
    (np.empty((4, 1)), r"got a numpy\.float64 array of shape \(4, 1\)"),
    (np.empty((2, 2)), r"shape \(2, 2\)"),
    ([0.0, 0.0, 0.0, 0.0], "got a list"),
    (np.empty(4, dtype=">f8" if np.little_endian else "<f8"), "byte-swapped"),
    (np.empty(4, dtype=np.int64), "int64"),
    (0.0, "got a float"),
])
def test_a_wrong_out_names_out_the_value_and_what_is_allowed(bad, got):
    h = jenkins_with_reversals()
    x = np.array([0.3, -0.6, 0.2, 0.9])
    allowed = r"out must be a writable 1-D numpy float64 array .* of length 4"
    for call in (h.forces, h.displacements):
        with pytest.raises(asperity.InvalidInput, match=allowed) as e:
            call(x * 0.1, out=bad)
        assert e.match(got)


def test_read_only_out_and_out_with_a_float_are_refused():
    h = jenkins_with_reversals()
    ro = np.empty(2)
    ro.flags.writeable = False
    with pytest.raises(asperity.InvalidInput, match=r"out must be a writable.*read-only"):
        h.forces(np.array([0.1, 0.2]), out=ro)
    # A float history gives a float: there is no array to fill.
    with pytest.raises(asperity.InvalidInput, match=r"out is for a 1-D history.*float \(0.3\)"):
        h.forces(0.3, out=np.empty(1))
    with pytest.raises(asperity.InvalidInput, match=r"out is for a 1-D history"):
        h.displacements(0.1, out=np.empty(1))
    # out=None is the allocating call; out is keyword-only (numpy's convention).
    assert h.forces(0.3, out=None) == h.forces(0.3)
    with pytest.raises(TypeError):
        h.forces(np.array([0.1]), np.empty(1))


def test_an_error_inside_a_history_leaves_later_calls_right():
    # Force control beyond the static limit (F = 1) fails part-way through the history,
    # leaving the per-thread scratch state the call ran on mid-history: the next calls
    # (short and long, scalar and array) equal those made before the failure.
    h = jenkins_with_reversals()
    q = np.array([0.2, -0.4, 0.5])
    x = history(3000)
    before = (h.displacements(q), h.displacements(0.3), h.forces(x), h.forces(x[:5]))
    for bad in (np.array([0.2, 5.0, 0.1]), 5.0, np.full(2000, 5.0)):
        with pytest.raises(asperity.InvalidInput, match="static friction limit"):
            h.displacements(bad)
    after = (h.displacements(q), h.displacements(0.3), h.forces(x), h.forces(x[:5]))
    for a, b in zip(before, after):
        np.testing.assert_array_equal(a, b)


def test_fast_entry_points_parse_arguments_as_the_signature_says():
    # forces/displacements are CPython method descriptors (python/src/hysteresis.cpp,
    # installed by asperity/__init__.py): their signature comes from __text_signature__,
    # and every misuse is a TypeError naming the method, as Python's own functions do.
    import inspect

    for name, first in (("forces", "x"), ("displacements", "Q")):
        sig = inspect.signature(getattr(asperity.Hysteresis, name))
        assert list(sig.parameters) == ["self", first, "out"]
        assert sig.parameters["self"].kind is inspect.Parameter.POSITIONAL_ONLY
        assert sig.parameters[first].kind is inspect.Parameter.POSITIONAL_OR_KEYWORD
        assert sig.parameters["out"].kind is inspect.Parameter.KEYWORD_ONLY
        assert sig.parameters["out"].default is None
    h = jenkins_with_reversals()
    x = history(16)
    ref = h.forces(x)
    # By position, by keyword, through the class, through a subclass: the same doubles.
    np.testing.assert_array_equal(h.forces(x=x), ref)
    np.testing.assert_array_equal(asperity.Hysteresis.forces(h, x), ref)

    class Tracked(asperity.Hysteresis):
        pass

    t = Tracked(asperity.JenkinsBackbone(2.0, 1.0))
    for v in (1.0, -0.25, 0.1):
        t.update(v)
    np.testing.assert_array_equal(t.forces(x), ref)
    # A keyword name built at run time is not the interned one (compared by identity
    # first): matched by value all the same.
    out_key = "".join(["o", "ut"])
    assert out_key is not sys.intern("out")
    buf = np.empty(16)
    assert h.forces(x, **{out_key: buf}) is buf
    np.testing.assert_array_equal(buf, ref)
    assert h.displacements(Q=0.5) == h.displacements(0.5)
    for call, message in [
        (lambda: h.forces(), r"forces\(\) missing required argument 'x'"),
        (lambda: h.forces(x, x), r"forces\(\) takes 1 positional argument \(x\) but 2 were given"),
        (lambda: h.forces(x, x=x), "unexpected or repeated keyword argument 'x'"),
        (lambda: h.displacements(0.1, Q=0.2), "unexpected or repeated keyword argument 'Q'"),
        (lambda: h.forces(x, outt=None), "unexpected or repeated keyword argument 'outt'"),
        (lambda: asperity.Hysteresis.forces(3, x), "doesn't apply to a 'int' object"),
        (lambda: asperity.Hysteresis.__new__(asperity.Hysteresis).forces(0.1),
         "not initialized"),
    ]:
        with pytest.raises(TypeError, match=message):
            call()
    # C++ errors arrive as the library's exceptions, with the library's message.
    with pytest.raises(asperity.InvalidInput, match="static limit|limit"):
        h.displacements(2.0)


def test_fast_entry_points_keep_references_and_refuse_none():
    import sys

    h = jenkins_with_reversals()
    x = history(8)
    out = np.empty(8)
    before = (sys.getrefcount(h), sys.getrefcount(x), sys.getrefcount(out))
    for _ in range(10000):
        assert h.forces(x, out=out) is out
        h.forces(x)
        with pytest.raises(asperity.InvalidInput):
            h.forces(x, out=np.empty(3))
    assert (sys.getrefcount(h), sys.getrefcount(x), sys.getrefcount(out)) == before
    for call in (lambda: h.forces(None), lambda: h.displacements(None)):
        with pytest.raises(TypeError, match="not None"):
            call()


def test_nanobind_methods_equal_the_fast_entry_points():
    # With ASPERITY_RAW_BINDINGS=1 (what the stub generator sees) forces/displacements are
    # nanobind's own methods: same along_history, so the same doubles and the same errors.
    import json
    import os
    import subprocess
    import sys

    script = (
        "import json, numpy as np, asperity\n"
        "h = asperity.Hysteresis(asperity.JenkinsBackbone(2.0, 1.0))\n"
        "[h.update(v) for v in (1.0, -0.25, 0.1)]\n"
        "x = np.cumsum(np.random.default_rng(3).normal(0.0, 0.15, 64)) % 1.2 - 0.6\n"
        "o = np.empty(64)\n"
        "r = {'kind': type(asperity.Hysteresis.__dict__['forces']).__name__,\n"
        "     'f': h.forces(x).tolist(), 'o': h.forces(x, out=o).tolist(),\n"
        "     'd': h.displacements(np.array([0.1, -0.3, 0.2])).tolist(), 's': h.forces(0.2)}\n"
        "try:\n"
        "    h.forces(x, out=np.empty(3))\n"
        "except asperity.InvalidInput as e:\n"
        "    r['e'] = str(e)\n"
        "print(json.dumps(r))\n")
    runs = {}
    for raw in ("1", ""):
        env = dict(os.environ, ASPERITY_RAW_BINDINGS=raw)
        p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                           env=env, timeout=120)
        assert p.returncode == 0, p.stderr
        runs[raw] = json.loads(p.stdout)
    assert runs["1"].pop("kind") == "nb_method"
    assert runs[""].pop("kind") == "method_descriptor"
    assert runs["1"] == runs[""]


def test_a_signal_handler_calling_forces_during_a_long_forces_call():
    # A long history runs on this thread's scratch state, with the GIL released in chunks
    # of 65536 points and Python's signal handlers run between them. A handler that calls
    # forces itself (a history turning at once, so it needs a state of its own) must get
    # a plain copy, not the scratch the long call is still using: both results equal
    # update() loops on replays. The timer fires every millisecond of wall time; the long
    # call is repeated until a handler ran inside it (each call takes tens of ms).
    h = rough_flat_with_reversals()
    long_x = np.tile(history(4096, seed=5), 600)  # 2.46e6 points
    short_x = np.array([h.x + 0.05, h.x - 0.1, h.x + 0.02, h.x - 0.3])  # turns at once
    replay = rough_flat_with_reversals()
    short_expected = np.array([replay.update(v) for v in short_x])
    nested = []
    in_long_call = [False]

    def handler(signum, frame):
        if in_long_call[0]:
            nested.append(h.forces(short_x))

    previous = signal.signal(signal.SIGALRM, handler)
    try:
        signal.setitimer(signal.ITIMER_REAL, 1e-3, 1e-3)
        for _ in range(20):
            in_long_call[0] = True
            long_q = h.forces(long_x)
            in_long_call[0] = False
            if nested:
                break
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0, 0.0)
        signal.signal(signal.SIGALRM, previous)
    assert nested, "no handler ran during a long call in 20 tries"
    for q in nested:
        np.testing.assert_array_equal(q, short_expected)
    # The long call against the same call without the timer, and its first 50000 points
    # against a replay (a Python loop over all 2.46e6 would take seconds).
    np.testing.assert_array_equal(long_q, h.forces(long_x))
    replay = rough_flat_with_reversals()
    np.testing.assert_array_equal(long_q[:50000],
                                  np.array([replay.update(v) for v in long_x[:50000]]))
