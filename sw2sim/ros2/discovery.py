"""Keeping ROS 2 on this machine: what every ROS 2 process the project starts is given.

Fast DDS discovers peers by multicast on every network interface by default. ROS 2's
`ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST` stops the multicast and sends only to
127.0.0.1, but it cannot bind the sockets to 127.0.0.1: under it, rmw_fastrtps adds its own
UDPv4 transport, with no interface allow-list, to whatever a profile gives (Jazzy's
rmw_fastrtps, participant.cpp, the LOCALHOST case,
https://github.com/ros2/rmw_fastrtps/blob/8.4.1/rmw_fastrtps_shared_cpp/src/participant.cpp#L185-L207;
8.4.2 and 8.4.3 did not change it). Fast DDS 2.14 binds such a transport's receiving
sockets to 0.0.0.0, and its sending sockets to 0.0.0.0 and to each network interface's
address (those for multicast)
(https://github.com/eProsima/Fast-DDS/blob/v2.14.5/src/cpp/rtps/transport/UDPv4Transport.cpp#L549-L565,
https://github.com/eProsima/Fast-DDS/blob/v2.14.5/src/cpp/rtps/transport/UDPTransportInterface.cpp#L340-L391).
Seen in /proc and with strace here: an rclpy node under LOCALHOST alone receives on
0.0.0.0; with this module's profile loaded as well, its 127.0.0.1 sockets take the
receiving ports first (the 0.0.0.0 binds fail), but the sending sockets on 0.0.0.0 and on
the network address stay. No datagram went anywhere but 127.0.0.1 in either case.

So the processes the project starts use the range SYSTEM_DEFAULT, under which
rmw_fastrtps leaves the transports and locators to the profile (the same file, L212-L214),
and the profile below (PROFILE, written to the file `profile_file()` returns) gives:

- one UDPv4 transport whose interface allow-list holds 127.0.0.1 alone: its receiving
  and sending sockets are all bound to 127.0.0.1 (UDPv4Transport.cpp L549-L565 above, and
  UDPTransportInterface.cpp L392-L413), and it reaches 32 participants on this machine
  through the initial peers, as rmw_fastrtps's LOCALHOST transport does (L204-L205);
- shared memory between the processes of this machine (sw2sim.ros2.shm removes the files
  a killed process leaves);
- none of Fast DDS's built-in transports;
- 127.0.0.1 as the one metatraffic (discovery) locator, so no multicast locator is made
  (https://github.com/eProsima/Fast-DDS/blob/v2.14.5/src/cpp/rtps/participant/RTPSParticipantImpl.cpp#L676-L698),
  and as the one initial peer.

A node that a reader starts with `ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST` alone (as
ROS 2 and the pages tell them) still finds these processes: both sides announce to
127.0.0.1 and use shared memory. Its own sockets are rmw_fastrtps's, as above.
`sockets(pid)` reads a process's sockets from /proc; `run.py` checks its own with it and
stops if Fast DDS did not apply the profile.

`environment(domain_id)` is what the tool, the tests and the page runner give each ROS 2
process they start: the range, the domain id (the processes of one run share it; a second
run with another id cannot see them), Fast DDS as the middleware and the profile.
"""

from __future__ import annotations

import hashlib
import ipaddress
import os
import socket
import struct
import tempfile
from pathlib import Path

DEFAULT_DOMAIN = 0
# The range under which rmw_fastrtps leaves the participant's transports to the profile.
RANGE = "SYSTEM_DEFAULT"

PROFILE = """\
<?xml version="1.0" encoding="UTF-8" ?>
<!-- sw2sim: ROS 2 discovery and data on 127.0.0.1 only (UDP on loopback, shared memory) -->
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor>
        <transport_id>sw2sim_loopback_udp</transport_id>
        <type>UDPv4</type>
        <maxInitialPeersRange>32</maxInitialPeersRange>
        <interfaces>
          <allowlist>
            <interface name="127.0.0.1"/>
          </allowlist>
        </interfaces>
      </transport_descriptor>
      <transport_descriptor>
        <transport_id>sw2sim_shared_memory</transport_id>
        <type>SHM</type>
      </transport_descriptor>
    </transport_descriptors>
    <participant profile_name="sw2sim_loopback" is_default_profile="true">
      <rtps>
        <userTransports>
          <transport_id>sw2sim_loopback_udp</transport_id>
          <transport_id>sw2sim_shared_memory</transport_id>
        </userTransports>
        <useBuiltinTransports>false</useBuiltinTransports>
        <builtin>
          <metatrafficUnicastLocatorList>
            <locator>
              <udpv4>
                <address>127.0.0.1</address>
              </udpv4>
            </locator>
          </metatrafficUnicastLocatorList>
          <initialPeersList>
            <locator>
              <udpv4>
                <address>127.0.0.1</address>
              </udpv4>
            </locator>
          </initialPeersList>
        </builtin>
      </rtps>
    </participant>
  </profiles>
</dds>
"""


