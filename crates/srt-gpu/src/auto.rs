//! How [`Method::Auto`](crate::Method::Auto) chooses, per object and per frame, between the two
//! exact methods that draw a static object: local ray tracing (LRT, one footprint per
//! triangle) and the BVH ray tracer (RT, one traced ray per fragment of the object's box).
//! Either is exact per pixel; the choice decides speed only.
//!
//! What the frame knows of an object before it is drawn is its [`ObjectLoad`]: its triangles,
//! the layers of them a line of sight through its box crosses, the layers of box footprints the
//! ray tracer would draw, and about how many pixels its bounding ball's image covers.
//! [`MethodCosts`] turns a load into each method's expected work on one kind of adapter, in
//! units of one triangle's LRT work (proxy pass and footprint draw), and the object goes to
//! the cheaper:
//!
//! - LRT: `triangles + per_layer_pixel × layers × seen_pixels` (its footprints' fragments
//!   grow with the layers over the pixels seen);
//! - RT: `per_traced_pixel × box_layers × seen_pixels + per_traced_object` (one walk of the BVH
//!   per fragment of the box's footprints, whatever the layers; the box's own passes).
//!
//! The constants of each adapter kind were fitted to the bench's recorded lines, on which the
//! rule then expects the faster method (within 5 %) on all but one: the H200's 83 lines with a
//! choice to make (docs/measurements/2026-11-27-h200) for a hardware GPU and lavapipe's 76 for
//! a CPU adapter, all but teaser@ct=−16.36, where RT was 5.5 % faster (the files with the
//! loads, `fit.py` and how well each constant is pinned are in
//! docs/measurements/2026-11-29-auto; llvmpipe through OpenGL, measured afterwards, agrees on
//! 57 of its 58). `cargo xtask bench` records every line's loads, and the replay test in xtask
//! (`bench::replay`) holds the rule to the committed lines.

/// What `auto` weighs of one object in one frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectLoad {
    /// Its triangles (LRT runs the proxy pass and draws a footprint for each).
    pub triangles: u64,
    /// Its surface over its box's: the layers of triangles an average line of sight through
    /// the box crosses (LRT's fragments per pixel grow with them; a traced ray's do not).
    pub layers: f64,
    /// How many layers of its box's footprints the ray tracer would draw this frame: 1 with
    /// the observer outside the box (its near faces culled), 2 from inside.
    pub box_layers: u32,
    /// About how many pixels its bounding ball's image covers in this frame
    /// ([`crate::culling::ball_seen_pixels`]).
    pub seen_pixels: f64,
}

/// The two exact methods' costs on one kind of adapter, in units of one triangle's LRT work.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MethodCosts {
    /// LRT's cost per layer of triangles per seen pixel (its footprints' fragments).
    pub per_layer_pixel: f64,
    /// RT's cost per seen pixel per layer of box footprints (a BVH walk each).
    pub per_traced_pixel: f64,
    /// RT's cost per object (its box's proxy, visibility and shading passes).
    pub per_traced_object: f64,
}

/// [`MethodCosts`] of a CPU adapter (Mesa's lavapipe and llvmpipe), fitted to lavapipe's 76
/// bench lines with a choice of 2026-11-29 (two cores): its per-triangle work (proxy pass,
/// footprint set-up and binning) is dear, and a fragment of a footprint costs about half a
/// traced one, so an object is traced where its triangles lie in more than 2 layers or are
/// many per pixel (the 1.9 M-triangle cube at 1280×720 but not at 1920×1080), or when few of
/// its pixels are seen (an engine passing beside the camera).
pub const CPU_ADAPTER_COSTS: MethodCosts = MethodCosts {
    per_layer_pixel: 5.3,
    per_traced_pixel: 10.5,
    per_traced_object: 450.0,
};

/// [`MethodCosts`] of a hardware GPU, fitted to the 83 lines with a choice an NVIDIA H200
/// recorded on 2026-11-27 (single frames by GPU timestamps, LRT with the flat varyings of the time): a
/// fragment costs little either way, so the choice turns on triangles per seen pixel, one to
/// about 17 pixels or more tracing (the 2CylinderEngine traced at 1920×1080, drawn by LRT at
/// 3840×2160). The lean varyings now used there ([`crate::pipelines::Varyings::Lean`]) have
/// not run in the bench on hardware: the throughput runs suggest they move the line towards
/// LRT (docs/performance.md, "How `auto` chooses").
pub const HARDWARE_COSTS: MethodCosts = MethodCosts {
    per_layer_pixel: 0.008,
    per_traced_pixel: 0.08,
    per_traced_object: 340.0,
};

