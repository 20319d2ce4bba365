#!/usr/bin/python3
"""SIGKILL during output writing (issue 21 item 5): every file left is
complete or absent.

Usage: kill_during_output.py PROGRAM OUTPUT_DIRECTORY [ARGUMENT ...]

Runs PROGRAM (with the ARGUMENTs: a run that writes several cycles) a few
times into fresh directories below OUTPUT_DIRECTORY. Each run is watched by
polling its directory, and killed with SIGKILL as soon as a NAME.tmp file
is seen: the first, the second, ... such file, so that the
kills land in the writes of different files and cycles. After each kill
every file under a final name must be complete:

  - .vtu: well-formed XML whose every binary DataArray decodes (deal.II's
    zlib-compressed base64) to the size its header and the piece's
    NumberOfPoints / NumberOfCells give;
  - .pvtu and .pvd: well-formed XML whose every listed file is there and
    complete;
  - summary.json: valid JSON with a list of cycles;
  - contact_CCC.csv: a header and rows of as many fields, ending in a
    newline.

NAME.tmp files may be left (README: a killed run can leave them, the next
run into the directory removes them). At least one kill must have landed
during a write (a .tmp file left behind), or the test tested nothing and
fails. A last, short run into a directory that a kill left a .tmp file in
must remove it.
"""

import base64
import json
import os
import shutil
import signal
import struct
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
import zlib

# Bytes per value of the VTK types deal.II writes.
VTK_TYPE_SIZE = {"Float32": 4, "Float64": 8, "Int32": 4, "UInt32": 4,
                 "Int64": 8, "UInt64": 8, "UInt8": 1, "Int8": 1}


class Incomplete(Exception):
    pass


def decoded_size(text, where):
    """Size of a deal.II binary DataArray: base64 of the header (UInt32
    blocks, block size, last block size, compressed sizes), then base64 of
    the zlib-compressed blocks."""
    text = "".join(text.split())
    n_blocks = struct.unpack("<I", base64.b64decode(text[:8])[:4])[0]
    header_bytes = 4 * (3 + n_blocks)
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = struct.unpack("<%dI" % (3 + n_blocks),
                           base64.b64decode(text[:header_chars]))
    data = base64.b64decode(text[header_chars:])
    if len(data) != sum(header[3:]):
        raise Incomplete("%s: %d compressed bytes, the header says %d"
                         % (where, len(data), sum(header[3:])))
    size, offset = 0, 0
    for b, compressed in enumerate(header[3:]):
        size += len(zlib.decompress(data[offset:offset + compressed]))
        offset += compressed
    expected = (n_blocks - 1) * header[1] + (header[2] or header[1])
    if n_blocks > 0 and size != expected:
        raise Incomplete("%s: %d bytes, the header says %d"
                         % (where, size, expected))
    return size


def check_vtu(path):
    root = ET.parse(path).getroot()
    if root.tag != "VTKFile" or root.get("type") != "UnstructuredGrid":
        raise Incomplete(path + ": not a VTK unstructured grid")
    pieces = root.findall("./UnstructuredGrid/Piece")
    if not pieces:
        raise Incomplete(path + ": no Piece")
    for piece in pieces:
        n = {"PointData": int(piece.get("NumberOfPoints")),
             "Points": int(piece.get("NumberOfPoints")),
             "CellData": int(piece.get("NumberOfCells"))}
        for part in piece:
            for array in part.iter("DataArray"):
                where = "%s: %s %s" % (path, part.tag, array.get("Name", ""))
                if array.get("format") != "binary":
                    continue
                size = decoded_size(array.text or "", where)
                if part.tag in n:
                    expected = (n[part.tag]
                                * int(array.get("NumberOfComponents", "1"))
                                * VTK_TYPE_SIZE[array.get("type")])
                    if size != expected:
                        raise Incomplete("%s: %d bytes, %d expected"
                                         % (where, size, expected))


def check_listed(path, tag, attribute, checked):
    root = ET.parse(path).getroot()
    for element in root.iter(tag):
        listed = os.path.join(os.path.dirname(path), element.get(attribute))
        if not os.path.isfile(listed):
            raise Incomplete("%s lists %s, which is not there"
                             % (path, os.path.basename(listed)))
        check_file(listed, checked)


