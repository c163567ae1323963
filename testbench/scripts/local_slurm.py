"""A single-node Slurm cluster on localhost for the backend tests: Debian's
munged, slurmctld and slurmd (packages munge, slurm-wlm; scripts/setup.sh
installs them) started in the foreground as child processes of the test, on a
slurm.conf generated in a temporary folder (proctrack/linuxproc, task/none, no
accounting, its own munge key and socket, free ports), and stopped by their
pids. Needs root: slurmd runs jobs as their submitting user and munged's
socket checks need a trusted owner.

    with LocalSlurm() as cluster:      # raises ClusterError saying what failed
        env = cluster.env              # SLURM_CONF for sbatch/squeue/sinfo
"""
import os
import shutil
import socket
import subprocess
import tempfile
import time

START_TIMEOUT_S = 60


class ClusterError(RuntimeError):
    pass


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


SLURM_CONF = """# Generated for a test: one node on localhost, no accounting, no cgroups.
ClusterName=vbsimtest
SlurmctldHost={host}(127.0.0.1)
SlurmctldPort={ctld_port}
SlurmdPort={slurmd_port}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={munge_socket}
SlurmUser=root
SlurmdUser=root
StateSaveLocation={d}/state
SlurmdSpoolDir={d}/spool
SlurmctldPidFile={d}/slurmctld.pid
SlurmdPidFile={d}/slurmd.pid
SlurmctldLogFile={d}/slurmctld.log
SlurmdLogFile={d}/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
ReturnToService=2
SlurmctldTimeout=30
SlurmdTimeout=30
MessageTimeout=20
KillWait=5
MinJobAge=600
NodeName={host} NodeAddr=127.0.0.1 CPUs={cpus} State=UNKNOWN
PartitionName=test Nodes={host} Default=YES MaxTime=INFINITE State=UP
"""


class LocalSlurm:
    def __init__(self, cpus=None):
        self.cpus = cpus or os.cpu_count() or 2
        self.procs = []
        self.dir = None

    def __enter__(self):
        try:
            self.start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, *exc):
        self.stop()

    def log_tail(self, name, lines=15):
        path = os.path.join(self.dir, name)
        if not os.path.exists(path):
            return f"({name}: none)"
        with open(path, errors="replace") as f:
            return f"--- {name}:\n" + "".join(f.readlines()[-lines:])

    def spawn(self, name, argv):
        with open(os.path.join(self.dir, name + ".out"), "w") as out:
            proc = subprocess.Popen(argv, stdout=out, stderr=subprocess.STDOUT, env=self.env)
        self.procs.append((name, proc))
        return proc

    def start(self):
        for tool in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "sinfo"):
            if not shutil.which(tool):
                raise ClusterError(f"`{tool}` is not installed (scripts/setup.sh installs munge and slurm-wlm)")
        self.dir = tempfile.mkdtemp(prefix="vbsim_slurm_")
        os.chmod(self.dir, 0o755)
        d = self.dir
        for sub in ("state", "spool", "munge"):
            os.makedirs(os.path.join(d, sub), mode=0o755)
        key = os.path.join(d, "munge", "munge.key")
        with open(key, "wb") as f:
            f.write(os.urandom(1024))
        os.chmod(key, 0o400)
        munge_socket = os.path.join(d, "munge", "munge.socket")
        host = socket.gethostname().split(".")[0]
        conf = os.path.join(d, "slurm.conf")
        with open(conf, "w") as f:
            f.write(SLURM_CONF.format(host=host, ctld_port=free_port(), slurmd_port=free_port(),
                                      munge_socket=munge_socket, d=d, cpus=self.cpus))
        self.env = {**os.environ, "SLURM_CONF": conf}
        self.spawn("munged", ["munged", "--foreground", "--force", f"--key-file={key}", f"--socket={munge_socket}",
                              f"--pid-file={d}/munge/munged.pid", f"--log-file={d}/munge/munged.log",
                              f"--seed-file={d}/munge/munged.seed"])
        self.wait_for(lambda: os.path.exists(munge_socket), "munged's socket", ["munged.out", "munge/munged.log"])
        self.spawn("slurmctld", ["slurmctld", "-D", "-f", conf])
        self.spawn("slurmd", ["slurmd", "-D", "-f", conf, "-N", host])
        self.wait_for(self.node_idle, "the node to come up idle",
                      ["slurmctld.out", "slurmctld.log", "slurmd.out", "slurmd.log"])

    def node_idle(self):
        proc = subprocess.run(["sinfo", "-h", "-o", "%T"], stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True, env=self.env)
        return proc.returncode == 0 and proc.stdout.strip() == "idle"

    def wait_for(self, ready, what, logs):
        deadline = time.monotonic() + START_TIMEOUT_S
        while time.monotonic() < deadline:
            for name, proc in self.procs:
                if proc.poll() is not None:
                    raise ClusterError(f"{name} exited ({proc.returncode}) while waiting for {what}\n" +
                                       "\n".join(self.log_tail(n) for n in logs))
            if ready():
                return
            time.sleep(0.2)
        raise ClusterError(f"no {what} after {START_TIMEOUT_S} s\n" + "\n".join(self.log_tail(n) for n in logs))

    def stop(self):
        """Stops the daemons this object started (by their pids), slurmd first."""
        for name, proc in reversed(self.procs):
            if proc.poll() is None:
                proc.terminate()
                try:
                    proc.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
        self.procs = []
        if self.dir and not os.environ.get("VBSIM_KEEP_SLURM_DIR"):
            shutil.rmtree(self.dir, ignore_errors=True)
