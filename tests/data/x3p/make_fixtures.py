#!/usr/bin/env python3
"""Small ISO 5436-2 X3P files built byte by byte, independently of asperity's writer.

The X3P round trip in tests/surface/profile_io_test.cpp writes with our writer and
reads with our reader, so a mistake made the same way in both (mask bit order,
integer offset/increment, DataList formatting) would pass it. These fixtures are
written here with the standard library only (zipfile, struct, hashlib), from the
layout the openGPS ISO 5436-2 XML reference library uses, and the tests pin the
heights and invalid points they must give:

- prf_int16_offset.x3p: profile (PRF), 7 points, z type I (int16) in
  bindata/data.bin, CZ Increment 1e-9 m and Offset 2.5e-6 m, so
  z = 2.5e-6 + 1e-9 * value; x from CX Offset 1e-3 m, Increment 0.5e-6 m.
  The values include -32768, 32767 and 1234 (bytes D2 04: read big-endian it
  would be -11772).
- sur_int32_mask.x3p: areal (SUR), 5 x 3 points, z type L (int32) in
  bindata/data.bin with CZ Increment 1e-10 m, Offset 0, and bindata/valid.bin, the
  invalid-point mask: one bit per point in data order (x fastest), bit k % 8 of
  byte k // 8, least significant bit first, 1 = valid (openGPS ISO5436_2_XML,
  src/ISO5436_2_XML/cxx/valid_buffer.cxx, ValidBuffer::IsValid; the unused high
  bit of the last byte is set, as that library's writer initialises the mask to
  0xFF). Invalid points: 1, 6, 7, 12 -> bytes 0x3D 0xEF. Read most significant bit
  first, the same bytes would make points 0, 1, 6, 11 invalid.
- prf_datalist_empty.x3p: profile, 6 points, z type D inline in
  Record3/DataList, point 3 an empty <Datum/> (invalid: the openGPS writer skips
  the value of an invalid point), values with white space and an exponent.

Usage: python3 make_fixtures.py [output directory]   (default: this directory)
The archives are stored (no compression) with a fixed time stamp, so the output
is byte for byte reproducible.
"""
import hashlib
import pathlib
import struct
import sys
import zipfile

HEADER = """<?xml version="1.0" encoding="UTF-8" standalone="no" ?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:schemaLocation="http://www.opengps.eu/2008/ISO5436_2 http://www.opengps.eu/2008/ISO5436_2/ISO5436_2.xsd">
"""


def record1(feature, cx, cy, cz):
    def axis(name, axis_type, data_type, increment, offset):
        return (f"      <{name}><AxisType>{axis_type}</AxisType><DataType>{data_type}</DataType>"
                f"<Increment>{increment}</Increment><Offset>{offset}</Offset></{name}>\n")
    return ("  <Record1>\n    <Revision>ISO5436 - 2000</Revision>\n"
            f"    <FeatureType>{feature}</FeatureType>\n    <Axes>\n"
            + axis("CX", "I", "D", *cx) + axis("CY", "I", "D", *cy) + axis("CZ", "A", *cz)
            + "    </Axes>\n  </Record1>\n")


RECORD2 = """  <Record2>
    <Date>2024-01-01T00:00:00</Date>
    <Instrument><Manufacturer>tests/data/x3p/make_fixtures.py</Manufacturer><Model>none</Model><Serial>none</Serial><Version>1</Version></Instrument>
    <CalibrationDate>2024-01-01T00:00:00</CalibrationDate>
    <ProbingSystem><Type>Software</Type><Identification>fixture</Identification></ProbingSystem>
    <Comment>independent fixture for the asperity X3P reader</Comment>
  </Record2>
"""

RECORD4 = "  <Record4>\n    <ChecksumFile>md5checksum.hex</ChecksumFile>\n  </Record4>\n</p:ISO5436_2>\n"


def md5(data):
    return hashlib.md5(data).hexdigest()


