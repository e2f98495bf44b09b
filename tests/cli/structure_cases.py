#!/usr/bin/env python3
"""Behaviour of `asperity structure` (issue 19): the summary.json contract on the shipped
two-block example, the files of --out (the reduced model read back by scipy and by
`asperity vibration`), and bad input (exit 2, one line naming the item, nothing written).

Usage: structure_cases.py ASPERITY_EXE CASE. Needs gmsh (scripts/setup.sh), scipy and jsonschema
(python/requirements.txt): without them the test fails, it does not skip.
Registered in tests/cli/CMakeLists.txt, one CTest per case (cli.structure.<case>).
"""
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import jsonschema
import numpy as np
import scipy.io

from summit_table import linear_moments

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLE = os.path.join(HERE, "..", "..", "examples", "structures", "two_blocks.toml")
with open(EXAMPLE) as f:
    TWO_BLOCKS = f.read()


def fail(msg):
    print("FAIL:", msg, file=sys.stderr)
    return 1


def run(exe, args, cwd=None):
    return subprocess.run([exe, *args], capture_output=True, text=True, timeout=900, cwd=cwd)


def write(tmp, name, text):
    path = os.path.join(tmp, name)
    with open(path, "w") as f:
        f.write(text)
    return path


def rough_on_every_element(tmp, model):
    """A vibration case with rough_contact on every interface element of the model file in
    contact at its rough prestress, and mode 7's backbone at small amplitudes."""
    return write(tmp, "rough.toml", f"""[structure]
model = "{model}"
rayleigh = {{ alpha = 0.0, beta = 1e-7 }}
output_dofs = [0]
[[element]]
type = "rough_contact"
T = {{ interface_element = "all" }}
[harmonic_balance]
max = 1
time_points = 32
[nonlinear_mode]
mode = 7
log10_amplitude = {{ from = -10.0, to = -8.0 }}
""")


def case_summary_keys(exe, tmp):
    p = run(exe, ["structure", EXAMPLE, "--json"])
    if p.returncode != 0:
        return fail(f"exit {p.returncode}: {p.stderr}")
    s = json.loads(p.stdout)
    for key in ["mesh", "rigid_body_modes", "linear_modes", "reduced_model", "prestress"]:
        if key not in s:
            return fail(f"summary has no {key}")
    if not (s["mesh"]["nodes"] > 1000 and s["mesh"]["elements"] > 500):
        return fail(f"mesh {s['mesh']}")
    if s["rigid_body_modes"] != 6:
        return fail(f"rigid_body_modes {s['rigid_body_modes']}, a free-free structure has 6")
    for name in ["open", "frictionless", "stuck"]:
        f = s["linear_modes"][name]["frequency_hz"]
        if len(f) != 8 or any(x <= 0 for x in f) or f != sorted(f):
            return fail(f"{name}: frequencies {f} must be 8 elastic ones, ascending")
    # Contact adds stiffness: each mode of (c) is at least the same-index mode of (b), and
    # (b) of (a) (Courant-Fischer: adding a positive semi-definite stiffness).
    lm = s["linear_modes"]
    for lo, hi in [("open", "frictionless"), ("frictionless", "stuck")]:
        for a, b in zip(lm[lo]["frequency_hz"], lm[hi]["frequency_hz"]):
            if b < a * (1 - 1e-9):
                return fail(f"{hi} mode {b} Hz below {lo} mode {a} Hz")
    r = s["reduced_model"]
    if r["interface_elements"] != 24 or r["dofs"] != 3 * 24 + 20 + 6 + 1:
        return fail(f"reduced_model {r}: 72 interface DOFs, 20 + 6 tied modes, 1 bolt vector")
    pre = s["prestress"]
    # Equilibrium: the interface carries the bolt's tension (load-dependent Ritz vector).
    if abs(pre["interface_normal_force_N"] / pre["bolt_load_N"] - 1) > 1e-6:
        return fail(f"prestress {pre}")
    # The rough flat's prestress ([rough_contact] of the example): the same equilibrium, to
    # Newton's 1e-10 residual (1e-8 of the load allows for the reduced model's conditioning);
    # a real contact area below the nominal one in contact; every linearised mode above the
    # open interface's (Courant-Fischer again).
    rough = s["rough_prestress"]
    if abs(rough["interface_normal_force_N"] / rough["bolt_load_N"] - 1) > 1e-8:
        return fail(f"rough prestress {rough}")
    if rough["relative_residual"] > 1e-10 or not (
        0 < rough["real_contact_area_m2"] < rough["contact_area_m2"]
    ):
        return fail(f"rough prestress {rough}")
    f = lm["rough"]["frequency_hz"]
    if len(f) != 8 or any(b < a * (1 - 1e-9) for a, b in zip(lm["open"]["frequency_hz"], f)):
        return fail(f"rough: frequencies {f} against open {lm['open']['frequency_hz']}")
    return 0


