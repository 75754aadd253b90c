"""The benchmark matrix over MPI ranks: `mpirun -np N python3 scripts/bench.py ...`.

Every rank starts bench.py. Rank 0 plans the matrix as one process would, skips
the runs whose finished record exists (Runner.finished: an interrupted matrix
resumes as before) and hands out the others one at a time, each to the next
rank that asks: a rank asks when it is free, so long and short runs, fast and
slow nodes even out by themselves. Ranks 1..N-1 only serve: they run what they
are handed (Runner.execute) and send the record back.

Each rank writes its own runs' records (atomically, runs/<key>.json), so that a
record is on disk as soon as its run ends, whatever becomes of rank 0, and
sends it to rank 0 too. passtrace writes the heat maps where it runs anyway:
the output folder, the binary and the scenes must be at the same paths on every
node (a shared filesystem). Only rank 0 writes results.json, REPORT.md and the plots.

Without an MPI launcher's variables in the environment this module never
imports mpi4py (importing it calls MPI_Init), and a Pool runs each job at once,
in this process, as bench.py always did.
"""
import collections
import os
import socket
import sys
import threading
import time
import traceback

# The variables by which passtrace (render/ranks.cpp) and this module know that
# an MPI launcher started them, and the prefixes of all a launcher sets.
LAUNCHER_VARIABLES = ("OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE")
LAUNCHER_PREFIXES = ("OMPI_", "PMIX_", "PMI_")
# A waiting rank sleeps this long between polls: Open MPI's blocking calls spin
# and would take a core from the runs beside them.
POLL_S = 0.02
HOST = socket.gethostname()

_mpi = None    # mpi4py's MPI, once a launcher started this process
# Rank 0's view of the other ranks, kept across Pools until close():
_idle = set()  # waiting for a job
_busy = {}     # rank -> the index of the job it runs
_gone = set()  # failed and ended
_hosts = {}    # rank -> its host


def child_env(base=None):
    """BASE (default os.environ) without the launcher's variables: a passtrace
    that saw them would initialise MPI and take itself for one of this job's ranks."""
    base = os.environ if base is None else base
    return {k: v for k, v in base.items() if not k.startswith(LAUNCHER_PREFIXES)}


def _world():
    """MPI_COMM_WORLD when an MPI launcher started this process, else None."""
    global _mpi
    if _mpi is None and any(v in os.environ for v in LAUNCHER_VARIABLES):
        try:
            import mpi4py
            mpi4py.rc.thread_level = "serialized"  # rank 0's dispatcher thread and main thread take turns
            from mpi4py import MPI
        except ImportError as e:
            raise SystemExit(f"bench: started by an MPI launcher, but {sys.executable} cannot import mpi4py ({e}; "
                             "apt-get install python3-mpi4py); without mpirun it runs as one process")
        if MPI.Query_thread() < MPI.THREAD_SERIALIZED:
            raise SystemExit("bench: this MPI library gives no MPI_THREAD_SERIALIZED, which rank 0's dispatcher needs")
        _mpi = MPI
    return _mpi.COMM_WORLD if _mpi else None


def rank():
    comm = _world()
    return comm.Get_rank() if comm else 0


def size():
    comm = _world()
    return comm.Get_size() if comm else 1


def _receive(comm, source, stop=None):
    """(source, message): the next message from SOURCE, polling; None once STOP is set."""
    status = _mpi.Status()
    while not comm.Iprobe(source=source, tag=0, status=status):
        if stop is not None and stop.is_set():
            return None
        time.sleep(POLL_S)
    return status.Get_source(), comm.recv(source=status.Get_source(), tag=0)


def _note(source, message):
    """Rank 0's view of SOURCE after its message: idle again (ready, done) or gone (failed)."""
    _busy.pop(source, None)
    if message[0] == "failed":
        _gone.add(source)
        return
    _idle.add(source)
    if message[0] == "ready":
        _hosts[source] = message[1]


