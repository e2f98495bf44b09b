"""What a sweep varies: key paths into a case file, grids and distributions, the design.

A *key path* addresses any value of a case file the way the case-file errors name it:
dotted table names, ``[i]`` (1-based) for an element of an array or array of tables,
``[*]`` for every element at once: ``load.bolts.nut_factor``,
``joint.half[1].roughness.sigma``, ``joint.half[*].material.H``,
``load.bolts.total_torques[2]``.

A *variation* is one of

* a grid: ``"200 N .. 800 N, 25 steps"`` (``, log`` for geometric spacing) or a TOML
  array of values (``["234 N", "526 N"]``);
* ``uniform(LOW, HIGH)``, ``normal(MEAN, SD)`` with SD absolute (same unit as MEAN) or
  relative (``10 %``), ``choice(A, B, ...)``: values, or names of ``[choices.KEY.NAME]``
  tables of key paths and values applied together (``roughness ~ choice(before, after)``).

Everything is checked against the case before any sample runs (:func:`Sweep.check`):
unknown key paths, a unit whose dimension is not the key's, parameters outside a
distribution's domain (LOW >= HIGH, SD <= 0) and values the case parser refuses at the
distribution's extremes (LOW and HIGH, MEAN +- 3 SD, every grid value and choice) are
refused with the key named (:class:`SweepError`, an ``asperity.InvalidInput``).
"""
from __future__ import annotations

import copy
import dataclasses
import math
import os
import re
import stat
import tomllib
from typing import Any, Iterator

import numpy as np

from .. import _core

# Design rows are generated in blocks of this many samples, each from its own seed
# (random) or by position (Sobol): the draws depend only on the seed, never on how the
# samples are distributed.
DESIGN_BLOCK = 4096
# Unit-interval draws are kept within [2^-54, 1 - 2^-53] before the inverse normal CDF,
# i.e. normal draws lie within about 8.3 standard deviations (a draw of exactly 0 would
# map to -inf).
_U_LOW, _U_HIGH = 2.0**-54, 1.0 - 2.0**-53
# A normal distribution is checked against the case at MEAN +- this many SD.
NORMAL_CHECK_SD = 3.0

METHODS = ("random", "sobol", "lhs")
# Most samples of one sweep (grid points times draws): 1e7 rows of results are ~1 GB of
# memory in the summary and its statistics; a grid of 1e9 steps died with a MemoryError at
# 8 GiB, and --samples 1e12 ran on without a word. More is a typing slip, refused before work.
MAX_SAMPLES = 10_000_000


class SweepError(_core.InvalidInput):
    """A sweep refused before any work: the message names the key, its value and what is
    allowed."""


# --------------------------------------------------------------------------- key paths

_SEGMENT = re.compile(r"^([A-Za-z_][A-Za-z0-9_-]*)((?:\[(?:\d+|\*)\])*)$")


def parse_path(path: str) -> list:
    """``"joint.half[1].material.H"`` -> ``["joint", "half", 0, "material", "H"]``
    (``"*"`` for ``[*]``; indexes 0-based inside)."""
    if not isinstance(path, str) or not path.strip():
        raise SweepError(f"key path {path!r}: empty; write e.g. load.bolts.nut_factor")
    out: list = []
    for seg in path.strip().split("."):
        m = _SEGMENT.match(seg)
        if not m:
            raise SweepError(f"key path {path!r}: segment {seg!r} is not NAME, NAME[i] (1-based) "
                             "or NAME[*]")
        out.append(m.group(1))
        for idx in re.findall(r"\[(\d+|\*)\]", m.group(2)):
            if idx == "*":
                out.append("*")
            else:
                if int(idx) < 1:
                    raise SweepError(f"key path {path!r}: index [{idx}] must be >= 1 (1-based)")
                out.append(int(idx) - 1)
    return out


def _format_path(parts: list) -> str:
    s = ""
    for p in parts:
        if isinstance(p, int):
            s += f"[{p + 1}]"
        elif p == "*":
            s += "[*]"
        else:
            s += ("." if s else "") + p
    return s


def _describe(node) -> str:
    if isinstance(node, dict):
        return "keys: " + ", ".join(sorted(node)) if node else "an empty table"
    if isinstance(node, list):
        return f"an array of {len(node)} elements ([1]..[{len(node)}] or [*])"
    return f"the value {node!r}"


