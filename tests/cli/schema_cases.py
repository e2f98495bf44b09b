"""The JSON of every command against its JSON Schema (docs/schema/<command>.schema.json).

Usage: schema_cases.py ASPERITY SOURCE_DIR COMMAND. Exit 0 on success. Needs the
`jsonschema` package (python/requirements.txt): without it the test fails, it does not skip.

Adding a command: its schema under docs/schema/ (CMake makes the test from the file name)
and one line in INVOCATIONS below.
"""
import atexit
import json
import os
import shutil
import subprocess
import sys
import tempfile

import jsonschema

exe, src, command = sys.argv[1], sys.argv[2], sys.argv[3]

MATERIALS = ["--E1", "207GPa", "--nu1", "0.3", "--G1", "82.7GPa", "--E2", "207GPa", "--nu2", "0.3",
             "--G2", "82.7GPa", "--H", "6.83GPa"]
STEEL420 = ["--E1", "200GPa", "--nu1", "0.24", "--G1", "80.7GPa", "--E2", "200GPa", "--nu2", "0.24",
            "--G2", "80.7GPa", "--H", "5.8GPa", "--sigma", "2.677um", "--eta", "2.91e-4um^-2",
            "--R", "30.14um", "--area", "170mm^2", "--P", "526N"]
CASE = "examples/joints/steel420_two_bolts.toml"
SYNTH = ["synthesize", CASE, "--imposed", "6.75um", "--P", "526N", "--out"]

# One line per command: invocations run in SOURCE_DIR ({tmp}: a scratch directory). An
# invocation of the command itself must print its JSON on stdout, which is validated;
# an invocation of another command comes first and only prepares inputs.
INVOCATIONS = {
    "sphere": [MATERIALS + ["--R1", "2.5mm", "--P", "35N", "--mu-cfc", "0.284", "--delta-max", "1.5um", "--json"], MATERIALS + ["--R1", "2.5mm", "--omega-star", "0.5", "--model", "KE", "--Q-max", "1N", "--json"], ["--E1", "207GPa", "--nu1", "0.1", "--E2", "207GPa", "--nu2", "0.1", "--H", "6.83GPa", "--R1", "2.5mm", "--P", "35N", "--mu-cfc", "0.284", "--json"]],
    "flat": [["--beta", "0.04", "--psi", "0.5", "--nu", "0.3", "--P-star", "1e-3", "--delta-star-max", "0.6", "--json"], ["--beta", "0.04", "--psi", "2", "--nu", "0.3", "--P-star", "1e-3", "--model", "ceb", "--json"], STEEL420 + ["--delta-max", "1um", "--json"]],
    "roughness": [["--surface", "examples/roughness/pzt_max.csv,examples/roughness/pzt_min.csv", "--surface", "examples/roughness/lc_max.csv,examples/roughness/lc_min.csv", "--E", "200GPa", "--nu", "0.24", "--H", "5.8GPa", "--json"], ["--params", "sigma=1.763um,eta=3.34e-4um^-2,R=40.76um", "--surface", "tests/data/mountainsmap-650x650.x3p", "--end", "regression", "--ls", "2um", "--lc", "none", "--json"], ["--surface", "tests/data/mountainsmap-650x650.x3p", "--lc", "26.5um", "--ls", "1.6um", "--spikes", "8", "--json"], ["--surface", "tests/data/mountainsmap-650x650.x3p", "--lc", "26.5um", "--ls", "1.6um", "--summits", "{tmp}/summits.csv", "--json"]],
    "predict": [[CASE, "--json"], ["examples/joints/steel_smooth.toml", "--json"], ["examples/joints/steel420_profiles.toml", "--out", "-"], ["examples/joints/steel420_bolt_field.toml", "--json"]],
    "analyze": [SYNTH + ["{tmp}/a.csv"], ["synthesize", CASE, "--imposed", "2um", "--P", "526N", "--seed", "2", "--out", "{tmp}/b.csv"], ["{tmp}/a.csv", "--P", "526N", "--model", CASE, "--json"], ["{tmp}/a.csv", "{tmp}/b.csv", "--P", "526N", "--json"], ["{tmp}/a.csv", "{tmp}/b.csv", "--P", "526N", "--fit", "iwan4", "--json"], ["{tmp}/a.csv", "--P", "526N", "--fit", "jenkins", "--json"]],
    "synthesize": [[CASE, "--imposed", "6.75um", "--out", "{tmp}/s.csv", "--json"], [CASE, "--imposed", "2um", "--no-imposed", "--out", "{tmp}/t.csv", "--json"]],
    "validate": [["--json"]],
    "dynamics": [[f"examples/dynamics/{n}.toml", "--json"] for n in ["impulse_dankowicz", "ramp_dankowicz_soft", "harmonic_mindlin", "impulse_joint_steel420", "impulse_none"]],
    "vibration": [[f"examples/vibration/{n}.toml", "--json"] for n in ["jenkins_sdof", "steel420_sdof", "steel420_2dof", "duffing_force_sweep", "duffing_phase_resonance", "duffing_superharmonic", "rough_contact_3d", "jenkins_backbone_rom"]] + [["examples/vibration/steel420_2dof.toml", "--json", "--stability"]],
    "structure": [["examples/structures/two_blocks.toml", "--json"], ["examples/structures/two_blocks.toml", "--fretting", "--json"]],
}

schema_path = os.path.join(src, "docs", "schema", f"{command}.schema.json")
with open(schema_path) as f:
    schema = json.load(f)
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)
if command not in INVOCATIONS:
    sys.exit(f"{schema_path} has no invocations: add a line for {command!r} to INVOCATIONS in {__file__}")

tmp = tempfile.mkdtemp(prefix="asperity-schema-")
atexit.register(shutil.rmtree, tmp, ignore_errors=True)  # no directory left per run
checked = 0
for args in INVOCATIONS[command]:
    args = [a.replace("{tmp}", tmp) for a in args]
    if args[0] not in INVOCATIONS or args[0] == command:  # the command itself
        args = [command] + args if args[0] != command else args
        validate = True
    else:
        validate = False
    p = subprocess.run([exe, *args], capture_output=True, text=True, cwd=src, timeout=600)
    if p.returncode not in (0, 1 if command == "validate" else 0):
        sys.exit(f"{args}: exit {p.returncode}\n{p.stderr}")
    if not validate:
        continue
    try:
        doc = json.loads(p.stdout)
    except json.JSONDecodeError as e:
        sys.exit(f"{args}: stdout is not JSON ({e}):\n{p.stdout[:500]}")
    errors = sorted(validator.iter_errors(doc), key=lambda e: list(e.path))
    if errors:
        sys.exit(f"{args}: does not follow {schema_path}:\n" + "\n".join(
            f"  at /{'/'.join(map(str, e.path))}: {e.message[:300]}" for e in errors[:20]))
    checked += 1
if checked == 0:
    sys.exit(f"no invocation of {command} was validated")
print(f"{command}: {checked} outputs follow {schema_path}")
