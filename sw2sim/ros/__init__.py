"""sw2sim ros: an exported package's own launch files under ROS 1, with MuJoCo standing in for
Gazebo (see sw2sim.ros.world and sw2sim.ros.run)."""
