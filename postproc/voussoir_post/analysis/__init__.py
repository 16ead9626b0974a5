"""Geometry of a run at a sample: block polygons, joint openings and hinge states of an
arch (:mod:`.kinematics`), the joints of any assembly (:mod:`.assembly_joints`); the true peak and the
full-cycle acceleration of an afd motion (:mod:`.afd`)."""
