"""Writes the topography fixtures of crates/tribo-case/src/topography/tests.rs.

Run from this directory with a Python that has numpy (the .npy files are written by numpy's
own writer, numpy.lib.format, so the reader is tested against numpy rather than against
itself). The X3P archives are written from ISO 25178-72 / the openGPS layout with the
standard library's zipfile: main.xml, bindata/data.bin (little-endian), the optional
bindata/valid.bin (one bit per point, least significant bit first, set = valid) and
md5checksum.hex.

Checked with an independent reader, surfalize 0.19.2 from PyPI (`Surface.load`): the
D, F, I (with the valid-points buffer) and L archives read as 4 rows (y) x 5 columns (x),
steps 0.5 and 0.25 um, the heights h(i, j) below and NaN at the same invalid points.

Every grid is nx = 5 points along x by ny = 4 along y, heights
h(i, j) = 1e-7 (i + 10 j) + 1e-8 i j (m), point (i, j) at (i dx, j dy).
"""

import hashlib
import io
import struct
import zipfile

import numpy as np

NX, NY = 5, 4
DX, DY = 0.5e-6, 0.25e-6


def h(i, j):
    return 1e-7 * (i + 10 * j) + 1e-8 * i * j


GRID = np.array([[h(i, j) for i in range(NX)] for j in range(NY)])  # rows along y


def main_xml(dtype, z_inc, z_off, data_link=None, valid_link=None, data_list=None,
             data_md5="", valid_md5="", feature="SUR", x_axis="I", size_z=1):
    z = f"<AxisType>A</AxisType><DataType>{dtype}</DataType>"
    if z_inc is not None:
        z += f"<Increment>{z_inc!r}</Increment><Offset>{z_off!r}</Offset>"
    if data_link is not None:
        record3_data = (f"<DataLink><PointDataLink>{data_link}</PointDataLink>"
                        f"<MD5ChecksumPointData>{data_md5}</MD5ChecksumPointData>")
        if valid_link is not None:
            record3_data += (f"<ValidPointsLink>{valid_link}</ValidPointsLink>"
                             f"<MD5ChecksumValidPoints>{valid_md5}</MD5ChecksumValidPoints>")
        record3_data += "</DataLink>"
    else:
        record3_data = "<DataList>" + "".join(f"<Datum>{d}</Datum>" for d in data_list) + "</DataList>"
    return f"""<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2" xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:schemaLocation="http://www.opengps.eu/2008/ISO5436_2 http://www.opengps.eu/2008/ISO5436_2/ISO5436_2.xsd">
  <Record1>
    <Revision>ISO5436 - 2000</Revision>
    <FeatureType>{feature}</FeatureType>
    <Axes>
      <CX><AxisType>{x_axis}</AxisType><DataType>D</DataType><Increment>{DX!r}</Increment><Offset>0.0</Offset></CX>
      <CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{DY!r}</Increment><Offset>0.0</Offset></CY>
      <CZ>{z}</CZ>
    </Axes>
  </Record1>
  <Record2>
    <Date>2026-11-25T00:00:00+00:00</Date>
    <Instrument><Manufacturer>tribo</Manufacturer><Model>fixture</Model><Serial>0</Serial><Version>1</Version></Instrument>
    <CalibrationDate>2026-11-25T00:00:00+00:00</CalibrationDate>
    <ProbingSystem><Type>NonContacting</Type><Identification>none</Identification></ProbingSystem>
    <Comment>test fixture of crates/tribo-case/src/topography</Comment>
  </Record2>
  <Record3>
    <MatrixDimension><SizeX>{NX}</SizeX><SizeY>{NY}</SizeY><SizeZ>{size_z}</SizeZ></MatrixDimension>
    {record3_data}
  </Record3>
  <Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>
""".encode()


def write_x3p(name, xml, files, compression=zipfile.ZIP_DEFLATED, skip_main=False):
    with zipfile.ZipFile(name, "w", compression) as z:
        if not skip_main:
            z.writestr("main.xml", xml)
            z.writestr("md5checksum.hex", f"{hashlib.md5(xml).hexdigest()} *main.xml\n")
        for n, b in files.items():
            z.writestr(n, b)


