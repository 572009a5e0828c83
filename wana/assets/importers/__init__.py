"""Importers for data a user owns: 3D-FRONT scenes, ShapeNetSem models, any OBJ/GLB + annotation."""
