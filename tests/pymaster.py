"""A Python co-simulation master over FMPy's FMU2Slave that reads the same JSON system files as
the Rust master (`crane-cosim run`) and follows the same algorithm, so the two can be compared
result for result.

Semantics mirrored from the Rust master: communication points t_k = start + k*h; every instance
set up, given its start values and put into initialization mode, then (in the listed order) its
connected inputs set from the latest outputs of their sources and its file inputs set at t0, then
initialization left; each macro step, Gauss-Seidel in the listed order (or Jacobi: all inputs
gathered first) sets file inputs at t_k (with the secant over [t_k, t_k+1] as input derivative
when `input_derivatives` is on and the FMU can interpolate), sets connected inputs, and steps.
With Gauss-Seidel and `input_derivatives`, a Real input of an FMU that can interpolate, fed by
an instance stepped earlier in the order, is set to its source's value at t_k with the slope to
t_k+1 as derivative.
"""
import json
import pathlib
import shutil

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


class Instance:
    def __init__(self, name, fmu_path):
        self.name = name
        self.md = read_model_description(str(fmu_path))
        self.dir = extract(str(fmu_path))
        self.vars = {v.name: v for v in self.md.modelVariables}
        self.slave = FMU2Slave(guid=self.md.guid, unzipDirectory=self.dir,
                               modelIdentifier=self.md.coSimulation.modelIdentifier, instanceName=name)
        self.can_interpolate = bool(self.md.coSimulation.canInterpolateInputs)

    def set(self, name, value):
        v = self.vars[name]
        if v.type == "Real":
            self.slave.setReal([v.valueReference], [float(value)])
        elif v.type in ("Integer", "Enumeration"):
            self.slave.setInteger([v.valueReference], [int(value)])
        elif v.type == "Boolean":
            self.slave.setBoolean([v.valueReference], [bool(value)])
        else:
            self.slave.setString([v.valueReference], [str(value)])

    def get(self, name):
        v = self.vars[name]
        if v.type == "Real":
            return self.slave.getReal([v.valueReference])[0]
        if v.type in ("Integer", "Enumeration"):
            return self.slave.getInteger([v.valueReference])[0]
        if v.type == "Boolean":
            return float(self.slave.getBoolean([v.valueReference])[0])
        return self.slave.getString([v.valueReference])[0]

    def close(self):
        self.slave.freeInstance()
        shutil.rmtree(self.dir, ignore_errors=True)


class InputFile:
    """Columns of a CSV, linearly interpolated (held outside the table)."""

    def __init__(self, path):
        data = np.genfromtxt(path, delimiter=",", names=True, deletechars="")
        self.t = np.atleast_1d(data["time"])
        self.columns = {n: np.atleast_1d(data[n]) for n in data.dtype.names if n != "time"}

    def value(self, name, t):
        return float(np.interp(t, self.t, self.columns[name]))


def split(reference):
    instance, _, variable = reference.partition(".")
    return instance, variable


class PyMaster:
    def __init__(self, system_path, overrides=None):
        path = pathlib.Path(system_path)
        self.system = json.loads(path.read_text())
        self.system.update(overrides or {})
        base = path.parent
        fmus = {alias: (base / p) for alias, p in self.system["fmus"].items()}
        self.instances = [Instance(i["name"], fmus[i["fmu"]]) for i in self.system["instances"]]
        self.by_name = {i.name: i for i in self.instances}
        self.starts = [i.get("start", {}) for i in self.system["instances"]]
        self.connections = [(split(c["from"]), split(c["to"])) for c in self.system.get("connections", [])]
        self.files = [(self.by_name[f["instance"]], InputFile(base / f["file"])) for f in self.system.get("inputs", [])]
        self.h = float(self.system["step_size"])
        self.t0 = float(self.system.get("start_time", 0.0))
        self.stop = float(self.system["stop_time"])
        self.derivatives = bool(self.system.get("input_derivatives", False))
        self.jacobi = self.system.get("algorithm", "gauss-seidel") == "jacobi"
        record = self.system.get("record", {}).get("variables")
        self.previous = {}
        self.record = record or [f"{i.name}.{v.name}" for i in self.instances
                                 for v in i.md.modelVariables if v.causality == "output"]

    def time(self, k):
        return self.t0 + k * self.h

    def gather(self, target):
        return [(dst_var, self.by_name[src].get(src_var))
                for (src, src_var), (dst, dst_var) in self.connections if dst == target.name]

    def apply_files(self, instance, t, t_next=None):
        for owner, table in self.files:
            if owner is not instance:
                continue
            for name in table.columns:
                value = table.value(name, t)
                instance.set(name, value)
                if t_next is not None and self.derivatives and instance.can_interpolate:
                    slope = (table.value(name, t_next) - value) / (t_next - t)
                    v = instance.vars[name]
                    instance.slave.setRealInputDerivatives([v.valueReference], [1], [slope])

    def interpolate(self, index, inst, values, h):
        """Sets derivatives for inputs from earlier sources; returns the values to set."""
        before = self.previous.get(inst.name, {})
        self.previous[inst.name] = dict(values)
        if self.jacobi or not (self.derivatives and inst.can_interpolate):
            return values
        earlier = {dst_var for (src, _), (dst, dst_var) in self.connections
                   if dst == inst.name and [i.name for i in self.instances].index(src) < index}
        result = []
        for name, value in values:
            if name in earlier and inst.vars[name].type == "Real":
                start = before[name]
                v = inst.vars[name]
                inst.set(name, start)  # setting a value clears its derivative, so value first
                inst.slave.setRealInputDerivatives([v.valueReference], [1], [(value - start) / h])
            else:
                result.append((name, value))
        return result

    def sample(self, t):
        return (t, *[self.by_name[i].get(v) for i, v in map(split, self.record)])

    def run(self):
        steps = int(np.floor((self.stop - self.t0) / self.h + 1e-9))
        try:
            for inst, start in zip(self.instances, self.starts):
                inst.slave.instantiate()
                inst.slave.setupExperiment(startTime=self.t0, stopTime=self.stop)
                for name, value in start.items():
                    inst.set(name, value)
            for inst in self.instances:
                inst.slave.enterInitializationMode()
            for inst in self.instances:
                gathered = self.gather(inst)
                self.apply_files(inst, self.t0)
                for name, value in gathered:
                    inst.set(name, value)
            for inst in self.instances:
                inst.slave.exitInitializationMode()
            for inst in self.instances:
                self.previous[inst.name] = dict(self.gather(inst))
            rows = [self.sample(self.t0)]
            for k in range(steps):
                t, t_next = self.time(k), self.time(k + 1)
                gathered = {i.name: self.gather(i) for i in self.instances} if self.jacobi else None
                for index, inst in enumerate(self.instances):
                    values = gathered[inst.name] if self.jacobi else self.gather(inst)
                    self.apply_files(inst, t, t_next)
                    for name, value in self.interpolate(index, inst, values, t_next - t):
                        inst.set(name, value)
                    inst.slave.doStep(currentCommunicationPoint=t, communicationStepSize=t_next - t)
                rows.append(self.sample(t_next))
            for inst in self.instances:
                inst.slave.terminate()
        finally:
            for inst in self.instances:
                inst.close()
        dtype = [("time", float)] + [(r, float) for r in self.record]
        return np.array(rows, dtype=dtype)
