"""rodimpact: axial impact of a rigid body with a spherical nose on an elastic rod.

Rebuilds Belyaev, Shurpatov & Ma (2018), "Determining the contact force of an axial
collision of an elastic rod with a rigid impactor", from configuration alone.
"""

__version__ = "0.1.0"
