"""Issue 13, Python: long calls release the GIL (threads get the same results as one
thread) and stop on Ctrl-C (SIGINT) with KeyboardInterrupt instead of running on.

No timing is asserted beyond generous bounds on how long an interrupted call may go on
(the uninterrupted calls take minutes)."""
import os
import signal
import subprocess
import sys
import textwrap
from concurrent.futures import ThreadPoolExecutor

import numpy as np

import asperity


def test_vectorized_calls_from_threads_equal_the_serial_results():
    flat = asperity.RoughFlat("bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
    chunks = [np.linspace(-1.0 + 0.1 * i, 3.0, 3_000 + 17 * i) for i in range(6)]
    serial = [flat.normal_load_star(d) for d in chunks]
    law = [asperity.normal_load_star("ke", np.linspace(0.0, 200.0, 50_000) + i, 0.3)
           for i in range(8)]
    with ThreadPoolExecutor(max_workers=4) as pool:
        threaded = list(pool.map(flat.normal_load_star, chunks))
        threaded_law = list(pool.map(
            lambda i: asperity.normal_load_star("ke", np.linspace(0.0, 200.0, 50_000) + i, 0.3),
            range(8)))
    for a, b in zip(serial, threaded):
        np.testing.assert_array_equal(a, b)  # same code, same inputs: bit for bit
    for a, b in zip(law, threaded_law):
        np.testing.assert_array_equal(a, b)


def test_hysteresis_forces_from_threads_equal_the_serial_results():
    flat = asperity.RoughFlat("bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
    h = asperity.Hysteresis(flat.backbone(flat.separation_star(1e-3)))
    x = [0.6 * np.sin(np.linspace(0, (6 + i) * np.pi, 100_000)) for i in range(6)]
    serial = [h.forces(xi) for xi in x]
    with ThreadPoolExecutor(max_workers=3) as pool:
        threaded = list(pool.map(h.forces, x))
    for a, b in zip(serial, threaded):
        np.testing.assert_array_equal(a, b)


def interrupted(body: str):
    """Runs `body` (after printing 'ready') in a child Python, sends SIGINT one second
    after 'ready', and returns (exit code, stderr)."""
    script = "import sys, numpy as np, asperity\n" + textwrap.dedent(body)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    # SIGINT at its default disposition in the child, as in a terminal: a runner that starts
    # the tests in the background (`cmd &` in a non-interactive shell) leaves it ignored, and
    # Python then keeps it ignored (measured: these tests then time out).
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
                         stderr=subprocess.PIPE, text=True, env=env)
    try:
        assert p.stdout.readline().strip() == "ready", p.stderr.read()
        try:
            p.wait(timeout=1.0)  # still running: it is inside the long call
        except subprocess.TimeoutExpired:
            pass
        assert p.poll() is None, "the call ended before the signal: it is not long enough"
        p.send_signal(signal.SIGINT)
        # Uninterrupted, each call runs for minutes; interrupted, it ends within one chunk
        # (16384 points) or one 50 ms check. 30 s is a bound for a loaded machine.
        rc = p.wait(timeout=30)
        return rc, p.stderr.read()
    finally:
        if p.poll() is None:
            p.kill()
            p.wait()


def test_ctrl_c_stops_a_long_vectorized_call():
    # 5e6 points of the Greenwood-Williamson integral: about 95 s before this fix.
    rc, err = interrupted("""
        flat = asperity.RoughFlat("bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
        d = np.linspace(-1.0, 3.0, 5_000_000)
        print("ready", flush=True)
        flat.normal_load_star(d)
        print("finished", flush=True)
    """)
    assert rc != 0 and "KeyboardInterrupt" in err, err


def test_ctrl_c_stops_a_long_simulation():
    rc, err = interrupted("""
        print("ready", flush=True)
        asperity.simulate(asperity.HarmonicExcitation(frequency=1.0, amplitude=1.0),
                          asperity.Dankowicz(F_max=1.5, delta=0.011), epsilon=0.032,
                          duration=1e9, output_interval=1e6)
    """)
    assert rc != 0 and "KeyboardInterrupt" in err, err

