from services.orchestrator.queries import QueryEngine, content_hash


def build(engine: QueryEngine, sentences: dict[str, str], calls: list[str]) -> int:
    def parse(sid: str) -> str:
        text = sentences[sid]

        def compute() -> str:
            calls.append(f"parse:{sid}")
            return text.lower().rstrip(".")

        return engine.query(f"parse:{sid}", text, compute)

    parsed = {sid: parse(sid) for sid in sentences}

    def count() -> int:
        calls.append("count")
        return sum(len(p.split()) for p in parsed.values())

    return engine.query("count", [engine.result_hash(f"parse:{s}") for s in sentences], count)


def test_first_revision_runs_every_query():
    engine, calls = QueryEngine(), []
    engine.new_revision()
    assert build(engine, {"s1": "Eve sits.", "s2": "Tom waves."}, calls) == 4
    assert engine.ran() == ["parse:s1", "parse:s2", "count"]


def test_editing_one_input_reruns_it_and_its_dependants_only():
    engine, calls = QueryEngine(), []
    engine.new_revision()
    build(engine, {"s1": "Eve sits.", "s2": "Tom waves."}, calls)
    engine.new_revision()
    assert build(engine, {"s1": "Eve sits down.", "s2": "Tom waves."}, calls) == 5
    assert engine.ran() == ["parse:s1", "count"]
    assert engine.reused() == ["parse:s2"]


def test_an_edit_that_leaves_the_result_unchanged_stops_early():
    engine, calls = QueryEngine(), []
    engine.new_revision()
    build(engine, {"s1": "Eve sits.", "s2": "Tom waves."}, calls)
    engine.new_revision()
    build(engine, {"s1": "EVE SITS.", "s2": "Tom waves."}, calls)  # parses to the same value
    assert engine.ran() == ["parse:s1"]
    assert engine.reused() == ["parse:s2", "count"]


def test_content_hash_distinguishes_values_and_ignores_dict_order():
    assert content_hash({"a": 1, "b": 2}) == content_hash({"b": 2, "a": 1})
    assert content_hash([1, 2]) != content_hash([2, 1])
    assert content_hash("x") != content_hash(b"x")
