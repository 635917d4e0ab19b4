"""Keeping ROS 2 on this machine: what every ROS 2 process the project starts is given.

Fast DDS discovers peers by multicast on every network interface by default. The ROS 2
setting `ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST` stops the multicast and sends only to
127.0.0.1, but under it alone Fast DDS binds its receiving sockets to 0.0.0.0, where other
machines can reach them (seen with `strace -e trace=network` on an rclpy node here). The
profile below (PROFILE, written to the file `profile_file()` returns) gives the
participants one UDP transport restricted to 127.0.0.1 (and shared memory between the
processes of this machine), none of Fast DDS's built-in transports, and 127.0.0.1 as
their only initial peer: every receiving socket is then bound to 127.0.0.1, and every
datagram goes to 127.0.0.1 (Fast DDS still opens a sending socket per local address,
never used).

`environment(domain_id)` is what the tool, the tests and the page runner give each ROS 2
process they start: the range, the domain id (the processes of one run share it; a second
run with another id cannot see them), Fast DDS as the middleware and the profile.
"""

from __future__ import annotations

import hashlib
import os
import tempfile
from pathlib import Path

DEFAULT_DOMAIN = 0

PROFILE = """\
<?xml version="1.0" encoding="UTF-8" ?>
<!-- sw2sim: ROS 2 discovery and data on 127.0.0.1 only (UDP on loopback, shared memory) -->
<dds xmlns="http://www.eprosima.com/XMLSchemas/fastRTPS_Profiles">
  <profiles>
    <transport_descriptors>
      <transport_descriptor>
        <transport_id>sw2sim_loopback_udp</transport_id>
        <type>UDPv4</type>
        <interfaceWhiteList>
          <address>127.0.0.1</address>
        </interfaceWhiteList>
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
            "ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST",
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
