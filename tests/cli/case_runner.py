"""The command line of the tests/cli/*_cases.py scripts: `SCRIPT ASPERITY_EXE SOURCE_DIR CASE`
runs the script's function `case_CASE(exe, src, tmp)` in a fresh temporary directory; a
failed `check` prints FAIL and the message and exits 1."""
import os
import sys
import tempfile


class Failure(Exception):
    pass


def check(cond, msg):
    if not cond:
        raise Failure(msg)


def main(namespace):
    """Runs the case named on the command line among the `case_*` functions of `namespace`
    (a script's globals())."""
    cases = {name[5:]: fn for name, fn in namespace.items() if name.startswith("case_")}
    if len(sys.argv) != 4 or sys.argv[3] not in cases:
        print(f"usage: {sys.argv[0]} ASPERITY_EXE SOURCE_DIR CASE ({', '.join(cases)})",
              file=sys.stderr)
        return 1
    exe, src, name = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2]), sys.argv[3]
    with tempfile.TemporaryDirectory() as tmp:
        try:
            cases[name](exe, src, tmp)
        except Failure as e:
            print("FAIL:", e, file=sys.stderr)
            return 1
    print("ok")
    return 0