impl MethodCosts {
    /// The costs of an adapter of `device_type`: [`CPU_ADAPTER_COSTS`] for a CPU adapter,
    /// [`HARDWARE_COSTS`] for any other.
    #[must_use]
    pub fn for_adapter(device_type: wgpu::DeviceType) -> Self {
        if device_type == wgpu::DeviceType::Cpu {
            CPU_ADAPTER_COSTS
        } else {
            HARDWARE_COSTS
        }
    }

    /// LRT's expected work on `load`.
    #[must_use]
    pub fn lrt(&self, load: &ObjectLoad) -> f64 {
        load.triangles as f64 + self.per_layer_pixel * load.layers * load.seen_pixels
    }

    /// The ray tracer's expected work on `load`.
    #[must_use]
    pub fn rt(&self, load: &ObjectLoad) -> f64 {
        self.per_traced_pixel * f64::from(load.box_layers) * load.seen_pixels
            + self.per_traced_object
    }

    /// Whether `auto` traces the object of `load`: the ray tracer expected cheaper (a tie
    /// goes to LRT, the paper's method).
    #[must_use]
    pub fn traces(&self, load: &ObjectLoad) -> bool {
        self.rt(load) < self.lrt(load)
    }

    /// Whether no seen pixels can make the ray tracer cheaper for an object of `triangles`
    /// in `layers` layers: then `auto` draws it by LRT without measuring its image.
    #[must_use]
    pub fn lrt_whatever_seen(&self, triangles: u64, layers: f64) -> bool {
        triangles as f64 <= self.per_traced_object
            && self.per_layer_pixel * layers <= self.per_traced_pixel
    }
}

#[cfg(test)]
mod tests {
    use super::{CPU_ADAPTER_COSTS, HARDWARE_COSTS, MethodCosts, ObjectLoad};

    /// The 2CylinderEngine (121 496 triangles, 2.80 layers) seen over the whole picture.
    fn engine(pixels: f64, box_layers: u32) -> ObjectLoad {
        ObjectLoad {
            triangles: 121_496,
            layers: 2.8,
            box_layers,
            seen_pixels: pixels,
        }
    }

    /// The rule's shape: deep models traced on a CPU adapter, shallow ones drawn by LRT; on a
    /// hardware GPU the engine traced at 1920×1080 and drawn by LRT at 3840×2160; an object
    /// out of sight but not culled traced (its triangles cost LRT, its box almost nothing);
    /// from inside the box the ray tracer is dearer.
    #[test]
    fn the_rule_traces_deep_models_and_draws_shallow_ones() {
        let cube = |pixels| ObjectLoad {
            triangles: 1200,
            layers: 1.0,
            box_layers: 1,
            seen_pixels: pixels,
        };
        assert!(CPU_ADAPTER_COSTS.traces(&engine(1280.0 * 720.0, 1)));
        assert!(!CPU_ADAPTER_COSTS.traces(&cube(258_300.0)));
        assert!(HARDWARE_COSTS.traces(&engine(1920.0 * 1080.0, 1)));
        assert!(!HARDWARE_COSTS.traces(&engine(3840.0 * 2160.0, 1)));
        assert!(!HARDWARE_COSTS.traces(&cube(581_175.0)));
        for costs in [CPU_ADAPTER_COSTS, HARDWARE_COSTS] {
            assert!(costs.traces(&engine(0.0, 1)));
            assert!(costs.rt(&engine(1e6, 2)) > costs.rt(&engine(1e6, 1)));
        }
        let device = MethodCosts::for_adapter(wgpu::DeviceType::Cpu);
        assert_eq!(device, CPU_ADAPTER_COSTS);
        assert_eq!(
            MethodCosts::for_adapter(wgpu::DeviceType::DiscreteGpu),
            HARDWARE_COSTS
        );
    }

    /// The shortcut never sends to LRT an object the full rule would trace, over a spread of
    /// loads.
    #[test]
    fn the_shortcut_agrees_with_the_rule() {
        for costs in [CPU_ADAPTER_COSTS, HARDWARE_COSTS] {
            for triangles in [1, 12, 300, 340, 450, 451, 10_000, 2_000_000] {
                for layers in [0.1, 1.0, 1.9, 2.0, 2.1, 10.0, 11.0] {
                    if !costs.lrt_whatever_seen(triangles, layers) {
                        continue;
                    }
                    for box_layers in [1, 2] {
                        for pixels in [0.0, 1.0, 1e3, 1e5, 1e7] {
                            let load = ObjectLoad {
                                triangles,
                                layers,
                                box_layers,
                                seen_pixels: pixels,
                            };
                            assert!(!costs.traces(&load), "{load:?}");
                        }
                    }
                }
            }
        }
    }
}