def case_out_files(exe, tmp):
    out = os.path.join(tmp, "out")
    p = run(exe, ["structure", EXAMPLE, "--out", out])
    if p.returncode != 0:
        return fail(f"exit {p.returncode}: {p.stderr}")
    for name in ["summary.json", "reduced_model.mat", "structure.vtu", "mesh.png", "mode_1.png",
                 "interface_pressure.png"]:
        if not os.path.getsize(os.path.join(out, name)) > 0:
            return fail(f"{name} missing or empty")
    m = scipy.io.loadmat(os.path.join(out, "reduced_model.mat"))
    M, K = m["M"], m["K"]
    if M.shape != K.shape or M.shape[0] != 99:
        return fail(f"M {M.shape}, K {K.shape}")
    if np.abs(M - M.T).max() > 1e-12 * np.abs(M).max() or np.abs(K - K.T).max() > 1e-12 * np.abs(K).max():
        return fail("M or K not symmetric")
    if m["Q"].shape != (72, 99) or m["element_area"].shape != (24, 1):
        return fail(f"Q {m['Q'].shape}, element_area {m['element_area'].shape}")
    if abs(m["element_area"].sum() - json.load(open(os.path.join(out, "summary.json")))["interfaces"][0]["area_m2"]) > 1e-12:
        return fail("element areas do not sum to the interface area")
    root = ET.parse(os.path.join(out, "structure.vtu")).getroot()
    names = [a.get("Name") for a in root.iter("DataArray")]
    if "prestress_pressure_Pa" not in names or not any(n.startswith("stuck_mode_1") for n in names):
        return fail(f"VTU fields {names}")
    # The reduced model in a vibration case: the quasi-static estimate of the first elastic
    # mode (modes 1-6 of a free-free model are rigid) with one Jenkins element on interface
    # element 0 (t1) runs on the model's 99 DOFs.
    case = write(tmp, "vib.toml", f"""[structure]
model = "{os.path.join(out, 'reduced_model.mat')}"
rayleigh = {{ alpha = 0.0, beta = 1e-7 }}
output_dofs = [0, 1]
[[element]]
type = "jenkins"
T = {{ interface_element = 0, directions = ["t1"] }}
k_t = 1e8
F_s = 100.0
[harmonic_balance]
max = 1
time_points = 64
[quasi_static_mode]
mode = 7
amplitude = {{ from = 1e-6, to = 1e-3 }}
points = 5
""")
    p = run(exe, ["vibration", case, "--json"])
    if p.returncode != 0:
        return fail(f"vibration on the model: exit {p.returncode}: {p.stderr}")
    if "quasi_static_mode" not in json.loads(p.stdout):
        return fail("no quasi_static_mode")
    # A force at the model's output point ("corner") along z: the same curve as the rows
    # R_z^T f written out (the recovery rows' virtual work, force_pair's point form); the
    # direction is normalised ([0, 0, 2] is z) and the force may carry units.
    forced = open(case).read().replace("[quasi_static_mode]\nmode = 7\namplitude = { from = 1e-6, to = 1e-3 }\n"
                          "points = 5\n", "")
    sweep = 'omega = { from = "9 kHz", to = "9.2 kHz" }\n'
    rz = m["R"][2]
    at_point = write(tmp, "point.toml", forced + "[[frequency_response]]\n"
                     'force_cos = { point = "corner", direction = [0, 0, 2], force = [0, "3 N"] }\n'
                     + sweep)
    rows = write(tmp, "rows.toml", forced + "[[frequency_response]]\nforce_cos = [["
                 + ", ".join(["0.0"] * len(rz)) + "], [" + ", ".join(repr(float(3.0 * x)) for x in rz)
                 + "]]\n" + sweep)
    curves = []
    for c in (at_point, rows):
        p = run(exe, ["vibration", c, "--json"])
        if p.returncode != 0:
            return fail(f"point force: exit {p.returncode}: {p.stderr}")
        curves.append(json.loads(p.stdout)["frequency_response"][0])
    a, b = (np.array(c["output_amplitude"]) for c in curves)
    if (a.shape != b.shape or len(a) < 3 or not np.abs(b).min() > 0
            or np.abs(a - b).max() > 1e-12 * np.abs(b).max()):
        return fail(f"a force at the point differs from its rows: {a} against {b}")
    # The legend and the text name the force given at the point, not its generalised norm.
    p = run(exe, ["vibration", at_point])
    if p.returncode != 0 or "F = 3 N at corner" not in p.stdout:
        return fail(f"point force label: exit {p.returncode}: {p.stdout}")
    bad = write(tmp, "bad_point.toml", open(at_point).read().replace('point = "corner"',
                                                                      'point = "tip"'))
    p = run(exe, ["vibration", bad])
    if p.returncode != 2 or 'force_cos.point = "tip": the model\'s output points are "corner"' not in p.stderr:
        return fail(f"unknown point: exit {p.returncode}: {p.stderr}")
    bad = write(tmp, "no_point.toml", open(at_point).read().replace('point = "corner", ', ''))
    p = run(exe, ["vibration", bad])
    if p.returncode != 2 or "force_cos.point is missing: the model's output points are" not in p.stderr:
        return fail(f"missing point: exit {p.returncode}: {p.stderr}")
    # rough_contact on every interface element in contact at the rough prestress (the
    # surface and pressures come with the model file): the stuck structure's linear modes
    # are the structure run's linearised `rough` modes (two code paths: the prestress's
    # stiffnesses and the elements' initial tangents; measured 8e-12 apart, 1e-9 asserted
    # for two eigensolvers), and the nonlinear mode starts there (within zeta^2 = 8.4e-6,
    # EPMC's frequency of a damped mode).
    summary = json.load(open(os.path.join(out, "summary.json")))
    case = rough_on_every_element(tmp, os.path.join(out, "reduced_model.mat"))
    p = run(exe, ["vibration", case, "--json"])
    if p.returncode != 0:
        return fail(f"rough_contact on every element: exit {p.returncode}: {p.stderr}")
    v = json.loads(p.stdout)
    touching = summary["rough_prestress"]["elements_in_contact"]
    if len(v["elements"]) != touching or not all(e["type"] == "rough_contact" for e in v["elements"]):
        return fail(f"{len(v['elements'])} elements placed, {touching} in contact")
    if touching < 24 and not any(f"{24 - touching} of the 24" in w for w in v["warnings"]):
        return fail(f"warnings {v['warnings']}")
    want = summary["linear_modes"]["rough"]["frequency_hz"]
    got = v["structure"]["linear_frequencies_hz_elements_stuck"][6:6 + len(want)]
    if any(abs(a - b) > 1e-9 * b for a, b in zip(got, want)):
        return fail(f"stuck linear modes {got}, the structure's rough modes {want}")
    f0 = v["nonlinear_mode"]["frequency_hz"][0]
    if abs(f0 - want[0]) > 8.4e-6 * want[0]:
        return fail(f"nonlinear mode starts at {f0} Hz, linear {want[0]} Hz")
    # The model's named output point ("corner") is reported along the backbone: its
    # first-harmonic acceleration is omega^2 times its displacement amplitude.
    ops = v["nonlinear_mode"]["output_points"]
    if [o["name"] for o in ops] != ["corner"] or ops[0]["point_m"] != [0.06, 0.02, 0.02]:
        return fail(f"output points {[(o['name'], o['point_m']) for o in ops]}")
    w = np.array(v["nonlinear_mode"]["omega_rad_s"])
    d = np.array(ops[0]["displacement_amplitude_m"])
    a = np.array(ops[0]["acceleration_amplitude_m_s2"])
    if d.shape != (len(w), 3) or np.abs(a - d * w[:, None] ** 2).max() > 1e-12 * np.abs(a).max():
        return fail("output point acceleration is not omega^2 x displacement")
    # Recovery rows that pick DOFs 0, 1, 2 (the model rewritten with R = [I 0]): the point's
    # displacement is the first-harmonic amplitude of those DOFs, computed by the output_dofs
    # path (HarmonicBalance::harmonic_amplitude), exactly.
    m = {k: x for k, x in scipy.io.loadmat(os.path.join(out, "reduced_model.mat")).items()
         if not k.startswith("__")}
    m["R"] = np.eye(3, m["M"].shape[0])
    m["output_names"] = "probe"
    m["output_points"] = np.zeros((1, 3))
    scipy.io.savemat(os.path.join(tmp, "probe.mat"), m)
    case = write(tmp, "probe.toml", open(case).read().replace(
        os.path.join(out, "reduced_model.mat"), os.path.join(tmp, "probe.mat")).replace(
        "output_dofs = [0]", "output_dofs = [0, 1, 2]"))
    p = run(exe, ["vibration", case, "--json", "--out", os.path.join(tmp, "probe_out")])
    if p.returncode != 0:
        return fail(f"probe model: exit {p.returncode}: {p.stderr}")
    v = json.loads(p.stdout)["nonlinear_mode"]
    got = np.array(v["output_points"][0]["displacement_amplitude_m"])
    if not np.array_equal(got, np.array(v["output_amplitude"])):
        return fail("output point rows [I 0] do not give the DOFs' amplitudes")
    for name in ["modal_frequency_probe.png", "modal_damping_probe.png"]:
        if not os.path.getsize(os.path.join(tmp, "probe_out", name)) > 0:
            return fail(f"{name} missing")
    header = open(os.path.join(tmp, "probe_out", "nonlinear_mode.csv")).readline()
    if "probe_z_acceleration_m_s2" not in header:
        return fail(f"nonlinear_mode.csv header {header}")
    # The interface map along a mode that slips (mode 9, a shear mode: damping ratio up to
    # 0.4 % by 1e-7): the elements' dissipation per cycle sums to the EPMC's energy balance
    # xi pi omega a^2 (with H = 1 and C = 0, the work of -xi M x' per period; a closed form
    # of the unknowns the summary reports, 1e-9 where the damping is resolved), and each
    # element's cycle-mean pressure at the smallest amplitude is its rough prestress.
    case = write(tmp, "map.toml", open(case).read().replace("mode = 7", "mode = 9").replace(
        "to = -8.0", "to = -7.0").replace("output_dofs = [0, 1, 2]", "output_dofs = [0]").replace(
        "rayleigh = { alpha = 0.0, beta = 1e-7 }\n", ""))
    p = run(exe, ["vibration", case, "--json", "--out", os.path.join(tmp, "map_out")])
    if p.returncode != 0:
        return fail(f"interface map run: exit {p.returncode}: {p.stderr}")
    full = json.loads(p.stdout)
    # The model-only keys (output_points, interface) against the published schema.
    jsonschema.validate(full, json.load(open(os.path.join(HERE, "..", "..", "docs", "schema",
                                                          "vibration.schema.json"))))
    v = full["nonlinear_mode"]
    it = v["interface"]
    if len(it["interface_elements"]) != touching:
        return fail(f"interface map of {len(it['interface_elements'])} elements, {touching} in contact")
    area = np.array(it["area_m2"])
    work = (np.array(it["dissipation_J_per_m2"]) * area).sum(axis=1)
    a, w, xi = (np.array(v[k]) for k in ("amplitude", "omega_rad_s", "xi_per_s"))
    balance = xi * np.pi * w * a ** 2
    resolved = np.array(v["damping_ratio"]) > 1e-6
    if resolved.sum() < 5 or np.abs(work / balance - 1.0)[resolved].max() > 1e-9:
        return fail(f"dissipation {work[resolved]} against xi pi omega a^2 {balance[resolved]}")
    p0 = m["rough_pressure"][:, 0][it["interface_elements"]]
    first = np.array(it["mean_pressure_Pa"][0], dtype=float)
    if np.abs(first / p0 - 1.0).max() > 1e-6:
        return fail(f"mean pressure at the smallest amplitude {first[:3]}, prestress {p0[:3]}")
    # Stick/slip: every element sticks at the smallest amplitude (no sample at its static
    # limit, none open), and the fractions stay in [0, 1].
    slip = np.array(it["slip_fraction"], dtype=float)
    opened = np.array(it["open_fraction"], dtype=float)
    if slip[0].max() != 0.0 or opened[0].max() != 0.0:
        return fail(f"slip {slip[0].max()} or open {opened[0].max()} at the smallest amplitude")
    if not (0.0 <= slip.min() and slip.max() <= 1.0 and 0.0 <= opened.min() and opened.max() <= 1.0):
        return fail("slip or open fractions outside [0, 1]")
    rows = open(os.path.join(tmp, "map_out", "interface_map.csv")).read().splitlines()
    if len(rows) != 1 + len(a) * touching:
        return fail(f"interface_map.csv: {len(rows)} lines")
    if not os.path.getsize(os.path.join(tmp, "map_out", "interface_dissipation.png")) > 0:
        return fail("interface_dissipation.png missing")
    # interface_map.vtu for ParaView: one vertex per element at the summary's centroids, and
    # per point the summary's values (written with 12 digits).
    root = ET.parse(os.path.join(tmp, "map_out", "interface_map.vtu")).getroot()
    piece = root.find("UnstructuredGrid/Piece")
    if int(piece.get("NumberOfPoints")) != touching or int(piece.get("NumberOfCells")) != touching:
        return fail(f"interface_map.vtu: {piece.attrib}")
    arrays = {a.get("Name"): np.array(a.text.split(), dtype=float) for a in root.iter("DataArray")}
    xyz = arrays[None].reshape(-1, 3) if None in arrays else None
    if xyz is None or np.abs(xyz - np.array(it["centroid_m"])).max() > 1e-15:
        return fail("interface_map.vtu: points are not the centroids")
    if not np.array_equal(arrays["types"], np.ones(touching)):
        return fail("interface_map.vtu: cells are not VTK_VERTEX")
    if not np.array_equal(arrays["log10_amplitude"], np.array(v["log10_amplitude"])):
        return fail("interface_map.vtu: log10_amplitude field")
    width = len(str(len(a) - 1))
    for k in [0, len(a) - 1]:
        for q, want in [("dissipation_J_per_m2", it["dissipation_J_per_m2"]),
                        ("slip_fraction", slip), ("mean_pressure_Pa", it["mean_pressure_Pa"])]:
            name = f"{q} point {k:0{width}d} log10a {v['log10_amplitude'][k]:.2f}"
            want_k = np.array(want[k], dtype=float)
            if name not in arrays or np.abs(arrays[name] - want_k).max() > 1e-11 * np.abs(want_k).max() + 1e-300:
                return fail(f"interface_map.vtu: {name} missing or not the summary's")
    return 0


