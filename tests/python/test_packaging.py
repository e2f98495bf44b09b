"""The package as a user meets it: signatures readable by `inspect`, type stubs, one version
everywhere, a clear message when the `plot` extra is missing, and the `asperity` command
installed next to the interpreter by `pip install .`."""
import inspect
import os
import pathlib
import re
import subprocess
import sys
import textwrap

import pytest

import asperity
import asperity.plotting
import asperity.thesis
from asperity import _core

ROOT = pathlib.Path(__file__).resolve().parents[2]
PACKAGE = pathlib.Path(asperity.__file__).resolve().parent


def _nb_parameter_names(fn, drop_first=False):
    """Parameter names as nanobind prints them in __nb_signature__ (the stub's source)."""
    text = fn.__nb_signature__[0][0]
    inside = text[text.index("(") + 1:text.rindex(") ->") if ") ->" in text else text.rindex(")")]
    names, depth, current = [], 0, ""
    for c in inside + ",":
        if c in "([{":
            depth += 1
        elif c in ")]}":
            depth -= 1
        if c == "," and depth == 0:
            name = current.split(":")[0].split("=")[0].strip().lstrip("*")
            if name and name not in ("/", ""):
                names.append(name)
            current = ""
        else:
            current += c
    return names[1:] if drop_first else names


def _public_compiled_functions():
    for name in dir(_core):
        if not name.startswith("_") and type(getattr(_core, name)).__name__ == "nb_func":
            yield f"asperity.{name}", getattr(asperity, name), getattr(_core, name)
    for name in dir(_core.mindlin):
        if not name.startswith("_") and type(getattr(_core.mindlin, name)).__name__ == "nb_func":
            yield (f"asperity.mindlin.{name}", getattr(asperity.mindlin, name),
                   getattr(_core.mindlin, name))


def test_inspect_signature_on_every_public_function():
    checked = 0
    for qualname, public, compiled in _public_compiled_functions():
        sig = inspect.signature(public)
        names = [p for p in sig.parameters if p not in ("args", "kwargs")] or []
        assert names == _nb_parameter_names(compiled), qualname
        assert public.__doc__ == compiled.__doc__, qualname
        checked += 1
    assert checked >= 50  # 51 functions and 10 of asperity.mindlin when written


def _public_compiled_methods():
    """(qualified name, class, attribute name, the nanobind callable) of every public method
    and static method defined by a class of asperity._core."""
    for cname in dir(_core):
        cls = getattr(_core, cname)
        if cname.startswith("_") or not isinstance(cls, type):
            continue
        for name, value in vars(cls).items():
            if name.startswith("_"):
                continue
            raw = inspect.unwrap(value.__func__ if isinstance(value, staticmethod) else value)
            if type(raw).__name__ in ("nb_method", "nb_func"):
                yield f"asperity.{cname}.{name}", cls, name, raw


def test_inspect_signature_on_every_public_method():
    checked = 0
    for qualname, cls, name, raw in _public_compiled_methods():
        if len(raw.__nb_signature__) != 1:
            continue  # overloads: no single signature exists (none today)
        on_class = getattr(cls, name)
        sig = inspect.signature(on_class)
        assert list(sig.parameters) == _nb_parameter_names(raw), qualname
        assert on_class.__doc__ == raw.__doc__ and on_class.__name__ == name, qualname
        assert on_class.__qualname__ == f"{cls.__name__}.{name}", qualname
        checked += 1
    assert checked >= 55  # 61 methods and static methods when written


