"""`sw2sim plot`: numeric fields of ROS topics drawn over ROS time, as rqt_plot draws them.

- `fields`: the names rqt_plot takes (`/topic/field/sub[3]`, `a,b`, `/topic/x:y`), each
  split into its topic and field path, checked against the message type, and read from a
  message;
- `ros1`: the topics, types and messages through rospy and the ROS 1 master;
- `ros2`: the same through rclpy;
- `recording`: the samples, on ROS time, and the CSV they make;
- `drawing`: the picture (matplotlib, imported only here): a PNG, or a live window;
- `run`: the command's course: which ROS, waiting for the topics and the first message,
  the time limit, Ctrl-C, what is written.

rqt_plot is read at its ROS 1 (noetic-devel) and ROS 2 Jazzy (1.4.0) sources; where this
command differs from it, the module that does says so.
"""
