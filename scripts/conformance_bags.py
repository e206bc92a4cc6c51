#!/usr/bin/python3
"""Writes ROS 1 bags with Python's rosbag (Debian python3-rosbag), the writer most recorders' tools use besides
the C++ one, into test/trials/data/conformance/: every compression with a tiny chunk threshold, one bag per
quirk real recordings carry, and Livox's livox_ros_driver/CustomMsg as FAST-LIO users record it (and the first
driver's older definition of that type, which cosmo refuses). The gtest TrialsConformance reads each with cosmo's reader and with librosbag and
compares them message for message; scripts/fuzz.sh seeds the ros1_bag target with them (fuzz/seed_dirs.txt).

Deterministic: fixed stamps and payloads, so running it again rewrites the same bytes (`git diff` shows none).

    /usr/bin/python3 scripts/conformance_bags.py [OUT_DIR]
"""
import os
import struct
import sys

import genpy
import genpy.dynamic
import rosbag
from geometry_msgs.msg import PoseStamped
from sensor_msgs.msg import PointCloud2, PointField
from std_msgs.msg import String

OUT = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "test", "trials", "data",
                                                          "conformance")


def cloud(k, stamp):
    """A 4-point PointCloud2 (x, y, z, intensity float32) whose values depend on k."""
    m = PointCloud2()
    m.header.seq = k
    m.header.stamp = stamp
    m.header.frame_id = "os_sensor"
    m.height, m.width = 1, 4
    m.fields = [PointField(n, 4 * i, PointField.FLOAT32, 1) for i, n in enumerate(("x", "y", "z", "intensity"))]
    m.is_bigendian = False
    m.point_step, m.row_step = 16, 64
    m.data = b"".join(struct.pack("<4f", k + i, -i, 0.5 * i, 10.0 * k) for i in range(4))
    m.is_dense = True
    return m


def pose(k, stamp):
    m = PoseStamped()
    m.header.seq = k
    m.header.stamp = stamp
    m.header.frame_id = "world"
    m.pose.position.x = 0.25 * k
    m.pose.orientation.w = 1.0
    return m


