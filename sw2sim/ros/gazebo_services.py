"""The simulation node's /clock publisher and its /gazebo services, as gazebo_ros's API
plugin (gazebo_ros_api_plugin.cpp) offers them, with upstream's message types: spawn a
URDF, apply and clear a joint effort, a joint's properties, pause and unpause the
physics, and the two resets (sw2sim.ros.world's World does each; this is their ROS side).
"""

from __future__ import annotations

import dataclasses
import time

import mujoco


@dataclasses.dataclass
class Effort:
    """One `apply_joint_effort` request, as gazebo_ros_api_plugin.cpp keeps it (a
    ForceJointJob): applied at every step from `start` until `until` (None: until
    cleared), added to the other requests on the same joint (ODE adds each SetForce)."""
    joint: str
    effort: float
    start: float
    until: float | None


def why_not_spawned(exc: Exception) -> str:
    """What `spawn_model` prints when the simulation cannot load the URDF: the reason on
    one line of the launch's screen (MuJoCo's messages take two), and where to see every
    problem of the package at once."""
    reason = " ".join(str(exc).split())
    return f"{reason} (`sw2sim check` on the package lists every problem, each with its fix)"


def advertise(world) -> None:
    """Publish /clock and answer the /gazebo services for `world` (a World)."""
    from gazebo_msgs.srv import (ApplyJointEffort, ApplyJointEffortResponse,
                                 GetJointProperties, GetJointPropertiesResponse,
                                 JointRequest, JointRequestResponse, SpawnModel,
                                 SpawnModelResponse)
    from rosgraph_msgs.msg import Clock
    from std_srvs.srv import Empty, EmptyResponse

    rospy = world.rospy
    world.clock = rospy.Publisher("/clock", Clock, queue_size=10)

    def spawn(req):
        try:
            said = world.spawn(req.model_xml, req.robot_namespace)
        except Exception as exc:  # noqa: BLE001  (the caller gets the reason)
            return SpawnModelResponse(success=False, status_message=why_not_spawned(exc))
        return SpawnModelResponse(success=True, status_message=said)

    def apply(req):
        with world.lock:
            try:
                world.model.joint(req.joint_name)
            except (KeyError, AttributeError):
                return ApplyJointEffortResponse(False, f"no joint {req.joint_name!r}")
            duration = req.duration.to_sec()
            if duration == 0:
                return ApplyJointEffortResponse(True, "duration 0: nothing applied")
            start = max(req.start_time.to_sec(), world.time)
            until = None if duration < 0 else start + max(duration, world.model.opt.timestep)
            world.efforts.append(Effort(req.joint_name, req.effort, start, until))
        return ApplyJointEffortResponse(True, "")

    def clear(req):
        with world.lock:
            world.efforts = [job for job in world.efforts if job.joint != req.joint_name]
        return JointRequestResponse()

    def properties(req):
        with world.lock:
            try:
                j = world.model.joint(req.joint_name).id
            except (KeyError, AttributeError):
                return GetJointPropertiesResponse(success=False,
                                                  status_message="no such joint")
            kind = 0 if int(world.model.jnt_type[j]) == int(mujoco.mjtJoint.mjJNT_HINGE) else 2
            return GetJointPropertiesResponse(
                type=kind, damping=[float(world.model.dof_damping[world.model.jnt_dofadr[j]])],
                position=[float(world.data.qpos[world.model.jnt_qposadr[j]])],
                rate=[float(world.data.qvel[world.model.jnt_dofadr[j]])], success=True)

    def pause(_):
        world.paused = True
        return EmptyResponse()

    def unpause(_):
        with world.lock:
            if world.paused:
                world.pace_from = (time.monotonic(), world.time)
            world.paused = False
        return EmptyResponse()

    def reset_simulation(_):
        world.reset_simulation()
        return EmptyResponse()

    def reset_world(_):
        world.reset_world()
        return EmptyResponse()

    rospy.Service("/gazebo/spawn_urdf_model", SpawnModel, spawn)
    rospy.Service("/gazebo/apply_joint_effort", ApplyJointEffort, apply)
    rospy.Service("/gazebo/clear_joint_forces", JointRequest, clear)
    rospy.Service("/gazebo/get_joint_properties", GetJointProperties, properties)
    rospy.Service("/gazebo/pause_physics", Empty, pause)
    rospy.Service("/gazebo/unpause_physics", Empty, unpause)
    rospy.Service("/gazebo/reset_simulation", Empty, reset_simulation)
    rospy.Service("/gazebo/reset_world", Empty, reset_world)
