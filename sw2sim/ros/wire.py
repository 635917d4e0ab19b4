"""Just enough of ROS 1's client protocol, in the standard library, for the stand-in's
small nodes (sw2sim.ros.nodes): call a service, and latch one message on a topic.

rospy would do, but importing it alone takes half a second of processor time, and a
launch file starts three of these nodes; here a node starts in a tenth of that. What it
speaks is ROS 1's own: XML-RPC with the master and the node's slave API, TCPROS for the
data, messages packed as genpy packs them. It does not follow /clock, log to /rosout or
resolve private (`~`) names; none of the three nodes needs them.
"""

from __future__ import annotations

import ast
import os
import socket
import struct
import sys
import threading
import time
import xmlrpc.client
from pathlib import Path
from socketserver import ThreadingMixIn
from xmlrpc.server import SimpleXMLRPCRequestHandler, SimpleXMLRPCServer


class RosError(Exception):
    """The master or a service said no, or did not answer in time."""


# -- the master ------------------------------------------------------------------------------
ANSWER_TIMEOUT = 3.0   # s for a master to answer; what holds a port and never answers is none


class _Timed(xmlrpc.client.Transport):
    def make_connection(self, host):
        connection = super().make_connection(host)
        connection.timeout = ANSWER_TIMEOUT
        return connection


def master_answers(uri: str) -> bool:
    """A ROS master answers at `uri` within ANSWER_TIMEOUT (rosgraph's is_online asks
    without a time limit, and waits for ever on a port whose holder accepts and says
    nothing)."""
    try:
        code, _, _ = xmlrpc.client.ServerProxy(uri, transport=_Timed()).getPid("/sw2sim")
    except (OSError, ValueError, xmlrpc.client.Error):
        return False
    return code == 1


# -- packing, as genpy does (little-endian) -------------------------------------------------

def string(text: str) -> bytes:
    data = text.encode("utf-8")
    return struct.pack("<I", len(data)) + data


def strings(items: list[str]) -> bytes:
    return struct.pack("<I", len(items)) + b"".join(string(s) for s in items)


def float64s(*values: float) -> bytes:
    return struct.pack(f"<{len(values)}d", *values)


def unpack_bool_and_string(data: bytes) -> tuple[bool, str]:
    """A response of `bool success` and `string status_message`."""
    (size,) = struct.unpack_from("<I", data, 1)
    return bool(data[0]), data[5:5 + size].decode("utf-8", "replace")


# -- what a message or service is: its type name, md5sum and definition --------------------

def definition(module_file: Path, type_name: str) -> tuple[str, str, str]:
    """(type, md5sum, full text) of a genpy-generated message or service module, read from
    its source (importing it would import genpy, and with it numpy)."""
    tree = ast.parse(module_file.read_text(encoding="utf-8"))
    for node in ast.walk(tree):
        if isinstance(node, ast.ClassDef) and node.name == type_name:
            values = {}
            for item in node.body:
                if isinstance(item, ast.Assign) and isinstance(item.targets[0], ast.Name):
                    try:
                        values[item.targets[0].id] = ast.literal_eval(item.value)
                    except ValueError:
                        pass
            return values["_type"], values["_md5sum"], values.get("_full_text", "")
    raise RosError(f"{module_file} defines no {type_name}")


def module_of(package: str, kind: str, name: str) -> Path:
    """The generated module of package/kind/name: the stand-in's own (sw2sim.ros.messages)
    or Debian's."""
    from . import messages
    for base in (messages.folder(), Path("/usr/lib/python3/dist-packages")):
        candidate = base / package / kind / f"_{name}.py"
        if candidate.is_file():
            return candidate
    raise RosError(f"no generated {package}/{name} (is ROS 1 installed?)")


# -- TCPROS framing -----------------------------------------------------------------------

def _header(fields: dict[str, str]) -> bytes:
    body = b"".join(string(f"{k}={v}") for k, v in fields.items())
    return struct.pack("<I", len(body)) + body


def _read_exactly(sock: socket.socket, size: int) -> bytes:
    data = b""
    while len(data) < size:
        chunk = sock.recv(size - len(data))
        if not chunk:
            raise RosError("the connection closed")
        data += chunk
    return data


