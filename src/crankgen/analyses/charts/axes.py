"""The default plane of a stability chart (no numerical imports: the command line reads it when it
builds its parser)."""

from ...declaration import schema

R = schema.UNIT_PARAMETERS["r"]          # the slenderness r/L: v* = v / r, deflection / L = v* r/L
X_DEFAULT = (schema.CRANK_SPEED, 0.2, 1.6)
Y_DEFAULT = (R, 0.005, 0.05)
