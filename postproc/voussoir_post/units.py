"""The one physical constant the postprocessor shares with the Fortran kernel.

``G_M_S2``: gravity [m/s2], ``g_m_s2`` of src/core/kinds.f90 (a test holds the two
equal): the kernel's weights, its static capacities lambda g, and the g by which
accelerations are written in g (PGA in g, records given in g).
"""

G_M_S2 = 9.81
