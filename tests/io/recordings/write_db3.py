"""Writes rosbag2 SQLite recordings from the CDR messages write_mcap.mjs serialised: ouster.db3
alone, and a rosbag2 folder (metadata.yaml) split over two .db3 files, in rosbag2's schema.

usage: write_db3.py OUT_DIR"""

import base64
import json
import os
import sqlite3
import sys

OUT = sys.argv[1]
SCHEMA = """
CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT NULL);
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL, data BLOB NOT NULL);
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
"""


def write(path, source, messages):
    if os.path.exists(path):
        os.remove(path)
    db = sqlite3.connect(path)
    db.executescript(SCHEMA)
    db.execute("INSERT INTO schema VALUES (3, 'humble')")
    db.execute("INSERT INTO topics VALUES (1, '/imu', 'sensor_msgs/msg/Imu', 'cdr', '')")
    db.execute("INSERT INTO topics VALUES (2, ?, ?, 'cdr', '')", (source["topic"], source["type"]))
    # written newest first: the reader orders by time, not by row
    for m in reversed(messages):
        db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (2, ?, ?)",
                   (int(m["timestamp"]), base64.b64decode(m["data"])))
    db.commit()
    db.close()


with open(os.path.join(OUT, "db3_messages.json")) as f:
    source = json.load(f)
write(os.path.join(OUT, "ouster.db3"), source, source["messages"])
folder = os.path.join(OUT, "ouster_bag")
os.makedirs(folder, exist_ok=True)
write(os.path.join(folder, "ouster_bag_0.db3"), source, source["messages"][:2])
write(os.path.join(folder, "ouster_bag_1.db3"), source, source["messages"][2:])
with open(os.path.join(folder, "metadata.yaml"), "w") as f:
    f.write("rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
            "  relative_file_paths:\n    - ouster_bag_0.db3\n    - ouster_bag_1.db3\n")
print("wrote ouster.db3 and ouster_bag/")
