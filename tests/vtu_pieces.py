#!/usr/bin/python3
"""Output/Cells per VTU piece: a body's fields written in several .vtu
pieces per rank (by concurrent tasks) hold exactly what one piece per rank
holds.

Runs blocks (P1 triangles, two uniform cycles) twice with the same ranks:
with 'Cells per VTU piece = 0' (one piece per rank) and with 50 cells per
piece. For every body and cycle it checks that the .pvtu lists pieces
numbered 0 ... n-1 that all exist, none with more than 50 cells, at least
ceil(cells / 50) of them and at most one more per further rank, and that
the pieces' points with all their field values, decoded (zlib), are the
same multiset as in the single-piece run, bit for bit (on several ranks,
whose solves agree to round-off only, to round-off). No temporary file
may be left behind, and a later run into the same directory with one
piece per rank, written in the foreground (Output/Write in background =
false), removes the extra pieces and writes the first run's .vtu files
byte for byte (bodies and contact; to round-off on several ranks). A piece that cannot be written
stops the run with a message naming it; the other pieces' temporary
files are removed and the earlier cycle stays intact.

usage: vtu_pieces.py [--mpiexec MPIEXEC --ranks N] EXE OUTPUT_DIR
"""

import argparse
import base64
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ElementTree
import zlib

from coulomb_adapt_run import report

MAX_CELLS = 50


def run(args, directory, cells_per_piece, clean=True, must_succeed=True,
        background=True):
    if clean:
        shutil.rmtree(directory, ignore_errors=True)
        os.makedirs(directory)
    settings = {
        "Scene/Name": "blocks",
        "Scene/Blocks/Upper body subdivisions": "2, 2",
        "Scene/Blocks/Lower body subdivisions": "4, 4",
        "Contact/Friction coefficient": "0.3",
        "Mesh/Cell type": "triangle",
        "Adaptation/Strategy": "uniform",
        "Adaptation/Target error": "0",
        "Adaptation/Number of cycles": "2",
        "Output/Cells per VTU piece": str(cells_per_piece),
        "Output/Write in background": "true" if background else "false",
        "Output/Output directory": directory,
    }
    command = [args.exe]
    if args.mpiexec:
        command = [args.mpiexec, "-np", str(args.ranks)] + command
    for key, value in settings.items():
        command += ["-s", key + "=" + value]
    result = subprocess.run(command, capture_output=True, text=True)
    if must_succeed and result.returncode != 0:
        sys.exit("run failed (%s):\n%s%s" %
                 (" ".join(command), result.stdout, result.stderr))
    return result


def decode(text):
    """A deal.II binary DataArray, zlib-compressed: the base64 header of
    four UInt32 (1 block, its size twice, the compressed size), then the
    base64 of the compressed block."""
    text = text.strip()
    header = base64.b64decode(text[:24])
    n_blocks, size, last_size, compressed_size = struct.unpack("<4I", header)
    if n_blocks != 1:
        sys.exit("unexpected number of compressed blocks: %d" % n_blocks)
    data = zlib.decompress(base64.b64decode(text[24:]))
    if len(data) != size:
        sys.exit("decompressed size %d, header says %d" % (len(data), size))
    return data


def point_rows(path):
    """The cells' count and the points' rows (coordinates, then every
    point field), as tuples of the stored 32-bit floats."""
    piece = ElementTree.parse(path).getroot().find("UnstructuredGrid/Piece")
    n_points = int(piece.get("NumberOfPoints"))
    n_cells = int(piece.get("NumberOfCells"))
    columns = []
    arrays = [piece.find("Points/DataArray")] + \
        list(piece.find("PointData") if piece.find("PointData") is not None
             else [])
    for array in arrays:
        if n_points == 0:
            break
        n_components = int(array.get("NumberOfComponents", "1"))
        values = struct.unpack("<%df" % (n_points * n_components),
                               decode(array.text))
        for c in range(n_components):
            columns.append(values[c::n_components])
    rows = list(zip(*columns)) if columns else []
    return n_cells, rows


