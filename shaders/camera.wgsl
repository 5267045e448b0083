// camera.wgsl — the pinhole camera of frame_uniforms (declared by the module that binds it:
// render_bindings.wgsl or sky.wgsl): the viewing direction through a pixel and its inverse.

// The pinhole camera as view_direction uses it, from frame_uniforms or carried to a fragment
// shader in flat varyings (lrt.wgsl: llvmpipe reads a storage buffer in a fragment shader one
// lane at a time).
struct ViewCamera {
    // Through the target's centre: the observer's forward, moved by the window's offset where
    // the target holds a window of a larger picture (srt_gpu::projection::TargetCamera).
    forward: vec3<f32>,
    // Scaled by tan(fov/2)·aspect (and by the target's share of the picture's width).
    right: vec3<f32>,
    // Scaled by tan(fov/2) (and by the target's share of the picture's height).
    up: vec3<f32>,
    // 1/width and 1/height in pixels⁻¹ (frame_uniforms.viewport.zw).
    inverse_size: vec2<f32>,
}

// The frame's camera. camera_right.w and camera_up.w are the target's centre in the picture in
// units of those axes: 0 for a whole picture, so that forward is then exactly camera_forward.
fn frame_camera() -> ViewCamera {
    let right = frame_uniforms.camera_right;
    let up = frame_uniforms.camera_up;
    return ViewCamera(
        frame_uniforms.camera_forward.xyz + right.w * right.xyz + up.w * up.xyz,
        frame_uniforms.camera_right.xyz,
        frame_uniforms.camera_up.xyz,
        frame_uniforms.viewport.zw,
    );
}

// Viewing direction in S through the framebuffer position `pixel` (x right, y down, pixel
// centres at half-integers); mirrors srt_scene::Observer::view_direction.
fn view_direction(pixel: vec2<f32>) -> vec3<f32> {
    return camera_view_direction(frame_camera(), pixel);
}

// view_direction for `camera`.
fn camera_view_direction(camera: ViewCamera, pixel: vec2<f32>) -> vec3<f32> {
    let ndc = vec2<f32>(
        2.0 * pixel.x * camera.inverse_size.x - 1.0,
        1.0 - 2.0 * pixel.y * camera.inverse_size.y,
    );
    return camera.forward + ndc.x * camera.right + ndc.y * camera.up;
}

// Pixel position (x right, y down, pixel centres at half-integers) of the direction `d` in S in
// xy; z = 1 in front of the camera, 0 behind. The inverse of view_direction; mirror of
// srt_trace::project.
fn project_direction(d: vec3<f32>) -> vec3<f32> {
    let forward = frame_uniforms.camera_forward.xyz;
    let right = frame_uniforms.camera_right.xyz;
    let up = frame_uniforms.camera_up.xyz;
    let depth = dot(d, forward);
    if (depth <= 0.0) {
        return vec3<f32>(0.0);
    }
    // camera_right and camera_up are scaled by tan(fov/2)·aspect and tan(fov/2) (times the
    // target's share of the picture); their w, the target's centre, is 0 for a whole picture.
    let offset = vec2<f32>(frame_uniforms.camera_right.w, frame_uniforms.camera_up.w);
    let ndc = vec2<f32>(dot(d, right) / (depth * dot(right, right)), dot(d, up) / (depth * dot(up, up))) - offset;
    return vec3<f32>(
        0.5 * (ndc.x + 1.0) * frame_uniforms.viewport.x,
        0.5 * (1.0 - ndc.y) * frame_uniforms.viewport.y,
        1.0,
    );
}