def expand(case: dict, path: str) -> list[list]:
    """The concrete locations (lists of keys/indexes) a path addresses in ``case``;
    ``[*]`` expands to every element. Raises SweepError naming the path when a segment
    does not exist."""
    parts = parse_path(path)
    locs: list[list] = [[]]
    for i, seg in enumerate(parts):
        nxt = []
        for loc in locs:
            node = get(case, loc)
            here = _format_path(loc) or "the case file"
            if isinstance(seg, str) and seg != "*":
                if not isinstance(node, dict) or seg not in node:
                    raise SweepError(
                        f"{path}: unknown key path: {here} has no key {seg!r} ({_describe(node)}); "
                        "to vary an optional key, give it a value in the case file or under "
                        "[set] first")
                nxt.append(loc + [seg])
            else:
                if not isinstance(node, list):
                    raise SweepError(f"{path}: unknown key path: {here} is not an array "
                                     f"({_describe(node)})")
                if seg == "*":
                    nxt.extend(loc + [k] for k in range(len(node)))
                elif seg >= len(node):
                    raise SweepError(f"{path}: unknown key path: {here} has {len(node)} "
                                     f"elements, so [{seg + 1}] does not exist")
                else:
                    nxt.append(loc + [seg])
        locs = nxt
    return locs


def get(case, loc):
    node = case
    for k in loc:
        node = node[k]
    return node


def put(case, loc, value):
    node = get(case, loc[:-1])
    node[loc[-1]] = value


# --------------------------------------------------------------------------- values

@dataclasses.dataclass(frozen=True)
class KeyKind:
    """What a key takes: ``quantity`` (with ``dimension``), ``number`` (dimensionless
    float), ``integer``, ``boolean``, ``word`` (a string that is not a quantity), or
    ``other`` (a table or array: only choice() of [choices] tables varies it)."""

    kind: str
    dimension: Any = None  # asperity.Dimension for quantities

    def describe(self) -> str:
        if self.kind == "quantity":
            return _core.dimension_name(self.dimension)
        return {"number": "a dimensionless number (no unit)", "integer": "an integer",
                "boolean": "true or false", "word": "a word (string)",
                "other": "a table or array"}[self.kind]


def kind_of(value) -> KeyKind:
    if isinstance(value, bool):
        return KeyKind("boolean")
    if isinstance(value, int):
        return KeyKind("integer")
    if isinstance(value, float):
        return KeyKind("number")
    if isinstance(value, str):
        try:
            q = _core.parse_quantity(value)
        except _core.InvalidInput:
            return KeyKind("word")
        return KeyKind("quantity", q.dimension)
    return KeyKind("other")


_NUMBER = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


@dataclasses.dataclass(frozen=True)
class Value:
    """One value as written into a case (``toml``: float, int, bool or str) and its
    coordinate (SI float for quantities and numbers, the text for words)."""

    toml: Any
    coord: Any


def _as_quantity(text: str, key: str, what: str):
    """(value_si, unit_text, dimension or None for a bare number)."""
    text = text.strip()
    if _NUMBER.match(text):
        return float(text), "", None
    m = re.match(r"^([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*(.+)$", text)
    q = _core.parse_quantity(text, f"{key} ({what})")
    unit = m.group(2).strip() if m else ""
    return q.value, unit, q.dimension


def _unit_scale(unit: str) -> float:
    return _core.parse_quantity(f"1 {unit}").value if unit else 1.0


def value_for(kind: KeyKind, x_si: float, unit: str, key: str) -> Value:
    """The case-file value for a number drawn in SI (written in the unit the user used)."""
    if kind.kind == "quantity":
        text = f"{x_si / _unit_scale(unit)!r} {unit}" if unit else f"{x_si!r}"
        return Value(text, _core.parse_quantity(text, key).value)
    if kind.kind == "integer":
        if x_si != round(x_si):
            raise SweepError(f"{key} = {x_si!r}: {key} takes an integer")
        return Value(int(round(x_si)), int(round(x_si)))
    return Value(float(x_si), float(x_si))


