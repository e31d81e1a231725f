"""A PythonFMU slave that follows a set-point schedule read from its resources folder.

Built into a Co-Simulation-only FMU by `pythonfmu build -f schedule.py schedule.csv` (the test
does this): PythonFMU copies `schedule.csv` into the FMU's `resources/`. Variables of every FMI
type: Real input `u` and parameter `gain`, Real output `y`, Integer output `phase`, Boolean output
`lifting` and String output `label`.
"""

import csv

from pythonfmu import Boolean, Fmi2Causality, Fmi2Slave, Fmi2Variability, Integer, Real, String


class Schedule(Fmi2Slave):
    """`y = gain · setpoint(t) + u`, with the schedule row active at the end of each step."""

    author = "crane-cosim tests"
    description = "Set-point schedule read from resources/schedule.csv"

    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        with open(f"{self.resources}/schedule.csv", newline="") as file:
            self.rows = [(float(r["time"]), float(r["setpoint"]), r["label"]) for r in csv.DictReader(file)]
        self.u = 0.0
        self.gain = 2.0
        self.phase = 0
        self.y = 0.0
        self.lifting = False
        self.label = self.rows[0][2]
        self.register_variable(Real("u", causality=Fmi2Causality.input))
        self.register_variable(Real("gain", causality=Fmi2Causality.parameter, variability=Fmi2Variability.tunable))
        self.register_variable(Real("y", causality=Fmi2Causality.output))
        self.register_variable(Integer("phase", causality=Fmi2Causality.output, variability=Fmi2Variability.discrete)
        )
        self.register_variable(Boolean("lifting", causality=Fmi2Causality.output, variability=Fmi2Variability.discrete)
        )
        self.register_variable(String("label", causality=Fmi2Causality.output, variability=Fmi2Variability.discrete)
        )

    def do_step(self, current_time, step_size):
        end = current_time + step_size
        # The last row whose time has been reached (times within 1e-9 s count as reached).
        self.phase = max(i for i, row in enumerate(self.rows) if row[0] <= end + 1e-9)
        _, setpoint, self.label = self.rows[self.phase]
        self.y = self.gain * setpoint + self.u
        self.lifting = setpoint > 1.0
        return True
