"""The Illinois false-position bracket shared by the locators of special points (core.py, along a
branch) and of codimension-two points (codim2.py, along a curve).

A test function f changes sign between s_a and s_b (distances along a direction from the bracket's
first point).  `trial()` is the false-position point s_c = (s_a f_b - s_b f_a) / (f_b - f_a);
`update(s_c, f_c)` replaces the end whose value has f_c's sign and, when the same end is replaced
twice running, halves the other end's value (the Illinois modification: superlinear convergence
where plain false position keeps one end fixed).  The callers decide when to stop."""

import numpy as np


class FalsePosition:
    """An Illinois false-position bracket [s_a, s_b] with the values f_a, f_b of opposite signs."""

    def __init__(self, s_a, f_a, s_b, f_b):
        self.s_a, self.f_a, self.s_b, self.f_b = s_a, f_a, s_b, f_b
        self.side = 0            # which end the last update replaced: -1 the far end b, +1 a

    def trial(self):
        """The false-position point between the ends."""
        return (self.s_a * self.f_b - self.s_b * self.f_a) / (self.f_b - self.f_a)

    @property
    def width(self):
        return abs(self.s_b - self.s_a)

    def update(self, s_c, f_c):
        """Replace the end on f_c's side by (s_c, f_c), halving the other's value when that end was
        replaced last time too."""
        if np.sign(f_c) == np.sign(self.f_b):
            self.s_b, self.f_b = s_c, f_c
            if self.side == -1:
                self.f_a *= 0.5
            self.side = -1
        else:
            self.s_a, self.f_a = s_c, f_c
            if self.side == 1:
                self.f_b *= 0.5
            self.side = 1
