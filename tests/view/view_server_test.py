"""eco view's server as an attacker and a flaky network see it: requests for files outside the run
folder (raw, percent-encoded once and twice, absolute, through symlinks) get 404 and a line in its
log; a missing folder, a folder without a recording and a port in use are refused with a message
naming them; a corrupt and a truncated frame file are answered 422 with the file's name and the
byte where it goes wrong; downloads dropped mid-transfer leave it serving. And an odometry's
recording (eco odometry --record) serves its map with the reference path, and eco odometry --view
serves its frames as they come.

usage: view_server_test.py ECO_CLI WORK_DIR [LIVE_RUNS]"""

import json
import os
import socket
import struct
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "bench"))
from eco_command import check, eco, start  # noqa: E402
from view_server import ViewServer  # noqa: E402

CLI, WORK = start(sys.argv)
RUN = os.path.join(WORK, "run")
eco("run", "--frames", "6", "--record", "--out", "run")
VIEW = os.path.join(RUN, "view")
check(sorted(f for f in os.listdir(VIEW) if f.endswith(".bin")) == [f"frame_{t:06d}.bin" for t in range(6)],
      f"--record wrote {os.listdir(VIEW)}")

# what lies outside the run folder, some of it reached through links inside it
with open(os.path.join(WORK, "secret.txt"), "w") as f:
    f.write("not for the browser\n")
os.symlink(os.path.join(WORK, "secret.txt"), os.path.join(RUN, "secret_link.txt"))
os.symlink(WORK, os.path.join(RUN, "outside"))
os.symlink("/etc", os.path.join(RUN, "etc"))

server = ViewServer([CLI, "view", RUN, "--port", "0"])
check(server.host == "127.0.0.1", f"binds {server.host} by default, not 127.0.0.1")

status, body = server.get("/api/run")
check(status == 200, f"/api/run: {status}")
run = json.loads(body)
check(run["frames"]["frame"] == list(range(6)) and run["error"] == "", f"/api/run: {run['frames']['frame']}")
check(run["run"]["title"] == "simulated drive" and run["run"]["box_side"] == 20, f"run.json: {run['run']}")
for path in ["/", "/index.html", "/viewer.js", "/viewer.css", "/three/three.min.js", "/three/OrbitControls.js",
             "/run/config.json", "/run/view/frames.csv", "/api/frame?n=5&budget=1000"]:
    status, body = server.get(path)
    check(status == 200 and body, f"{path}: {status}, {len(body)} bytes")

# the page's bytes for frame 5: a header naming its counts, thinned to the budget asked
status, body = server.get("/api/frame?n=5&budget=1000")
length = struct.unpack_from("<I", body)[0]
header = json.loads(body[4:4 + length])
check(header["frame"] == 5 and header["drawn"] <= 1000 and header["held"] > 100000, f"frame 5: {header}")

refused = [
    "/../../../../etc/passwd",
    "/run/../../../../etc/passwd",
    "/run/%2e%2e/%2e%2e/%2e%2e/%2e%2e/etc/passwd",
    "/run/..%2f..%2f..%2f..%2fetc%2fpasswd",
    "/run/%252e%252e/%252e%252e/etc/passwd",
    "/run/view/../../secret.txt",
    "/run/%2Fetc%2Fpasswd",
    "/run//etc/passwd",
    "//etc/passwd",
    "/run/secret_link.txt",
    "/run/outside/secret.txt",
    "/run/etc/passwd",
    "/run/view",
    "/three/../../../etc/passwd",
    "/api/frame?n=99",
    "/api/frame?n=-1",
    "/api/frame?n=1&budget=lots",
    "/nothing.html",
]
for path in refused:
    status, body = server.get(path)
    check(status == 404, f"{path}: {status}, not 404")
    check(b"not for the browser" not in body and b"root:" not in body, f"{path} leaked a file")

# downloads dropped part-way, a dozen times, and a request never finished
frame_file = "/run/view/frame_000005.bin"
for _ in range(12):
    with socket.create_connection((server.host, server.port)) as s:
        s.sendall(f"GET {frame_file} HTTP/1.1\r\nHost: x\r\n\r\n".encode())
        s.recv(100)
with socket.create_connection((server.host, server.port)) as s:
    s.sendall(b"GET /api/ru")
status, body = server.get(frame_file)
check(status == 200 and len(body) == os.path.getsize(os.path.join(VIEW, "frame_000005.bin")),
      f"after dropped downloads: {status}, {len(body)} bytes")

# damaged frames: one cut short, one with a byte flipped; the others still served
with open(os.path.join(VIEW, "frame_000003.bin"), "r+b") as f:
    f.truncate(5000)