def bad(exe, tmp, text, needle, name="case.toml", extra=()):
    path = write(tmp, name, text)
    out = os.path.join(tmp, "bad_out")
    p = run(exe, ["structure", path, "--out", out, *extra])
    if p.returncode != 2:
        return fail(f"exit {p.returncode}, expected 2: {p.stderr}")
    if needle not in p.stderr:
        return fail(f"message does not name {needle!r}: {p.stderr}")
    if p.stdout or os.path.exists(out):
        return fail("output written on bad input")
    return 0


def case_bad_input_bolt_outside(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace("head = [30, 10, 20]", "head = [90, 10, 20]").replace(
        "nut = [30, 10, 0]", "nut = [90, 10, 0]"), 'bolt "m6": the head footprint')


def case_bad_input_interface_not_touching(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace('bodies = ["lower", "upper"]',
                                            'bodies = ["lower", "upper"]\nnormal = [1, 0, 0]'),
               'interface "joint": the surfaces of bodies "lower" and "upper" do not touch')


def case_bad_input_prism_does_not_close(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace(
        'add = [{ box = { corner = [0, 0, 10], size = [60, 20, 10] } }]',
        'add = [{ prism = { polygon = [[0, 0, 10], [60, 0, 10]], extrusion = [0, 0, 10] } }]'),
        "does not close")


