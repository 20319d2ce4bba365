#!/usr/bin/python3
"""SIGKILL during output writing (issue 21 item 5): every file left is
complete or absent.

Usage: kill_during_output.py [--mpiexec MPIEXEC --ranks N]
                             [--kill-at NAME ...]
                             PROGRAM OUTPUT_DIRECTORY [ARGUMENT ...]

Runs PROGRAM (with the ARGUMENTs: a run that writes several cycles) a few
times into fresh directories below OUTPUT_DIRECTORY, on N MPI ranks with
--mpiexec (MPIEXEC -np N PROGRAM ...). Each run is watched by polling its
directory, and killed with SIGKILL as soon as a new file name is seen: the
first, the second, ... new name, so that the kills land in the writes of
different files and cycles. A new NAME.tmp is a write that has begun; a
new final name must be a complete file renamed, and a file written under
its final name (no NAME.tmp) is caught as it is opened. Then, per
--kill-at NAME, runs killed as soon as NAME or NAME.tmp appears, aimed at
the write of that file (a piece of a .pvtu, the .pvd, an .h5 file): up
to three, until one leaves a .tmp (a small file can be written and
renamed before the kill arrives). The run is a session of its own, and all of
it is killed at once: mpirun's process group and every process of the
session (Open MPI gives each rank a process group of its own), so that
the ranks die wherever they are, as on a node failure; the script waits
until no process of the session is left. After each kill
every file under a final name must be complete:

  - .vtu: well-formed XML whose every binary DataArray decodes (deal.II's
    zlib-compressed base64) to the size its header and the piece's
    NumberOfPoints / NumberOfCells give;
  - .pvtu and .pvd: well-formed XML whose every listed file is there and
    complete;
  - summary.json: valid JSON with a list of cycles;
  - contact_CCC.csv: a header and rows of as many fields, ending in a
    newline;
  - .h5: an HDF5 file whose superblock's end-of-file address is the
    file's size (HDF5 writes it when the file is closed);
  - .xdmf: well-formed XML whose every HDF5 file named in a DataItem is
    there and complete.

NAME.tmp files may be left (README: a killed run can leave them, the next
run into the directory removes them). At least one kill must have landed
during a write (a .tmp file left behind), or the test tested nothing and
fails. A last, short run into a directory that a kill left a .tmp file in
must remove it.
"""

import base64
import json
import os
import re
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


def check_xdmf(path, checked):
    """Every DataItem names FILE.h5:/DATASET; the file must be complete."""
    root = ET.parse(path).getroot()
    items = list(root.iter("DataItem"))
    if root.tag != "Xdmf" or not items:
        raise Incomplete(path + ": not an XDMF file with data items")
    for item in items:
        name = (item.text or "").strip().split(":")[0]
        listed = os.path.join(os.path.dirname(path), name)
        if not os.path.isfile(listed):
            raise Incomplete("%s lists %s, which is not there"
                             % (path, name))
        check_file(listed, checked)


def check_hdf5(path):
    """The superblock (HDF5 file format specification, section II.A) at
    offset 0: the end-of-file address it holds is the file's size once the
    file is closed; a file cut short, or still open, differs (or has no
    superblock yet)."""
    with open(path, "rb") as f:
        head = f.read(128)
    size = os.path.getsize(path)
    if head[:8] != b"\x89HDF\r\n\x1a\n":
        raise Incomplete(path + ": no HDF5 signature (%d bytes)" % size)
    version = head[8]
    if version in (0, 1):
        n_offsets = head[13]
        # Versions, sizes, leaf/internal K, flags; version 1 adds 4 bytes.
        start = 24 + (4 if version == 1 else 0)
        eof_at = start + 2 * n_offsets
    else:
        n_offsets = head[9]
        eof_at = 12 + 2 * n_offsets
    fmt = {4: "<I", 8: "<Q"}[n_offsets]
    eof = struct.unpack(fmt, head[eof_at:eof_at + n_offsets])[0]
    if eof != size:
        raise Incomplete("%s: %d bytes, its superblock says %d"
                         % (path, size, eof))


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
        elif name.endswith(".h5"):
            check_hdf5(path)
        elif name.endswith(".xdmf"):
            check_xdmf(path, checked)
    except (ET.ParseError, ValueError, zlib.error, struct.error,
            KeyError, IndexError) as e:
        raise Incomplete("%s: %s" % (path, e))


def check_directory(directory):
    """The final-named files checked, and the .tmp files left."""
    checked, left = set(), []
    for name in sorted(os.listdir(directory)):
        # With MPI-IO's lock test file of a parallel HDF5 NAME.tmp.
        if re.search(r"\.tmp(\.locktest\.[0-9]+)?$", name):
            left.append(name)
        else:
            check_file(os.path.join(directory, name), checked)
    return len(checked), left