def team_messages(n=12):
    """Three topics at 10 Hz, the pose and the text at the same receive time as a cloud (ties between
    connections), in receive-time order."""
    out = []
    for k in range(n):
        t = genpy.Time(1700000000, 100000000 * (k % 10)) + genpy.Duration(k // 10)
        out.append(("/os_cloud_node/points", cloud(k, t), t))
        out.append(("/pose", pose(k, t), t))
        if k % 3 == 0:
            out.append(("/chatter", String(data="message %d" % k), t))
    return out


# livox_ros_driver/CustomMsg as the driver defines it (msg/CustomMsg.msg, msg/CustomPoint.msg; md5sum
# e4d6829bdfe657cb6c21a746c86b21a6), and the first release's definition of the same type (a `timestep` member,
# points without `offset_time` and `tag`; md5sum a3e5532e86bb82ac2085ba9c8e7e4e45). genpy builds the classes from
# the full text, as rosbag does for a bag's connection, and computes their md5sums as genmsg does.
SEPARATOR = "=" * 80 + "\n"
HEADER_TEXT = "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n"
LIVOX_TEXT = ("Header header\nuint64 timebase\nuint32 point_num\nuint8 lidar_id\nuint8[3] rsvd\n"
              "CustomPoint[] points\n\n" + SEPARATOR + HEADER_TEXT + "\n" + SEPARATOR +
              "MSG: livox_ros_driver/CustomPoint\nuint32 offset_time\nfloat32 x\nfloat32 y\nfloat32 z\n"
              "uint8 reflectivity\nuint8 tag\nuint8 line\n")
LIVOX_OLD_TEXT = ("Header header\nuint64 timebase\nuint32 timestep\nuint32 point_num\nuint8 lidar_id\n"
                  "uint8[3] rsvd\nCustomPoint[] points\n\n" + SEPARATOR + HEADER_TEXT + "\n" + SEPARATOR +
                  "MSG: livox_ros_driver/CustomPoint\nfloat32 x\nfloat32 y\nfloat32 z\nuint8 reflectivity\n"
                  "uint8 line\n")


def livox_classes(text):
    classes = genpy.dynamic.generate_dynamic("livox_ros_driver/CustomMsg", text)
    return classes["livox_ros_driver/CustomMsg"], classes["livox_ros_driver/CustomPoint"]


def livox_messages(n=5, points=4):
    """Sweeps of 0.1 s at 10 Hz: the header stamped at `timebase` (the sweep start, as the driver stamps it), point
    i of sweep k at timebase + i * 25 ms, x = 1 + k + i, y = -i, z = 0.5 i, reflectivity 10 i, line i % 4."""
    msg_class, point_class = livox_classes(LIVOX_TEXT)
    out = []
    for k in range(n):
        t = genpy.Time(1700000000, 100000000 * k)
        m = msg_class()
        m.header.seq = k
        m.header.stamp = t
        m.header.frame_id = "livox_frame"
        m.timebase = t.to_nsec()
        m.point_num = points
        m.lidar_id = 0
        m.rsvd = [0, 0, 0]
        m.points = [point_class(offset_time=25000000 * i, x=1.0 + k + i, y=-float(i), z=0.5 * i,
                                reflectivity=10 * i, tag=0, line=i % 4) for i in range(points)]
        out.append(("/livox/lidar", m, t + genpy.Duration(0, 100000000)))
    return out


def livox_old_messages(n=3):
    msg_class, point_class = livox_classes(LIVOX_OLD_TEXT)
    out = []
    for k in range(n):
        t = genpy.Time(1700000000, 100000000 * k)
        m = msg_class(timebase=t.to_nsec(), timestep=0, point_num=2, lidar_id=0, rsvd=[0, 0, 0],
                      points=[point_class(x=1.0 + k, y=0.0, z=0.0, reflectivity=1, line=0)] * 2)
        m.header.stamp = t
        m.header.frame_id = "livox_frame"
        out.append(("/livox/lidar", m, t))
    return out


class RepeatingBag(rosbag.Bag):
    """Writes every connection record again at the start of each chunk, as the C++ recorder does for the
    connections a chunk uses and as bags appended to or merged by other tools carry them."""

    def _start_writing_chunk(self, t):
        super()._start_writing_chunk(t)
        for c in self._connections.values():
            self._write_connection_record(c, False)


def write(name, messages, compression=rosbag.Compression.NONE, chunk_threshold=256, headers=None, kind=rosbag.Bag):
    path = os.path.join(OUT, name)
    with kind(path, "w", compression=compression, chunk_threshold=chunk_threshold) as bag:
        for topic, msg, t in messages:
            bag.write(topic, msg, t, connection_header=(headers or {}).get(topic))
    return path


def main():
    os.makedirs(OUT, exist_ok=True)
    msgs = team_messages()
    for compression, tag in ((rosbag.Compression.NONE, "none"), (rosbag.Compression.BZ2, "bz2"),
                             (rosbag.Compression.LZ4, "lz4")):
        write("py_%s_tiny_chunks.bag" % tag, msgs, compression)
    # Connection records repeated in every chunk.
    write("py_repeated_connections.bag", msgs, rosbag.Compression.NONE, chunk_threshold=6000,
          kind=RepeatingBag)
    # One chunk for the whole recording (the default threshold), uncompressed.
    write("py_one_chunk.bag", msgs, chunk_threshold=768 * 1024)
    # Written out of receive-time order (a recorder whose callbacks run late): the chunk's index is sorted, the
    # records are not.
    write("py_late_writes.bag", [msgs[i] for i in (0, 3, 1, 2, 6, 4, 5, 8, 7)] + msgs[9:], chunk_threshold=4096)
    # An empty `latching=` value in the connection header (what some recorders write for a topic never latched).
    chatter = String(data="latched?")
    header = {"topic": "/chatter", "type": String._type, "md5sum": String._md5sum,
              "message_definition": String._full_text, "latching": "", "callerid": ""}
    write("py_empty_latching.bag", [(t, m, s) for t, m, s in msgs if t != "/chatter"] +
          [("/chatter", chatter, genpy.Time(1700000003, 0))], headers={"/chatter": header})
    # A message definition that does not match the type's md5sum (a recording made with an older definition).
    old_definition = "string data\nint32 revision\n"
    header = {"topic": "/chatter", "type": String._type, "md5sum": String._md5sum,
              "message_definition": old_definition}
    write("py_definition_mismatch.bag", [m for m in msgs if m[0] == "/chatter"], headers={"/chatter": header})
    # Messages at receive time 0 (a clock not yet set): rosbag's index leaves them out.
    zero = [("/chatter", String(data="before the clock"), genpy.Time(0, 0))] + \
        [m for m in msgs if m[0] == "/chatter"]
    write("py_time_zero.bag", zero, chunk_threshold=4096)
    # Livox's CustomMsg, lz4 in small chunks, and the first driver's definition of that type.
    livox = livox_messages()
    assert livox[0][1]._md5sum == "e4d6829bdfe657cb6c21a746c86b21a6", livox[0][1]._md5sum
    write("py_livox_custom.bag", livox, rosbag.Compression.LZ4, chunk_threshold=512)
    old = livox_old_messages()
    assert old[0][1]._md5sum == "a3e5532e86bb82ac2085ba9c8e7e4e45", old[0][1]._md5sum
    write("py_livox_custom_old.bag", old)
    for name in sorted(os.listdir(OUT)):
        print("%s %d bytes" % (os.path.join(OUT, name), os.path.getsize(os.path.join(OUT, name))))


if __name__ == "__main__":
    main()