def case_bad_input_unknown_key(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace("patches = 24", "patches = 24\npatchez = 3"),
               'unknown key "patchez"')


def case_bad_input_held_by_nothing(exe, tmp):
    # No bolt: with the interface open the blocks are two free bodies (12 rigid-body modes).
    text = TWO_BLOCKS[:TWO_BLOCKS.index("[[bolt]]")] + TWO_BLOCKS[TWO_BLOCKS.index("[[output]]"):]
    return bad(exe, tmp, text, "more than a free-free structure allows (6)")


def case_bad_input_too_many_patches(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace("patches = 24", "patches = 5000"),
               "`patches` = 5000 but the interface has only")


def vib_on(exe, tmp, mat):
    path = os.path.join(tmp, "m.mat")
    scipy.io.savemat(path, mat)
    case = write(tmp, "v.toml", f'[structure]\nmodel = "{path}"\n[harmonic_balance]\nmax = 1\n'
                 '[quasi_static_mode]\nmode = 1\namplitude = { from = 1e-3, to = 1.0 }\n')
    return run(exe, ["vibration", case, "--json"])


def case_bad_input_model_missing_matrix(exe, tmp):
    p = vib_on(exe, tmp, {"M": np.eye(3)})
    if p.returncode != 2 or "has no matrix named K" not in p.stderr:
        return fail(f"exit {p.returncode}: {p.stderr}")
    return 0


