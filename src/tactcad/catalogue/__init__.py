"""What each part is, without building it: name, process, material, colour,
expected volume and bounding box, joint frames, and the assemblies' instances.
No CAD kernel here."""
