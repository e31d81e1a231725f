"""A minimal FMI 2.0 co-simulation loop over FMPy's FMU2Slave for one FMU.

Communication points are t_k = start + k*h (an integer step count, as the Rust master does).
Inputs are functions of time; when `derivatives` is on, each step also passes the slope of the
input over [t_k, t_k+1] with fmi2SetRealInputDerivatives (order 1), so an FMU that interpolates
sees the exact piecewise-linear signal through the sample points.
"""
import shutil

import numpy as np
from fmpy import extract, read_model_description
from fmpy.fmi2 import FMU2Slave


class Rig:
    def __init__(self, fmu_path, instance_name="rig"):
        self.md = read_model_description(str(fmu_path))
        self.dir = extract(str(fmu_path))
        self.vr = {v.name: v.valueReference for v in self.md.modelVariables}
        self.type = {v.name: v.type for v in self.md.modelVariables}
        self.slave = FMU2Slave(
            guid=self.md.guid,
            unzipDirectory=self.dir,
            modelIdentifier=self.md.coSimulation.modelIdentifier,
            instanceName=instance_name,
        )

    def run(self, start_values, inputs, outputs, stop_time, step, derivatives=False):
        """inputs: {name: f(t)}; returns a structured array with time and the outputs."""
        s = self.slave
        s.instantiate()
        s.setupExperiment(startTime=0.0, stopTime=stop_time)
        for name, value in start_values.items():
            self.set_start(name, value)
        in_vrs = [self.vr[n] for n in inputs]
        out_vrs = [self.vr[n] for n in outputs]
        funcs = list(inputs.values())

        def apply(t, t_next):
            if not in_vrs:
                return
            now = [f(t) for f in funcs]
            s.setReal(in_vrs, now)
            if derivatives:
                slope = [(f(t_next) - v) / (t_next - t) for f, v in zip(funcs, now)]
                s.setRealInputDerivatives(in_vrs, [1] * len(in_vrs), slope)

        s.enterInitializationMode()
        apply(0.0, step)
        s.exitInitializationMode()
        n = int(round(stop_time / step))
        rows = [(0.0, *s.getReal(out_vrs))]
        for k in range(n):
            t, t_next = k * step, (k + 1) * step
            apply(t, t_next)
            s.doStep(currentCommunicationPoint=t, communicationStepSize=t_next - t)
            rows.append((t_next, *s.getReal(out_vrs)))
        s.terminate()
        s.freeInstance()
        dtype = [("time", float)] + [(n, float) for n in outputs]
        return np.array(rows, dtype=dtype)

    def set_start(self, name, value):
        """Sets a start value with the setter of the variable's type."""
        vr, kind = [self.vr[name]], self.type[name]
        if kind == "Real":
            self.slave.setReal(vr, [float(value)])
        elif kind in ("Integer", "Enumeration"):
            self.slave.setInteger(vr, [int(value)])
        elif kind == "Boolean":
            self.slave.setBoolean(vr, [bool(value)])
        else:
            self.slave.setString(vr, [str(value)])

    def close(self):
        shutil.rmtree(self.dir, ignore_errors=True)
