"""Writers for STEP, DXF, meshes and the manifest; every file is written atomically."""
