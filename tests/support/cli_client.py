"""The tests' stand-in for ``python -m server ARGS`` (support/forked_cli.py): run as ``python -S
cli_client.py SOCKET UNBUFFERED ARGS``, it asks the CLI starter listening on SOCKET to fork the
command with this process's standard streams, environment and working folder, passes on the
signals it gets to the command, and ends as the command ended.

It imports only the standard library's built-in modules, so it starts in a few milliseconds.
"""

import json
import os
import signal
import socket
import sys

PASSED_ON = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP, signal.SIGQUIT, signal.SIGUSR1, signal.SIGUSR2)


def main() -> None:
    path, unbuffered, args = sys.argv[1], sys.argv[2] == "1", sys.argv[3:]
    conn = socket.socket(socket.AF_UNIX, socket.SOCK_SEQPACKET)
    conn.connect(path)
    pending = []
    started = []

    def pass_on(sig, _frame):
        if started:
            conn.send(json.dumps({"signal": int(sig)}).encode())
        else:
            pending.append(int(sig))

    for sig in PASSED_ON:
        signal.signal(sig, pass_on)
    request = {"args": args, "env": dict(os.environ), "cwd": os.getcwd(), "unbuffered": unbuffered}
    socket.send_fds(conn, [json.dumps(request).encode()], [0, 1, 2])
    while True:
        data = conn.recv(4096)
        if not data:  # the starter has gone (its pytest process ended)
            sys.exit(1)
        reply = json.loads(data)
        if reply["op"] == "started":
            started.append(reply["pid"])
            for sig in pending:
                conn.send(json.dumps({"signal": sig}).encode())
        elif reply["op"] == "exit":
            break
    code = reply["code"]
    if code < 0:  # killed by a signal: end the same way
        for sig in PASSED_ON:
            signal.signal(sig, signal.SIG_DFL)
        signal.signal(-code, signal.SIG_DFL)
        os.kill(os.getpid(), -code)
        code = 128 - code
    sys.exit(code)


main()
