"""The silicon die's mechanics: its beams at fem3d, their strength, resonances, crosstalk through the handle, and the piezoresistive read-out."""