BRB_SURFACE = os.path.join(HERE, "..", "..", "examples", "brb", "brb_surface_data.mat")


def surface_case(tmp, extra="", pz=None):
    """The two-block example with the measured BRB summit table (surface_data) in place of
    sigma, R and eta; pz replaces its density."""
    d = scipy.io.loadmat(BRB_SURFACE)
    keep = {k: d[k] for k in ["Re", "area_density", "z_max", "normzinterp", "pzinterp"]}
    if pz is not None:
        keep["pzinterp"] = pz
    scipy.io.savemat(os.path.join(tmp, "surface.mat"), keep)
    text = TWO_BLOCKS.replace('sigma = "2.7 um"\nR = "30.1 um"\neta = "2.9e8 m^-2"\n',
                              f'surface_data = "surface.mat"\n{extra}')
    # A coarser mesh than the example's (a third of its run time): the checks below are
    # about the summit table, not the mesh.
    text = text.replace("size = 6\ninterface_size = 3\nhole_size = 2\n",
                        "size = 10\ninterface_size = 5\nhole_size = 3\n")
    assert "surface_data" in text and "size = 10\n" in text
    return write(tmp, "surface.toml", text)


def case_measured_summit_table(exe, tmp):
    # The measured summit-height density is summed as such (Eq. 4.4 over the table): the
    # reduced model carries it standardized (unit integral, mean 0, standard deviation 1,
    # exact moments of the piecewise-linear density: 1e-12) with sigma its standard
    # deviation in metres; the prestress differs from the Gaussian's of the same sigma
    # (summit_distribution = "gaussian": real contact area 2 % apart here, > 0.5 % asserted)
    # while both carry the bolt load; and rough_contact elements built from the model's
    # table have the structure's linearised modes as their stuck modes (1e-9, as above).
    path = surface_case(tmp)
    out = os.path.join(tmp, "out")
    p = run(exe, ["structure", path, "--out", out, "--json"])
    if p.returncode != 0:
        return fail(f"exit {p.returncode}: {p.stderr}")
    table = json.loads(p.stdout)
    m = scipy.io.loadmat(os.path.join(out, "reduced_model.mat"))
    if "rough_summit_heights" not in m or m["rough_summit_heights"].shape[1] != 2:
        return fail(f"reduced model variables {sorted(m)}")
    zs, ps = m["rough_summit_heights"][:, 0], m["rough_summit_heights"][:, 1]
    I, mean, var = linear_moments(zs, ps)
    if abs(I - 1) > 1e-12 or abs(mean) > 1e-12 or abs(var - 1) > 1e-12:
        return fail(f"stored table: integral {I}, mean {mean}, variance {var}")
    d = scipy.io.loadmat(BRB_SURFACE)
    _, _, var0 = linear_moments(d["normzinterp"].ravel() * d["z_max"].item(), d["pzinterp"].ravel())
    surface = m["rough_surface"].ravel()
    if abs(surface[4] / np.sqrt(var0) - 1) > 1e-12 or surface[7] != 1:
        return fail(f"rough_surface {surface}: sigma should be {np.sqrt(var0)} m, summit flag 1")
    p = run(exe, ["structure", surface_case(tmp, 'summit_distribution = "gaussian"\n'), "--json"])
    if p.returncode != 0:
        return fail(f"gaussian: exit {p.returncode}: {p.stderr}")
    gauss = json.loads(p.stdout)
    for s in (table, gauss):
        r = s["rough_prestress"]
        if abs(r["interface_normal_force_N"] / r["bolt_load_N"] - 1) > 1e-8:
            return fail(f"rough prestress {r}")
    # The summary says which: the table's rows over its support (runs of zero density at
    # either end dropped but for one zero row: here rows 0-971 of 1001).
    nz = np.flatnonzero(d["pzinterp"].ravel())
    rows = min(nz[-1] + 1, d["pzinterp"].size - 1) - max(nz[0] - 1, 0) + 1
    said = (table["rough_prestress"]["summit_heights"], gauss["rough_prestress"]["summit_heights"])
    if said != (f"measured table ({rows} points)", "gaussian"):
        return fail(f"summit_heights {said}")
    if abs(table["rough_prestress"]["sigma_m"] / np.sqrt(var0) - 1) > 1e-12:
        return fail(f"sigma_m {table['rough_prestress']['sigma_m']}")
    a_t = table["rough_prestress"]["real_contact_area_m2"]
    a_g = gauss["rough_prestress"]["real_contact_area_m2"]
    if not abs(a_t / a_g - 1) > 5e-3:
        return fail(f"real contact area {a_t} over the table, {a_g} over the Gaussian: the same")
    # The same table as a CSV file (summit_heights, the format `asperity roughness --summits`
    # writes; heights and densities as the .mat holds them, repr: the same doubles) with the
    # file's R and eta: the same model, to round-off (1e-12).
    z_m = d["normzinterp"].ravel() * d["z_max"].item()
    write(tmp, "table.csv", "# the BRB summit table\nheight[m],density\n" +
          "".join(f"{float(a)!r},{float(b)!r}\n" for a, b in zip(z_m, d["pzinterp"].ravel())))
    text = open(surface_case(tmp)).read().replace(
        'surface_data = "surface.mat"\n',
        f'summit_heights = "table.csv"\nR = "{float(d["Re"].item())!r} m"\neta = "{float(d["area_density"].item())!r} m^-2"\n')
    p = run(exe, ["structure", write(tmp, "csv.toml", text), "--json"])
    if p.returncode != 0:
        return fail(f"summit_heights: exit {p.returncode}: {p.stderr}")
    csv = json.loads(p.stdout)
    for key in ("real_contact_area_m2", "max_pressure_Pa", "sigma_m"):
        if abs(csv["rough_prestress"][key] / table["rough_prestress"][key] - 1) > 1e-12:
            return fail(f"{key}: {csv['rough_prestress'][key]} from the CSV, "
                        f"{table['rough_prestress'][key]} from surface_data")
    if csv["rough_prestress"]["summit_heights"] != table["rough_prestress"]["summit_heights"]:
        return fail(f"CSV table: {csv['rough_prestress']['summit_heights']}")
    for a, b in zip(csv["linear_modes"]["rough"]["frequency_hz"],
                    table["linear_modes"]["rough"]["frequency_hz"]):
        if abs(a / b - 1) > 1e-12:
            return fail(f"rough mode {a} Hz from the CSV, {b} Hz from surface_data")
    case = rough_on_every_element(tmp, os.path.join(out, "reduced_model.mat"))
    p = run(exe, ["vibration", case, "--json"])
    if p.returncode != 0:
        return fail(f"rough_contact over the table: exit {p.returncode}: {p.stderr}")
    want = table["linear_modes"]["rough"]["frequency_hz"]
    got = json.loads(p.stdout)["structure"]["linear_frequencies_hz_elements_stuck"][6:6 + len(want)]
    if any(abs(a - b) > 1e-9 * b for a, b in zip(got, want)):
        return fail(f"stuck linear modes {got}, the structure's rough modes {want}")
    return 0


