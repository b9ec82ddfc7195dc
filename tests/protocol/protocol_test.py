#!/usr/bin/env python3
"""Checks a real `voxhap controller` against docs/protocol.md, with a Python client
written from the doc and the schema alone.

    protocol_test.py VOXHAP_EXE FRONTEND_PROTO ASSETS_DIR

Generates frontend_pb2.py with protoc into a temp dir, starts the controller on
127.0.0.1:0, prints one line per check and exits non-zero at the first failure. A second
run listens on a non-loopback address of this machine (when there is one) with --token.
"""

import argparse
import math
import os
import queue
import re
import shutil
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

OVERALL_TIMEOUT_S = 60
HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import voxhap_client as vc  # noqa: E402

pb = None  # frontend_pb2, generated at start


class CheckFailed(Exception):
    pass


def check(cond, what):
    if not cond:
        raise CheckFailed(what)


def ok(what):
    print(f"ok   {what}", flush=True)


def note(what):
    print(f"note {what}", flush=True)


def expect_error(client, field, body, want_field, what):
    """A request that must fail with an Error naming `want_field`; the connection stays."""
    try:
        client.request(field, body)
    except vc.RequestFailed as e:
        check(e.error.field == want_field,
              f"{what}: error field {e.error.field!r}, expected {want_field!r} ({e.error.message})")
        check(e.error.message and "\n" not in e.error.message, f"{what}: message not one line")
        return e.error
    raise CheckFailed(f"{what}: accepted, expected an error naming {want_field!r}")


# ---- the controller process ---------------------------------------------------------------


class Controller:
    """`voxhap controller …` as a child; its stderr read by a thread (so it never blocks)."""

    def __init__(self, exe, args, cwd):
        self.lines = []
        self._port = queue.Queue()
        self.proc = subprocess.Popen([exe, "controller", *args], cwd=cwd,
                                     stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                     stderr=subprocess.PIPE, text=True)
        threading.Thread(target=self._read, daemon=True).start()
        self.stdout = ""
        threading.Thread(target=self._read_out, daemon=True).start()

    def _read(self):
        for line in self.proc.stderr:
            self.lines.append(line.rstrip("\n"))
            m = re.search(r"listening on (\S+):(\d+)$", line.strip())
            if m:
                self._port.put((m.group(1), int(m.group(2))))
        self._port.put(None)

    def _read_out(self):
        self.stdout = self.proc.stdout.read()

    def address(self, timeout_s=30):
        try:
            got = self._port.get(timeout=timeout_s)
        except queue.Empty:
            got = None
        if got is None:
            raise CheckFailed("controller printed no 'listening on HOST:PORT': "
                              + " | ".join(self.lines[-5:]))
        return got

    def kill(self):
        if self.proc.poll() is None:
            self.proc.kill()
            self.proc.wait(5)


# ---- the checks ---------------------------------------------------------------------------


def quat_angle(a, b):
    dot = abs(a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z)
    return 2 * math.acos(min(1.0, dot))


def check_hello(host, port):
    with vc.Client(pb, host, port) as c:
        r = c.hello("protocol_test")
        check(r.protocol_version == 1, f"hello: protocol_version {r.protocol_version}")
        check(r.controller_version.startswith("voxhap "),
              f"hello: controller_version {r.controller_version!r}")
        check("ball-and-socket" in r.scene, f"hello: scene {r.scene!r}")
        check(r.frame_period_s == 0.001, f"hello: frame_period_s {r.frame_period_s}")
        ok(f"hello: version 1, {r.controller_version!r}, scene {r.scene!r}, period 1 ms")


def check_list_objects(c):
    objs = c.request("list_objects", expect="object_list").objects
    names = [o.name for o in objs]
    check(names[:2] == ["ball", "socket"], f"list_objects: names {names}")
    ball, socket_ = objs[0], objs[1]
    check(ball.index == 0 and ball.moving and ball.mass_kg > 0 and ball.points > 0,
          f"list_objects: ball {ball}")
    check(ball.held_by == "script:assets/scripts/ball-turn.txt",
          f"list_objects: ball held_by {ball.held_by!r}")
    check(socket_.index == 1 and not socket_.moving and socket_.held_by == "",
          f"list_objects: socket {socket_}")
    check([o.index for o in objs] == list(range(len(objs))), "list_objects: indices")
    moving = [o.moving for o in objs]
    check(moving == sorted(moving, reverse=True), "list_objects: moving objects not first")
    ok(f"list_objects: ball (moving, {ball.mass_kg:.3f} kg, {ball.points} points, "
       f"held by {ball.held_by}), socket (static)")


