//! [`GpuError`], why the GPU could not do what was asked: a leaf module, so that every other
//! module can return it without depending on the device code in [`crate::context`].

/// Why the GPU could not be used.
#[derive(Debug, Clone, thiserror::Error)]
pub enum GpuError {
    /// No adapter at all (no GPU driver, no software rasteriser).
    #[error(
        "no GPU adapter found (install Mesa's lavapipe with `apt-get install mesa-vulkan-drivers`, or use the CPU backend)"
    )]
    NoAdapter,
    /// The adapter refused to create a device.
    #[error("the GPU adapter {adapter} could not open a device: {reason}")]
    Device {
        /// Adapter name.
        adapter: String,
        /// wgpu's message.
        reason: String,
    },
    /// wgpu reported a validation or out-of-memory error.
    #[error("GPU error: {0}")]
    Wgpu(String),
    /// Waiting for the GPU or mapping a buffer failed.
    #[error("GPU readback failed: {0}")]
    Readback(String),
    /// A request exceeds one of the adapter's limits; nothing was allocated. Callers may match
    /// it (`GpuError::ExceedsLimit { .. }`) to fall back to the CPU.
    #[error(
        "{what} is {requested} {unit}, but this adapter ({adapter}) allows at most {limit} ({limit_name})"
    )]
    ExceedsLimit {
        /// What was asked for, e.g. "the width of the 32768 × 4 render target".
        what: String,
        /// The amount requested.
        requested: u64,
        /// The unit of `requested` and `limit`: "pixels", "bytes", "workgroups"…
        unit: &'static str,
        /// The adapter's limit.
        limit: u64,
        /// The name of the limit, as wgpu's `Limits` field or another source names it.
        limit_name: &'static str,
        /// The adapter's name.
        adapter: String,
    },
    /// A batch's BVH is deeper than the GPU ray tracer's traversal stack allows
    /// ([`crate::types::BVH_STACK_SIZE`]); the other methods can still render the scene.
    #[error(
        "the BVH of {what} is {depth} levels deep, but the GPU ray tracer walks at most {limit}; use --method lrt"
    )]
    BvhTooDeep {
        /// The batch, e.g. "parts 0, 1 of object \"engine\"".
        what: String,
        /// Edges on the longest root-to-leaf path.
        depth: usize,
        /// The deepest the traversal supports.
        limit: usize,
    },
    /// The scene's objects or parts changed since it was uploaded, or it gained moving lights
    /// ([`crate::GpuRenderer`] renders only the structure it uploaded).
    #[error("the scene's objects or lights changed since it was uploaded")]
    SceneChanged,
    /// Something was asked of a renderer or view before it had what it needs.
    #[error("{0}")]
    NotReady(&'static str),
    /// The chosen method cannot draw something in the scene (the late shadows a spinning or
    /// thrusting body casts; [`crate::Method::cannot_draw`]); the CPU reference can.
    #[error("{0}")]
    Unsupported(String),
}