def literal(text, kind: KeyKind, key: str) -> Value:
    """A value of a grid array or choice() (text or TOML value) checked against the key."""
    if isinstance(text, bool) or kind.kind == "boolean":
        if isinstance(text, bool):
            return Value(text, text)
        if str(text).strip() in ("true", "false"):
            return Value(str(text).strip() == "true", str(text).strip() == "true")
        raise SweepError(f"{key} = {text!r}: {key} takes true or false")
    if kind.kind == "word":
        if not isinstance(text, str):
            raise SweepError(f"{key} = {text!r}: {key} takes a word (string)")
        return Value(text.strip(), text.strip())
    if kind.kind == "other":
        raise SweepError(f"{key}: is a table or array; vary one of its keys, or use "
                         "choice() of [choices] tables")
    if isinstance(text, (int, float)):
        x, unit, dim = float(text), "", None
    else:
        x, unit, dim = _as_quantity(str(text), key, "value")
    check_unit(kind, dim, key, str(text))
    if kind.kind == "quantity":  # written as the user typed it
        return Value(str(text).strip(), _core.parse_quantity(str(text), key).value)
    return value_for(kind, x, unit, key)


def check_unit(kind: KeyKind, dim, key: str, text: str):
    if kind.kind == "quantity":
        if dim is None:
            raise SweepError(f"{key} = {text}: a bare number; {key} is a quantity of "
                             f"{kind.describe()}: give the unit")
        if not dim == kind.dimension:
            raise SweepError(f"{key} = {text}: has the units of {_core.dimension_name(dim)}, "
                             f"but {key} is {kind.describe()}")
    elif kind.kind in ("number", "integer"):
        if dim is not None:
            raise SweepError(f"{key} = {text}: {key} is dimensionless and takes no unit")
    else:
        raise SweepError(f"{key} = {text}: {key} takes {kind.describe()}")


# --------------------------------------------------------------------------- variations

def _split_args(inner: str) -> list[str]:
    return [a.strip() for a in inner.split(",")] if inner.strip() else []


@dataclasses.dataclass
class Variation:
    """One varied key: ``grid`` (values), ``uniform``, ``normal`` or ``choice``."""

    key: str
    text: str
    form: str
    values: list = dataclasses.field(default_factory=list)  # grid and choice: list[Value]
    params: tuple = ()  # uniform (low, high), normal (mean, sd): SI
    unit: str = ""
    kind: KeyKind | None = None
    locations: list = dataclasses.field(default_factory=list)
    choice_tables: dict | None = None  # name -> {path: value} (choice of [choices] tables)

    @property
    def drawn(self) -> bool:
        return self.form != "grid"

    def at(self, u: float) -> Value:
        """The value at unit-interval coordinate u (inverse CDF)."""
        if self.form == "uniform":
            lo, hi = self.params
            return value_for(self.kind, lo + u * (hi - lo), self.unit, self.key)
        if self.form == "normal":
            from scipy.special import ndtri

            mean, sd = self.params
            return value_for(self.kind, mean + sd * float(ndtri(u)), self.unit, self.key)
        if self.form == "choice":
            return self.values[min(int(u * len(self.values)), len(self.values) - 1)]
        raise AssertionError(self.form)

    def extremes(self) -> list[Value]:
        """The values checked against the case before any work."""
        if self.form == "uniform":
            lo, hi = self.params
            return [value_for(self.kind, lo, self.unit, self.key),
                    value_for(self.kind, hi, self.unit, self.key)]
        if self.form == "normal":
            mean, sd = self.params
            return [value_for(self.kind, mean + s * NORMAL_CHECK_SD * sd, self.unit, self.key)
                    for s in (-1.0, 1.0)]
        return list(self.values)


_FORM = re.compile(r"^\s*(uniform|normal|choice)\s*\((.*)\)\s*$", re.S)
_GRID = re.compile(r"^\s*(.+?)\s*\.\.\s*(.+?)\s*,\s*(\d+)\s*steps?\s*(,\s*(log|linear)\s*)?$")