def check_subscribe(c):
    c.request("subscribe", pb.Subscribe(rate_hz=100), expect="done")
    frames = []
    while len(frames) < 25:
        e = c.next_event(5)
        check(e.WhichOneof("body") == "frame_update", f"subscribe: event {e}")
        frames.append(e.frame_update)
    nums = [f.frame for f in frames]
    check(all(b > a for a, b in zip(nums, nums[1:])), f"frame_update: frames not increasing {nums}")
    times = [f.time_s for f in frames]
    check(all(b > a for a, b in zip(times, times[1:])), "frame_update: time_s not increasing")
    for f in frames:
        check(len(f.objects) == 1 and f.objects[0].index == 0, f"frame_update: objects {f.objects}")
        q = f.objects[0].pose.orientation
        check(abs(q.w ** 2 + q.x ** 2 + q.y ** 2 + q.z ** 2 - 1) < 1e-6, "frame_update: quaternion")
        check(0 <= f.objects[0].travel_share <= 1 + 1e-9, "frame_update: travel_share")
    # the script grabs the ball as the controller starts: from its first frame or the next
    held = [f.objects[0].HasField("handle") for f in frames]
    check(all(held[1:]), f"frame_update: the held ball has no handle in frames {nums} ({held})")
    turn = quat_angle(frames[0].objects[0].pose.orientation, frames[-1].objects[0].pose.orientation)
    check(turn > 1e-3, f"frame_update: the ball did not turn ({turn} rad)")
    # the ball (r = 25 mm, centred on its pose's position) turns seated in its socket
    for f in frames:
        o = f.objects[0]
        xyz = o.contact_point_m
        check(len(xyz) % 3 == 0 and (o.contacts > 0) == (len(xyz) > 0) and len(xyz) <= 3 * min(o.contacts, 64),
              f"frame_update: {o.contacts} contacts, {len(xyz)} contact point coordinates")
        centre = o.pose.position_m
        for i in range(0, len(xyz), 3):
            r = math.dist(xyz[i:i + 3], (centre.x, centre.y, centre.z))
            check(abs(r - 0.025) < 0.0015, f"frame_update: a contact point {r * 1000:.2f} mm from the ball's centre")
    seated = sum(1 for f in frames if f.objects[0].contacts > 0)
    check(seated > 0, "frame_update: the ball turned in its socket without a contact")
    ok(f"subscribe 100 Hz: {len(frames)} frame_updates, frames {nums[0]}..{nums[-1]} increasing, "
       f"ball turned {math.degrees(turn):.1f} deg, contact points on its surface in {seated} frames")
    c.request("subscribe", pb.Subscribe(rate_hz=0), expect="done")
    # events already queued may still come; the stream must stop soon after
    deadline = time.monotonic() + 1.0
    quiet_since = time.monotonic()
    while time.monotonic() < deadline:
        try:
            c.next_event(0.3)
            quiet_since = time.monotonic()
        except TimeoutError:
            break
    check(time.monotonic() - quiet_since >= 0.29, "subscribe 0: frame_updates go on")
    c.events.clear()
    ok("subscribe 0 stops the frame_updates")
    expect_error(c, "subscribe", pb.Subscribe(rate_hz=1001), "rate_hz", "subscribe 1001 Hz")
    expect_error(c, "subscribe", pb.Subscribe(rate_hz=-1), "rate_hz", "subscribe -1 Hz")
    expect_error(c, "subscribe", pb.Subscribe(rate_hz=0.5), "rate_hz", "subscribe 0.5 Hz")
    ok("subscribe 1001 Hz, -1 Hz and 0.5 Hz: error naming rate_hz")