def case_bad_input_summit_table_negative(exe, tmp):
    d = scipy.io.loadmat(BRB_SURFACE)
    pz = d["pzinterp"].copy()
    pz[0, 500] = -0.1
    path = surface_case(tmp, pz=pz)
    return bad(exe, tmp, open(path).read(), "with a density >= 0", name="neg.toml")


def case_bad_input_summit_distribution_unknown(exe, tmp):
    path = surface_case(tmp, 'summit_distribution = "lognormal"\n')
    return bad(exe, tmp, open(path).read(), '`summit_distribution` = "lognormal": allowed are',
               name="unknown.toml")


def case_bad_input_summit_distribution_without_table(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace('asperity_model = "bke"',
                                            'asperity_model = "bke"\nsummit_distribution = "table"'),
               "`summit_distribution` needs a measured table")


def table_case(tmp, csv_text, extra=""):
    write(tmp, "t.csv", csv_text)
    return TWO_BLOCKS.replace('sigma = "2.7 um"\n', f'summit_heights = "t.csv"\n{extra}')


def case_bad_input_summit_heights_and_sigma(exe, tmp):
    return bad(exe, tmp, table_case(tmp, "height[um],count\n0,0\n1,2\n2,0\n", 'sigma = "2 um"\n'),
               "give `sigma` or `summit_heights` (whose standard deviation is the summits' sigma)")


def case_bad_input_summit_heights_columns(exe, tmp):
    return bad(exe, tmp, table_case(tmp, "z[um],density\n0,0\n1,2\n2,0\n"),
               "t.csv\": a summit-height table has the columns height[unit] and density (or count)")


def case_bad_input_summit_heights_not_increasing(exe, tmp):
    return bad(exe, tmp, table_case(tmp, "height[um],density\n0,0\n1,2\n1,1\n2,0\n"),
               "height 1e-06 at point 3 does not exceed the one before")


def case_bad_input_summit_heights_with_surface_data(exe, tmp):
    text = open(surface_case(tmp)).read().replace(
        'surface_data = "surface.mat"\n', 'surface_data = "surface.mat"\nsummit_heights = "t.csv"\n')
    return bad(exe, tmp, text, "give `surface_data` (a measured surface file) or `summit_heights`")


def case_bad_input_model_not_symmetric(exe, tmp):
    K = np.eye(3)
    K[0, 1] = 0.5
    p = vib_on(exe, tmp, {"M": np.eye(3), "K": K, "L": np.eye(3), "Qm": np.ones((1, 1)),
                          "Tm": np.ones((1, 1)), "Fv": np.zeros((3, 1))})
    if p.returncode != 2 or "K is not symmetric" not in p.stderr:
        return fail(f"exit {p.returncode}: {p.stderr}")
    return 0


def case_bad_input_all_elements_without_rough(exe, tmp):
    # interface_element = "all" needs the rough surface and pressures a structure run stores.
    path = os.path.join(tmp, "m.mat")
    scipy.io.savemat(path, {"M": np.eye(3), "K": np.eye(3), "L": np.eye(3), "Qm": np.ones((1, 1)),
                            "Tm": np.ones((1, 1)), "Fv": np.zeros((3, 1))})
    case = write(tmp, "v.toml", f'[structure]\nmodel = "{path}"\n[[element]]\n'
                 'type = "rough_contact"\nT = { interface_element = "all" }\n'
                 '[harmonic_balance]\nmax = 1\n[nonlinear_mode]\nmode = 1\n')
    p = run(exe, ["vibration", case, "--json"])
    if p.returncode != 2 or "[rough_contact]" not in p.stderr or "element[" not in p.stderr:
        return fail(f"exit {p.returncode}: {p.stderr}")
    return 0


def case_bad_input_model_wrong_size(exe, tmp):
    p = vib_on(exe, tmp, {"M": np.eye(3), "K": np.eye(4), "L": np.eye(3), "Qm": np.ones((1, 1)),
                          "Tm": np.ones((1, 1)), "Fv": np.zeros((3, 1))})
    if p.returncode != 2 or "K is 4 x 4, expected 3 x 3" not in p.stderr:
        return fail(f"exit {p.returncode}: {p.stderr}")
    return 0


