"""A small client for the Voxhap front-end protocol (docs/protocol.md), from the doc alone.

Frames: a 4-byte little-endian length N, then N bytes of one serialized protobuf message.
The caller passes the generated module (frontend_pb2) so this file does not depend on
where protoc put it.
"""

import socket
import struct
import time

MAX_FRAME = 16 * 1024 * 1024  # 16 MiB, both directions
PROTOCOL_VERSION = 1


class ProtocolError(Exception):
    """The peer broke the framing or the request/reply rules."""


class Closed(ProtocolError):
    """The controller closed the connection."""


class RequestFailed(Exception):
    """The controller answered a request with an Error."""

    def __init__(self, error):
        super().__init__(f"{error.message} (field {error.field!r})")
        self.error = error


class Client:
    """One connection. Requests get ids 1, 2, 3, …; events (id 0) read while waiting for
    a reply are kept in `events` for next_event()."""

    def __init__(self, pb, host, port, timeout_s=5.0):
        self.pb = pb
        self.timeout_s = timeout_s
        self.sock = socket.create_connection((host, port), timeout=timeout_s)
        self.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.next_id = 1
        self.events = []  # events received while waiting for replies, oldest first
        self.replies = {}  # replies to other requests received meanwhile, by id
        self.reply_order = []  # ids of the replies in the order they arrived
        self._buf = b""

    def close(self):
        try:
            self.sock.close()
        except OSError:
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ---- framing -------------------------------------------------------------------------

    def send_raw(self, data):
        """Bytes as they are (for tests of bad input)."""
        self.sock.sendall(data)

    def send_frame(self, payload):
        self.sock.sendall(struct.pack("<I", len(payload)) + payload)

    def _read_exact(self, n, deadline):
        while len(self._buf) < n:
            left = deadline - time.monotonic()
            if left <= 0:
                raise TimeoutError(f"no complete frame within {self.timeout_s} s")
            self.sock.settimeout(left)
            try:
                chunk = self.sock.recv(max(65536, n - len(self._buf)))
            except socket.timeout:
                raise TimeoutError(f"no complete frame within {self.timeout_s} s") from None
            except ConnectionResetError:
                chunk = b""
            if not chunk:
                raise Closed("connection closed by the controller"
                             + (" mid-frame" if self._buf else ""))
            self._buf += chunk
        out, self._buf = self._buf[:n], self._buf[n:]
        return out

    def read_message(self, timeout_s=None):
        """The next ServerMessage, whatever it is."""
        deadline = time.monotonic() + (self.timeout_s if timeout_s is None else timeout_s)
        (n,) = struct.unpack("<I", self._read_exact(4, deadline))
        if n > MAX_FRAME:
            raise ProtocolError(f"controller announced a frame of {n} bytes")
        msg = self.pb.ServerMessage()
        msg.ParseFromString(self._read_exact(n, deadline))
        return msg

    # ---- requests ------------------------------------------------------------------------

    def send(self, field, body=None, msg_id=None):
        """Sends one request (`field` is the oneof's name, body its message); its id."""
        m = self.pb.ClientMessage()
        m.id = self.next_id if msg_id is None else msg_id
        self.next_id = max(self.next_id, m.id) + 1
        getattr(m, field).SetInParent()
        if body is not None:
            getattr(m, field).CopyFrom(body)
        self.send_frame(m.SerializeToString())
        return m.id

    def wait_reply(self, msg_id, timeout_s=None):
        """The ServerMessage with `msg_id`, keeping events and other replies read
        meanwhile (a load_scene's reply comes late, others may pass it)."""
        deadline = time.monotonic() + (self.timeout_s if timeout_s is None else timeout_s)
        while msg_id not in self.replies:
            m = self.read_message(max(0.0, deadline - time.monotonic()))
            if m.id == 0:
                self.events.append(m)
            elif m.id in self.replies or m.id >= self.next_id:
                raise ProtocolError(f"reply with id {m.id}, not an open request's")
            else:
                self.replies[m.id] = m
                self.reply_order.append(m.id)
        return self.replies.pop(msg_id)

    def request(self, field, body=None, expect=None, timeout_s=None):
        """Sends a request and returns the reply's body message; an Error raises
        RequestFailed; `expect` checks the body's name."""
        reply = self.wait_reply(self.send(field, body), timeout_s)
        kind = reply.WhichOneof("body")
        if kind == "error":
            raise RequestFailed(reply.error)
        if expect is not None and kind != expect:
            raise ProtocolError(f"{field}: reply {kind}, expected {expect}")
        return getattr(reply, kind)

    def next_event(self, timeout_s=None):
        """The next event (id 0): first those kept while waiting for replies."""
        if self.events:
            return self.events.pop(0)
        deadline = time.monotonic() + (self.timeout_s if timeout_s is None else timeout_s)
        while True:
            m = self.read_message(max(0.0, deadline - time.monotonic()))
            if m.id == 0:
                return m
            self.replies[m.id] = m  # a reply to a request still open
            self.reply_order.append(m.id)

    def hello(self, name="voxhap_client.py", token=b"", version=PROTOCOL_VERSION):
        h = self.pb.Hello(protocol_version=version, client_name=name, token=token)
        return self.request("hello", h, expect="hello_reply")

    # ---- helpers -------------------------------------------------------------------------

    def wait_closed(self, timeout_s=None):
        """Reads until the controller closes the connection; the messages read meanwhile.
        TimeoutError when it stays open."""
        got = []
        while True:
            try:
                got.append(self.read_message(timeout_s))
            except Closed:
                return got


def pose(pb, position=(0.0, 0.0, 0.0), quat=(1.0, 0.0, 0.0, 0.0)):
    """A Pose from a position (m) and a quaternion (w, x, y, z)."""
    p = pb.Pose()
    p.position_m.x, p.position_m.y, p.position_m.z = position
    p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z = quat
    return p
