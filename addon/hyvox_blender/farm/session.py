# SPDX-License-Identifier: GPL-3.0-or-later
"""One Blender for the tasks of a worker session, as Deadline's Blender adaptor keeps one:
Blender's start-up (and hyvox's GL context) is paid once per session, not once per task.

    blender -b --python-expr <bootstrap> -- serve --socket PATH --announce-fd N --session-dir DIR

listens on a Unix socket. A task connects with client.py, sends its farm command line (one
JSON line {"argv": [...]}), and gets back its output as it is printed ({"out": text},
{"err": text}) and its exit status ({"exit": code}); {"stop": true} ends the session.
When listening, the server writes to file descriptor N what the session needs to reach it,
as Open Job Description environment lines (openjd_env: NAME=value), then closes it: the
job's onEnter action waits on that pipe, so it returns as soon as Blender is ready, or
with Blender's log if it died first. Each task opens its .blend afresh (--blend). The
server also ends when its socket or the session's folder is gone (a session that ended
without its onExit action)."""

import json
import os
import signal
import socket
import sys

from .task import run_command

IDLE_CHECK_SECONDS = 5.0  # how often an idle server checks that its socket is still there


class _Stream:
    """sys.stdout / sys.stderr during a task: each write goes to the task's client and to
    the session's own log."""

    def __init__(self, connection, key, log):
        self.connection, self.key, self.log = connection, key, log

    def write(self, text):
        if text:
            self.log.write(text)
            try:
                self.connection.sendall((json.dumps({self.key: text}) + "\n").encode())
            except OSError:  # the client went away (its task was cancelled): the log has it
                pass
        return len(text)

    def flush(self):
        self.log.flush()


def _announce(fd, socket_path):
    client = os.path.join(os.path.dirname(os.path.abspath(__file__)), "client.py")
    lines = [
        f"openjd_env: HYVOX_FARM_SOCKET={socket_path}",
        f"openjd_env: HYVOX_FARM_PYTHON={sys.executable}",
        f"openjd_env: HYVOX_FARM_CLIENT={client}",
        f"openjd_env: HYVOX_FARM_PID={os.getpid()}",
        f"hyvox: session Blender {os.getpid()} ready on {socket_path}",
    ]
    os.write(fd, ("\n".join(lines) + "\n").encode())
    os.close(fd)


def _serve_one(connection):
    """One request; False when it asked the server to stop."""
    reader = connection.makefile("r", encoding="utf-8")
    line = reader.readline()
    if not line:
        return True
    request = json.loads(line)
    connection.sendall((json.dumps({"pid": os.getpid()}) + "\n").encode())
    if request.get("stop"):
        connection.sendall(b'{"exit": 0}\n')
        return False
    out, err = sys.stdout, sys.stderr
    sys.stdout, sys.stderr = _Stream(connection, "out", out), _Stream(connection, "err", err)
    try:
        code = run_command(request["argv"])
    finally:
        sys.stdout, sys.stderr = out, err
        out.flush()
        err.flush()
    try:
        connection.sendall((json.dumps({"exit": code}) + "\n").encode())
    except OSError:
        pass
    return True


def serve(argv):
    import argparse

    parser = argparse.ArgumentParser(prog="hyvox farm serve")
    parser.add_argument("--socket", required=True)
    parser.add_argument("--announce-fd", type=int, required=True)
    parser.add_argument("--session-dir", required=True)
    args = parser.parse_args(argv)
    path = os.path.abspath(args.socket)
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(path)
    listener.listen(4)
    listener.settimeout(IDLE_CHECK_SECONDS)
    # Between tasks SIGTERM ends the session; during one, task.cancel_on_sigterm cancels it.
    stopping = []
    signal.signal(signal.SIGTERM, lambda signum, frame: stopping.append(signum))
    _announce(args.announce_fd, path)
    try:
        while not stopping:
            try:
                connection, _ = listener.accept()
            except socket.timeout:
                if not (os.path.exists(path) and os.path.isdir(args.session_dir)):
                    break  # nobody will come
                continue
            except InterruptedError:
                continue
            with connection:
                connection.settimeout(None)
                if not _serve_one(connection):
                    break
    finally:
        listener.close()
        if os.path.exists(path):
            os.remove(path)
    print("hyvox: session Blender stopped", flush=True)