def serve():
    """Ranks 1..N-1: runs the jobs rank 0 hands out until it says stop. The exit status."""
    comm = _world()
    comm.send(("ready", HOST), dest=0)
    key = None
    try:
        while True:
            _, message = _receive(comm, 0)
            if message[0] == "stop":
                return 0
            _, index, runner, job = message
            key = job[0]["key"]
            comm.send(("done", index, runner.execute(*job)), dest=0)
    except BaseException as e:  # Ctrl-C too: rank 0 waits for this rank's answer, and MPI_Finalize for rank 0
        traceback.print_exc()
        comm.send(("failed", f"{key}: {type(e).__name__}: {e}"), dest=0)
        return 1


class Pool:
    """One loop's jobs (Runner.execute's arguments): run in this process as they
    are submitted when there is one rank, else queued and handed out by finish()."""

    def __init__(self, runner, started, done):
        """started(index, where) as a job starts (`where` names its rank and host
        when there are several, else is empty); done(index, record) when it ended."""
        self.runner, self.started, self.done = runner, started, done
        self.ranks = size()
        self.queue = collections.deque()

    def submit(self, index, job):
        if self.ranks > 1:
            self.queue.append((index, job))
            return
        self.started(index, "")
        self.done(index, self.runner.execute(*job))

    def finish(self):
        """Several ranks: runs the queued jobs, each on the next rank that asks.

        Rank 0 runs jobs too, so that one rank per node keeps every node busy;
        its dispatching goes on beside them in a thread that sleeps between
        polls. Ctrl-C, or a rank that fails (SystemExit), stops the handing out:
        the jobs already handed out end on their ranks, which write their records
        (close() waits for them); the report has the ones that came back."""
        if not self.queue:
            return
        comm, lock, stop, failed = _world(), threading.Lock(), threading.Event(), []

        def take(rank, host):
            with lock:  # each job taken once, the callbacks one at a time
                if stop.is_set() or not self.queue:
                    return None
                index, job = self.queue.popleft()
                self.started(index, f" on rank {rank} ({host})")
                return index, job

        def dispatch():
            try:
                hand_out()
            except BaseException as e:  # a callback's error: the main thread stops too, and says why
                failed.append(f"bench: rank 0's dispatcher failed: {type(e).__name__}: {e}")
                stop.set()
                raise

        def hand_out():
            while True:
                for r in sorted(_idle):
                    taken = take(r, _hosts[r])
                    if taken is None:
                        break
                    _idle.discard(r)
                    _busy[r] = taken[0]
                    comm.send(("run", taken[0], self.runner, taken[1]), dest=r)
                if stop.is_set() or not (self.queue or _busy):
                    return
                received = _receive(comm, _mpi.ANY_SOURCE, stop)
                if received is None:
                    return
                _note(*received)
                source, message = received
                if message[0] == "done":
                    with lock:
                        self.done(message[1], message[2])
                elif message[0] == "failed":
                    failed.append(f"bench: rank {source} ({_hosts.get(source)}) failed on {message[1]}; the "
                                  "finished runs are kept: rerun the command to resume")
                    stop.set()

        thread = threading.Thread(target=dispatch, name="bench-dispatch")
        thread.start()
        try:
            while (taken := take(0, HOST)) is not None:
                record = self.runner.execute(*taken[1])
                with lock:
                    self.done(taken[0], record)
            thread.join()  # until the other ranks' last jobs are back
        except BaseException:
            stop.set()
            thread.join()  # within a poll
            raise
        if failed:
            raise SystemExit(failed[0])


def close():
    """Rank 0, however it ends: waits for the runs still going on the other ranks
    (they write their records), then tells every rank to stop."""
    comm = _world()
    if comm is None or comm.Get_size() == 1:
        return
    others = set(range(1, comm.Get_size()))
    if _busy:
        print(f"bench: waiting for the runs still going on rank(s) {', '.join(map(str, sorted(_busy)))}",
              file=sys.stderr, flush=True)
    try:
        while others - _idle - _gone:
            _note(*_receive(comm, _mpi.ANY_SOURCE))
        for r in sorted(others - _gone):
            comm.send(("stop",), dest=r)
    except BaseException:  # a second Ctrl-C: end every rank now, rather than all wait in MPI_Finalize
        comm.Abort(1)