def test_wrapped_methods_bind_and_call_as_the_compiled_ones():
    flat = asperity.RoughFlat(model="bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)
    h = asperity.Hysteresis(flat.backbone(flat.separation_star(1e-3)))
    h.update(0.5)
    raw = asperity.Hysteresis.force.__wrapped__
    # Bound method: self dropped from the signature, results equal to the compiled call by
    # position, by keyword and through the class.
    assert list(inspect.signature(h.force).parameters) == ["x"]
    assert h.force(0.2) == raw(h, 0.2) == h.force(x=0.2) == asperity.Hysteresis.force(h, 0.2)
    with pytest.raises(TypeError, match="incompatible function arguments"):
        h.force()
    # A static method does not bind: called through an instance it gets no self.
    pair = asperity.ContactPair.combine(asperity.Material(E=200e9, nu=0.3, H=2e9),
                                        asperity.Material(E=200e9, nu=0.3, H=2e9), 1e-3)
    assert list(inspect.signature(asperity.ContactPair.combine).parameters)[:2] == ["body1",
                                                                                   "body2"]
    assert pair.combine(asperity.Material(E=200e9, nu=0.3, H=2e9),
                        asperity.Material(E=200e9, nu=0.3, H=2e9), 1e-3).R == pair.R
    # Errors pass through unchanged.
    with pytest.raises(asperity.InvalidInput):
        asperity.Hysteresis(asperity.JenkinsBackbone(1.0, 1.0)).displacements(2.0)


def _compiled_constructors():
    """(class name, class, nanobind __init__) of every public class of asperity._core that
    defines a constructor with one overload."""
    for cname in dir(_core):
        cls = getattr(_core, cname)
        if cname.startswith("_") or not isinstance(cls, type):
            continue
        init = inspect.unwrap(cls.__dict__.get("__init__", None) or (lambda: None))
        if type(init).__name__ == "nb_method" and len(init.__nb_signature__) == 1:
            yield cname, cls, init


def test_inspect_signature_on_every_constructor():
    """inspect.signature(Class.__init__) (issue 21: "no signature found for builtin nb_method"
    in the installed package) and inspect.signature(Class), for every class with one
    constructor."""
    checked = 0
    for cname, cls, raw in _compiled_constructors():
        names = _nb_parameter_names(raw)
        assert names[0] == "self", cname
        assert list(inspect.signature(cls.__init__).parameters) == names, cname
        assert list(inspect.signature(cls).parameters) == names[1:], cname
        assert cls.__init__.__qualname__ == f"{cname}.__init__", cname
        checked += 1
    # 23 classes when written; SpectralMoments has two constructors, so no single signature.
    assert checked >= 20
    # Constructing still goes through nanobind's own constructor; a Python subclass's
    # super().__init__ through the wrapper: both give the same object state.
    flat = asperity.RoughFlat(model="bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)

    class Sub(asperity.RoughFlat):
        def __init__(self):
            super().__init__(model="bke", beta=0.04, psi=0.5, nu=0.3, G_over_E=0.7 / 3.4)

    assert Sub().separation_star(1e-3) == flat.separation_star(1e-3)


def test_signature_details_match_the_binding():
    sig = inspect.signature(asperity.simulate)
    assert sig.parameters["epsilon"].kind is inspect.Parameter.KEYWORD_ONLY
    assert sig.parameters["epsilon"].default == 0.032  # Table 7.2's epsilon, the binding's default
    assert sig.parameters["friction"].default is None
    sig = inspect.signature(asperity.RoughFlat)
    assert list(sig.parameters)[:5] == ["model", "beta", "psi", "nu", "G_over_E"]
    assert sig.parameters["slip_scaling"].default == "elastic"
    # The wrapper calls the compiled function: same results, same errors.
    assert asperity.hardness_factor(0.3) == _core.hardness_factor(0.3)
    with pytest.raises(asperity.InvalidInput, match="torque"):
        asperity.bolt_preload(-1.0, diameter=2.9e-3)


def test_python_helpers_have_signatures():
    for fn in (asperity.joints.plot_loops, asperity.dynamics.run_case,
               asperity.plotting.plot_loop, asperity.thesis_normalization):
        assert inspect.signature(fn).parameters


def test_type_stubs_and_marker_ship_with_the_package():
    assert (PACKAGE / "py.typed").is_file()
    stub = (PACKAGE / "_core" / "__init__.pyi").read_text()
    assert "def simulate(excitation:" in stub and "class RoughFlat:" in stub
    mindlin = (PACKAGE / "_core" / "mindlin.pyi").read_text()
    assert "def loading_force_tilde(" in mindlin


def test_one_version_everywhere():
    cmake = (ROOT / "CMakeLists.txt").read_text()
    assert re.search(r"project\(asperity VERSION (\S+)", cmake).group(1) == asperity.__version__
    info = asperity.version_info()
    assert info["version"] == asperity.__version__
    assert info["git_revision"] and info["build_type"]


def test_plotting_without_matplotlib_names_the_extra():
    # A fresh interpreter in which `import matplotlib` fails as it does when it is absent.
    code = textwrap.dedent("""
        import sys
        sys.modules["matplotlib"] = None
        sys.modules["matplotlib.pyplot"] = None
        import asperity, asperity.plotting, asperity.thesis
        pair = asperity.thesis.micro_pair()
        model = asperity.PartialSlipModel.from_load(pair, "ke", 35.0, asperity.thesis.micro_params())
        try:
            asperity.plotting.plot_loop(model.loop(1.5e-6))
        except ModuleNotFoundError as e:
            print("ERROR:", e, "| name:", e.name)
    """)
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                       env={**os.environ}, timeout=120)
    assert r.returncode == 0, r.stderr
    assert "asperity[plot]" in r.stdout and "name: matplotlib" in r.stdout, r.stdout


def test_the_command_comes_with_the_package():
    """Installed (site-packages): pip put the `asperity` command next to the interpreter (a
    wheel's scripts go to the environment's bin/). From a build tree (ctest's PYTHONPATH):
    the CLI of the same build, ASPERITY_CLI. Either way it is this build's version."""
    if "site-packages" in PACKAGE.parts:
        exe = pathlib.Path(sys.executable).parent / "asperity"
        assert exe.is_file(), f"pip install . gave no {exe}"
    else:
        assert os.environ.get("ASPERITY_CLI"), "ASPERITY_CLI is not set for a build-tree run"
        exe = pathlib.Path(os.environ["ASPERITY_CLI"])
    r = subprocess.run([str(exe), "--version"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    info = asperity.version_info()
    assert r.stdout.strip() == (f"asperity {info['version']} (git {info['git_revision']}, "
                                f"{info['build_type']})")


# The C and C++ runtimes a wheel takes from the system (glibc's libraries, libstdc++,
# libgcc_s: manylinux's list); everything else the module and the command load comes with
# the wheel (python/CMakeLists.txt, "A self-contained wheel").
SYSTEM_RUNTIME = re.compile(r"^(linux-vdso|ld-linux|libc\.so|libm\.so|libmvec\.so|"
                            r"libpthread\.so|libdl\.so|librt\.so|libresolv\.so|libutil\.so|"
                            r"libstdc\+\+\.so|libgcc_s\.so)")


def _loaded_libraries(path):
    """{soname: resolved path or None} of every library the loader maps for `path` (ldd)."""
    r = subprocess.run(["ldd", str(path)], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0, r.stderr
    found = {}
    for line in r.stdout.splitlines():
        m = re.match(r"\s*(\S+)\s+=>\s+(not found|\S+)", line)
        if m:
            found[m.group(1)] = None if m.group(2) == "not found" else pathlib.Path(m.group(2))
    return found


def test_the_wheel_carries_its_libraries():
    """Installed (site-packages): the module and the `asperity` command load every library but
    the C and C++ runtimes from the wheel's asperity.libs, so the package runs on a machine
    without fmt, libzip, pugixml, toml++ or matio. From a build tree: every library the module
    and the command need is found."""
    module = pathlib.Path(_core.__file__)
    if "site-packages" in PACKAGE.parts:
        command = pathlib.Path(sys.executable).parent / "asperity"
        bundle = PACKAGE.parent / "asperity.libs"
        assert bundle.is_dir(), f"the wheel has no {bundle}"
        shipped = {p.name for p in bundle.iterdir()}
        for name in ["libfmt.so.9", "libzip.so.4", "libpugixml.so.1", "libmatio.so.11"]:
            assert name in shipped, f"{name} not in {sorted(shipped)}"
    else:
        assert os.environ.get("ASPERITY_CLI"), "ASPERITY_CLI is not set for a build-tree run"
        command, bundle = pathlib.Path(os.environ["ASPERITY_CLI"]), None
    for binary in (module, command):
        libraries = _loaded_libraries(binary)
        assert "libfmt.so.9" in libraries, f"{binary}: {libraries}"
        for name, where in libraries.items():
            assert where is not None, f"{binary}: {name} not found"
            if bundle is not None and not SYSTEM_RUNTIME.match(name):
                assert where.resolve().parent == bundle.resolve(), (
                    f"{binary}: {name} from {where}, not {bundle}")


def test_wrapped_callables_pickle_copy_and_show_as_python_functions_do():
    import copy
    import pickle

    for fn in (asperity.bolt_preload, asperity.mindlin.loading_force_tilde,
               asperity.Hysteresis.force, asperity.ContactPair.combine):
        assert type(fn).__name__ in ("signed_function", "signed_method"), fn
        # By reference, as Python pickles its own functions: the same object comes back.
        assert pickle.loads(pickle.dumps(fn)) is fn
        assert copy.copy(fn) is fn and copy.deepcopy(fn) is fn
        assert vars(fn)["__signature__"] == inspect.signature(fn)
    assert repr(asperity.bolt_preload) == "<compiled function bolt_preload>"
    assert repr(asperity.Hysteresis.force) == "<compiled method Hysteresis.force>"
    # A bad __qualname__ written by a user is not read as text (falls back to the target).
    f = asperity.hardness_factor
    saved = f.__qualname__
    try:
        f.__qualname__ = 5
        assert repr(f) == repr(f.__wrapped__)
        with pytest.raises(TypeError, match="__qualname__"):
            pickle.dumps(f)
    finally:
        f.__qualname__ = saved
    # The forwarders are not constructible from Python.
    with pytest.raises(TypeError):
        type(f)()


def test_forwarders_leak_no_references():
    import sys

    h = asperity.Hysteresis(asperity.JenkinsBackbone(2.0, 1.0))
    x = 0.25
    before = (sys.getrefcount(h), sys.getrefcount(x), sys.getrefcount(asperity.Hysteresis.force))
    for _ in range(10000):
        h.force(x)
        asperity.Hysteresis.force(h, x)
        asperity.hardness_factor(0.3)
    after = (sys.getrefcount(h), sys.getrefcount(x), sys.getrefcount(asperity.Hysteresis.force))
    assert after == before