def check_set_parameters(c):
    p = c.request("set_parameters", pb.SetParameters(), expect="parameters")  # nothing set: no change
    check(1 <= p.min_force_layer <= p.force_layer <= p.max_force_layer, f"set_parameters: force layer in range {p}")
    check(p.coupling_stiffness_share == 1.0 and p.coupling_damping_ratio == 1.0, f"default coupling {p}")
    check(len(p.coupling) == 1 and p.coupling[0].linear_stiffness_n_per_m > 0, f"coupling gains {p}")
    p3 = c.request("set_parameters", pb.SetParameters(force_layer=3), expect="parameters")
    check(p3.force_layer == 3, f"set_parameters force_layer 3: {p3.force_layer}")
    half = c.request("set_parameters", pb.SetParameters(coupling_stiffness_share=0.5), expect="parameters")
    k0, k = p.coupling[0].linear_stiffness_n_per_m, half.coupling[0].linear_stiffness_n_per_m
    check(abs(k - 0.5 * k0) <= 1e-9 * k0, f"share 0.5 halves the stiffness: {k0} -> {k}")
    ok(f"set_parameters: none, force_layer 3, coupling share 0.5 (stiffness {k0:.0f} -> {k:.0f} N/m)")
    for field, value in (("force_layer", 0), ("force_layer", 100000), ("force_layer", p.max_force_layer + 1),
                         ("coupling_stiffness_share", 0.0), ("coupling_damping_ratio", 5.0),
                         ("voxel_size_m", -1.0), ("point_offset_m", 2.0)):
        err = expect_error(c, "set_parameters", pb.SetParameters(**{field: value}), field,
                           f"set_parameters {field} {value}")
    back = c.request("set_parameters", pb.SetParameters(force_layer=p.force_layer, coupling_stiffness_share=1.0),
                     expect="parameters")
    check(back.force_layer == p.force_layer and back.coupling_stiffness_share == 1.0, f"restored {back}")
    ok(f"set_parameters out of range: error naming the field ({err.message!r}), nothing changed")


def check_statistics(c):
    s = c.request("get_statistics", expect="statistics")
    check(s.frames > 0, f"statistics: frames {s.frames}")
    check(0 < s.period_p50_s <= s.period_p99_s <= s.period_p999_s <= s.period_max_s,
          f"statistics: period percentiles {s}")
    check(0 < s.compute_p50_s <= s.compute_p99_s <= s.compute_max_s,
          f"statistics: compute percentiles {s}")
    check(not s.realtime and not s.memory_locked, "statistics: realtime under --no-realtime")
    ok(f"get_statistics: {s.frames} frames, period p50 {s.period_p50_s * 1e6:.0f} us, "
       f"max {s.period_max_s * 1e6:.0f} us, {s.overruns} overruns, realtime {s.realtime}")


def check_unknown_request(c):
    m = pb.ClientMessage(id=c.next_id)  # no request field set, as from a newer client
    c.next_id += 1
    c.send_frame(m.SerializeToString())
    r = c.wait_reply(m.id)
    check(r.WhichOneof("body") == "error", f"unset request: reply {r}")
    c.request("list_objects", expect="object_list")
    ok(f"a request with no field set: error ({r.error.message!r}), connection stays")
    # the doc says "not served yet"; a newer controller answers with a proximity
    try:
        r = c.request("get_proximity", pb.GetProximity(object="ball"))
    except vc.RequestFailed as e:
        ok(f"get_proximity: error ({e.error.message!r}), as the doc says (not served yet)")
    else:
        check(isinstance(r, pb.Proximity) and r.object == "ball" and len(r.vertex_distance_m) > 0,
              f"get_proximity: reply {type(r).__name__}")
        note(f"get_proximity is served: proximity of {r.object!r}, "
             f"{len(r.vertex_distance_m)} vertex distances (the doc says not served yet)")
        expect_error(c, "get_proximity", pb.GetProximity(object="socket"), "object",
                     "get_proximity of a static object")


