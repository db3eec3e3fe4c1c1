"""A rosbag2 SQLite file (rosbag2's schema) of the CDR messages kitti_to_mcap.mjs --cdr wrote.

usage: cdrs_to_db3.py IN.cdrs OUT.db3 TOPIC"""

import os
import sqlite3
import struct
import sys

source, out, topic = sys.argv[1:4]
if os.path.exists(out):
    os.remove(out)
db = sqlite3.connect(out)
db.executescript("""
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);
""")
db.execute("INSERT INTO topics VALUES (1, ?, 'sensor_msgs/msg/PointCloud2', 'cdr', '')", (topic,))
with open(source, "rb") as f:
    while head := f.read(12):
        stamp, length = struct.unpack("<QI", head)
        db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (1, ?, ?)", (stamp, f.read(length)))
db.commit()