def profile_file() -> Path:
    """The profile as a file (written once, named by its content)."""
    name = f"sw2sim-fastdds-loopback-{hashlib.sha256(PROFILE.encode()).hexdigest()[:10]}.xml"
    base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "sw2sim"
    try:
        base.mkdir(parents=True, exist_ok=True)
    except OSError:
        base = Path(tempfile.gettempdir())
    path = base / name
    if not path.is_file() or path.read_text(encoding="utf-8") != PROFILE:
        scratch = path.with_suffix(f".{os.getpid()}.tmp")
        scratch.write_text(PROFILE, encoding="utf-8")
        scratch.replace(path)
    return path


def domain_id(env: dict[str, str] | None = None) -> int:
    """The user's ROS_DOMAIN_ID when set (0-232), else DEFAULT_DOMAIN."""
    text = (os.environ if env is None else env).get("ROS_DOMAIN_ID", "").strip()
    try:
        value = int(text)
    except ValueError:
        return DEFAULT_DOMAIN
    return value if 0 <= value <= 232 else DEFAULT_DOMAIN


def settings(domain: int) -> dict[str, str]:
    """Only the variables this module sets, for a process with the given domain id."""
    profile = str(profile_file())
    return {"ROS_DOMAIN_ID": str(domain),
            "ROS_AUTOMATIC_DISCOVERY_RANGE": RANGE,
            "RMW_IMPLEMENTATION": "rmw_fastrtps_cpp",
            "FASTRTPS_DEFAULT_PROFILES_FILE": profile,
            "FASTDDS_DEFAULT_PROFILES_FILE": profile}


def environment(domain: int, base: dict[str, str] | None = None) -> dict[str, str]:
    """`base` (default os.environ) with ROS 2 kept on this machine in domain `domain`."""
    env = dict(os.environ if base is None else base)
    env.update(settings(domain))
    env.pop("ROS_LOCALHOST_ONLY", None)   # the older switch, which the range supersedes
    env.pop("ROS_STATIC_PEERS", None)
    return env


def sockets(pid: int | str = "self") -> list[str]:
    """The process's UDP and TCP sockets as `address:port` (IPv6 in brackets), read from
    /proc: its network namespace's tables, kept to the inodes its descriptors hold. Empty
    where there is no /proc."""
    base = Path(f"/proc/{pid}")
    held = set()
    try:
        for fd in (base / "fd").iterdir():
            try:
                target = os.readlink(fd)
            except OSError:
                continue
            if target.startswith("socket:["):
                held.add(target[8:-1])
    except OSError:
        return []
    found = []
    for table in ("udp", "udp6", "tcp", "tcp6"):
        try:
            rows = (base / "net" / table).read_text().splitlines()[1:]
        except OSError:
            continue
        for row in rows:
            fields = row.split()
            if len(fields) > 9 and fields[9] in held:
                found.append(_address(fields[1]))
    return found


def _address(text: str) -> str:
    """/proc/net's `0100007F:1B58` as 127.0.0.1:7000 (the address in host byte order)."""
    hexadecimal, port = text.split(":")
    raw = bytes.fromhex(hexadecimal)
    if len(raw) == 4:
        return f"{socket.inet_ntop(socket.AF_INET, raw[::-1])}:{int(port, 16)}"
    words = b"".join(struct.pack("<I", int.from_bytes(raw[i:i + 4], "big"))
                     for i in range(0, 16, 4))
    return f"[{socket.inet_ntop(socket.AF_INET6, words)}]:{int(port, 16)}"


def is_loopback(text: str) -> bool:
    """Whether `address:port` (as sockets() gives it) is on a loopback address."""
    address = ipaddress.ip_address(text.rsplit(":", 1)[0].strip("[]"))
    if isinstance(address, ipaddress.IPv6Address) and address.ipv4_mapped:
        address = address.ipv4_mapped
    return address.is_loopback


def beyond_loopback(pid: int | str = "self") -> list[str]:
    """The process's sockets bound to anything but a loopback address."""
    return [text for text in sockets(pid) if not is_loopback(text)]