def check_load_scene(c, host, port):
    expect_error(c, "load_scene", pb.LoadScene(scene="peg-in-hole"), "move", "load_scene, no move")
    expect_error(c, "load_scene", pb.LoadScene(scene="no-such-scene", move=["x"]), "scene",
                 "load_scene no-such-scene")
    try:
        c.request("load_scene", pb.LoadScene(scene="peg-in-hole", move=["no-such-object"]))
        raise CheckFailed("load_scene with an unknown move: accepted")
    except vc.RequestFailed as e:
        check(e.error.field in ("move", "scene"), f"load_scene unknown move: {e}")
        if e.error.field != "move":
            note(f"load_scene with an unknown `move` name: error field {e.error.field!r} "
                 f"({e.error.message!r})")
    ok("load_scene errors: no move -> field move, unknown scene -> field scene")
    c.events.clear()

    load_id = c.send("load_scene", pb.LoadScene(scene="peg-in-hole", move=["peg"]))
    list_id = c.send("list_objects")  # answered meanwhile, against one scene or the other
    reply = c.wait_reply(load_id, 60)
    listed = c.wait_reply(list_id)
    check(listed.WhichOneof("body") == "object_list", f"list_objects during a load: {listed}")
    check(reply.WhichOneof("body") == "object_list", f"load_scene reply: {reply}")
    names = [(o.name, o.moving) for o in reply.object_list.objects]
    check(names == [("peg", True), ("block", False)], f"load_scene object_list: {names}")
    progress = [e.load_progress for e in c.events if e.WhichOneof("body") == "load_progress"]
    c.events.clear()
    check(progress, "load_scene: no load_progress events before the reply")
    check(all(p.request_id == load_id for p in progress), "load_progress: request_id")
    check(all(0 <= p.fraction <= 1 for p in progress), "load_progress: fraction beyond 0..1")
    check(progress[-1].fraction == 1, f"load_progress: last fraction {progress[-1].fraction}")
    fr = [p.fraction for p in progress]
    if any(b < a for a, b in zip(fr, fr[1:])):
        note(f"load_progress fractions not monotonic: {fr}")
    ok(f"load_scene peg-in-hole: {len(progress)} load_progress events "
       f"({', '.join(sorted(set(p.stage for p in progress)))}), last fraction 1, then "
       f"object_list {[n for n, _ in names]}; list_objects answered during the load")
    with vc.Client(pb, host, port) as d:
        check("peg-in-hole" in d.hello().scene, "hello after load: scene")
    ok("hello on a new connection names the new scene")


def check_grab(c, host, port):
    c.request("grab", pb.Grab(object="peg", device="client"), expect="done")
    peg = c.request("list_objects").objects[0]
    check(peg.held_by == "client", f"grab: held_by {peg.held_by!r}")
    c.request("move_handle", pb.MoveHandle(object="peg", handle=vc.pose(pb, (0, 0, 0.01))),
              expect="done")
    c.request("subscribe", pb.Subscribe(rate_hz=50), expect="done")
    deadline = time.monotonic() + 5
    z = None
    while time.monotonic() < deadline:
        s = c.next_event(5).frame_update.objects[0]
        z = s.pose.position_m.z
        check(s.HasField("handle") and abs(s.handle.position_m.z - 0.01) < 1e-9,
              f"frame_update: handle {s.handle}")
        if abs(z - 0.01) < 1e-4:
            break
    check(z is not None and abs(z - 0.01) < 1e-4, f"move_handle: the peg at z {z}, not 0.01")
    c.request("subscribe", pb.Subscribe(rate_hz=0), expect="done")
    ok("grab peg with device client, move_handle 10 mm up: the peg follows its handle")

    for body, fld in ((pb.Grab(object="nope", device="client"), "object"),
                      (pb.Grab(object="block", device="client"), "object"),
                      (pb.Grab(object="peg", device="bogus"), "device"),
                      (pb.Grab(object="peg", device="script:/no/such/script.txt"), "device")):
        expect_error(c, "grab", body, fld, f"grab {body.object} {body.device}")
    expect_error(c, "move_handle", pb.MoveHandle(object="peg", handle=vc.pose(pb, quat=(2, 0, 0, 0))),
                 "handle", "move_handle with a non-unit quaternion")
    ok("grab with a bad object/device and move_handle with a bad pose: errors naming the field")

    with vc.Client(pb, host, port) as d:
        d.hello()
        expect_error(d, "move_handle", pb.MoveHandle(object="peg", handle=vc.pose(pb)), "object",
                     "move_handle from a connection that does not hold the peg")
        ok("move_handle from another connection: error naming object")
        c.close()  # the holder leaves: the peg is released
        deadline = time.monotonic() + 3
        while True:
            peg = d.request("list_objects").objects[0]
            if peg.held_by == "" or time.monotonic() > deadline:
                break
            time.sleep(0.05)
        check(peg.held_by == "", f"after the holder disconnects: held_by {peg.held_by!r}")
        ok("the holder disconnects: the peg is released")
        d.request("grab", pb.Grab(object="peg", device="client"), expect="done")
        d.request("release", pb.Release(object="peg"), expect="done")
        check(d.request("list_objects").objects[0].held_by == "", "release: still held")
        ok("grab then release: free")