# Two runs on several ranks agree to round-off only: the same settings
# gave solutions differing by 4.6e-15 (against 4.68) in a tangential
# traction, 3.6e-17 in a displacement near 0 and 2.2e-18 in gaps of
# closed nodes (at most 1.9e-18) in one run of 25 (an order of summation
# that varies between runs). Their 32-bit fields then differ by a
# rounding of the last bit at most, or by such tiny values near 0:
# compared to ROUND_OFF of each column's largest value, plus NOISE of the
# largest value of the whole file (a column of round-off values, such as
# those gaps). A wrong, missing or misplaced value differs by far more. On
# one rank the runs must agree bit for bit.
ROUND_OFF = 1e-6
NOISE = 1e-14


def same_rows(rows_a, rows_b, exact):
    """Whether two lists of point rows hold the same points with the same
    fields: bit for bit if @p exact, otherwise to round-off (above). The
    points' coordinates (the first three columns) come from the mesh and
    agree bit for bit; the rows at one point (one per cell around it) are
    matched to round-off, whatever their order."""
    if exact or len(rows_a) != len(rows_b):
        return sorted(rows_a) == sorted(rows_b)
    n_columns = len(rows_a[0]) if rows_a else 0
    scales = [max(abs(r[c]) for r in rows_a + rows_b)
              for c in range(n_columns)]
    largest = max(scales, default=0)
    tolerances = [ROUND_OFF * scale + NOISE * largest for scale in scales]

    def close(a, b):
        return all(abs(x - y) <= t for x, y, t in zip(a, b, tolerances))

    at_point = {}
    for row in rows_b:
        at_point.setdefault(row[:3], []).append(row)
    for row in rows_a:
        candidates = at_point.get(row[:3], [])
        match = next((i for i, b in enumerate(candidates) if close(row, b)),
                     None)
        if match is None:
            return False
        candidates.pop(match)
    return True


