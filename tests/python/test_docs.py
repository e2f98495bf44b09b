"""Every fenced code block of README.md, docs/*.md and examples/**/*.md runs, so that a doc
cannot drift from the code. The convention (docs/architecture.md, "Docs that run"):

* ```sh (or bash) blocks run with bash -e -o pipefail, ```python blocks with this
  interpreter, each in a fresh temporary directory holding copies of examples/,
  tests/data/ and scripts/, with `asperity` (the CLI of this build or of the installed
  wheel) first on PATH and also at build/release/src/cli/asperity, the README's path.
  Each block stands alone (no state is shared between blocks).
* ```toml and ```json blocks are parsed.
* ```text blocks are output listings or diagrams, never run.
* A block that must not run carries `<!-- no-run: REASON -->` on the line before its
  opening fence; the reason is required. Any other block (no language, or a language not
  listed) is an error, so a new page cannot add an unchecked block by accident.

The command comes from ASPERITY_CLI (ctest sets it to the build's executable) or, for an
installed wheel, from next to the interpreter.
"""
from __future__ import annotations

import json
import os
import pathlib
import re
import shutil
import subprocess
import sys
import tomllib
from dataclasses import dataclass

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
RUN = {"sh": "sh", "bash": "sh", "python": "python"}
PARSE = {"toml", "json"}
LISTING = {"text"}
NO_RUN = re.compile(r"^\s*<!--\s*no-run:\s*(?P<reason>.*?)\s*-->\s*$")
FENCE = re.compile(r"^(?P<indent>\s*)(?P<fence>```+|~~~+)\s*(?P<info>[^`]*)$")
TIMEOUT = 600  # seconds per block; the slowest block (README's command line) takes ~10 s


@dataclass
class Block:
    path: pathlib.Path
    line: int  # of the opening fence, 1-based
    language: str
    code: str
    no_run: str | None  # the reason, when marked

    @property
    def id(self) -> str:
        return f"{self.path.relative_to(ROOT)}:{self.line}"


def doc_files() -> list[pathlib.Path]:
    files = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")),
             *sorted((ROOT / "examples").rglob("*.md"))]
    return [f for f in files if f.is_file()]


def blocks_of(path: pathlib.Path) -> list[Block]:
    lines = path.read_text(encoding="utf-8").splitlines()
    out, i = [], 0
    while i < len(lines):
        m = FENCE.match(lines[i])
        if not m:
            i += 1
            continue
        fence, indent = m.group("fence"), len(m.group("indent"))
        info = m.group("info").strip()
        previous = next((lines[k] for k in range(i - 1, -1, -1) if lines[k].strip()), "")
        marker = NO_RUN.match(previous)
        body, j = [], i + 1
        while j < len(lines):
            close = lines[j].strip()
            if close.startswith(fence[0] * len(fence)) and not close.strip(fence[0]):
                break
            body.append(lines[j][indent:] if lines[j][:indent].isspace() else lines[j])
            j += 1
        if j == len(lines):
            raise AssertionError(f"{path}:{i + 1}: fenced block never closed")
        out.append(Block(path, i + 1, info.split()[0] if info else "", "\n".join(body) + "\n",
                         marker.group("reason") if marker else None))
        i = j + 1
    return out


ALL_BLOCKS = [b for f in doc_files() for b in blocks_of(f)]


def asperity_command() -> pathlib.Path:
    if os.environ.get("ASPERITY_CLI"):
        return pathlib.Path(os.environ["ASPERITY_CLI"]).resolve()
    installed = pathlib.Path(sys.executable).parent / "asperity"
    if installed.is_file():
        return installed
    found = shutil.which("asperity")
    if found:
        return pathlib.Path(found)
    raise AssertionError("no asperity command: set ASPERITY_CLI or pip install the package")


def workspace(tmp: pathlib.Path) -> dict:
    """A directory laid out like the repository for the paths the docs use; the environment."""
    shutil.copytree(ROOT / "examples", tmp / "examples")
    shutil.copytree(ROOT / "tests" / "data", tmp / "tests" / "data")
    shutil.copytree(ROOT / "scripts", tmp / "scripts")
    exe = asperity_command()
    for link in (tmp / ".bin" / "asperity", tmp / "build" / "release" / "src" / "cli" / "asperity"):
        link.parent.mkdir(parents=True, exist_ok=True)
        link.symlink_to(exe)
    env = dict(os.environ)
    env["PATH"] = os.pathsep.join([str(tmp / ".bin"), str(pathlib.Path(sys.executable).parent),
                                   env.get("PATH", "")])
    env["MPLBACKEND"] = "Agg"
    # The asperity package this test imports (a build tree on a relative PYTHONPATH, or the
    # installed one), whatever the block's working directory.
    import asperity

    package_parent = str(pathlib.Path(asperity.__file__).resolve().parent.parent)
    env["PYTHONPATH"] = os.pathsep.join(
        [package_parent] + [str(pathlib.Path(p).resolve())
                            for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
    return env


def test_every_block_follows_the_convention():
    problems = []
    for b in ALL_BLOCKS:
        if b.no_run is not None:
            if not b.no_run:
                problems.append(f"{b.id}: <!-- no-run: --> without a reason")
        elif b.language not in RUN and b.language not in PARSE and b.language not in LISTING:
            problems.append(
                f"{b.id}: a ```{b.language or '(no language)'} block: tag it sh or python (run), "
                "toml or json (parsed), text (an output listing or diagram), or put "
                "<!-- no-run: REASON --> on the line before it")
    assert not problems, "\n".join(problems)
    assert sum(b.language in RUN and b.no_run is None for b in ALL_BLOCKS) >= 8


RUNNABLE = [b for b in ALL_BLOCKS if b.no_run is None and b.language in RUN]
PARSED = [b for b in ALL_BLOCKS if b.no_run is None and b.language in PARSE]


@pytest.mark.parametrize("block", RUNNABLE, ids=[b.id for b in RUNNABLE])
def test_block_runs(block, tmp_path):
    env = workspace(tmp_path)
    if RUN[block.language] == "sh":
        cmd = ["bash", "-e", "-o", "pipefail", "-c", block.code]
    else:
        cmd = [sys.executable, "-c", block.code]
    r = subprocess.run(cmd, cwd=tmp_path, env=env, capture_output=True, text=True,
                       timeout=TIMEOUT)
    assert r.returncode == 0, (f"{block.id} exited {r.returncode}\n--- block ---\n{block.code}"
                               f"--- stdout ---\n{r.stdout[-3000:]}\n--- stderr ---\n"
                               f"{r.stderr[-3000:]}")


@pytest.mark.parametrize("block", PARSED, ids=[b.id for b in PARSED])
def test_block_parses(block):
    if block.language == "toml":
        tomllib.loads(block.code)
    else:
        json.loads(block.code)


def test_the_parser_sees_markers_and_listings(tmp_path):
    doc = tmp_path / "page.md"
    doc.write_text("text\n\n<!-- no-run: installs packages -->\n```sh\napt-get install x\n```\n"
                   "\n```text\n$ asperity\n```\n  ```python\n  print(1)\n  ```\n")
    b = blocks_of(doc)
    assert [(x.language, x.no_run, x.line) for x in b] == [
        ("sh", "installs packages", 4), ("text", None, 8), ("python", None, 11)]
    assert b[2].code == "print(1)\n"