def case_bad_input_inverted_element(exe, tmp):
    # One C3D10 with two corners swapped: negative Jacobian.
    nodes = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
    mids = [(0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3)]
    pts = nodes + [tuple((a + b) / 2 for a, b in zip(nodes[i], nodes[j])) for i, j in mids]
    lines = ["*NODE"] + [f"{k + 1}, {x}, {y}, {z}" for k, (x, y, z) in enumerate(pts)]
    conn = [2, 1, 3, 4, 5, 7, 6, 9, 8, 10]  # corners 1 and 2 swapped (mid-edges to match)
    lines += ["*ELEMENT, TYPE=C3D10, ELSET=BLOCK", "1, " + ", ".join(map(str, conn))]
    write(tmp, "one.inp", "\n".join(lines) + "\n")
    text = ('[mesh]\nfile = "one.inp"\nunit = "mm"\n[[material]]\nname = "s"\nE = "200 GPa"\n'
            'nu = 0.3\nrho = "7800 kg/m^3"\n[[body]]\nname = "BLOCK"\nmaterial = "s"\n')
    return bad(exe, tmp, text, "is inverted")


def case_bad_input_rough_two_sigmas(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace('sigma = "2.7 um"', 'sigma = "2.7 um"\nsigma_summits = "3 um"'),
               "[rough_contact]: give `sigma` (surface heights) or `sigma_summits`, not both")


def case_bad_input_rough_gap_map_missing(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace('asperity_model = "bke"',
                                            'asperity_model = "bke"\ngap_map = "nowhere.mat"'),
               "nowhere.mat")


def case_bad_input_rough_hardness(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace('hardness = "5.8 GPa"', 'hardness = "-5.8 GPa"'),
               "[rough_contact]: `hardness` = -5800000000: give a value > 0")

def case_fretting_cycles(exe, tmp):
    """--fretting on the two-block example: the apparatus's cycles obey what every loop must
    (positive energy, closed, forces and amplitudes growing with the tip amplitude, secant
    stiffness below the stuck one: a Masing backbone is concave), the rough prestress carries
    the bolt load, and the files agree with the summary."""
    out = os.path.join(tmp, "fr")
    p = run(exe, ["structure", EXAMPLE, "--fretting", "--out", out, "--json"])
    if p.returncode != 0:
        return fail(f"exit {p.returncode}: {p.stderr}")
    j = json.loads(p.stdout)
    schema = json.load(open(os.path.join(HERE, "..", "..", "docs", "schema",
                                         "structure.schema.json")))
    jsonschema.validate(j, schema)
    if sorted(f for f in os.listdir(out) if not f.startswith(".")) != sorted(["summary.json", "fretting_cycles.csv", "fretting_loops.csv",
                                          "fretting_loops.png", "fretting_energy.png"]):
        return fail(f"files: {sorted(os.listdir(out))}")
    # Every step's cost carries the peak memory after it (a run of meshes takes megabytes).
    if not all(c["peak_rss_MiB"] > 1 for c in j["costs"]):
        return fail(f"peak memory not recorded: {j['costs']}")
    app = j["apparatus"]
    if app["held"]["nodes"] < 10 or app["driven"]["nodes"] < 10:
        return fail(f"grips hold too few nodes: {app}")
    (run_,) = j["fretting"]
    # The bolts are tightened in the grips: the interface and the grips share the preload
    # (equilibrium of one block along the bolt).
    share = run_["interface_normal_force_N"] + run_["preload_through_grips_N"]
    if abs(share - run_["total_preload_N"]) > 1e-9 * run_["total_preload_N"] or not (
            0 < run_["interface_normal_force_N"] <= run_["total_preload_N"] * (1 + 1e-9)):
        return fail(f"the interface and grips do not carry the bolt load: {run_}")
    k = run_["stiffness_N_per_m"]
    cycles = run_["cycles"]
    tips = [c["tip_amplitude_m"] for c in cycles]
    if tips != sorted(tips) or len(tips) < 3:
        return fail(f"tip amplitudes {tips}")
    prev = None
    for c in cycles:
        if not (c["energy_J"] > 0 and c["relative_residual"] <= 1e-5):
            return fail(f"cycle {c}")
        secant = c["force_amplitude_N"] / c["displacement_amplitude_m"]
        if secant > k * (1 + 1e-6):
            return fail(f"secant stiffness {secant} above the stuck joint's {k}: {c}")
        if prev and not (c["force_amplitude_N"] > prev["force_amplitude_N"]
                         and c["displacement_amplitude_m"] > prev["displacement_amplitude_m"]
                         and c["energy_J"] > prev["energy_J"]):
            return fail(f"not growing with the tip amplitude: {prev} -> {c}")
        prev = c
    # The loops of the CSV: one period of N_t samples each, the apparatus's force balance
    # Q = k_drive (Delta - delta), and the loop's area (trapezoids over the closed samples)
    # within 1e-3 of the summary's W (from the first harmonic: exact for the series; the
    # trapezoids of 128 samples of a degree-7 trig series are exact too, so 1e-3 is generous).
    data = np.genfromtxt(os.path.join(out, "fretting_loops.csv"), delimiter=",", names=True)
    kd = app["drive_stiffness_N_per_m"]
    for c in cycles:
        sel = data[np.isclose(data["tip_amplitude_m"], c["tip_amplitude_m"], rtol=1e-12)]
        if len(sel) != app["time_points"]:
            return fail(f"{len(sel)} samples for {c['tip_amplitude_m']}")
        theta = 2 * np.pi * np.arange(len(sel)) / len(sel)
        balance = kd * (c["tip_amplitude_m"] * np.sin(theta) - sel["delta_m"]) - sel["force_N"]
        if np.abs(balance).max() > 1e-9 * kd * c["tip_amplitude_m"]:
            return fail(f"Q != k (Delta - delta): {np.abs(balance).max()}")
        d = np.append(sel["delta_m"], sel["delta_m"][0])
        q = np.append(sel["force_N"], sel["force_N"][0])
        area = float(np.sum(0.5 * (q[1:] + q[:-1]) * np.diff(d)))
        if abs(area - c["energy_J"]) > 1e-3 * c["energy_J"]:
            return fail(f"loop area {area} against W {c['energy_J']}")
    return 0


