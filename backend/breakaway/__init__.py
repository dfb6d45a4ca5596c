"""Breakaway: Ruderman's break-away friction model, its explorer and identification engine.

Model modules, one per physical concept (equation numbers of the note in brackets):

- :mod:`breakaway.params`      defaults, presets and parameter validation
- :mod:`breakaway.steady`      Stribeck steady state g, Fss (E2)
- :mod:`breakaway.presliding`  presliding shape f (E4) and the reversal-memory law (E6')
- :mod:`breakaway.quasistatic` phase family (E12) and break-away curve (E13)
- :mod:`breakaway.dynamics`    ramp experiment (E7) and LuGre, one integrator
"""

__version__ = "0.1.0"
