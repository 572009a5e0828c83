"""The orchestrator: a library, not a bus worker. The gateway (`wana serve`) and the CLI (`wana animate`)
run it in their own process; it reaches the services through a Backend (the bus, or their handlers
in-process) and keeps one incremental session per document.

Modules, in the order a request flows:
    session     Orchestrator (opens sessions over one SQLite file) and Session (edit, compute)
    document    the text as sentences with stable ids; edits as text diffs
    store       sessions and edits in SQLite (WAL)
    pipeline    one compute: the stages in order, the query nodes they ask for, the result
    stages/     parse (+ resolve), scene, social, motion: each stage's nodes and service calls
    views       what each node reads of the bigger values (its dependencies)
    queries     the query engine: memos keyed by input hashes, early cutoff, the ran/reused log
    timeline    when each character's actions happen (story order, responses, waits)
    backend     Backend.call(request) -> its reply: in-process, over the bus, limited to some services
    registry    the one service list, and which service answers which request
    embedded    the broker and one worker per service in this process (the embedded default)
    exports     ExportRequests to the render service (animate and the gateway)
    animate     `wana animate FILE -o DIR`
"""