with open(os.path.join(VIEW, "frame_000004.bin"), "r+b") as f:
    f.seek(3000)
    byte = f.read(1)
    f.seek(3000)
    f.write(bytes([byte[0] ^ 0x40]))
status, body = server.get("/api/frame?n=3")
check(status == 422 and body.decode().startswith("frame_000003.bin: byte ") and "the file ends" in body.decode(),
      f"truncated frame: {status} {body[:200]}")
status, body = server.get("/api/frame?n=4")
check(status == 422 and "frame_000004.bin: byte" in body.decode() and "checksum mismatch" in body.decode(),
      f"flipped byte: {status} {body[:200]}")
status, _ = server.get("/api/frame?n=2")
check(status == 200, f"frame 2 after the damaged ones: {status}")

check(server.alive(), "the server died")
log = server.stop()
check(log.count("eco view: 404 for GET") >= len(refused), f"{log.count('404 for')} refusals logged of {len(refused)}:\n{log}")
check("eco view: 422 for frame 3: frame_000003.bin" in log, f"the damaged frame is not logged:\n{log}")

# an odometry's recording: its map's points, its path beside the reference path
eco("odometry", "--frames", "3", "--record", "--out", "odometry")
server = ViewServer([CLI, "view", os.path.join(WORK, "odometry", "eco"), "--port", "0"])
run = json.loads(server.get("/api/run")[1])
check(run["run"]["has_reference"] and run["run"]["title"].startswith("odometry on eco"), f"odometry run.json: {run['run']}")
check(run["frames"]["frame"] == [0, 1, 2] and all(ref is not None for ref in run["frames"]["ref"]),
      f"odometry index: {run['frames']}")
check(run["frames"]["inserted"][0] == run["frames"]["held"][0] > 0, f"odometry counts: {run['frames']}")
status, body = server.get("/api/frame?n=2")
check(status == 200 and json.loads(body[4:4 + struct.unpack_from("<I", body)[0]])["held"] == run["frames"]["held"][2],
      f"odometry frame 2: {status}")
server.stop()

# eco odometry --view: served while the maps run in their child processes, its frames appearing,
# and after the last; its server, a process of its own, ends with it. LIVE_RUNS times (under
# AddressSanitizer, 10): forking the maps beside the server's threads once hung one run in four.
LIVE_RUNS = int(sys.argv[3]) if len(sys.argv) > 3 else 1


def servers_of(pid):
    """The processes serving for `pid` (eco view --child-of PID)."""
    found = []
    for entry in os.listdir("/proc"):
        try:
            with open(f"/proc/{entry}/cmdline", "rb") as f:
                if f"\0--child-of\0{pid}\0".encode() in f.read():
                    found.append(int(entry))
        except OSError:
            pass
    return found


for run_number in range(LIVE_RUNS):
    live = ViewServer([CLI, "odometry", "--frames", "6", "--view", "--port", "0",
                       "--pace", "0.2", "--out", "odometry-live"], cwd=WORK)
    seen = []
    deadline = time.time() + 240
    while time.time() < deadline and (not seen or seen[-1] < 6):
        seen.append(len(json.loads(live.get("/api/run")[1])["frames"]["frame"]))
        time.sleep(0.1)
    check(seen and seen[-1] == 6 and len(set(seen)) > 2,
          f"run {run_number}: frames served while eco odometry --view ran: {sorted(set(seen))}")
    check(live.alive(), f"run {run_number}: eco odometry --view did not go on serving after its last frame")
    check(len(servers_of(live.process.pid)) == 1, f"run {run_number}: no server process of its own")
    log = live.stop()
    check(servers_of(live.process.pid) == [], f"run {run_number}: the server outlived eco odometry --view")
    check("fork refused" not in log, log)

# the folder: missing, without a recording; the port: taken
done = eco("view", "missing-run", ok=False)
check("no run folder at missing-run" in done.stderr, f"missing folder: {done.stderr}")
os.makedirs(os.path.join(WORK, "empty"))
done = eco("view", "empty", ok=False)
check("empty holds no recording" in done.stderr and "eco run --record --out empty" in done.stderr,
      f"no recording: {done.stderr}")
with socket.socket() as taken:
    taken.bind(("127.0.0.1", 0))
    taken.listen()
    done = eco("view", "run", "--port", str(taken.getsockname()[1]), ok=False)
    check(f"cannot serve on 127.0.0.1:{taken.getsockname()[1]}" in done.stderr, f"port in use: {done.stderr}")

print("ok")