def bad_input_cases():
    """(name, whether to say hello first, what to do on the connection)."""
    def oversize(c):
        c.send_raw(struct.pack("<I", vc.MAX_FRAME + 1))

    def not_client_message(c):
        c.send_frame(b"\xff\xff\xff\xff\x0f")  # field 31 with an invalid wire type

    def mid_frame(c):
        c.send_raw(struct.pack("<I", 100) + b"\x08\x05")
        c.sock.shutdown(socket.SHUT_WR)

    def non_increasing(c):
        c.request("list_objects")  # id 2
        c.send("list_objects", msg_id=2)

    def zero_id(c):
        c.send("list_objects", msg_id=0)

    def before_hello(c):
        c.send("list_objects")

    def second_hello(c):
        c.send("hello", pb.Hello(protocol_version=1))

    def wrong_version(c):
        c.send("hello", pb.Hello(protocol_version=2))

    return [("a frame announcing 16 MiB + 1", True, oversize, 0),
            ("a frame that is not a ClientMessage", True, not_client_message, 0),
            ("a connection ending mid-frame", True, mid_frame, 0),
            ("a non-increasing id", True, non_increasing, 2),
            ("a zero id", True, zero_id, 0),
            ("a request before hello", False, before_hello, 1),
            ("a second hello", True, second_hello, 2),
            ("protocol_version 2", False, wrong_version, 1)]


def check_bad_inputs(good, host, port):
    for name, hello, act, err_id in bad_input_cases():
        with vc.Client(pb, host, port, timeout_s=3) as c:
            if hello:
                c.hello()
            act(c)
            try:
                got = c.wait_closed(3)
            except TimeoutError:
                raise CheckFailed(f"{name}: the connection stays open") from None
            errs = [m for m in got if m.WhichOneof("body") == "error"]
            check(errs and errs[-1].id in (0, err_id),
                  f"{name}: expected an error (id 0 or {err_id}) before the close, got {got}")
        good.request("list_objects", expect="object_list")
        ok(f"{name}: error {errs[-1].error.message!r}, closed; another connection still served")

    with vc.Client(pb, host, port) as c:  # exactly 16 MiB is allowed: it waits for the rest
        c.hello()
        c.send_raw(struct.pack("<I", vc.MAX_FRAME))
        try:
            c.read_message(0.5)
            raise CheckFailed("a 16 MiB announcement: got a message")
        except TimeoutError:
            pass
    ok("a frame announcing exactly 16 MiB: the connection stays open")


def check_shutdown(ctl, c, host, port):
    other = vc.Client(pb, host, port)
    other.hello()
    t0 = time.monotonic()
    c.request("shutdown", expect="done")
    try:
        other.wait_closed(5)
    except TimeoutError:
        raise CheckFailed("shutdown: another connection stays open") from None
    try:
        rc = ctl.proc.wait(5)
    except subprocess.TimeoutExpired:
        raise CheckFailed("shutdown: the controller did not exit within 5 s") from None
    check(rc == 0, f"shutdown: exit status {rc}")
    ok(f"shutdown: done, every connection closed, exit 0 after {time.monotonic() - t0:.2f} s")


def run_loopback(exe, cwd, tmp):
    # a voxel cache of its own: the run neither reads nor fills the user's
    ctl = Controller(exe, ["ball-and-socket", "--move", "ball", "--device",
                           "script:assets/scripts/ball-turn.txt", "--listen", "127.0.0.1:0",
                           "--no-realtime", "--cache-dir", os.path.join(tmp, "cache")], cwd)
    try:
        host, port = ctl.address()
        ok(f"controller listening on {host}:{port}")
        check_hello(host, port)
        c = vc.Client(pb, host, port)
        c.hello("protocol_test main")
        check_list_objects(c)
        check_subscribe(c)
        check_set_parameters(c)
        check_statistics(c)
        check_unknown_request(c)
        good = vc.Client(pb, host, port)  # stays on while the others misbehave
        good.hello("protocol_test good")
        check_bad_inputs(good, host, port)
        check_load_scene(c, host, port)
        check_grab(c, host, port)
        check_shutdown(ctl, good, host, port)
    finally:
        ctl.kill()