def check_csv(path):
    with open(path) as f:
        text = f.read()
    if not text.endswith("\n"):
        raise Incomplete(path + ": no newline at the end")
    lines = text.splitlines()
    n_fields = len(lines[0].split(","))
    if lines[0].split(",")[:2] != ["x", "y"]:
        raise Incomplete(path + ": no header")
    for number, line in enumerate(lines[1:], start=2):
        if len(line.split(",")) != n_fields:
            raise Incomplete("%s, line %d: %d fields, the header has %d"
                             % (path, number, len(line.split(",")),
                                n_fields))


def check_file(path, checked):
    """Check @p path once; the kinds of file the program writes."""
    if path in checked:
        return
    checked.add(path)
    name = os.path.basename(path)
    try:
        if name.endswith(".vtu"):
            check_vtu(path)
        elif name.endswith(".pvtu"):
            check_listed(path, "Piece", "Source", checked)
        elif name.endswith(".pvd"):
            check_listed(path, "DataSet", "file", checked)
        elif name == "summary.json":
            with open(path) as f:
                summary = json.load(f)
            if not isinstance(summary.get("cycles"), list):
                raise Incomplete(path + ": no list of cycles")
        elif name.endswith(".csv"):
            check_csv(path)
    except (ET.ParseError, ValueError, zlib.error, struct.error) as e:
        raise Incomplete("%s: %s" % (path, e))


def check_directory(directory):
    """The final-named files checked, and the .tmp files left."""
    checked, left = set(), []
    for name in sorted(os.listdir(directory)):
        if name.endswith(".tmp"):
            left.append(name)
        else:
            check_file(os.path.join(directory, name), checked)
    return len(checked), left


def run_and_kill(command, directory, trigger, timeout):
    """Run @p command, SIGKILL it once the @p trigger-th distinct NAME.tmp
    file has been seen in @p directory. Returns the name of
    that file, or None if the run ended first."""
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL)
    seen = []
    killed_at = None
    start = time.monotonic()
    while process.poll() is None:
        if time.monotonic() - start > timeout:
            process.kill()
            process.wait()
            raise SystemExit("the run did not end within %g s" % timeout)
        try:
            with os.scandir(directory) as entries:
                for entry in entries:
                    if entry.name.endswith(".tmp") and entry.name not in seen:
                        seen.append(entry.name)
        except FileNotFoundError:
            pass
        if len(seen) >= trigger:
            process.send_signal(signal.SIGKILL)
            killed_at = seen[trigger - 1]
            break
        time.sleep(0.0005)
    process.wait()
    return killed_at


def main():
    program, output = sys.argv[1], sys.argv[2]
    arguments = sys.argv[3:]
    shutil.rmtree(output, ignore_errors=True)
    os.makedirs(output)
    timeout = 60
    landed = None
    failures = []
    for trigger in (1, 2, 4, 7, 12, 20, 30):
        directory = os.path.join(output, "kill_%02d" % trigger)
        command = [program] + arguments + [
            "-s", "Output/Output directory=" + directory]
        killed_at = run_and_kill(command, directory, trigger, timeout)
        try:
            n_checked, left = check_directory(directory)
        except (Incomplete, OSError) as e:
            failures.append(str(e))
            print("kill at .tmp file %d (%s): INCOMPLETE: %s"
                  % (trigger, killed_at, e))
            continue
        print("kill at .tmp file %d (%s): %d files complete, left: %s"
              % (trigger, killed_at or "run ended first", n_checked,
                 ", ".join(left) or "none"))
        if left and landed is None:
            landed = directory
    if failures:
        raise SystemExit("incomplete files after SIGKILL:\n  "
                         + "\n  ".join(failures))
    if landed is None:
        raise SystemExit("no kill landed during a write (no .tmp file "
                         "left): nothing was tested")

    # The next run into a directory with a .tmp file left removes it.
    command = [program] + arguments + [
        "-s", "Output/Output directory=" + landed,
        "-s", "Adaptation/Number of cycles=1"]
    result = subprocess.run(command, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, universal_newlines=True,
                            timeout=timeout)
    if result.returncode != 0:
        raise SystemExit("the run after the kill failed:\n" + result.stderr)
    n_checked, left = check_directory(landed)
    if left:
        raise SystemExit("the next run left the killed run's .tmp files: "
                         + ", ".join(left))
    print("the next run into %s: %d files complete, no .tmp file left"
          % (os.path.basename(landed), n_checked))


if __name__ == "__main__":
    main()