def write_archive(path, members, compression=zipfile.ZIP_STORED):
    """members: [(name, bytes)] with main.xml first; md5checksum.hex is appended."""
    main = dict(members)["main.xml"]
    members = list(members) + [("md5checksum.hex", f"{md5(main)} *main.xml\n".encode())]
    with zipfile.ZipFile(path, "w", compression) as z:
        for name, data in members:
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = compression
            info.external_attr = 0o644 << 16
            z.writestr(info, data)


def dimension(sx, sy):
    return (f"    <MatrixDimension><SizeX>{sx}</SizeX><SizeY>{sy}</SizeY>"
            "<SizeZ>1</SizeZ></MatrixDimension>\n")


# The values below are repeated, as expected heights, in tests/surface/profile_io_test.cpp
# (X3pIndependentFixtures) and tests/python/test_surface.py.
PRF_INT16_VALUES = [-32768, -1, 0, 1, 1234, -1234, 32767]
SUR_INT32_VALUES = [1000 * k - 7000 for k in range(15)]
SUR_INVALID = {1, 6, 7, 12}
DATALIST_TEXT = ["1.5e-6", "-2.25E-06", None, " 3.0e-6 ", "4e-7", "0"]


def prf_int16_offset():
    data = struct.pack("<7h", *PRF_INT16_VALUES)
    xml = (HEADER + record1("PRF", ("5.0e-7", "1.0e-3"), ("5.0e-7", "0"), ("I", "1.0e-9", "2.5e-6"))
           + RECORD2 + "  <Record3>\n" + dimension(7, 1)
           + "    <DataLink>\n      <PointDataLink>bindata/data.bin</PointDataLink>\n"
           + f"      <MD5ChecksumPointData>{md5(data)}</MD5ChecksumPointData>\n"
           + "    </DataLink>\n  </Record3>\n" + RECORD4).encode()
    return [("main.xml", xml), ("bindata/data.bin", data)]


def mask_bytes(n, invalid):
    mask = bytearray(b"\xff" * ((n + 7) // 8))
    for k in invalid:
        mask[k // 8] &= ~(1 << (k % 8)) & 0xFF
    return bytes(mask)


def sur_int32_mask():
    values = [0 if k in SUR_INVALID else v for k, v in enumerate(SUR_INT32_VALUES)]
    data = struct.pack("<15i", *values)
    mask = mask_bytes(15, SUR_INVALID)
    assert mask == b"\x3d\xef", mask.hex()
    xml = (HEADER + record1("SUR", ("1.0e-6", "0"), ("2.0e-6", "5.0e-6"), ("L", "1.0e-10", "0"))
           + RECORD2 + "  <Record3>\n" + dimension(5, 3)
           + "    <DataLink>\n      <PointDataLink>bindata/data.bin</PointDataLink>\n"
           + f"      <MD5ChecksumPointData>{md5(data)}</MD5ChecksumPointData>\n"
           + "      <ValidPointsLink>bindata/valid.bin</ValidPointsLink>\n"
           + f"      <MD5ChecksumValidPoints>{md5(mask)}</MD5ChecksumValidPoints>\n"
           + "    </DataLink>\n  </Record3>\n" + RECORD4).encode()
    return [("main.xml", xml), ("bindata/data.bin", data), ("bindata/valid.bin", mask)]


def prf_datalist_empty():
    datums = "".join("\n      <Datum/>" if t is None else f"\n      <Datum>{t}</Datum>"
                     for t in DATALIST_TEXT)
    xml = (HEADER + record1("PRF", ("2.0e-6", "0"), ("2.0e-6", "0"), ("D", "1", "0"))
           + RECORD2 + "  <Record3>\n" + dimension(6, 1)
           + f"    <DataList>{datums}\n    </DataList>\n  </Record3>\n" + RECORD4).encode()
    return [("main.xml", xml)]


FIXTURES = {
    "prf_int16_offset.x3p": prf_int16_offset,
    "sur_int32_mask.x3p": sur_int32_mask,
    "prf_datalist_empty.x3p": prf_datalist_empty,
}


def main():
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(__file__).parent
    out.mkdir(parents=True, exist_ok=True)
    for name, build in FIXTURES.items():
        write_archive(out / name, build())
        print(out / name)


if __name__ == "__main__":
    main()
