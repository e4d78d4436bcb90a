"""A student's node that tries one thing (``-p check:=NAME -p arg:=VALUE``) and prints one line,
``PROBE <check> ok <detail>`` or ``PROBE <check> blocked <why>``. The tests run it through a class
server that sandboxes students' nodes and through one started with ``--student-code unsandboxed``.
"""

import os
import socket
import sys

FORKS = 100  # more than the sandbox's 64 processes, few enough for any machine
MEMORY_MIB = 768  # more than the sandbox's 512 MiB
CHUNK_MIB = 64


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


def priority(_arg):
    try:
        with open("/proc/self/autogroup") as file:
            words = file.read().split()  # empty in the root group
        group = words[-1] if words else "none"
    except FileNotFoundError:
        group = "none"
    return f"nice {os.getpriority(os.PRIO_PROCESS, 0)} group {group}"


CHECKS = {
    "read": read,
    "env": env,
    "tcp": tcp,
    "dns": dns,
    "fork": fork,
    "memory": memory,
    "write": write,
    "priority": priority,
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
