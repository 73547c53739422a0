"""Browsers watching the status page, as the gateway sees them: N event streams
(/api/events?open=NAME, what the page's script opens), each read to its end by a thread of its
own that counts the events it got; a stream that got none fails the run. A build without the
page is NotInBuild."""

import socket
import threading

from benchlib.builds import NotInBuild
from benchlib.util import HOST


class EventStreams:
    def __init__(self, port, opened, build):
        """One stream per name of `opened` (the exchange that page has open), to the listener
        on `port` of `build`'s gateway."""
        self.port, self.opened, self.build = port, list(opened), build
        self.sockets, self.threads, self.events = [], [], [0] * len(self.opened)

    def __enter__(self):
        for i, name in enumerate(self.opened):
            s = socket.create_connection((HOST, self.port), timeout=10)
            self.sockets.append(s)
            s.sendall(f"GET /api/events?open={name} HTTP/1.1\r\nHost: {HOST}\r\n\r\n".encode())
            head = s.recv(4096)
            if not head.startswith(b"HTTP/1.1 200") or b"text/event-stream" not in head:
                self.close()
                raise NotInBuild(self.build, "no status page event stream: " +
                                 head.split(b"\r\n", 1)[0].decode(errors="replace"))
            self.events[i] += head.count(b"event: ")
            thread = threading.Thread(target=self.read, args=(i, s), daemon=True)
            thread.start()
            self.threads.append(thread)
        return self

    def read(self, i, s):
        s.settimeout(5)  # an event comes every second
        try:
            while data := s.recv(65536):
                self.events[i] += data.count(b"event: ")
        except OSError:  # closed by __exit__, or no event for 5 s: the count says so
            pass

    def close(self):
        for s in self.sockets:
            try:
                s.shutdown(socket.SHUT_RDWR)
            except OSError:
                pass
            s.close()
        for thread in self.threads:
            thread.join(timeout=10)

    def __exit__(self, exc_type, *exc):
        """Closes every stream; a stream that got no event fails the run (it was not live)."""
        self.close()
        if exc_type is None and min(self.events, default=0) == 0:
            raise RuntimeError(f"an event stream on port {self.port} got no event: "
                               f"{self.events}")
        return False
