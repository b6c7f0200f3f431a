"""The flutter-margin target is computed for the aircraft given, cached by its content.

The old cache was keyed by the aircraft's file path and name and reloaded the file, so an aircraft modified in
memory (``StructuralScaling.apply`` keeps ``source`` and ``name``) got the stock GTM's flutter point
(measured: M 0.6904 instead of its own 0.6237 for ``wing_gj = 0.8``). Invariant checked: 20 % less wing
torsional stiffness lowers the antisymmetric wing-flutter Mach number (Theodorsen-type bending-torsion
flutter speed grows with the torsion frequency; Bisplinghoff, Ashley & Halfman 1955 ch. 9) by more than 0.03
(measured 0.067); an aircraft of equal content but another ``source`` reuses the cached point.
"""

from dataclasses import replace

from flexsim.envs.flutter_margin import WingFlutterMarginTask
from flexsim.linear.flutter import flutter_condition
from flexsim.aircraft.calibration import StructuralScaling
from flexsim.aircraft.toml_loader import load_aircraft


def test_flutter_condition_is_keyed_by_aircraft_content():
    task = WingFlutterMarginTask()
    args = ("unsteady", task.altitude_m, task.flutter_mach_range)
    gtm = load_aircraft("gtm")
    stock = flutter_condition(gtm, *args)
    softer = StructuralScaling(wing_gj=0.8).apply(gtm)
    assert (softer.source, softer.name) == (gtm.source, gtm.name)  # what the old cache was keyed by
    own = flutter_condition(softer, *args)
    assert own.mach < stock.mach - 0.03
    assert flutter_condition(replace(gtm, source="<python>"), *args) is stock