def x3p_fixtures():
    # D: float64, x fastest (row j = y index), one NaN (invalid) at (i, j) = (2, 1).
    vals = GRID.copy()
    vals[1, 2] = np.nan
    data = vals.astype("<f8").tobytes()  # C order of [j, i]: x fastest
    write_x3p("grid_d.x3p", main_xml("D", 1.0, 0.0, "bindata/data.bin", data_md5=hashlib.md5(data).hexdigest()),
              {"bindata/data.bin": data})
    # F: float32, no Increment/Offset (defaults 1, 0).
    data = GRID.astype("<f4").tobytes()
    write_x3p("grid_f.x3p", main_xml("F", None, None, "bindata/data.bin"), {"bindata/data.bin": data})
    # I: int16 counts of 1 nm with an offset of 5 nm, and a valid-points buffer marking
    # (i, j) = (4, 0) and (0, 3) invalid; stored uncompressed.
    counts = np.rint((GRID - 5e-9) / 1e-9).astype("<i2")
    valid = np.ones(NX * NY, dtype=bool)
    valid[0 * NX + 4] = False
    valid[3 * NX + 0] = False
    bits = np.packbits(valid, bitorder="little").tobytes()
    write_x3p("grid_i_valid.x3p",
              main_xml("I", 1e-9, 5e-9, "bindata/data.bin", valid_link="bindata/valid.bin"),
              {"bindata/data.bin": counts.tobytes(), "bindata/valid.bin": bits},
              compression=zipfile.ZIP_STORED)
    # L: int32 counts of 0.1 nm.
    counts = np.rint(GRID / 1e-10).astype("<i4")
    write_x3p("grid_l.x3p", main_xml("L", 1e-10, 0.0, "bindata/data.bin"), {"bindata/data.bin": counts.tobytes()})
    # Inline DataList, D, with an empty Datum (invalid) at (1, 2).
    datums = [repr(float(GRID[j, i])) if (i, j) != (1, 2) else "" for j in range(NY) for i in range(NX)]
    write_x3p("grid_list.x3p", main_xml("D", 1.0, 0.0, data_list=datums), {})
    # Broken ones.
    data = GRID.astype("<f8").tobytes()
    write_x3p("no_main.x3p", b"", {"bindata/data.bin": data}, skip_main=True)
    write_x3p("short_data.x3p", main_xml("D", 1.0, 0.0, "bindata/data.bin"), {"bindata/data.bin": data[:-8]})
    write_x3p("profile.x3p", main_xml("D", 1.0, 0.0, "bindata/data.bin", feature="PRF"), {"bindata/data.bin": data})
    write_x3p("absolute_x.x3p", main_xml("D", 1.0, 0.0, "bindata/data.bin", x_axis="A"), {"bindata/data.bin": data})
    write_x3p("bad_dtype.x3p", main_xml("Q", 1.0, 0.0, "bindata/data.bin"), {"bindata/data.bin": data})
    with open("grid_d.x3p", "rb") as f:
        whole = f.read()
    with open("truncated.x3p", "wb") as f:
        f.write(whole[: len(whole) // 2])
    checksum_fixtures()


def checksum_fixtures():
    """grid_d.x3p with a corrupted checksum: of the point data (one height changed after the
    MD5 was taken) and of main.xml (md5checksum.hex of another text), from grid_d.x3p's
    entries."""
    with zipfile.ZipFile("grid_d.x3p") as z:
        xml, data = z.read("main.xml"), z.read("bindata/data.bin")
    corrupt = bytearray(data)
    corrupt[0] ^= 0x01  # the first height's lowest mantissa bit
    write_x3p("bad_md5_data.x3p", xml, {"bindata/data.bin": bytes(corrupt)})
    with zipfile.ZipFile("bad_md5_main.x3p", "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("main.xml", xml)
        z.writestr("md5checksum.hex", f"{hashlib.md5(xml + b' ').hexdigest()} *main.xml\n")
        z.writestr("bindata/data.bin", data)


def npy_fixtures():
    def save(name, arr, version=None):
        with open(name, "wb") as f:
            np.lib.format.write_array(f, arr, version=version)

    save("c_f8.npy", GRID.astype("<f8"))
    save("fortran_f4_big.npy", np.asfortranarray(GRID.astype(">f4")))
    save("c_i4_nm.npy", np.rint(GRID / 1e-9).astype("<i4"))  # heights in nm
    save("v2_f8.npy", GRID.astype("<f8"), version=(2, 0))
    save("v3_f8_big.npy", GRID.astype(">f8"), version=(3, 0))
    save("three_d.npy", np.zeros((2, 2, 2)))
    save("f2.npy", GRID.astype("<f2"))
    with open("c_f8.npy", "rb") as f:
        whole = f.read()
    with open("short.npy", "wb") as f:
        f.write(whole[:-8])


def ascii_fixtures():
    rows = "\n".join(" ".join(f"{GRID[j, i] * 1e6:.6f}" for i in range(NX)) for j in range(NY))
    with open("tribo_header.txt", "w") as f:
        f.write("# tribo topography\n# dx: 0.5 um\n# dy: 250 nm\n# Value units: um\n" + rows + "\n")
    rows_m = "\n".join("\t".join(repr(float(GRID[j, i])) for i in range(NX)) for j in range(NY))
    with open("gwyddion.txt", "w") as f:
        # Gwyddion's "ASCII data matrix" export with the informational header: the real size
        # is points times spacing (2.5 um = 5 x 0.5 um, 1 um = 4 x 0.25 um).
        f.write("# Channel: Height\n# Width: 2.500 µm\n# Height: 1.000 µm\n# Value units: m\n" + rows_m + "\n")
    rows_c = "\n".join(",".join(repr(float(GRID[j, i])) if (i, j) != (3, 1) else "NaN" for i in range(NX)) for j in range(NY))
    with open("headerless.csv", "w") as f:
        f.write(rows_c + "\n")
    with open("ragged.csv", "w") as f:
        f.write("1,2,3\n4,5,6\n7,8\n")


if __name__ == "__main__":
    x3p_fixtures()
    npy_fixtures()
    ascii_fixtures()
