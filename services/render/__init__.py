"""The render service: frames, MP4 video, animated GLB and BVH exports of an animation.

CONTRACT:
    RenderRequest (proto.render) -> RenderReply: frames [start_frame, end_frame) as PNG, JPEG or raw RGB
        bytes, or one H.264 MP4 chunk (chunks of one animation join with services.render.video.join_chunks).
    ExportRequest (proto.render) -> ExportReply: the whole MP4 (with its camera checks, in_view and
        command_visible, by sentence id), the animated GLB, or one character's BVH.
    Either may carry the document's sentences with their commands (`story`): the service then places the
    captions and commands on frames itself (services.render.timeline), as `wana animate` and the gateway ask.
    Either may instead answer proto.common.ErrorReply (E010 invalid input, E009 handler failure).

In-process API: services.render.export.write_outputs (every output into a folder without the bus, and the
video's camera checks), services.render.camera_checks.camera_checks (the same checks without rendering),
services.render.staging.camera_track (every frame's camera), services.render.gallery.contact_sheet
(failing frames on one PNG),
services.render.renderer.FrameRenderer, services.render.gltf_export.scene_glb,
services.render.bvh_export.motion_bvh, services.render.video.encode_mp4 / join_chunks.
"""