def parse_variation(key: str, spec, case: dict, choices: dict | None = None) -> Variation:
    """Parses and checks one variation of ``key`` against ``case`` (see module doc)."""
    if isinstance(spec, str) and spec.strip().startswith("~"):
        spec = spec.strip()[1:]
    if isinstance(spec, list):
        form, text = "grid", repr(spec)
    elif isinstance(spec, str):
        text = spec.strip()
        m = _FORM.match(text)
        form = m.group(1) if m else ("grid" if _GRID.match(text) else None)
        if form is None:
            raise SweepError(
                f"{key} = {text!r}: not a variation; write a grid \"LOW .. HIGH, N steps\" or "
                "[values], or uniform(LOW, HIGH), normal(MEAN, SD or N %), choice(A, B, ...)")
    else:
        raise SweepError(f"{key} = {spec!r}: not a variation (a string or an array of values)")

    choice_tables = (choices or {}).get(key)
    if choice_tables is not None:
        if form != "choice":
            raise SweepError(f"{key}: has [choices.{key}] tables, so it takes choice(NAME, ...)")
        names = _split_args(_FORM.match(text).group(2))
        if not names:
            raise SweepError(f"{key} = {text}: choice() needs at least one option")
        for n in names:
            if n not in choice_tables:
                raise SweepError(f"{key} = {text}: option {n!r} has no [choices.{key}.{n}] "
                                 f"table (there are: {', '.join(sorted(choice_tables))})")
        v = Variation(key, text, "choice", values=[Value(n, n) for n in names],
                      kind=KeyKind("word"), choice_tables={})
        for n in names:
            overrides = {}
            for p, val in choice_tables[n].items():
                kind = _kind_at(case, p)
                lit = literal(val, kind, p) if kind.kind != "other" else Value(val, None)
                overrides[p] = lit.toml
            v.choice_tables[n] = overrides
        return v

    locations = expand(case, key)
    kinds = {(k.kind, str(k.dimension)) for k in (kind_of(get(case, loc)) for loc in locations)}
    kind = _kind_at(case, key)
    if len(kinds) != 1:
        raise SweepError(f"{key}: the elements it addresses take different kinds of value")
    v = Variation(key, text, form, kind=kind, locations=locations)

    if form == "grid":
        if isinstance(spec, list):
            if not spec:
                raise SweepError(f"{key} = []: a grid needs at least one value")
            v.values = [literal(x, kind, key) for x in spec]
        else:
            g = _GRID.match(text)
            lo, u_lo, d_lo = _as_quantity(g.group(1), key, "grid start")
            hi, u_hi, d_hi = _as_quantity(g.group(2), key, "grid end")
            check_unit(kind, d_lo, key, g.group(1))
            check_unit(kind, d_hi, key, g.group(2))
            n = int(g.group(3))
            log = g.group(5) == "log"
            if n > MAX_SAMPLES:
                raise SweepError(f"{key} = {text}: {n} steps is above the limit of "
                                 f"{MAX_SAMPLES:,} samples of a sweep")
            if n < 1 or (n == 1 and lo != hi):
                raise SweepError(f"{key} = {text}: {n} steps; a grid from LOW to HIGH needs "
                                 ">= 2 steps (1 only when LOW = HIGH)")
            if log and (lo <= 0 or hi <= 0):
                raise SweepError(f"{key} = {text}: a log grid needs LOW > 0 and HIGH > 0")
            xs = np.geomspace(lo, hi, n) if log else np.linspace(lo, hi, n)
            v.unit = u_lo
            v.values = [value_for(kind, float(x), u_lo, key) for x in xs]
        return v

    args = _split_args(_FORM.match(text).group(2))
    if form == "choice":
        if not args:
            raise SweepError(f"{key} = {text}: choice() needs at least one option")
        v.values = [literal(a, kind, key) for a in args]
        return v
    if kind.kind not in ("quantity", "number"):
        raise SweepError(f"{key} = {text}: {form}() draws real numbers, but {key} takes "
                         f"{kind.describe()}; use a grid or choice()")
    if len(args) != 2:
        raise SweepError(f"{key} = {text}: {form}() takes two parameters, got {len(args)}")
    a, unit, dim_a = _as_quantity(args[0], key, f"{form} parameter 1")
    check_unit(kind, dim_a, key, args[0])
    v.unit = unit
    if form == "uniform":
        b, _, dim_b = _as_quantity(args[1], key, "uniform parameter 2")
        check_unit(kind, dim_b, key, args[1])
        if not (math.isfinite(a) and math.isfinite(b) and a < b):
            raise SweepError(f"{key} = {text}: uniform(LOW, HIGH) needs finite LOW < HIGH")
        v.params = (a, b)
    else:
        pct = re.match(r"^([+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)\s*%$", args[1])
        if pct:
            sd = float(pct.group(1)) / 100.0 * abs(a)
        else:
            sd, _, dim_b = _as_quantity(args[1], key, "normal standard deviation")
            check_unit(kind, dim_b, key, args[1])
        if not (math.isfinite(a) and math.isfinite(sd) and sd > 0):
            raise SweepError(f"{key} = {text}: normal(MEAN, SD) needs a finite MEAN and SD > 0 "
                             "(absolute, in the unit of MEAN, or relative: N %)")
        v.params = (a, sd)
    return v


