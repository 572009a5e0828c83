"""The social service: faces, response timing, distances and open reactions of interacting characters.

After Zhao et al., "Triangular Character Animation Sampling" (see DESIGN.md §2): relation r = (dominance,
intimacy), emotion e as a VAD change per character, motion m scored by its verb's VAD (Glasgow Norms);
pairwise potentials φ_me, φ_re, φ_rm and temporal potentials ψ form an energy that Metropolis-Hastings
samples with relation, emotion and motion proposals (fixed seed, bounded steps).

CONTRACT:
    SocialPlanRequest      -> SocialPlanReply | ErrorReply        plan a document's social animation
    ExpressionTrackRequest -> ExpressionTrackReply | ErrorReply   (T, E) face weights for one character

Python API (in-process, no bus):
    plan.plan_social(graphs, *, seed=0, steps=0) -> proto.social.SocialPlan
    plan.expression_track(plan, character, segments, fps=30, *, frames=None, others=None)
        -> (T, E) float32 face blendshape weights (wana.assets.characters.EXPRESSIONS order)
    face.face_weights(vad) -> (E,) | (N, E) float32; lexicon.word_vad(word), lexicon.action_vad(action, verb)

Modules: lexicon (the committed VAD table, assets/social/vad.tsv), build_vad (rebuilds it from the
Glasgow Norms and VADER), relations (label -> dominance, intimacy), story (graphs -> acts, labels,
responses), energy (the factors), sampler (Metropolis-Hastings), face (linear VAD -> face), plan (API),
handlers, worker.
"""
