"""A student's node that tries one thing (``-p check:=NAME -p arg:=VALUE``) and prints one line,
``PROBE <check> ok <detail>`` or ``PROBE <check> blocked <why>``. The tests run it through a class
server that sandboxes students' nodes and through one started with ``--student-code unsandboxed``.
"""

import ctypes
import mmap
import os
import socket
import sys
import time

FORKS = 100  # more than the sandbox's 64 processes, few enough for any machine
MEMORY_MIB = 768  # more than the sandbox's 512 MiB
CHUNK_MIB = 64
SHM_MIB = 256
DEEP = 1100  # nested folders: deeper than Python's recursion limit
SWAP_S = 4.0  # how long the link race runs


def param(name):
    prefix = name + ":="
    return next((a[len(prefix) :] for a in sys.argv if a.startswith(prefix)), "")


def read(path):
    with open(path) as file:
        return f"read {len(file.read())} characters"


def env(name):
    if name not in os.environ:
        raise OSError(f"no {name} in its environment")
    return f"{name} is set"


def tcp(port):
    with socket.create_connection(("127.0.0.1", int(port)), timeout=3):
        return f"connected to 127.0.0.1:{port}"


def dns(name):
    return f"{name} is {socket.getaddrinfo(name, 80)[0][4][0]}"


def fork(_arg):
    gate_read, gate_write = os.pipe()
    children = []
    try:
        for _ in range(FORKS):
            pid = os.fork()
            if pid == 0:  # the child waits for the parent's word, then leaves at once
                os.close(gate_write)
                os.read(gate_read, 1)
                os._exit(0)
            children.append(pid)
    except OSError as exc:
        raise OSError(f"fork {len(children) + 1} refused: {exc}") from None
    finally:
        os.close(gate_write)
        for pid in children:
            os.waitpid(pid, 0)
    return f"{len(children)} processes"


def memory(_arg):
    held = [bytearray(CHUNK_MIB * 1024 * 1024) for _ in range(MEMORY_MIB // CHUNK_MIB)]
    return f"held {sum(len(b) for b in held) // (1024 * 1024)} MiB"


def write(path):
    with open(path, "w") as file:
        file.write("written by a student's node\n")
    return f"wrote {path}"


def status(_arg):
    """What the kernel says of this process as the student's code starts."""
    fields = {}
    with open("/proc/self/status") as file:
        for line in file:
            key, _, value = line.partition(":")
            fields[key] = value.split()[0] if value.split() else ""
    return " ".join(f"{k}={fields[k]}" for k in ("Uid", "CapEff", "NoNewPrivs", "Seccomp"))


def handle(path):
    """Open ``path`` by its file handle (past mounts and namespaces, given CAP_DAC_READ_SEARCH)."""
    libc = ctypes.CDLL(None, use_errno=True)
    buffer = ctypes.create_string_buffer(8 + 128)
    ctypes.memmove(buffer, (128).to_bytes(4, sys.byteorder), 4)
    mount_id = ctypes.c_int()
    if libc.name_to_handle_at(-100, path.encode(), buffer, ctypes.byref(mount_id), 0) != 0:
        raise OSError(ctypes.get_errno(), f"name_to_handle_at: {os.strerror(ctypes.get_errno())}")
    root = os.open("/", os.O_RDONLY | os.O_DIRECTORY)
    try:
        fd = libc.open_by_handle_at(root, buffer, os.O_RDONLY | os.O_DIRECTORY)
        if fd < 0:
            raise OSError(ctypes.get_errno(), f"open_by_handle_at: {os.strerror(ctypes.get_errno())}")
        os.close(fd)
    finally:
        os.close(root)
    return f"opened {path} by its handle"


def shm(path):
    """Fill a file in a tmpfs (its pages are memory no rlimit counts)."""
    try:
        with open(path, "wb") as file:
            block = b"x" * (1024 * 1024)
            for _ in range(SHM_MIB):
                file.write(block)
    finally:
        if os.path.exists(path):
            os.remove(path)
    return f"wrote {SHM_MIB} MiB to {path}"


def shared(mib):
    """Touch ``mib`` MiB of shared anonymous memory (not counted by RLIMIT_DATA)."""
    size = int(mib) * 1024 * 1024
    region = mmap.mmap(-1, size, flags=mmap.MAP_SHARED)
    for offset in range(0, size, mmap.PAGESIZE):
        region[offset] = 1
    return f"touched {mib} MiB of shared memory"


def link(pair):
    """A symbolic link at ``where`` to ``target`` (``where=target``)."""
    where, target = pair.split("=", 1)
    os.symlink(target, where)
    return f"linked {where} to {target}"


def swap(pair):
    """Swap the file ``where`` for a link to ``target`` and back, for SWAP_S seconds."""
    where, target = pair.split("=", 1)
    with open(where, "rb") as file:
        original = file.read()
    spare, swaps, until = where + "-link", 0, time.monotonic() + SWAP_S
    print("PROBE swap started", flush=True)  # the test reads while it swaps
    while time.monotonic() < until:
        os.symlink(target, spare)
        os.rename(spare, where)  # now a link
        with open(spare, "wb") as file:
            file.write(original)
        os.rename(spare, where)  # a file again
        swaps += 1
    return f"swapped {swaps} times"


def deep(folder):
    os.mkdir(folder)
    path = folder
    for _ in range(DEEP):
        path = os.path.join(path, "d")
        os.mkdir(path)
    with open(os.path.join(path, "deep.txt"), "w") as file:
        file.write("at the bottom\n")
    return f"made {DEEP} nested folders"


def priority(_arg):
    try:
        with open("/proc/self/autogroup") as file:
            words = file.read().split()  # empty in the root group
        group = words[-1] if words else "none"
    except FileNotFoundError:
        group = "none"
    return f"nice {os.getpriority(os.PRIO_PROCESS, 0)} group {group}"


def realtime(_arg):
    """The class the node started in, then the real-time class taken (the worlds' loop's, above it)."""
    started = "normal" if os.sched_getscheduler(0) == os.SCHED_OTHER else "real-time"
    try:
        os.sched_setscheduler(0, os.SCHED_FIFO, os.sched_param(1))
    except OSError as exc:
        raise OSError(f"started {started}, SCHED_FIFO refused: {exc}") from None
    os.sched_setscheduler(0, os.SCHED_OTHER, os.sched_param(0))
    return f"started {started}, took SCHED_FIFO 1"


def cgroup(procs):
    with open(procs, "w") as file:  # a control group's cgroup.procs: this process moves into it
        file.write(str(os.getpid()))
    return f"moved into {procs}"


CHECKS = {
    "read": read,
    "env": env,
    "tcp": tcp,
    "dns": dns,
    "fork": fork,
    "memory": memory,
    "write": write,
    "priority": priority,
    "realtime": realtime,
    "cgroup": cgroup,
    "status": status,
    "handle": handle,
    "shm": shm,
    "shared": shared,
    "link": link,
    "swap": swap,
    "deep": deep,
}


def main():
    check = param("check")
    try:
        detail = CHECKS[check](param("arg"))
    except OSError as exc:
        print(f"PROBE {check} blocked {exc}", flush=True)
        return
    print(f"PROBE {check} ok {detail}", flush=True)


if __name__ == "__main__":
    main()
