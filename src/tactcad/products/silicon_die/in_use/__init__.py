"""The silicon die in use: its K_obj budget and the grasp in its jaw."""
