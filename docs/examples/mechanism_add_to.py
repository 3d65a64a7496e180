"""A piezo bender driving a user-built rigid lever, solved with mbs.SolveDynamic."""

import exudyn as exu
from exudyn import itemInterface as ii

import exudyn_atcm as atcm
from exudyn_atcm.mbs import add_post_step
from exudyn_atcm.model import Triangle

cfc = atcm.Layer(thickness=0.2e-3, youngs_modulus=70e9, density=1550.0)
mfc = atcm.Layer(thickness=0.3e-3, youngs_modulus=30.336e9, density=5440.0)
bender = atcm.Bender("bender", width=10e-3, passive=cfc, active=mfc, length=0.03, n_cells=8,
                     drive=atcm.PiezoDrive(Triangle(750.0, 750.0, 0.2)), cell="rigid")  # 0 V -> 1500 V -> 0 V

SC = exu.SystemContainer()
mbs = SC.AddSystem()
h = atcm.add_to(mbs, bender)  # base clamped at the origin, the tip free at (0.03, 0)

# the user's parts: a connecting rod from the bender tip (0.03, 0) up to (0.03, 0.01) and a
# lever pivoted on the ground at (0.02, 0.01), 40 mm long, driven 10 mm from its pivot: about 4 times the stroke
ground = mbs.AddObject(ii.ObjectGround())


def rigid_bar(start, end, mass=1e-4):
    """A 2D rigid bar between two points [m]; returns the body and markers at its ends."""
    center = [(start[0] + end[0]) / 2, (start[1] + end[1]) / 2]
    half = [(end[0] - start[0]) / 2, (end[1] - start[1]) / 2]
    length = 2 * (half[0] ** 2 + half[1] ** 2) ** 0.5
    node = mbs.AddNode(ii.NodeRigidBody2D(referenceCoordinates=[center[0], center[1], 0.0]))
    body = mbs.AddObject(ii.ObjectRigidBody2D(
        nodeNumber=node, mass=mass, inertia=mass * length**2 / 12,
        visualization={"show": True, "graphicsDataUserFunction": 0,
                       "graphicsData": [exu.graphics.Lines([[start[0], start[1], 0], [end[0], end[1], 0]])]}))
    at = [mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=body, localPosition=[s * half[0], s * half[1], 0.0]))
          for s in (-1, 1)]
    return body, at


rod, (rod_bottom, rod_top) = rigid_bar((0.03, 0.0), (0.03, 0.01))
lever, (lever_pivot, lever_end_marker) = rigid_bar((0.02, 0.01), (0.06, 0.01))
lever_at_rod = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=lever, localPosition=[-0.01, 0.0, 0.0]))
ground_pivot = mbs.AddMarker(ii.MarkerBodyPosition(bodyNumber=ground, localPosition=[0.02, 0.01, 0.0]))
mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[h.position_marker(bender.tip), rod_bottom]))
mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[rod_top, lever_at_rod]))
mbs.AddObject(ii.ObjectJointRevolute2D(markerNumbers=[ground_pivot, lever_pivot]))
lever_end = mbs.AddSensor(ii.SensorBody(bodyNumber=lever, localPosition=[0.02, 0.0, 0.0],
                                        outputVariableType=exu.OutputVariableType.Position, storeInternal=True))

# your own step function runs next to the package's hysteresis hooks
peak = {"y": 0.0}


def track_peak(mbs, t):
    peak["y"] = max(peak["y"], mbs.GetSensorValues(lever_end)[1])
    return True


add_post_step(mbs, track_peak)

mbs.Assemble()
settings = exu.SimulationSettings()
settings.timeIntegration.endTime = 0.2
settings.timeIntegration.numberOfSteps = 400
settings.timeIntegration.newton.absoluteTolerance = 1e-8  # SI units: forces of mN
settings.timeIntegration.verboseMode = 0
settings.solution.file.write = False
settings.solution.sensors.writePeriod = 5e-4
mbs.SolveDynamic(settings)

result = h.result()  # the bender's columns: time [s], bender.voltage [V], bender.tip_y [m], ...
end_y = mbs.GetSensorStoredData(lever_end)[:, 2]  # the lever end's y [m] at each stored time
print(f"bender tip up to {result['bender.tip_y'].max() * 1e3:.3f} mm, lever end up by {(peak['y'] - 0.01) * 1e3:.3f} mm")
