"""Retrieval: scene SSG -> one composed room; action words -> template clips.

CONTRACT (services.retrieval.handlers.CONTRACT, messages in proto/retrieval.py):
    ComposeRequest     -> ComposeReply       objects + relations + room kind -> proto.scene.Scene, the
                                             matching map (paper Algorithm 1), relation checks, overlaps
    ActionMatchRequest -> ActionMatchReply   (verb, object, instrument, manner) -> clips, best first
    anything else / undecodable / refused  -> proto.common.ErrorReply (E001, E004, E009, E010)

Python API (in-process):
    services.retrieval.compose.compose_scene(objects, relations, *, room_type="", seed=0, previous=None)
        -> (proto.scene.Scene, ComposeReport)
    services.retrieval.matching.match_relation_first(objects, relations, db) -> Matching
    services.retrieval.lds.match_object_first(objects, relations, db) -> Matching   (LDS baseline)
    services.retrieval.actions.match_action(ActionQuery, prepare_clips(load_library()), top_k=3)
        -> ActionMatchResult

Modules: database (scene DB as networkx graphs), similarity (categories, attributes, relations),
matching (Algorithm 1), lds (baseline), placement (poses per relation), screen (fast relation screen),
layout (search over poses), room (kind, size, context objects), geometry (boxes), compose (the API),
actions (clip retrieval), errors (diagnostic codes), handlers / worker (the service).
"""
