# SPDX-License-Identifier: GPL-3.0-or-later
"""A task's side of the session Blender (session.py), run by any Python 3 (the jobs use the
one the session's Blender reports):

    python client.py SOCKET run ARGS...     the farm command, its output and exit status
    python client.py SOCKET stop            end the session's Blender

SIGTERM (the farm cancelling the task) is passed on to Blender, which cancels the task and
leaves no partial file. Standard library only: this file is not imported with the add-on."""

import json
import os
import signal
import socket
import sys


def main(argv):
    if len(argv) < 2:
        print("usage: client.py SOCKET (run ARGS... | stop)", file=sys.stderr)
        return 2
    path, command = argv[0], argv[1:]
    connection = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        connection.connect(path)
    except OSError as exc:
        print(f"hyvox: error: the session's Blender is not listening on {path}: {exc}", file=sys.stderr)
        return 1
    request = {"stop": True} if command == ["stop"] else {"argv": command}
    connection.sendall((json.dumps(request) + "\n").encode())
    server = []

    def forward(signum, frame):
        if server:
            os.kill(server[0], signal.SIGTERM)

    signal.signal(signal.SIGTERM, forward)
    signal.signal(signal.SIGINT, forward)
    for line in connection.makefile("r", encoding="utf-8"):
        message = json.loads(line)
        if "pid" in message:
            server.append(message["pid"])
        elif "out" in message:
            sys.stdout.write(message["out"])
            sys.stdout.flush()
        elif "err" in message:
            sys.stderr.write(message["err"])
            sys.stderr.flush()
        elif "exit" in message:
            return int(message["exit"])
    print(
        "hyvox: error: the session's Blender stopped during the task (its log is in the session folder)",
        file=sys.stderr,
    )
    return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
