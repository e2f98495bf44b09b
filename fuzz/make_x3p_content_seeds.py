#!/usr/bin/env python3
"""Seeds of fuzz/x3p_content_fuzz.cpp from the shipped X3P files.

Each archive of tests/data/x3p/ and fuzz/corpus/x3p/ becomes one seed: main.xml with
the MD5s of bindata/data.bin and bindata/valid.bin replaced by the placeholders
{md5:data} and {md5:valid}, then "\\0data.bin\\0" and the point data, then
"\\0valid.bin\\0" and the mask (the layout x3p_content_fuzz.cpp splits).

Usage: python3 fuzz/make_x3p_content_seeds.py   (writes fuzz/corpus/x3p_content/)
"""
import hashlib
import pathlib
import zipfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
SOURCES = [ROOT / "tests" / "data" / "x3p", ROOT / "fuzz" / "corpus" / "x3p"]
OUT = ROOT / "fuzz" / "corpus" / "x3p_content"


def seed(path):
    with zipfile.ZipFile(path) as z:
        names = set(z.namelist())
        xml = z.read("main.xml")
        data = z.read("bindata/data.bin") if "bindata/data.bin" in names else None
        valid = z.read("bindata/valid.bin") if "bindata/valid.bin" in names else None
    out = xml
    if data is not None:
        out = out.replace(hashlib.md5(data).hexdigest().encode(), b"{md5:data}")
    if valid is not None:
        out = out.replace(hashlib.md5(valid).hexdigest().encode(), b"{md5:valid}")
    if data is not None:
        out += b"\0data.bin\0" + data
        if valid is not None:
            out += b"\0valid.bin\0" + valid
    return out


def main():
    OUT.mkdir(parents=True, exist_ok=True)
    for d in SOURCES:
        for path in sorted(d.glob("*.x3p")):
            target = OUT / (path.stem + ".bin")
            target.write_bytes(seed(path))
            print(target)


if __name__ == "__main__":
    main()
