#!/usr/bin/python3
"""A run killed while it wrote an HDF5 file must not hang the next runs.

Usage: stale_io_semaphore.py MPIEXEC PROGRAM OUTPUT_DIRECTORY PARAMETER_FILE

Open MPI 4.1's OMPIO creates a POSIX named semaphore
/dev/shm/sem.OMPIO_<file name> for every file it opens on one node; a run
killed while it holds it leaves it locked, and every later run that writes
a file of that name waited on it forever (a CI run of
bad_input.killed_during_hdf5_output.mpirun=2 hung so). The program asks for
MPI-IO without such semaphores (app/parallel_file_io.h).

This test leaves the semaphore of body-1_000.h5.tmp (the first HDF5 file
of any run) locked, as such a kill does, and runs PROGRAM with
`Output/Format = hdf5` on 2 ranks: it must end within 60 s (a short run
takes about 1 s), exit 0 and write body-1_000.h5 whole (the superblock's
end-of-file address is the file's size). The semaphore is removed at the
end, whatever happened. An OMPI_MCA_io of the caller's is removed first:
the program's own choice is what is tested.
"""

import _multiprocessing
import os
import shutil
import subprocess
import sys

from kill_during_output import (Incomplete, check_hdf5, kill_group,
                                 wait_for_group)

SEMAPHORE = "/OMPIO_body-1_000.h5.tmp"


def main():
    mpiexec, program, out, prm = sys.argv[1:5]
    shutil.rmtree(out, ignore_errors=True)
    env = dict(os.environ)
    env.pop("OMPI_MCA_io", None)
    try:
        _multiprocessing.sem_unlink(SEMAPHORE)
    except OSError:
        pass
    # kind 1: a counting semaphore; value 0: locked, as a killed holder
    # leaves it.
    locked = _multiprocessing.SemLock(1, 0, 1, SEMAPHORE, False)
    assert os.path.exists("/dev/shm/sem" + SEMAPHORE.replace("/", "."))
    try:
        command = [mpiexec, "-np", "2", program, prm,
                   "-s", "Output/Format=hdf5",
                   "-s", "Output/Output directory=" + out,
                   "-s", "Adaptation/Number of cycles=2",
                   "-s", "Adaptation/Minimum number of cycles=1"]
        process = subprocess.Popen(command, env=env, text=True,
                                   stdout=subprocess.PIPE,
                                   stderr=subprocess.STDOUT,
                                   start_new_session=True)
        try:
            output = process.communicate(timeout=60)[0]
        except subprocess.TimeoutExpired:
            # mpirun and the ranks (process groups of their own).
            kill_group(process)
            wait_for_group(process.pid)
            print("FAILED: the run did not end within 60 s beside a locked "
                  "semaphore %s (the files written: %s)"
                  % (SEMAPHORE, sorted(os.listdir(out))
                     if os.path.isdir(out) else "none"))
            return 1
        if process.returncode != 0:
            print("FAILED: exit code %d\n%s" % (process.returncode, output))
            return 1
        path = os.path.join(out, "body-1_000.h5")
        try:
            check_hdf5(path)
        except (Incomplete, OSError) as error:
            print("FAILED: " + str(error))
            return 1
        size = os.path.getsize(path)
        print("OK: 2 ranks wrote %s (%d bytes, complete) beside a locked "
              "semaphore %s" % (path, size, SEMAPHORE))
        return 0
    finally:
        del locked
        _multiprocessing.sem_unlink(SEMAPHORE)


if __name__ == "__main__":
    sys.exit(main())
