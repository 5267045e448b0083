//! WGSL sources, composed from the shared modules in `shaders/` (WGSL has no includes).

/// Shared physics (mirror of srt-physics).
pub const PHYSICS: &str = include_str!("../../../shaders/physics.wgsl");
/// Shared data layouts (twins of [`crate::types`]).
pub const TYPES: &str = include_str!("../../../shaders/types.wgsl");
/// Kernel probes (see [`crate::probe`]); composed after [`PHYSICS`] and [`COLOUR`].
pub const PROBE: &str = include_str!("../../../shaders/probe.wgsl");

/// Colour-table sampling (mirror of `TemperatureLut::sample`).
pub const COLOUR: &str = include_str!("../../../shaders/colour.wgsl");
/// Bindings and helpers shared by the render passes.
pub const RENDER_BINDINGS: &str = include_str!("../../../shaders/render_bindings.wgsl");
/// Intersection and shading (mirror of srt-trace).
pub const SURFACE: &str = include_str!("../../../shaders/surface.wgsl");
/// The footprint compute pass (mirror of srt-proxy).
pub const PROXY: &str = include_str!("../../../shaders/proxy.wgsl");
/// The local ray tracing pass.
pub const LRT: &str = include_str!("../../../shaders/lrt.wgsl");
/// The polygon-rendering baseline pass.
pub const POLYGON: &str = include_str!("../../../shaders/polygon.wgsl");

/// The footprint compute shader.
#[must_use]
pub fn proxy() -> String {
    compose(&[
        ("physics.wgsl", PHYSICS),
        ("types.wgsl", TYPES),
        ("render_bindings.wgsl", RENDER_BINDINGS),
        ("proxy.wgsl", PROXY),
    ])
}

/// The local ray tracing shader.
#[must_use]
pub fn lrt() -> String {
    compose(&[
        ("physics.wgsl", PHYSICS),
        ("types.wgsl", TYPES),
        ("colour.wgsl", COLOUR),
        ("render_bindings.wgsl", RENDER_BINDINGS),
        ("surface.wgsl", SURFACE),
        ("lrt.wgsl", LRT),
    ])
}

/// The polygon-rendering shader.
#[must_use]
pub fn polygon() -> String {
    compose(&[
        ("physics.wgsl", PHYSICS),
        ("types.wgsl", TYPES),
        ("colour.wgsl", COLOUR),
        ("render_bindings.wgsl", RENDER_BINDINGS),
        ("surface.wgsl", SURFACE),
        ("polygon.wgsl", POLYGON),
    ])
}

/// Composes `modules` into one WGSL source, each preceded by a comment naming it.
#[must_use]
pub fn compose(modules: &[(&str, &str)]) -> String {
    modules
        .iter()
        .map(|(name, source)| format!("// ---- {name}\n{source}\n"))
        .collect()
}

/// Every complete shader srt builds, by name, for validation.
#[must_use]
pub fn all() -> Vec<(&'static str, String)> {
    vec![
        (
            "physics+types",
            compose(&[("physics.wgsl", PHYSICS), ("types.wgsl", TYPES)]),
        ),
        ("proxy", proxy()),
        ("lrt", lrt()),
        ("polygon", polygon()),
        ("colour", compose(&[("colour.wgsl", COLOUR)])),
        ("probe", crate::probe::source()),
    ]
}
