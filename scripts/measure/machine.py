"""The machine a measurement ran on and its load, for the record beside every figure."""
import os
import platform


def cpu_model():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def cpu_flags():
    """The SIMD levels the CPU reports (avx2, avx512f), as a short string."""
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("flags"):
                flags = set(line.split(":", 1)[1].split())
                return " ".join(f for f in ("avx2", "fma", "avx512f") if f in flags) or "-"
    except OSError:
        pass
    return "unknown"


def usable_cpus():
    """nproc: the CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def load():
    """{"loadavg": [1, 5, 15 min], "runnable": running/total tasks} now."""
    try:
        fields = open("/proc/loadavg").read().split()
        return {"loadavg": [float(x) for x in fields[:3]], "runnable": fields[3]}
    except OSError:
        return {"loadavg": [round(x, 2) for x in os.getloadavg()], "runnable": "?"}


def describe():
    """One line: host, nproc, CPU model and SIMD flags, kernel."""
    return (f"{platform.node()}: nproc {usable_cpus()}, {cpu_model()} ({cpu_flags()}), "
            f"Linux {platform.release()}")