FRETTING = TWO_BLOCKS[TWO_BLOCKS.index("\n[fretting]\n") + 1:]


def case_bad_input_fretting_without_table(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace(FRETTING, ""), "--fretting needs a [fretting] table",
               extra=["--fretting"])


def case_bad_input_fretting_grip_off_the_body(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace("point = [60, 10, 15]", "point = [55, 10, 15]"),
               "[fretting].driven: no boundary face of body \"upper\" lies in the plane",
               extra=["--fretting"])


def case_bad_input_fretting_tip_amplitudes(exe, tmp):
    return bad(exe, tmp, TWO_BLOCKS.replace('tip_amplitudes = ["3 um", "10 um"',
                                            'tip_amplitudes = ["10 um", "3 um"'),
               "`tip_amplitudes`[2] = \"3 um\": give values > 0 in ascending order",
               extra=["--fretting"])


def case_bad_input_fretting_without_rough_contact(exe, tmp):
    text = TWO_BLOCKS[:TWO_BLOCKS.index("[rough_contact]")] + FRETTING
    return bad(exe, tmp, text, "the fretting apparatus needs the rough interface")



LAP = os.path.join(HERE, "..", "..", "examples", "lap_joint_ch5", "lap_joint_ch5.toml")


def coarse_lap(tmp, tips='["0.25 um", "0.5 um", "6.75 um"]'):
    """The chapter 5 lap joint of examples/ on a coarse mesh (12 interface elements), its
    [fretting] at Table 5.5's preloads with Table 5.6's 6.75 um tip."""
    with open(LAP) as f:
        text = f.read()
    for old, new in [("size = 1.6", "size = 3.2"), ("interface_size = 0.9", "interface_size = 1.8"),
                     ("hole_size = 0.6", "hole_size = 1.2"), ("patches = 40", "patches = 12")]:
        if old not in text:
            raise AssertionError(f"{old!r} not in {LAP}")
        text = text.replace(old, new)
    start = text.index("tip_amplitudes = ")
    end = text.index("\n", start)
    text = text[:start] + "tip_amplitudes = " + tips + text[end:]
    return write(tmp, "lap.toml", text)


def case_validate_fem_rows(exe, tmp):
    """`asperity validate --fem`: twelve model-vs-experiment rows (stiffness, Table 5.6's
    delta_max, the energy-force exponent at each of the four preloads), never failures, and
    the same numbers as `asperity structure --fretting` of the case."""
    case = coarse_lap(tmp)
    p = run(exe, ["validate", "--fem", case, "--json"])
    if p.returncode != 0:
        return fail(f"exit {p.returncode}: {p.stderr}")
    j = json.loads(p.stdout)
    rows = [r for r in j["rows"] if r["quantity"].endswith("finite elements")]
    if len(rows) != 12 or any(r["kind"] != "model vs experiment" for r in rows):
        return fail(f"rows: {rows}")
    if j["failures"] != 0 or any(r["verdict"] == "FAIL" for r in rows):
        return fail("a model-vs-experiment row failed")
    q = run(exe, ["structure", case, "--fretting", "--json"])
    if q.returncode != 0:
        return fail(f"structure --fretting: {q.stderr}")
    runs = json.loads(q.stdout)["fretting"]
    k = [r["ours"] for r in rows if r["quantity"].startswith("k at")]
    d = [r["ours"] for r in rows if r["quantity"].startswith("delta_max")]
    for i, run_ in enumerate(runs):
        if abs(k[i] - run_["stiffness_N_per_m"] * 1e-6) > 1e-12 * k[i]:
            return fail(f"stiffness {k[i]} against {run_['stiffness_N_per_m']}")
        last = run_["cycles"][-1]
        if abs(d[i] - last["displacement_amplitude_m"] * 1e6) > 1e-12 * d[i]:
            return fail(f"delta_max {d[i]} against {last}")
    # Stiffer with preload (the rough interface stiffens, Eq. 4.12), and every delta_max
    # below the 6.75 um the tip imposes.
    if k != sorted(k) or not all(0 < x < 6.75 for x in d):
        return fail(f"k {k}, delta_max {d}")
    return 0


def case_bad_input_validate_fem_without_table_5_6(exe, tmp):
    case = coarse_lap(tmp, tips='["0.25 um", "0.5 um", "6 um"]')
    p = run(exe, ["validate", "--fem", case])
    if p.returncode != 2 or "tip_amplitudes with \"6.75 um\"" not in p.stderr or p.stdout:
        return fail(f"exit {p.returncode}: {p.stderr}")
    return 0


CASES = {name[len("case_"):]: fn for name, fn in globals().items() if name.startswith("case_")}

if __name__ == "__main__":
    exe, case = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory(prefix="asperity-structure-") as tmp:
        sys.exit(CASES[case](exe, tmp))
