// camera.wgsl — the camera of frame_uniforms (declared by the module that binds it:
// render_bindings.wgsl or sky.wgsl): the viewing direction through a pixel and its inverse, in
// the frame's projection (PROJECTION_*): the pinhole, or a wide projection of the whole picture
// (equirectangular, fisheye), whose conventions are srt_scene::Projection's.

// The camera as view_direction uses it, from frame_uniforms or carried to a fragment shader in
// flat varyings (lrt.wgsl: llvmpipe reads a storage buffer in a fragment shader one lane at a
// time). For a wide projection forward, right and up are the observer's unit basis.
struct ViewCamera {
    // The pinhole's ray through the target's centre: the observer's forward, moved by the
    // window's offset where the target holds a window of a larger picture
    // (srt_gpu::projection::TargetCamera).
    forward: vec3<f32>,
    // The pinhole's: scaled by tan(fov/2)·aspect (and by the target's share of the picture's
    // width).
    right: vec3<f32>,
    // The pinhole's: scaled by tan(fov/2) (and by the target's share of the picture's height).
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
// centres at half-integers); mirrors srt_scene::ViewRays::ray's direction.
fn view_direction(pixel: vec2<f32>) -> vec3<f32> {
    return camera_view_direction(frame_camera(), pixel);
}

// Whether the picture holds a stereo pair (FrameUniforms.eye_separation ≥ 0).
fn is_stereo() -> bool {
    return frame_uniforms.eye_separation >= 0.0;
}

// Whether a pixel's ray follows from its place in the whole picture (a wide projection, a
// stereo pair) rather than from the window-offset pinhole of ViewCamera.
fn picture_decides() -> bool {
    return frame_uniforms.projection != PROJECTION_PERSPECTIVE || is_stereo();
}

// view_direction for `camera`; for a wide projection the unit direction, or 0 where the picture
// sees nothing (sees_nothing).
fn camera_view_direction(camera: ViewCamera, pixel: vec2<f32>) -> vec3<f32> {
    if (picture_decides()) {
        return eye_direction(camera, eye_point(picture_ndc(pixel)).ndc);
    }
    let ndc = vec2<f32>(
        2.0 * pixel.x * camera.inverse_size.x - 1.0,
        1.0 - 2.0 * pixel.y * camera.inverse_size.y,
    );
    return camera.forward + ndc.x * camera.right + ndc.y * camera.up;
}

// The direction through the point `ndc` of one eye's picture (the whole picture without
// stereo): the pinhole's through `camera` (whose axes are scaled for the eye's picture), or a
// wide projection's through its unit basis.
fn eye_direction(camera: ViewCamera, ndc: vec2<f32>) -> vec3<f32> {
    if (frame_uniforms.projection == PROJECTION_PERSPECTIVE) {
        return camera.forward + ndc.x * camera.right + ndc.y * camera.up;
    }
    return wide_direction(ndc, camera.forward, camera.right, camera.up);
}

// Which eye sees a point of the picture and where in its own picture (srt_scene::EyePoint):
// eye −1 (left) or +1 (right), 0 without stereo.
struct EyePoint {
    eye: f32,
    ndc: vec2<f32>,
}

// The eye seeing the point `ndc` of the whole picture and the point in its half; mirror of
// srt_scene::Stereo::eye_at (top-bottom for the equirectangular projection, side by side for
// the pinhole).
fn eye_point(ndc: vec2<f32>) -> EyePoint {
    if (!is_stereo()) {
        return EyePoint(0.0, ndc);
    }
    if (frame_uniforms.projection == PROJECTION_EQUIRECTANGULAR) {
        if (ndc.y > 0.0) {
            return EyePoint(-1.0, vec2<f32>(ndc.x, 2.0 * ndc.y - 1.0));
        }
        return EyePoint(1.0, vec2<f32>(ndc.x, 2.0 * ndc.y + 1.0));
    }
    if (ndc.x < 0.0) {
        return EyePoint(-1.0, vec2<f32>(2.0 * ndc.x + 1.0, ndc.y));
    }
    return EyePoint(1.0, vec2<f32>(2.0 * ndc.x - 1.0, ndc.y));
}

// The offset (in S) from the observer of the eye whose ray leaves through the framebuffer
// position `pixel`: 0 without stereo; mirror of srt_scene::Stereo::eye_offset.
fn eye_offset(pixel: vec2<f32>) -> vec3<f32> {
    if (!is_stereo()) {
        return vec3<f32>(0.0);
    }
    let point = eye_point(picture_ndc(pixel));
    let half = 0.5 * frame_uniforms.eye_separation * point.eye;
    let right = normalize(frame_uniforms.camera_right.xyz);
    if (frame_uniforms.projection != PROJECTION_EQUIRECTANGULAR) {
        return half * right;
    }
    let longitude = PI * point.ndc.x;
    return half * (cos(longitude) * right - sin(longitude) * frame_uniforms.camera_forward.xyz);
}

// The viewing direction through the framebuffer position `step` beyond `pixel`, from the same
// eye, or 0 where the picture sees nothing there; mirror of srt_scene::ViewRays::neighbour.
fn neighbour_view_direction(pixel: vec2<f32>, step: vec2<f32>) -> vec3<f32> {
    if (!is_stereo()) {
        if (sees_nothing(pixel + step)) {
            return vec3<f32>(0.0);
        }
        return view_direction(pixel + step);
    }
    let point = eye_point(picture_ndc(pixel));
    // Each half is stretched over [−1, 1] along the axis the halves share.
    var stretch = vec2<f32>(2.0, 1.0);
    if (frame_uniforms.projection == PROJECTION_EQUIRECTANGULAR) {
        stretch = vec2<f32>(1.0, 2.0);
    }
    let ndc_step = vec2<f32>(2.0 * step.x / frame_uniforms.picture.x, -2.0 * step.y / frame_uniforms.picture.y);
    return eye_direction(frame_camera(), point.ndc + ndc_step * stretch);
}

// Pixel position (x right, y down, pixel centres at half-integers) of the direction `d` in S in
// xy; z = 1 in front of the camera, 0 behind (outside a fisheye's field). The inverse of
// view_direction for one picture (`eye` 0) or the eye −1 (left) or +1 (right) of a stereo pair;
// mirror of srt_trace::project.
fn project_direction(d: vec3<f32>, eye: f32) -> vec3<f32> {
    let forward = frame_uniforms.camera_forward.xyz;
    let right = frame_uniforms.camera_right.xyz;
    let up = frame_uniforms.camera_up.xyz;
    var ndc: vec3<f32>;
    if (frame_uniforms.projection != PROJECTION_PERSPECTIVE) {
        ndc = wide_ndc(d, forward, right, up);
    } else {
        let depth = dot(d, forward);
        if (depth <= 0.0) {
            return vec3<f32>(0.0);
        }
        // camera_right and camera_up are scaled by tan(fov/2)·aspect and tan(fov/2) (times the
        // target's share of the picture, or for an eye of a stereo pair its half's aspect);
        // their w, the target's centre, is 0 for a whole picture.
        let offset = vec2<f32>(frame_uniforms.camera_right.w, frame_uniforms.camera_up.w);
        ndc = vec3<f32>(vec2<f32>(dot(d, right) / (depth * dot(right, right)), dot(d, up) / (depth * dot(up, up))) - offset, 1.0);
        if (!is_stereo()) {
            return vec3<f32>(
                0.5 * (ndc.x + 1.0) * frame_uniforms.viewport.x,
                0.5 * (1.0 - ndc.y) * frame_uniforms.viewport.y,
                1.0,
            );
        }
    }
    if (ndc.z == 0.0) {
        return vec3<f32>(0.0);
    }
    var point = ndc.xy;
    if (is_stereo()) {
        // srt_scene::Stereo::picture_point.
        if (frame_uniforms.projection == PROJECTION_EQUIRECTANGULAR) {
            point = vec2<f32>(point.x, 0.5 * (point.y - eye));
        } else {
            point = vec2<f32>(0.5 * (point.x + eye), point.y);
        }
    }
    let picture = frame_uniforms.picture;
    return vec3<f32>(
        0.5 * (point.x + 1.0) * picture.x - picture.z,
        0.5 * (1.0 - point.y) * picture.y - picture.w,
        1.0,
    );
}

// The target pixels (min x, min y, max x, max y) of the picture seen by `eye` (0: the whole
// picture; −1, +1: that eye's half of a stereo pair), where a star's splat may land.
fn eye_bounds(eye: f32) -> vec4<f32> {
    let picture = frame_uniforms.picture;
    var bounds = vec4<f32>(0.0, 0.0, picture.x, picture.y);
    if (eye != 0.0) {
        let first = eye < 0.0;
        if (frame_uniforms.projection == PROJECTION_EQUIRECTANGULAR) {
            bounds = select(vec4<f32>(0.0, 0.5 * picture.y, picture.x, picture.y), vec4<f32>(0.0, 0.0, picture.x, 0.5 * picture.y), first);
        } else {
            bounds = select(vec4<f32>(0.5 * picture.x, 0.0, picture.x, picture.y), vec4<f32>(0.0, 0.0, 0.5 * picture.x, picture.y), first);
        }
    }
    return bounds - vec4<f32>(picture.zw, picture.zw);
}

// The point of the whole picture (normalised device coordinates, x right, y up) at the target's
// framebuffer position `pixel`: the target is the picture's window from
// (frame_uniforms.picture.zw) on, in a picture of frame_uniforms.picture.xy pixels.
fn picture_ndc(pixel: vec2<f32>) -> vec2<f32> {
    let p = pixel + frame_uniforms.picture.zw;
    return vec2<f32>(2.0 * p.x / frame_uniforms.picture.x - 1.0, 1.0 - 2.0 * p.y / frame_uniforms.picture.y);
}

// Whether the picture sees nothing at the framebuffer position `pixel` (outside a fisheye's
// circle): the background there, and no object.
fn sees_nothing(pixel: vec2<f32>) -> bool {
    return frame_uniforms.projection == PROJECTION_FISHEYE && length(picture_ndc(pixel)) > 1.0;
}

// The unit direction through the point `ndc` of a wide projection for the unit basis (forward,
// right, up), or 0 outside a fisheye's circle; mirror of srt_scene::Projection::wide_direction.
fn wide_direction(ndc: vec2<f32>, forward: vec3<f32>, right: vec3<f32>, up: vec3<f32>) -> vec3<f32> {
    if (frame_uniforms.projection == PROJECTION_EQUIRECTANGULAR) {
        let longitude = PI * ndc.x;
        let latitude = 0.5 * PI * ndc.y;
        let horizontal = cos(longitude) * forward + sin(longitude) * right;
        return cos(latitude) * horizontal + sin(latitude) * up;
    }
    let rho = length(ndc);
    if (rho > 1.0) {
        return vec3<f32>(0.0);
    }
    let angle = rho * frame_uniforms.fisheye_half_fov;
    var across = vec3<f32>(0.0);
    if (rho > 0.0) {
        across = (ndc.x * right + ndc.y * up) / rho;
    }
    return cos(angle) * forward + sin(angle) * across;
}

// The point (xy, normalised device coordinates of one picture) of a wide projection where `d`
// is seen, z = 1, or z = 0 outside a fisheye's field; mirror of
// srt_scene::Projection::wide_image_point. Angles come from atan2 alone: llvmpipe's asin and
// acos are far less precise (a star's tent weights moved by a few hundredths of a pixel with
// asin).
fn wide_ndc(d: vec3<f32>, forward: vec3<f32>, right: vec3<f32>, up: vec3<f32>) -> vec3<f32> {
    let unit = normalize(d);
    let along = dot(unit, forward);
    let across = dot(unit, right);
    let above = dot(unit, up);
    if (frame_uniforms.projection == PROJECTION_EQUIRECTANGULAR) {
        return vec3<f32>(atan2(across, along) / PI, atan2(above, length(vec2<f32>(along, across))) / (0.5 * PI), 1.0);
    }
    let sideways = vec2<f32>(across, above);
    let rho = atan2(length(sideways), along) / frame_uniforms.fisheye_half_fov;
    if (rho > 1.0) {
        return vec3<f32>(0.0);
    }
    var azimuth = vec2<f32>(1.0, 0.0);
    if (dot(sideways, sideways) > 0.0) {
        azimuth = normalize(sideways);
    }
    return vec3<f32>(rho * azimuth, 1.0);
}