def _kind_at(case: dict, key: str) -> KeyKind:
    kinds = [kind_of(get(case, loc)) for loc in expand(case, key)]
    if not kinds:
        raise SweepError(f"{key}: addresses no value (an empty array)")
    return kinds[0]


# --------------------------------------------------------------------------- TOML out

def _toml_string(v: str) -> str:
    """A TOML basic string (toml.io v1.0.0, "String"): backslash, quote and every control
    character escaped (\\b \\t \\n \\f \\r by name, the others as \\u and four hex digits)."""
    named = {"\\": "\\\\", '"': '\\"', "\b": "\\b", "\t": "\\t", "\n": "\\n",
             "\f": "\\f", "\r": "\\r"}
    out = []
    for ch in v:
        if ch in named:
            out.append(named[ch])
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _toml_key(k: str) -> str:
    return k if re.match(r"^[A-Za-z0-9_-]+$", k) else _toml_string(k)


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise SweepError(f"value {v!r}: not finite")
        return repr(v)
    if isinstance(v, str):
        return _toml_string(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_toml_key(k)} = {_toml_value(x)}" for k, x in v.items()) + " }"
    raise SweepError(f"value {v!r}: cannot be written to a case file")


def to_toml(case: dict) -> str:
    """A case dict (as tomllib reads it) back to TOML text: tables as [headers], arrays of
    tables as [[headers]], everything else inline."""
    lines: list[str] = []

    def table(d: dict, prefix: str):
        subs = []
        for k, v in d.items():
            if isinstance(v, dict):
                subs.append(("t", k, v))
            elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
                subs.append(("a", k, v))
            else:
                lines.append(f"{_toml_key(k)} = {_toml_value(v)}")
        for what, k, v in subs:
            name = f"{prefix}.{_toml_key(k)}" if prefix else _toml_key(k)
            if what == "t":
                lines.append(f"[{name}]")
                table(v, name)
            else:
                for el in v:
                    lines.append(f"[[{name}]]")
                    table(el, name)

    table(case, "")
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- the sweep