def non_loopback_ipv4():
    """An IPv4 address of this machine other than 127.x, or None."""
    if shutil.which("ip"):
        out = subprocess.run(["ip", "-4", "-o", "addr", "show"], capture_output=True,
                             text=True, timeout=5).stdout
        for a in re.findall(r"inet (\d+\.\d+\.\d+\.\d+)/", out):
            if not a.startswith("127."):
                return a
    try:  # the interface a route would use (a UDP connect sends nothing)
        with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as s:
            s.connect(("192.0.2.1", 9))
            a = s.getsockname()[0]
            return None if a.startswith("127.") or a == "0.0.0.0" else a
    except OSError:
        return None


def run_token(exe, cwd, tmp):
    addr = non_loopback_ipv4()
    if addr is None:
        note("no non-loopback IPv4 address on this machine: token check skipped")
        return
    r = subprocess.run([exe, "controller", "ball-and-socket", "--move", "ball", "--listen",
                        f"{addr}:0", "--no-realtime", "--duration", "5",
                        "--cache-dir", os.path.join(tmp, "cache")],
                       cwd=cwd, capture_output=True, text=True, timeout=20)
    check(r.returncode != 0, f"--listen {addr} without --token: exit {r.returncode}")
    ok(f"--listen {addr}:0 without --token: refused, exit {r.returncode}")

    token_file = os.path.join(tmp, "token")
    with open(token_file, "w") as f:
        f.write("py-client-token-8c1f\n")
    token = b"py-client-token-8c1f"  # the file's contents without the final line end
    ctl = Controller(exe, ["ball-and-socket", "--move", "ball", "--listen", f"{addr}:0",
                           "--token", token_file, "--no-realtime",
                           "--cache-dir", os.path.join(tmp, "cache")], cwd)
    try:
        host, port = ctl.address()
        ok(f"controller with --token listening on {host}:{port}")
        for name, t in (("no token", b""), ("a wrong token", b"py-client-token-0000")):
            with vc.Client(pb, host, port, timeout_s=3) as c:
                try:
                    c.hello(token=t)
                    raise CheckFailed(f"hello with {name}: accepted")
                except vc.RequestFailed as e:
                    msg = e.error.message
                except vc.Closed:
                    msg = "(closed without an error)"
                try:
                    c.wait_closed(3)
                except TimeoutError:
                    raise CheckFailed(f"hello with {name}: the connection stays open") from None
            ok(f"hello with {name}: refused ({msg!r}), closed")
        with vc.Client(pb, host, port) as c:
            c.hello(token=token)
            c.request("list_objects", expect="object_list")
            ok("hello with the token: served")
            c.request("shutdown", expect="done")
        check(ctl.proc.wait(5) == 0, "token run: exit status")
        ok("token run: shutdown, exit 0")
    finally:
        ctl.kill()


def main():
    global pb
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("voxhap", help="the voxhap executable")
    ap.add_argument("proto", help="net/proto/frontend.proto")
    ap.add_argument("assets", help="the assets folder (holding scripts/ball-turn.txt)")
    ap.add_argument("--protoc", default=shutil.which("protoc") or "protoc")
    a = ap.parse_args()
    exe = os.path.abspath(a.voxhap)
    cwd = os.path.dirname(os.path.abspath(a.assets))  # so script:assets/… resolves

    def on_alarm(*_):
        raise CheckFailed(f"overall time-out of {OVERALL_TIMEOUT_S} s")
    signal.signal(signal.SIGALRM, on_alarm)
    signal.alarm(OVERALL_TIMEOUT_S)
    try:
        with tempfile.TemporaryDirectory() as tmp:
            proto = os.path.abspath(a.proto)
            subprocess.run([a.protoc, f"--python_out={tmp}", "-I", os.path.dirname(proto), proto],
                           check=True, timeout=30)
            sys.path.insert(0, tmp)
            import frontend_pb2
            pb = frontend_pb2
            ok("frontend_pb2 generated by protoc")
            run_loopback(exe, cwd, tmp)
            run_token(exe, cwd, tmp)
    except (CheckFailed, vc.ProtocolError, vc.RequestFailed, TimeoutError, OSError,
            subprocess.SubprocessError) as e:
        print(f"FAIL {type(e).__name__}: {e}", flush=True)
        return 1
    finally:
        signal.alarm(0)
    print("all protocol checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
