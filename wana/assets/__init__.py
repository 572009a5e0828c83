"""The asset library: object vocabulary, procedural catalog, scene database and characters.

Modules (import what you need; nothing heavy is imported here):

- ``vocabulary``: category table, synonyms, hypernyms, attribute words, room types.
- ``catalog``: parametric object generators -> ``AssetObject`` (mesh, collision boxes, contact points).
- ``relations``: geometric predicates for SSG relations between placed objects.
- ``scenes`` / ``scenedb``: the seeded scene grammar and the committed scene database.
- ``characters``: procedural skinned characters with face blendshapes, glTF export/import.
- ``importers``: 3D-FRONT / ShapeNetSem / OBJ+annotation importers.
"""
