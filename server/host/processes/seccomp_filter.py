"""The system calls a sandboxed node may not make: a seccomp filter that bubblewrap loads into the
node's process before it runs anything (``bwrap --seccomp FD``), kept by every process it starts.

A node is a Python program that publishes and subscribes: it never needs to open files by handle
(``open_by_handle_at`` reads any file of a file system whose handle it guesses, past every mount),
trace or read another process's memory, mount, change its root, enter or make namespaces, touch the
kernel's keyrings, load BPF or kernel modules, use ``perf_event_open`` or ``userfaultfd`` (the
kernel's usual exploit primitives), or set the clock. Each is refused with EPERM, as a kernel
without the feature would; ``clone3`` answers ENOSYS (its flags sit in memory a filter cannot read),
so the C library falls back to ``clone``, whose namespace flags the filter can see and refuses.

The filter is built with libseccomp (``pyseccomp``, a ctypes binding of the system's
``libseccomp.so.2``) once per server process, for the machine's own architecture.
"""

from __future__ import annotations

import errno
import functools
import os
import tempfile

REFUSED = (
    # files by handle, past mounts and namespaces
    "open_by_handle_at",
    "name_to_handle_at",
    # other processes
    "ptrace",
    "process_vm_readv",
    "process_vm_writev",
    "kcmp",
    "pidfd_getfd",
    # mounts, roots and namespaces
    "mount",
    "umount2",
    "pivot_root",
    "chroot",
    "unshare",
    "setns",
    "mount_setattr",
    "move_mount",
    "open_tree",
    "fsopen",
    "fsconfig",
    "fsmount",
    "fspick",
    # the kernel's keyrings, BPF, modules and the usual exploit primitives
    "keyctl",
    "add_key",
    "request_key",
    "bpf",
    "perf_event_open",
    "userfaultfd",
    "init_module",
    "finit_module",
    "delete_module",
    "kexec_load",
    "kexec_file_load",
    "io_uring_setup",
    # the machine's own settings
    "reboot",
    "swapon",
    "swapoff",
    "acct",
    "settimeofday",
    "clock_settime",
    "clock_adjtime",
    "adjtimex",
    "syslog",
    "quotactl",
    "iopl",
    "ioperm",
    "personality",
    "vhangup",
)
# clone()'s flags that make a namespace (sched.h).
NAMESPACE_FLAGS = (
    0x00020000,  # CLONE_NEWNS
    0x02000000,  # CLONE_NEWCGROUP
    0x04000000,  # CLONE_NEWUTS
    0x08000000,  # CLONE_NEWIPC
    0x10000000,  # CLONE_NEWUSER
    0x20000000,  # CLONE_NEWPID
    0x40000000,  # CLONE_NEWNET
    0x00000080,  # CLONE_NEWTIME
)


class SeccompUnavailableError(RuntimeError):
    """No filter can be built on this machine (no libseccomp, or an unknown architecture)."""


@functools.cache
def program() -> bytes:
    """The filter as the kernel's BPF program, for ``bwrap --seccomp``. SeccompUnavailableError
    names what is missing."""
    try:
        import pyseccomp as seccomp
    except (ImportError, OSError) as exc:  # the module loads libseccomp.so.2 as it is imported
        raise SeccompUnavailableError(
            f"libseccomp cannot be loaded ({exc}): install Debian's 'libseccomp2'"
        ) from None
    try:
        rules = seccomp.SyscallFilter(seccomp.ALLOW)
        for name in REFUSED:
            try:
                rules.add_rule(seccomp.ERRNO(errno.EPERM), name)
            except OSError:  # a call this architecture does not have (iopl on arm64): nothing to refuse
                continue
        rules.add_rule(seccomp.ERRNO(errno.ENOSYS), "clone3")
        for flag in NAMESPACE_FLAGS:
            rules.add_rule(seccomp.ERRNO(errno.EPERM), "clone", seccomp.Arg(0, seccomp.MASKED_EQ, flag, flag))
        with tempfile.TemporaryFile() as out:
            rules.export_bpf(out)
            out.seek(0)
            return out.read()
    except (OSError, RuntimeError) as exc:
        raise SeccompUnavailableError(f"libseccomp could not build the filter: {exc}") from None


def program_fd() -> int:
    """A descriptor to read the filter from, once (the read end of a pipe holding it): the caller
    passes it to bubblewrap and closes its own copy once bwrap has started."""
    data = program()
    read_end, write_end = os.pipe()  # the program is a few hundred bytes: far below a pipe's buffer
    try:
        os.write(write_end, data)
    finally:
        os.close(write_end)
    return read_end
