"""A TCP relay between one MQTT 5 client and its broker that reads what the client sends: every
PUBLISH packet's size on the wire, its topic (an alias resolved to the name it was given with),
and whether it went by alias. What it relays is unchanged, in both directions."""

import socket
import threading

from benchlib.util import HOST

CONNECT = 1
PUBLISH = 3
TOPIC_ALIAS = 0x23
# The MQTT 5 properties a PUBLISH may carry, by identifier: the size of their value, or the
# kind of value that says its own size.
FIXED = {0x01: 1, 0x02: 4, 0x23: 2}
STRING = {0x03, 0x08, 0x09}  # content type, response topic, correlation data: 2-byte length
PAIR = 0x26  # user property: two strings
VARINT = 0x0B  # subscription identifier


def varint(data, at):
    """(value, position after it) of the variable byte integer at `at`, or None if cut."""
    value, shift = 0, 0
    for i in range(4):
        if at + i >= len(data):
            return None
        byte = data[at + i]
        value |= (byte & 0x7F) << shift
        if not byte & 0x80:
            return value, at + i + 1
        shift += 7
    raise ValueError("malformed variable byte integer")


def publish_alias(body, qos, version):
    """(topic name, topic alias or 0) of a PUBLISH packet's variable header, in MQTT
    `version` (its protocol level: 5, or 4 for 3.1.1, which has no properties)."""
    length = int.from_bytes(body[0:2], "big")
    topic = body[2:2 + length].decode()
    if version < 5:
        return topic, 0
    at = 2 + length + (2 if qos else 0)
    size, at = varint(body, at)
    end, alias = at + size, 0
    while at < end:
        key = body[at]
        at += 1
        if key in FIXED:
            if key == TOPIC_ALIAS:
                alias = int.from_bytes(body[at:at + 2], "big")
            at += FIXED[key]
        elif key in STRING:
            at += 2 + int.from_bytes(body[at:at + 2], "big")
        elif key == PAIR:
            for _ in range(2):
                at += 2 + int.from_bytes(body[at:at + 2], "big")
        elif key == VARINT:
            at = varint(body, at)[1]
        else:
            raise ValueError(f"unknown PUBLISH property {key:#x}")
    return topic, alias


class MqttTap:
    """Listens on a free loopback port for the client; `port` is where to point it.
    `publications` holds (topic, bytes on the wire, by alias) of each PUBLISH not marked DUP."""

    def __init__(self, broker_port):
        self.broker_port = broker_port
        self.server = socket.create_server((HOST, 0))
        self.port = self.server.getsockname()[1]
        self.lock = threading.Lock()
        self.publications = []
        self.duplicates = 0  # bytes of re-sent PUBLISH packets (DUP set)
        self.threads = [threading.Thread(target=self.serve, daemon=True)]
        self.threads[0].start()

    def serve(self):
        while True:
            try:
                client, _ = self.server.accept()
            except OSError:
                return  # closed
            broker = socket.create_connection((HOST, self.broker_port))
            for source, sink, read in ((client, broker, True), (broker, client, False)):
                t = threading.Thread(target=self.pump, args=(source, sink, read), daemon=True)
                t.start()
                self.threads.append(t)

    def pump(self, source, sink, read):
        # What the broker keeps per connection: its protocol level, and the aliases given.
        pending, connection = b"", {"version": 5, "aliases": {}}
        try:
            while chunk := source.recv(65536):
                sink.sendall(chunk)
                if read:
                    pending = self.take(pending + chunk, connection)
        except OSError:
            pass
        finally:
            for s in (source, sink):
                try:
                    s.shutdown(socket.SHUT_RDWR)
                except OSError:
                    pass

    def take(self, data, connection):
        """Reads the whole packets at the head of `data`; what is left of it."""
        while len(data) >= 2:
            length = varint(data, 1)
            if length is None or length[1] + length[0] > len(data):
                return data
            end = length[1] + length[0]
            header, body = data[0], data[length[1]:end]
            if header >> 4 == CONNECT:  # "MQTT" (its length first), then the level
                connection["version"] = body[6]
            elif header >> 4 == PUBLISH:
                self.publication(header, body, end, connection)
            data = data[end:]
        return data

    def publication(self, header, body, size, connection):
        topic, alias = publish_alias(body, (header >> 1) & 3, connection["version"])
        aliases = connection["aliases"]
        if alias and topic:
            aliases[alias] = topic
        by_alias = bool(alias) and not topic
        with self.lock:
            if header & 0x08:
                self.duplicates += size
            else:
                self.publications.append((aliases[alias] if by_alias else topic, size, by_alias))

    def snapshot(self):
        with self.lock:
            return list(self.publications), self.duplicates

    def close(self):
        try:
            self.server.shutdown(socket.SHUT_RDWR)  # wakes the accept
        except OSError:
            pass
        self.server.close()