def _read_header(sock: socket.socket) -> dict[str, str]:
    (size,) = struct.unpack("<I", _read_exactly(sock, 4))
    data, fields, at = _read_exactly(sock, size), {}, 0
    while at < size:
        (length,) = struct.unpack_from("<I", data, at)
        key, _, value = data[at + 4:at + 4 + length].decode("utf-8", "replace").partition("=")
        fields[key] = value
        at += 4 + length
    return fields


# -- the node -------------------------------------------------------------------------------

def _host() -> str:
    return os.environ.get("ROS_HOSTNAME") or os.environ.get("ROS_IP") or "127.0.0.1"


class _Server(ThreadingMixIn, SimpleXMLRPCServer):
    daemon_threads = True


class _Quiet(SimpleXMLRPCRequestHandler):
    def log_message(self, *args):
        pass


class Node:
    """A ROS 1 node: its name from `__name:=` (or `base` with the process id, as rospy's
    anonymous names), its namespace from `__ns:=` or ROS_NAMESPACE, remappings `a:=b`."""

    def __init__(self, base: str, argv: list[str]):
        special = dict(a[2:].split(":=", 1) for a in argv if a.startswith("__") and ":=" in a)
        self.remaps = dict(a.split(":=", 1) for a in argv
                           if ":=" in a and not a.startswith("__"))
        self.namespace = "/" + (special.get("ns") or os.environ.get("ROS_NAMESPACE", "")).strip("/")
        name = special.get("name") or f"{base}_{os.getpid()}_{int(time.time() * 1000)}"
        self.name = self.resolve(name)
        self.master_uri = os.environ.get("ROS_MASTER_URI", "http://127.0.0.1:11311")
        self.master = xmlrpc.client.ServerProxy(self.master_uri, allow_none=True)
        self.stopped = threading.Event()
        self.published: dict[str, tuple[str, str, str, bytes]] = {}
        self.rpc = self.data = None   # the slave API and TCPROS servers, once it publishes

    def _serve(self) -> None:
        """Start the slave API (XML-RPC) and the TCPROS server a publisher needs."""
        host = _host()
        self.rpc = _Server((host, 0), requestHandler=_Quiet, logRequests=False,
                           allow_none=True)
        for method in (self.getPid, self.getMasterUri, self.getBusInfo, self.getBusStats,
                       self.getSubscriptions, self.getPublications, self.paramUpdate,
                       self.publisherUpdate, self.requestTopic, self.shutdown):
            self.rpc.register_function(method, method.__name__)
        self.uri = f"http://{host}:{self.rpc.server_address[1]}/"
        threading.Thread(target=self.rpc.serve_forever, daemon=True).start()
        self.data = socket.create_server((host, 0))
        threading.Thread(target=self._serve_topics, daemon=True).start()

    # names
    def resolve(self, name: str) -> str:
        absolute = name if name.startswith("/") else \
            f"{self.namespace.rstrip('/')}/{name}"
        for key, value in self.remaps.items():
            if (key if key.startswith("/") else f"{self.namespace.rstrip('/')}/{key}") == absolute:
                return value if value.startswith("/") else f"{self.namespace.rstrip('/')}/{value}"
        return absolute

    # the master
    def _ask(self, method: str, *args):
        code, message, value = getattr(self.master, method)(self.name, *args)
        if code != 1:
            raise RosError(f"{method}: {message}")
        return value

    def get_param(self, name: str):
        return self._ask("getParam", self.resolve(name))

    def wait_for_service(self, service: str, timeout: float) -> str:
        """The service's rosrpc:// address once the master knows it."""
        deadline = time.monotonic() + timeout
        while True:
            try:
                return self._ask("lookupService", service)
            except (RosError, OSError):
                if time.monotonic() > deadline:
                    raise RosError(f"no service {service} after {timeout:g} s") from None
                time.sleep(0.1)

    # services
    def call(self, service: str, srv: tuple[str, str, str], request: bytes,
             timeout: float = 60.0) -> bytes:
        """Call `service` (resolved) of type `srv` with a packed request; the packed response."""
        address = self.wait_for_service(service, timeout)
        host, port = address[len("rosrpc://"):].rstrip("/").rsplit(":", 1)
        with socket.create_connection((host, int(port)), timeout=timeout) as sock:
            sock.sendall(_header({"callerid": self.name, "service": service,
                                  "md5sum": srv[1], "type": srv[0]}))
            answer = _read_header(sock)
            if "error" in answer:
                raise RosError(f"{service}: {answer['error']}")
            sock.sendall(struct.pack("<I", len(request)) + request)
            ok = _read_exactly(sock, 1)[0]
            (size,) = struct.unpack("<I", _read_exactly(sock, 4))
            data = _read_exactly(sock, size)
        if not ok:
            raise RosError(f"{service}: {data.decode('utf-8', 'replace')}")
        return data

    # a latched topic
    def latch(self, topic: str, msg: tuple[str, str, str], message: bytes) -> None:
        """Publish one message on `topic`, latched: every subscriber, now or later, gets it."""
        if self.rpc is None:
            self._serve()
        topic = self.resolve(topic)
        self.published[topic] = (*msg, message)
        self._ask("registerPublisher", topic, msg[0], self.uri)

    def _serve_topics(self) -> None:
        while not self.stopped.is_set():
            try:
                sock, _ = self.data.accept()
            except OSError:
                return
            threading.Thread(target=self._subscriber, args=(sock,), daemon=True).start()

    def _subscriber(self, sock: socket.socket) -> None:
        with sock:
            try:
                asked = _read_header(sock)
                topic = asked.get("topic", "")
                if topic not in self.published:
                    sock.sendall(_header({"error": f"{self.name} does not publish {topic}"}))
                    return
                kind, md5, text, message = self.published[topic]
                if asked.get("md5sum") not in ("*", md5):
                    sock.sendall(_header({"error": f"md5sum of {topic} is {md5}, not "
                                                   f"{asked.get('md5sum')}"}))
                    return
                sock.sendall(_header({"callerid": self.name, "topic": topic, "type": kind,
                                      "md5sum": md5, "message_definition": text,
                                      "latching": "1"}))
                sock.sendall(struct.pack("<I", len(message)) + message)
                self.stopped.wait()
            except (OSError, RosError):
                return

    def spin(self) -> None:
        """Until Ctrl-C (roslaunch's SIGINT), SIGTERM or the slave API's shutdown."""
        import signal
        signal.signal(signal.SIGTERM, lambda *_: self.stopped.set())
        try:
            while not self.stopped.wait(0.2):
                pass
        except KeyboardInterrupt:
            pass
        self.close()

    def close(self) -> None:
        self.stopped.set()
        for topic in self.published:
            try:
                self._ask("unregisterPublisher", topic, self.uri)
            except (RosError, OSError):
                pass
        if self.rpc is not None:
            self.data.close()
            self.rpc.server_close()

    # the slave API (what the master, rosnode and subscribers ask of a node)
    def getPid(self, caller):
        return [1, "", os.getpid()]

    def getMasterUri(self, caller):
        return [1, "", self.master_uri]

    def getBusInfo(self, caller):
        return [1, "", []]

    def getBusStats(self, caller):
        return [1, "", [[], [], []]]

    def getSubscriptions(self, caller):
        return [1, "", []]

    def getPublications(self, caller):
        return [1, "", [[t, v[0]] for t, v in self.published.items()]]

    def paramUpdate(self, caller, key, value):
        return [1, "", 0]

    def publisherUpdate(self, caller, topic, publishers):
        return [1, "", 0]

    def requestTopic(self, caller, topic, protocols):
        if topic not in self.published:
            return [-1, f"{self.name} does not publish {topic}", []]
        if not any(p and p[0] == "TCPROS" for p in protocols):
            return [0, "only TCPROS is spoken here", []]
        return [1, "ready", ["TCPROS", _host(), self.data.getsockname()[1]]]

    def shutdown(self, caller, message=""):
        self.stopped.set()
        return [1, "shutting down", 0]


def log(level: str, text: str) -> None:
    """A line as rospy prints it on the screen: `[INFO] [wall time]: text`."""
    stream = sys.stderr if level in ("ERROR", "WARN", "FATAL") else sys.stdout
    print(f"[{level}] [{time.time():.6f}]: {text}", file=stream, flush=True)
