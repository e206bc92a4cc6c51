#!/usr/bin/python3
"""team_launcher: starts one front-end per robot of the team (launch/robot.launch once per robot, through
roslaunch's own API), so that a launch file needs no block per robot and no robot count to keep in step with
the sequence.

Robots: ~robots ([a, b, c] or "a,b,c"); without it, the player's resolved sequence (/player/robots, set once the
player has loaded the sequence config; waited for). Every private parameter under ~robot_args is handed to each
robot's launch file as an argument (odometry, config_dir, noise_models, lockstep, ...), and robot:=<r>.
~launch: the per-robot launch file (default: cosmo's launch/robot.launch).

The front-ends are this node's children: they stop when it stops (roslaunch stops it with the rest of the launch).
"""
import sys
import time

import rospkg
import rospy
import roslaunch


def robot_ids(value, name):
    if isinstance(value, str):
        value = value.replace(",", " ").replace("[", " ").replace("]", " ").split()
    if not isinstance(value, list) or not value or any(not isinstance(r, str) or len(r) != 1 for r in value):
        raise ValueError("%s: expected a non-empty list of one-character robot ids, got %r" % (name, value))
    return value


def team_robots():
    if rospy.has_param("~robots"):
        return robot_ids(rospy.get_param("~robots"), "~robots")
    rospy.loginfo("team_launcher: waiting for the player's robots (/player/robots)")
    while not rospy.is_shutdown():
        if rospy.has_param("/player/robots"):
            return robot_ids(rospy.get_param("/player/robots"), "/player/robots")
        time.sleep(0.1)
    return []


def launch_args(robot):
    args = ["robot:=%s" % robot]
    for key, value in sorted(rospy.get_param("~robot_args", {}).items()):
        if isinstance(value, bool):
            value = "true" if value else "false"
        args.append("%s:=%s" % (key, value))
    return args


def main():
    rospy.init_node("team_launcher", disable_signals=True)
    default_launch = rospkg.RosPack().get_path("cosmo") + "/launch/robot.launch"
    launch_file = rospy.get_param("~launch", default_launch)
    try:
        robots = team_robots()
    except ValueError as e:
        rospy.logfatal("team_launcher: %s", e)
        return 1
    if not robots:
        return 0
    files = [(launch_file, launch_args(r)) for r in robots]
    rospy.loginfo("team_launcher: %d front-ends (%s) from %s", len(robots), ", ".join(robots), launch_file)
    uuid = roslaunch.rlutil.get_or_generate_uuid(None, False)
    parent = roslaunch.parent.ROSLaunchParent(uuid, files, show_summary=False)
    parent.start()
    try:
        parent.spin()  # until SIGINT / SIGTERM (roslaunch stopping the launch) or every child ended
    finally:
        parent.shutdown()
    return 0


if __name__ == "__main__":
    sys.exit(main())