def pieces_of(directory, record):
    root = ElementTree.parse(os.path.join(directory, record)).getroot()
    return [p.get("Source") for p in root.iter("Piece")]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mpiexec")
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("exe")
    parser.add_argument("output")
    args = parser.parse_args()

    whole = os.path.join(args.output, "one_piece_per_rank")
    split = os.path.join(args.output, "pieces")
    run(args, whole, 0)
    run(args, split, MAX_CELLS)

    failures = []
    for body in ("body-1", "body-2"):
        for cycle in (0, 1):
            stem = "%s_%03d" % (body, cycle)
            whole_pieces = pieces_of(whole, stem + ".pvtu")
            split_pieces = pieces_of(split, stem + ".pvtu")
            n = len(split_pieces)
            digits = len(str(n - 1)) if n > 1 else 1
            expected_names = ["%s.%0*d.vtu" % (stem, digits, p)
                              for p in range(n)]
            if split_pieces != expected_names:
                failures.append("%s.pvtu lists %s, expected %s" %
                                (stem, split_pieces, expected_names))
                continue
            cells_whole, rows_whole = 0, []
            for name in whole_pieces:
                c, r = point_rows(os.path.join(whole, name))
                cells_whole += c
                rows_whole += r
            cells_split, rows_split, largest = 0, [], 0
            for name in split_pieces:
                c, r = point_rows(os.path.join(split, name))
                cells_split += c
                rows_split += r
                largest = max(largest, c)
            fewest = math.ceil(cells_whole / MAX_CELLS)
            most = fewest + args.ranks - 1
            print("%s: %d cells, %d pieces of at most %d cells "
                  "(one per rank: %d)" %
                  (stem, cells_split, n, largest, len(whole_pieces)))
            if cells_split != cells_whole:
                failures.append("%s: %d cells in the pieces, %d in one per "
                                "rank" % (stem, cells_split, cells_whole))
            if largest > MAX_CELLS:
                failures.append("%s: a piece has %d cells > %d" %
                                (stem, largest, MAX_CELLS))
            if not fewest <= n <= most:
                failures.append("%s: %d pieces, expected %d ... %d" %
                                (stem, n, fewest, most))
            if not same_rows(rows_split, rows_whole, args.ranks == 1):
                failures.append("%s: the pieces' points and fields differ "
                                "from those of one piece per rank" % stem)
    for directory in (whole, split):
        for name in os.listdir(directory):
            if name.endswith(".tmp"):
                failures.append("temporary file left: " + name)

    # A run with one piece per rank into the directory of the split run
    # removes the split run's pieces: only the listed ones remain. It
    # writes every cycle before going on: cycle 0, which the first run
    # wrote in the background while cycle 1 solved, must come out the
    # same.
    run(args, split, 0, clean=False, background=False)
    listed = set()
    for record in os.listdir(split):
        if record.endswith(".pvtu"):
            listed.update(pieces_of(split, record))
    written = set(name for name in os.listdir(split) if name.endswith(".vtu")
                  and re.fullmatch(r"body-[12]_.*", name))
    if written != listed:
        failures.append("after a run with one piece per rank, pieces not "
                        "listed in any .pvtu: %s" % sorted(written - listed))
    else:
        print("rerun with one piece per rank: %d pieces, all listed" %
              len(written))

    # That rerun has the first run's settings but for the background
    # writing: every .vtu it wrote (the bodies' pieces and the contact
    # polylines) must be the first run's, byte for byte (no date in the
    # headers; the .pvtu and .pvd records carry deal.II's date), and so
    # must the records but for the date.
    vtu_files = sorted(name for name in os.listdir(whole)
                       if name.endswith(".vtu"))
    def same_vtu(name):
        a, b = os.path.join(whole, name), os.path.join(split, name)
        if not os.path.exists(b):
            return False
        if args.ranks == 1:
            return open(a, "rb").read() == open(b, "rb").read()
        (cells_a, rows_a), (cells_b, rows_b) = point_rows(a), point_rows(b)
        return cells_a == cells_b and same_rows(rows_a, rows_b, False)
    differing = [name for name in vtu_files if not same_vtu(name)]
    def undated(path):
        return [line for line in open(path)
                if "generated by the deal.II library" not in line]
    records = sorted(name for name in os.listdir(whole)
                     if name.endswith(".pvtu") or name.endswith(".pvd"))
    differing += [name for name in records
                  if not os.path.exists(os.path.join(split, name)) or
                  undated(os.path.join(whole, name)) !=
                  undated(os.path.join(split, name))]
    if differing or not any(n.startswith("contact") for n in vtu_files) \
            or "body-1_000.pvtu" not in records:
        failures.append("a run written in the background and one written "
                        "in the foreground wrote different files: %s "
                        "(of %s)" % (differing, vtu_files + records))
    else:
        print("rerun written in the foreground: its %d .vtu files (bodies "
              "and contact) are the first run's, %s, its %d "
              ".pvtu and .pvd records too but for the date" %
              (len(vtu_files), "byte for byte" if args.ranks == 1 else
               "to round-off", len(records)))

    # One piece that cannot be written (a directory where its temporary
    # file goes) among the concurrent ones: the run stops with a message
    # naming that piece, removes the other pieces' temporary files and
    # leaves the earlier cycle's record as it was.
    failing = os.path.join(args.output, "failing_piece")
    shutil.rmtree(failing, ignore_errors=True)
    os.makedirs(os.path.join(failing, "body-2_001.05.vtu.tmp"))
    result = run(args, failing, MAX_CELLS, clean=False, must_succeed=False)
    message = "output file '%s/body-2_001.05.vtu': cannot open it for " \
        "writing" % failing
    left = sorted(name for name in os.listdir(failing)
                  if name.endswith(".tmp") and
                  name != "body-2_001.05.vtu.tmp")
    earlier = [name for name in pieces_of(failing, "body-2_000.pvtu")
               if not os.path.exists(os.path.join(failing, name))]
    if result.returncode == 0:
        failures.append("a piece that cannot be written: the run succeeded")
    elif message not in result.stdout + result.stderr:
        failures.append("a piece that cannot be written: no message '%s' "
                        "in:\n%s%s" % (message, result.stdout,
                                       result.stderr[-2000:]))
    elif left or earlier or \
            os.path.exists(os.path.join(failing, "body-2_001.pvtu")):
        failures.append("a piece that cannot be written: temporary files "
                        "left %s, cycle 0's missing pieces %s, or a record "
                        "of cycle 1" % (left, earlier))
    else:
        print("a piece that cannot be written: exit %d, named in the "
              "message, no other temporary file, cycle 0 intact" %
              result.returncode)

    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