@dataclasses.dataclass
class Sweep:
    """A case and what varies. ``case`` is the parsed case file after ``set``/``unset``;
    ``base_dir`` resolves its relative paths (profile scans)."""

    case: dict
    base_dir: str
    variations: list[Variation]
    samples: int = 1
    seed: int = 0
    method: str = "random"
    case_path: str = "<case>"
    kind: str = "joint"

    @property
    def grid(self) -> list[Variation]:
        return [v for v in self.variations if not v.drawn]

    @property
    def drawn(self) -> list[Variation]:
        return [v for v in self.variations if v.drawn]

    @property
    def grid_points(self) -> int:
        return int(np.prod([len(v.values) for v in self.grid])) if self.grid else 1

    @property
    def size(self) -> int:
        """Samples in all: every grid point times ``samples`` draws (the same draws at
        every grid point: common random numbers)."""
        return self.grid_points * self.samples

    def assignments(self, overrides: list[tuple[Variation, Value]]) -> list:
        """``[(locations, value)]`` that make a sample's case from the base case."""
        out = []
        for v, val in overrides:
            if v.choice_tables is not None:
                for p, x in v.choice_tables[val.toml].items():
                    out.append((expand(self.case, p), x))
            else:
                out.append((v.locations, val.toml))
        return out

    def apply(self, overrides: list[tuple[Variation, Value]]) -> dict:
        return apply_assignments(self.case, self.assignments(overrides))

    # Design ----------------------------------------------------------------------
    def _unit_rows(self, start: int, stop: int, cache: dict) -> np.ndarray:
        """Rows [start, stop) of the unit-hypercube design of the drawn keys."""
        d = len(self.drawn)
        if d == 0:
            return np.zeros((stop - start, 0))
        if self.method == "lhs":
            if "u" not in cache:
                from scipy.stats import qmc

                cache["u"] = qmc.LatinHypercube(d=d, seed=self.seed).random(self.samples)
            u = cache["u"][start:stop]
        else:
            rows = []
            b0, b1 = start // DESIGN_BLOCK, (stop - 1) // DESIGN_BLOCK
            for b in range(b0, b1 + 1):
                n = min(DESIGN_BLOCK, self.samples - b * DESIGN_BLOCK)
                if cache.get("block", (None,))[0] == b:  # batches share a block
                    blk = cache["block"][1]
                elif self.method == "random":
                    g = np.random.Generator(np.random.PCG64(np.random.SeedSequence([self.seed, b])))
                    blk = g.random((n, d))
                else:
                    import warnings

                    from scipy.stats import qmc

                    s = qmc.Sobol(d=d, scramble=True, seed=self.seed)
                    if b:  # scipy 1.17 refuses fast_forward(0)
                        s.fast_forward(b * DESIGN_BLOCK)
                    with warnings.catch_warnings():  # balance needs 2^m points; any n is valid
                        warnings.simplefilter("ignore", UserWarning)
                        blk = s.random(n)
                cache["block"] = (b, blk)
                lo = max(start - b * DESIGN_BLOCK, 0)
                hi = min(stop - b * DESIGN_BLOCK, n)
                rows.append(blk[lo:hi])
            u = np.concatenate(rows)
        return np.clip(u, _U_LOW, _U_HIGH)

    def sample_inputs(self, start: int, stop: int, _cache: dict | None = None
                      ) -> Iterator[tuple[int, list[tuple[Variation, Value]]]]:
        """(sample index, [(variation, value)]) for samples [start, stop): sample
        s = g * samples + r takes grid point g and design row r."""
        cache = _cache if _cache is not None else {}
        grid = self.grid
        sizes = [len(v.values) for v in grid]
        r0, r1 = start % self.samples, None
        # Rows needed: all of [start, stop) mapped to rows; fetch the covering row range.
        rows_needed = sorted({s % self.samples for s in range(start, stop)})
        r0, r1 = rows_needed[0], rows_needed[-1] + 1
        u = self._unit_rows(r0, r1, cache)
        for s in range(start, stop):
            g, r = divmod(s, self.samples)
            vals = []
            if grid:
                idx = np.unravel_index(g, sizes)
                vals += [(v, v.values[int(i)]) for v, i in zip(grid, idx)]
            vals += [(v, v.at(float(u[r - r0, j]))) for j, v in enumerate(self.drawn)]
            yield s, vals

    # Checks -----------------------------------------------------------------------
    def check(self, check_case) -> None:
        """Refuses the sweep (SweepError naming the key) when the case with a variation at
        any of its extremes is refused by ``check_case(dict)`` (the case parser)."""
        for v in self.variations:
            for val in v.extremes():
                c = self.apply([(v, val)])
                try:
                    check_case(c)
                except _core.InvalidInput as e:
                    where = (f" (a normal distribution is checked at MEAN +- "
                             f"{NORMAL_CHECK_SD:g} SD)" if v.form == "normal" else "")
                    raise SweepError(f"{v.key} ~ {v.text}: at {v.key} = {val.toml!r}{where} the "
                                     f"case is refused: {e}") from None


def apply_assignments(case: dict, assignments: list) -> dict:
    """A copy of ``case`` with ``[(locations, value)]`` written in."""
    c = copy.deepcopy(case)
    for locs, x in assignments:
        for loc in locs:
            put(c, loc, copy.deepcopy(x))
    return c


# Largest case or sweep file read, as the C++ commands' (core::kMaxCaseFileBytes, 4 MiB):
# a case is a few KB; more is a wrong file (a mesh, a log, a device).
MAX_CASE_FILE_BYTES = 4 << 20


def read_toml(path: str) -> dict:
    try:
        st = os.stat(path)
        if stat.S_ISDIR(st.st_mode) or not stat.S_ISREG(st.st_mode):
            kind = "a directory" if stat.S_ISDIR(st.st_mode) else "not a regular file"
            raise SweepError(f"{path}: {kind}; give a case or sweep file (TOML)")
        if st.st_size > MAX_CASE_FILE_BYTES:
            raise SweepError(f"{path}: {st.st_size} bytes, more than the limit of 4 MiB for a "
                             "case or sweep file (a case is a few KB of TOML)")
        with open(path, "rb") as f:
            data = f.read(MAX_CASE_FILE_BYTES + 1)
        if len(data) > MAX_CASE_FILE_BYTES:
            raise SweepError(f"{path}: more than the limit of 4 MiB for a case or sweep file")
        return tomllib.loads(data.decode("utf-8"))
    except OSError as e:
        raise SweepError(f"{path}: cannot be read: {e.strerror}") from None
    except tomllib.TOMLDecodeError as e:
        raise SweepError(f"{path}: TOML syntax error: {e}") from None
    except UnicodeDecodeError as e:
        line = e.object[:e.start].count(b"\n") + 1
        raise SweepError(f"{path}:{line}: byte 0x{e.object[e.start]:02x} at offset {e.start} is "
                         "not UTF-8: a case or sweep file is TOML text in UTF-8") from None


