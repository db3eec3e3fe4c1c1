"""A ROS 1 graph of its own for a test or a benchmark: roscore on a free port (ROS_MASTER_URI), its logs in a
folder of the caller's, and eco_node started and stopped as a process, as a user runs them."""

import os
import signal
import socket
import subprocess
import time

import rosgraph


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class Graph:
    """roscore for the `with` block; env() is what a process of the graph needs."""

    def __init__(self, work):
        self.work = work
        os.makedirs(work, exist_ok=True)
        self.port = free_port()
        self.uri = f"http://127.0.0.1:{self.port}"
        os.environ.update(self.env())  # rospy in this process joins the same graph
        self.started = []  # the nodes, stopped with the graph if a check failed first

    def env(self):
        env = dict(os.environ)
        env.update(ROS_MASTER_URI=self.uri, ROS_HOME=self.work, ROS_LOG_DIR=os.path.join(self.work, "log"),
                   ROS_IP="127.0.0.1", ROS_HOSTNAME="127.0.0.1")
        env.pop("ROS_NAMESPACE", None)
        return env

    def __enter__(self):
        self.core = subprocess.Popen(["roscore", "-p", str(self.port)], env=self.env(), stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL, start_new_session=True)
        master = rosgraph.Master("/eco_test", master_uri=self.uri)
        deadline = time.monotonic() + 60
        while not master.is_online():
            if self.core.poll() is not None or time.monotonic() > deadline:
                raise RuntimeError(f"roscore on port {self.port} did not start")
            time.sleep(0.1)
        while True:  # rosout is up once it has subscribed to /rosout
            try:
                if any(t == "/rosout" for t, _ in master.getSystemState()[1]):
                    break
            except Exception:
                pass
            time.sleep(0.1)
        return self

    def __exit__(self, *exc):
        for process in self.started:
            if process.poll() is None:
                process.kill()
                process.wait()
        os.killpg(self.core.pid, signal.SIGINT)
        try:
            self.core.wait(timeout=20)
        except subprocess.TimeoutExpired:
            os.killpg(self.core.pid, signal.SIGKILL)
            self.core.wait()

    def node(self, eco_node, name, parameters, prefix=()):
        """eco_node as `name` with private parameters (_name:=value), its output in a file; `prefix`
        runs it through another command (taskset -c 0)."""
        args = [*prefix, eco_node, f"__name:={name}"] + [f"_{k}:={v}" for k, v in parameters.items()]
        log = open(os.path.join(self.work, name + ".log"), "w")
        process = subprocess.Popen(args, env=self.env(), stdout=log, stderr=subprocess.STDOUT)
        self.started.append(process)
        return process

    def wait_for_service(self, service, process, timeout=30):
        master = rosgraph.Master("/eco_test", master_uri=self.uri)
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            if process.poll() is not None:
                raise RuntimeError(f"the node stopped with {process.returncode} before offering {service}")
            try:
                master.lookupService(service)
                return
            except Exception:
                time.sleep(0.05)
        raise RuntimeError(f"{service} not offered within {timeout} s")

    def log_of(self, name):
        with open(os.path.join(self.work, name + ".log")) as f:
            return f.read()


def stop(process, timeout=30):
    """SIGINT, as Ctrl-C would; returns the exit code."""
    process.send_signal(signal.SIGINT)
    return process.wait(timeout=timeout)
