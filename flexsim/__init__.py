"""flexsim: flexible aircraft in manoeuvring flight.

Implements the whole-aircraft flexible multibody model of Tuzcu & Nguyen, *Flutter of Maneuvering
Aircraft*, J. Aerosp. Eng. 28(4), 2015 (accepted manuscript 2014), built on Meirovitch & Tuzcu's unified
formulation (Lagrange's equations in quasi-coordinates).

Conventions (SI units and radians inside the library, body axes x forward / y right / z down) are in
``docs/conventions.md``.
"""

__version__ = "0.1.0"