def case_kind(case: dict) -> str:
    """``dynamics`` for a case with a [dynamics] table, ``vibration`` for a case of
    ``asperity vibration`` (a [structure] table), else ``joint`` (``asperity predict``)."""
    if "structure" in case or "vibration" in case:
        return "vibration"
    if "dynamics" in case:
        return "dynamics"
    return "joint"


def build(case_path: str, vary: dict, *, samples: int | None = None, seed: int = 0,
          method: str = "random", set_: dict | None = None, unset: list | None = None,
          choices: dict | None = None) -> Sweep:
    """A Sweep from a case file and ``{key path: variation}`` (see module doc)."""
    case = read_toml(case_path)
    for p in unset or []:
        for loc in expand(case, p):
            node = get(case, loc[:-1])
            if isinstance(node, dict):
                del node[loc[-1]]
            else:
                raise SweepError(f"unset {p}: only table keys can be removed, not array elements")
    for p, val in (set_ or {}).items():
        parts = parse_path(p)
        try:
            locs = expand(case, p)
        except SweepError:
            # A new key of an existing table.
            parent = expand(case, _format_path(parts[:-1])) if len(parts) > 1 else [[]]
            if not isinstance(parts[-1], str) or parts[-1] == "*":
                raise
            locs = [loc + [parts[-1]] for loc in parent]
            for loc in locs:
                if not isinstance(get(case, loc[:-1]), dict):
                    raise
        for loc in locs:
            put(case, loc, copy.deepcopy(val))
    if method not in METHODS:
        raise SweepError(f"method = {method!r}: allowed: {', '.join(METHODS)}")
    if not isinstance(seed, int) or isinstance(seed, bool) or seed < 0:
        raise SweepError(f"seed = {seed!r}: a non-negative integer")
    if not vary:
        raise SweepError("nothing varies: give at least one key to vary ([vary] or --vary)")
    variations = []
    for key, spec in vary.items():
        variations.append(parse_variation(key, spec, case, choices))
    seen: dict = {}
    for v in variations:
        for loc in v.locations:
            t = tuple(loc)
            if t in seen:
                raise SweepError(f"{v.key}: addresses the same value as {seen[t]}")
            seen[t] = v.key
    drawn = any(v.drawn for v in variations)
    if samples is None:
        samples = 100 if drawn else 1
    if not isinstance(samples, int) or isinstance(samples, bool) or samples < 1:
        raise SweepError(f"samples = {samples!r}: a positive integer")
    if not drawn and samples != 1:
        raise SweepError(f"samples = {samples}: nothing is drawn (grids only), so samples must "
                         "be 1; every grid point runs once")
    grid_points = 1
    for v in variations:
        if not v.drawn:
            grid_points *= len(v.values)
    if grid_points * samples > MAX_SAMPLES:
        raise SweepError(f"samples = {samples} at {grid_points} grid point(s) is "
                         f"{grid_points * samples:,} samples, above the limit of {MAX_SAMPLES:,} "
                         "of a sweep: lower samples or the grid steps")
    return Sweep(case=case, base_dir=os.path.dirname(os.path.abspath(case_path)),
                 variations=variations, samples=samples, seed=seed, method=method,
                 case_path=case_path, kind=case_kind(case))


def parse_vary_flag(text: str) -> tuple[str, str]:
    """``"KEY ~ DIST"`` or ``"KEY = GRID"`` (the --vary flag) -> (key, variation)."""
    m = re.match(r"^\s*([^~=\s]+)\s*[~=]\s*(.+)$", text)
    if not m:
        raise SweepError(f"--vary {text!r}: write KEY ~ DISTRIBUTION or KEY = GRID, e.g. "
                         "'load.bolts.nut_factor ~ uniform(0.158, 0.267)'")
    value = m.group(2).strip()
    if value.startswith("["):  # an array of grid values, TOML syntax
        try:
            return m.group(1), tomllib.loads(f"v = {value}")["v"]
        except tomllib.TOMLDecodeError as e:
            raise SweepError(f"--vary {text!r}: the array of values is not TOML: {e}") from None
    return m.group(1), value
