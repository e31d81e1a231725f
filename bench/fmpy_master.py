"""A Jacobi co-simulation master in Python over FMPy's FMU2Slave, the reference point for
crane-cosim's speed: each macro step gets all connected outputs, sets all inputs, then steps
every instance, and records the system's variables.

It is written to be fast for Python (one get/set call per instance and type, index lists built
once) and follows crane-cosim's semantics: start values before initialization, inputs set in the
listed order during initialization, communication points t_k = t0 + k*h.

Usage: fmpy_master.py SYSTEM.json RESULTS.csv   (prints {"wall_s": ...}: loading to last step)
"""
import sys
import time
from collections import defaultdict

from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave

from common import load_system, report, split, steps, write_csv

GETTERS = {"Real": "getReal", "Integer": "getInteger", "Boolean": "getBoolean"}
SETTERS = {"Real": "setReal", "Integer": "setInteger", "Boolean": "setBoolean"}


def kind(variable):
    """The FMI call family of a variable (enumerations travel as integers)."""
    return "Integer" if variable.type == "Enumeration" else variable.type


class Instance:
    def __init__(self, name, model, directory):
        self.name = name
        self.vars = {v.name: v for v in model.modelVariables}
        self.slave = FMU2Slave(guid=model.guid, unzipDirectory=directory,
                               modelIdentifier=model.coSimulation.modelIdentifier, instanceName=name)

    def call(self, table, variable_type, *args):
        return getattr(self.slave, table[variable_type])(*args)

    def set_start(self, name, value):
        v = self.vars[name]
        cast = {"Real": float, "Integer": int, "Boolean": bool}.get(kind(v), str)
        setter = SETTERS.get(kind(v), "setString")
        getattr(self.slave, setter)([v.valueReference], [cast(value)])


class Reads:
    """Values to get from instances, grouped per (instance, type) so that each is one call."""

    def __init__(self, instances):
        self.instances = instances
        self.groups = defaultdict(list)  # (instance, type) -> [vr]
        self.slots = {}

    def slot(self, instance, variable):
        """Where the value of instance.variable will be: (group, index)."""
        v = self.instances[instance].vars[variable]
        key = (instance, kind(v))
        if (key, v.valueReference) not in self.slots:
            self.slots[(key, v.valueReference)] = (key, len(self.groups[key]))
            self.groups[key].append(v.valueReference)
        return self.slots[(key, v.valueReference)]

    def read(self):
        return {key: self.instances[key[0]].call(GETTERS, key[1], vrs) for key, vrs in self.groups.items()}


class JacobiMaster:
    def __init__(self, system):
        self.system = system
        models = {alias: (read_model_description(path), extract(path)) for alias, path in system["fmus"].items()}
        self.order = [i["name"] for i in system["instances"]]
        self.instances = {i["name"]: Instance(i["name"], *models[i["fmu"]]) for i in system["instances"]}
        self.starts = {i["name"]: i.get("start", {}) for i in system["instances"]}
        self.connections = [(split(c["from"]), split(c["to"])) for c in system.get("connections", [])]
        self.outputs = Reads(self.instances)
        # Per destination and type: the input vrs and the slots of their sources.
        self.inputs = defaultdict(lambda: ([], []))
        for (src, src_var), (dst, dst_var) in self.connections:
            v = self.instances[dst].vars[dst_var]
            vrs, slots = self.inputs[(dst, kind(v))]
            vrs.append(v.valueReference)
            slots.append(self.outputs.slot(src, src_var))
        self.recorded = Reads(self.instances)
        self.record_slots = [self.recorded.slot(i, v) for i, v in system["record_pairs"]]

    def set_inputs(self, values, only=None):
        for (dst, variable_type), (vrs, slots) in self.inputs.items():
            if only is None or dst == only:
                self.instances[dst].call(SETTERS, variable_type, vrs, [values[key][k] for key, k in slots])

    def sample(self, t):
        values = self.recorded.read()
        return [t] + [values[key][k] for key, k in self.record_slots]

    def initialize(self, t0, stop):
        for name in self.order:
            instance = self.instances[name]
            instance.slave.instantiate()
            instance.slave.setupExperiment(startTime=t0, stopTime=stop)
            for variable, value in self.starts[name].items():
                instance.set_start(variable, value)
        for name in self.order:
            self.instances[name].slave.enterInitializationMode()
        # In the listed order, each instance's inputs from the outputs as they are then.
        for name in self.order:
            self.set_inputs(self.outputs.read(), only=name)
        for name in self.order:
            self.instances[name].slave.exitInitializationMode()

    def run(self):
        t0, h, stop = self.system.get("start_time", 0.0), self.system["step_size"], self.system["stop_time"]
        self.initialize(t0, stop)
        rows = [self.sample(t0)]
        slaves = [self.instances[name].slave for name in self.order]
        for k in range(steps(self.system)):
            t, t_next = t0 + k * h, t0 + (k + 1) * h
            self.set_inputs(self.outputs.read())
            for slave in slaves:
                slave.doStep(currentCommunicationPoint=t, communicationStepSize=t_next - t)
            rows.append(self.sample(t_next))
        for slave in slaves:
            slave.terminate()
            slave.freeInstance()
        return rows


def main(system_path, csv_path):
    system = load_system(system_path)
    clock = time.perf_counter()
    rows = JacobiMaster(system).run()
    wall = time.perf_counter() - clock
    write_csv(csv_path, system, rows)
    report(wall)


if __name__ == "__main__":
    main(*sys.argv[1:3])
