"""eco view as the tests drive it: started on any free port, its address read from what it prints,
asked with raw HTTP requests (so that paths reach it exactly as written, not tidied by a client),
and ended with SIGTERM, its stderr kept for the refusals it logged.

usage: server = ViewServer(cli, folder[, extra args]); server.get("/api/run"); server.stop()"""

import os
import re
import select
import socket
import subprocess
import time


class ViewServer:
    def __init__(self, command, cwd=None, timeout=120):
        """Runs `command` (an eco command line that serves, e.g. [eco, "view", folder, "--port", "0"])
        and waits for its "viewer: http://host:port/" line."""
        self.command = command
        self.process = subprocess.Popen(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
        self._pending = b""
        self.stdout_lines = []
        deadline = time.time() + timeout
        while time.time() < deadline and self.alive():
            for line in self.read_lines(wait=1.0):
                found = re.search(r"http://([\d.]+):(\d+)/", line)
                if found:
                    self.host, self.port = found.group(1), int(found.group(2))
                    self.url = f"http://{self.host}:{self.port}/"
                    return
        err = self.stop()
        raise RuntimeError(f"{' '.join(command)} did not serve:\n{''.join(self.stdout_lines)}\n{err}")

    def raw(self, request_bytes, read_all=True):
        """Sends `request_bytes` as they are; returns (status, body bytes)."""
        with socket.create_connection((self.host, self.port), timeout=30) as s:
            s.sendall(request_bytes)
            data = b""
            while read_all:
                chunk = s.recv(1 << 16)
                if not chunk:
                    break
                data += chunk
        head, _, body = data.partition(b"\r\n\r\n")
        status = int(head.split(b" ", 2)[1]) if head else 0
        return status, body

    def get(self, path):
        """GET `path` exactly as written, the connection closed after it; returns (status, body bytes)."""
        return self.raw(f"GET {path} HTTP/1.1\r\nHost: {self.host}\r\nConnection: close\r\n\r\n".encode())

    def read_lines(self, wait=0.0):
        """The lines the command printed since the last call (waiting up to `wait` seconds for some)."""
        fd = self.process.stdout.fileno()
        fresh = []
        while select.select([fd], [], [], wait)[0]:
            chunk = os.read(fd, 1 << 16)
            if not chunk:
                break
            self._pending += chunk
            *complete, self._pending = self._pending.split(b"\n")
            fresh += [line.decode() + "\n" for line in complete]
            wait = 0.0
        self.stdout_lines += fresh
        return fresh

    def alive(self):
        return self.process.poll() is None

    def stop(self):
        """Ends the command; returns what it wrote to stderr."""
        if self.alive():
            self.process.terminate()
        try:
            _, err = self.process.communicate(timeout=30)
        except subprocess.TimeoutExpired:
            self.process.kill()
            _, err = self.process.communicate()
        return err.decode(errors="replace")
