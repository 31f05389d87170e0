"""A 4-axle vehicle (8 wheel/rail contacts) in ONE FMU instance, from OSP libcosim.

    python examples/vehicle_libcosim.py [FMU]

Same FMU and signals as ``examples/vehicle_fmpy.py``: ``WheelRailContact_8contacts.fmu``
(``python build_fmu.py --contacts 8``), variables ``name[k]``, k = 1..8.

In a co-simulation the contacts' inputs come from the vehicle-dynamics model, another FMU,
and the forces go back to it. libcosim moves such values itself, so here that model is a
small PythonFMU (``VehicleModel``, built below into a temporary directory) that plays the
signals of ``examples/vehicle_track.py`` as its outputs and takes the forces as inputs; its
outputs are connected to the contact FMU's inputs and the forces back to its inputs, a
time-series observer records the forces, and the whole run is ONE ``execution.step(n)``
call: no Python of this script per step. (Setting the 88 inputs before every step from
Python through libcosim's override manipulator instead costs libcosim about 9 us per variable
and step, 0.8 ms a step, several times the contact FMU's own step; and its last-value observer
reads every variable of every slave after every step: docs/performance.md.)
"""

import sys
import tempfile
from pathlib import Path

import numpy as np
from libcosimpy.CosimEnums import CosimVariableType
from libcosimpy.CosimExecution import CosimExecution
from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
from libcosimpy.CosimObserver import CosimObserver
from libcosimpy.CosimSlave import CosimLocalSlave
from pythonfmu.builder import FmuBuilder

from vehicle_track import CONTACTS, INPUTS, signals

if len(sys.argv) > 1:
    fmu = sys.argv[1]
else:   # the checkout's vehicle FMU, (re)built if the sources changed
    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "fmu_src"))
    from railcontact.fmu_build import up_to_date_fmu

    fmu = str(up_to_date_fmu(contacts=CONTACTS))

FORCES = ("Fx", "Fy", "Mz")

# The vehicle model's side: outputs name_k played from resources/signals.npy (row j at
# t = j h), inputs Fx_k, Fy_k, Mz_k (a real vehicle model integrates its equations of motion
# with them).
VEHICLE_MODEL = f'''
from pathlib import Path

import numpy as np
from pythonfmu import Fmi2Causality, Fmi2Slave, Real


class VehicleModel(Fmi2Slave):
    def __init__(self, **kwargs):
        super().__init__(**kwargs)
        self.table = (np.load(Path(self.resources) / "signals.npy") if self.resources
                      else np.zeros((1, {CONTACTS * len(INPUTS)})))
        self.h = {1e-3!r}
        self.row = self.table[0].tolist()
        self.forces = [0.0] * {CONTACTS * len(FORCES)}
        for k in range({CONTACTS}):
            for j, name in enumerate({INPUTS!r}):
                self.register_variable(Real(f"{{name}}_{{k + 1}}", causality=Fmi2Causality.output,
                                            getter=lambda i={len(INPUTS)} * k + j: self.row[i]))
            for j, name in enumerate({FORCES!r}):
                i = 3 * k + j
                self.register_variable(Real(f"{{name}}_{{k + 1}}", causality=Fmi2Causality.input,
                                            getter=lambda i=i: self.forces[i],
                                            setter=lambda v, i=i: self.forces.__setitem__(i, v)))

    def do_step(self, current_time, step_size):
        j = min(int(round((current_time + step_size) / self.h)), len(self.table) - 1)
        self.row = self.table[j].tolist()
        return True
'''

log_output_level(CosimLogLevel.WARNING)                      # libcosim logs debug by default
step = 1e-3                                                  # [s]
t = np.arange(0.0, 0.5 + step / 2, step)
values = signals(t)                                          # name -> (len(t), 8)
n = t.size - 1                                               # steps

with tempfile.TemporaryDirectory() as work:
    work = Path(work)
    (work / "vehiclemodel.py").write_text(VEHICLE_MODEL)
    # row j: the inputs at t[j], contact by contact, in the order of INPUTS
    np.save(work / "signals.npy", np.stack([values[n_] for n_ in INPUTS], axis=-1)
            .reshape(t.size, -1))
    model_fmu = FmuBuilder.build_FMU(work / "vehiclemodel.py", dest=work / "VehicleModel.fmu",
                                     project_files=[work / "signals.npy"])

    execution = CosimExecution.from_step_size(int(round(step * 1e9)))   # nanoseconds
    vehicle = execution.add_local_slave(CosimLocalSlave(fmu_path=fmu, instance_name="vehicle"))
    model = execution.add_local_slave(CosimLocalSlave(fmu_path=str(model_fmu),
                                                      instance_name="model"))
    ref = {v.name.decode(): v.reference for v in execution.slave_variables(vehicle)}
    model_ref = {v.name.decode(): v.reference for v in execution.slave_variables(model)}
    execution.string_initial_value(vehicle, ref["scene_file"], "creep_exact_table")
    for k in range(1, CONTACTS + 1):
        for name in INPUTS:         # model -> contacts (0: success)
            assert execution.connect_real_variables(model, model_ref[f"{name}_{k}"], vehicle,
                                                    ref[f"{name}[{k}]"]) == 0, name
        for name in FORCES:         # contacts -> model
            assert execution.connect_real_variables(vehicle, ref[f"{name}[{k}]"], model,
                                                    model_ref[f"{name}_{k}"]) == 0, name
    out_refs = [ref[f"{name}[{k}]"] for k in range(1, CONTACTS + 1) for name in FORCES]
    observer = CosimObserver.create_time_series(n + 1)
    execution.add_observer(observer)
    for r in out_refs:
        observer.start_time_series(vehicle, r, CosimVariableType.REAL)

    assert execution.step(n), "the run failed"
    # sample j (step j + 1): the forces of the step from t[j] with the inputs at t[j]
    forces = np.array([observer.time_series_real_samples(vehicle, r, 1, n)[2]
                       for r in out_refs]).T.reshape(n, CONTACTS, 3)

fx, fy = forces[..., 0], forces[..., 1]
mu_n = (values["friction_coefficient"] * values["normal_force"])[:-1]
print(f"{len(forces)} steps x {CONTACTS} contacts")
print(f"|T| <= mu N at every contact and step: {bool(np.all(np.hypot(fx, fy) <= mu_n * (1 + 1e-12)))}")
for k in range(1, CONTACTS + 1):
    fx_k, fy_k, mz_k = forces[-1, k - 1]
    print(f"contact {k}: final Fx = {fx_k:.6e} N, Fy = {fy_k:.6e} N, Mz = {mz_k:.6e} N.m")
