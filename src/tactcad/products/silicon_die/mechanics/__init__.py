"""The silicon die's mechanics: its beams at fem3d, their strength, resonances, crosstalk through the handle, and the piezoresistive read-out."""

#: The stiffness levels a die's beams are solved at (the die's ladder): declared here, where
#: a command's help reads it without importing the die's views.
DIE_STIFFNESS_LEVELS = ("closed-form", "fem3d")