def run_and_kill(command, directory, trigger, timeout):
    """Run @p command, SIGKILL it once the @p trigger-th distinct file
    name has been seen in @p directory (@p trigger a number), or the file
    @p trigger (a name) or its NAME.tmp. Returns that name, or None if the
    run ended first."""
    # Ranks that wait yield the CPU instead of spinning (Open MPI): two
    # spinning ranks on two cores kept the polling loop below off the CPU
    # for tens of milliseconds, in which the run wrote and renamed many
    # files, so that no kill landed in a write. (A lower priority for the
    # run was tried: beside other tests it outlasted the timeout.)
    environment = dict(os.environ, OMPI_MCA_mpi_yield_when_idle="1")
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL,
                               stderr=subprocess.DEVNULL,
                               start_new_session=True,
                               env=environment)
    seen = []
    killed_at = None
    start = time.monotonic()
    # The run's processes (mpirun's ranks), looked up every 20 ms, so that
    # a kill hits them at once (kill_group).
    members, members_time = [], 0.
    while process.poll() is None:
        if time.monotonic() - members_time > 0.02:
            members, members_time = (session_members(process.pid),
                                     time.monotonic())
        if time.monotonic() - start > timeout:
            kill_group(process)
            raise SystemExit("the run did not end within %g s" % timeout)
        try:
            with os.scandir(directory) as entries:
                for entry in entries:
                    if entry.name not in seen:
                        seen.append(entry.name)
        except FileNotFoundError:
            pass
        if isinstance(trigger, int):
            hit = seen[trigger - 1] if len(seen) >= trigger else None
        else:
            hit = next((name for name in seen
                        if name in (trigger, trigger + ".tmp")), None)
        if hit is not None:
            kill_group(process, members)
            killed_at = hit
            break
        time.sleep(0.0005)
    process.wait()
    wait_for_group(process.pid)
    return killed_at


def session_members(sid):
    """The live processes of session @p sid (from /proc; a zombie writes
    nothing more, and a container's init may never reap it)."""
    members = []
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                with open("/proc/%s/stat" % entry) as f:
                    # pid (comm) state ppid pgrp session ...: comm may
                    # hold blanks.
                    fields = f.read().rsplit(")", 1)[1].split()
                if fields[0] != "Z" and int(fields[3]) == sid:
                    members.append(int(entry))
            except (OSError, IndexError, ValueError):
                pass
    return members


def kill_group(process, known_members=()):
    """SIGKILL to every process of the run: its process group, and every
    process of its session (Open MPI's mpirun puts each rank in a process
    group of its own, in mpirun's session; a rank that outlived mpirun
    would write on). The members already known (@p known_members) are
    killed first: scanning /proc takes milliseconds, longer than a small
    file's write, which the ranks would finish in the meantime."""
    def kill(members):
        for pid in [process.pid] + list(members):
            try:
                if pid == process.pid:
                    os.killpg(pid, signal.SIGKILL)
                else:
                    os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass

    kill(known_members)
    kill(session_members(process.pid))
    process.wait()


def wait_for_group(sid, timeout=10):
    """Until no process of the run's session @p sid is left."""
    start = time.monotonic()
    while session_members(sid):
        if time.monotonic() - start > timeout:
            raise SystemExit("processes %s of the killed run are still "
                             "there after %g s" % (session_members(sid),
                                                   timeout))
        time.sleep(0.01)


def main():
    launcher = []
    args = sys.argv[1:]
    if args[:1] == ["--mpiexec"]:
        if args[2:3] != ["--ranks"]:
            raise SystemExit("--mpiexec MPIEXEC needs --ranks N")
        launcher = [args[1], "-np", args[3]]
        args = args[4:]
    names = []
    while args[:1] == ["--kill-at"]:
        names.append(args[1])
        args = args[2:]
    program, output = launcher + [args[0]], args[1]
    arguments = args[2:]
    shutil.rmtree(output, ignore_errors=True)
    os.makedirs(output)
    timeout = 60
    landed = None
    failures = []
    # A named file's kill is tried up to 3 times, until it leaves a .tmp
    # (the kill landed in a write): a small file can be written and renamed
    # before the kill arrives.
    runs = [(trigger, 1) for trigger in [1, 2, 4, 7, 12, 20, 30, 45]] + \
        [(name, attempt) for name in names for attempt in (1, 2, 3)]
    hit_names = set()
    for number, (trigger, attempt) in enumerate(runs):
        if trigger in hit_names:
            continue
        directory = os.path.join(output, "kill_%02d" % number)
        command = program + arguments + [
            "-s", "Output/Output directory=" + directory]
        killed_at = run_and_kill(command, directory, trigger, timeout)
        try:
            n_checked, left = check_directory(directory)
        except (Incomplete, OSError) as e:
            failures.append(str(e))
            print("kill at new file %s (%s): INCOMPLETE: %s"
                  % (trigger, killed_at, e))
            continue
        print("kill at new file %s (%s)%s: %d files complete, left: %s"
              % (trigger, killed_at or "run ended first",
                 ", attempt %d" % attempt if attempt > 1 else "",
                 n_checked, ", ".join(left) or "none"))
        if left and isinstance(trigger, str):
            hit_names.add(trigger)
        if left and landed is None:
            landed = directory
    if failures:
        raise SystemExit("incomplete files after SIGKILL:\n  "
                         + "\n  ".join(failures))
    if landed is None:
        raise SystemExit("no kill landed during a write (no .tmp file "
                         "left): nothing was tested")

    # The next run into a directory with a .tmp file left removes it.
    command = program + arguments + [
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
