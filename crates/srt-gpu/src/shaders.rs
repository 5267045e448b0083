//! WGSL sources, composed from the shared modules in `shaders/` (WGSL has no includes), and the
//! values of their pipeline-overridable constants (WGSL `override`s without a default: the
//! value lives here, in Rust, and the pipeline cannot be created without it).

use crate::motion::MotionCode;
use crate::types::SurfaceColourCode;

/// Shared physics (mirror of srt-physics).
pub const PHYSICS: &str = include_str!("../shaders/physics.wgsl");
/// Shared data layouts (twins of [`crate::types`]).
pub const TYPES: &str = include_str!("../shaders/types.wgsl");
/// Kernel probes (see the `probe` module (feature `probe`)).
pub const PROBE: &str = include_str!("../shaders/probe.wgsl");
/// Colour-table sampling (mirror of `TemperatureLut::sample`).
pub const COLOUR: &str = include_str!("../shaders/colour.wgsl");
/// Spectral surface colour (mirror of srt-color's spectral path).
pub const SPECTRAL: &str = include_str!("../shaders/spectral.wgsl");
/// The light a pass draws and what it writes for it (mirror of srt-trace's `Arriving`).
pub const LIGHT: &str = include_str!("../shaders/light.wgsl");
/// Bindings and helpers shared by the render passes.
pub const RENDER_BINDINGS: &str = include_str!("../shaders/render_bindings.wgsl");
/// The clock face (mirror of srt-trace's `clock`).
pub const CLOCK: &str = include_str!("../shaders/clock.wgsl");
/// The one watertight ray–triangle test of every pass that meets triangles (mirror of
/// `srt_trace::intersect_triangle`).
pub const TRIANGLE: &str = include_str!("../shaders/triangle.wgsl");
/// Shading (mirror of srt-trace).
pub const SURFACE: &str = include_str!("../shaders/surface.wgsl");
/// The footprint compute pass (mirror of srt-proxy).
pub const PROXY: &str = include_str!("../shaders/proxy.wgsl");
/// The local ray tracing pass.
pub const LRT: &str = include_str!("../shaders/lrt.wgsl");
/// Spinning and thrusting bodies: their body-space curves and local rest frames (mirror of
/// srt-trace's `moving`).
pub const MOTION: &str = include_str!("../shaders/motion.wgsl");
/// The GPU ray tracer's visibility pass (composed after [`LRT`]).
pub const RT: &str = include_str!("../shaders/rt.wgsl");
/// The slab test of BVH traversal (the ray tracer's and the shadows').
pub const BVH: &str = include_str!("../shaders/bvh.wgsl");
/// Moving lights and their late shadows (mirror of `srt_physics::RetardedLight` and srt-trace's
/// shadow test).
pub const SHADOWS: &str = include_str!("../shaders/shadows.wgsl");
/// The polygon-rendering baseline pass.
pub const POLYGON: &str = include_str!("../shaders/polygon.wgsl");
/// The image-based method's cube-map faces and look-up (Table 1's "IB").
pub const IMAGE_BASED: &str = include_str!("../shaders/image_based.wgsl");
/// The stars and the image of the sky.
pub const SKY: &str = include_str!("../shaders/sky.wgsl");
/// The pinhole camera: viewing directions through pixels and back.
pub const CAMERA: &str = include_str!("../shaders/camera.wgsl");

/// Showing a frame: display colours into an 8-bit target (the `display` module draws it).
pub const DISPLAY: &str = include_str!("../shaders/display.wgsl");

/// Invocations per workgroup of every compute entry point (WGSL `override WORKGROUP_SIZE`).
pub const WORKGROUP_SIZE: u32 = 64;

/// The overrides of the proxy shader.
const PROXY_OVERRIDES: &[Override] = &[
    ("WORKGROUP_SIZE", WORKGROUP_SIZE as f64),
    ("MAX_TANGENT_REACH", srt_proxy::MAX_TANGENT_REACH),
    ("MAX_SCREEN_REACH", srt_proxy::MAX_SCREEN_REACH),
    ("SPLIT_AREA_FRACTION", srt_proxy::SPLIT_AREA_FRACTION),
    ("LOOSE_HULL_FACTOR", srt_proxy::LOOSE_HULL_FACTOR),
    ("NEAR_CLIP_FRACTION", srt_proxy::NEAR_CLIP_FRACTION),
];

/// One pipeline-overridable constant: its WGSL name and the value Rust gives it.
type Override = (&'static str, f64);

/// `first` then `second` as one array of `N` = `A` + `B` overrides (checked at compile time).
const fn joined<const A: usize, const B: usize, const N: usize>(
    first: [Override; A],
    second: [Override; B],
) -> [Override; N] {
    assert!(A + B == N, "joined: N must be A + B");
    let mut all = [("", 0.0); N];
    let mut i = 0;
    while i < A {
        all[i] = first[i];
        i += 1;
    }
    while i < N {
        all[i] = second[i - A];
        i += 1;
    }
    all
}

/// The overrides of spectral.wgsl: the constants of Planck's law (Eq. 10: c₂ = hc/k and 2hc²;
/// Wien's x_max), the CIE table's step (Eq. 11) and the band edges of the reflectance policy.
const SPECTRAL_OVERRIDES: [Override; 6] = [
    (
        "SECOND_RADIATION_CONSTANT",
        srt_color::SECOND_RADIATION_CONSTANT,
    ),
    (
        "RADIANCE_CONSTANT",
        2.0 * srt_color::PLANCK_CONSTANT * srt_color::SPEED_OF_LIGHT * srt_color::SPEED_OF_LIGHT,
    ),
    ("WIEN_X", srt_color::WIEN_X),
    ("CIE_1931_STEP_M", srt_color::CIE_1931_STEP_M),
    (
        "ULTRAVIOLET_BELOW_NM",
        srt_color::spectral::ULTRAVIOLET_BELOW_NM,
    ),
    ("INFRARED_ABOVE_NM", srt_color::spectral::INFRARED_ABOVE_NM),
];

/// The relative margin of the shadow test (WGSL override `SHADOW_MARGIN`): a triangle blocks the
/// segment from the surface event to the light's retarded event (in its object's rest frame)
/// only where it crosses it more than `SHADOW_MARGIN · (1 + length + max|from|)` from either
/// end. The CPU takes 10⁻⁹ (f64); in f32 the surface point itself is known to a few ulps of
/// its coordinates (about 10⁻⁶ relative), and a segment leaving the surface at an angle θ meets
/// its own face that far over sin θ from its start: 10⁻⁴ keeps points from shadowing themselves
/// down to grazing angles of about 10⁻², where the light is dim anyway, and misses a blocker only
/// within 10⁻⁴ of the scene's size of the lit point (far below a pixel in srt's scenes).
pub const SHADOW_MARGIN: f32 = 1e-4;

/// The overrides of the shadow test (shadows.wgsl) and its slab test (bvh.wgsl), with the
/// moving lights compiled in (1) or out (0), `MOVING_LIGHTS`, and their shadow test likewise,
/// `MOVING_LIGHT_SHADOWS`.
const fn shadow_overrides(moving_lights: f64, shadows: f64) -> [Override; 4] {
    [
        ("SLAB_TOLERANCE", crate::bvh::SLAB_TOLERANCE as f64),
        ("SHADOW_MARGIN", SHADOW_MARGIN as f64),
        ("MOVING_LIGHTS", moving_lights),
        ("MOVING_LIGHT_SHADOWS", shadows),
    ]
}

/// What a shader of the object passes (LRT, the ray tracer's visibility, polygon) is compiled
/// for: the choices that are fixed for a whole draw or frame. Each is a pipeline override, not a
/// run-time branch, because a software rasteriser (Mesa's llvmpipe) runs every side of a branch
/// its pixels do not all take, so code for a case the draw does not have costs as much as code
/// it runs (docs/ARCHITECTURE.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ObjectVariant {
    /// Every visibility fragment and every shaded pixel adds 1 to the fragment counter (for
    /// measurements only: one global atomic per fragment; `COUNT_FRAGMENTS`).
    pub counting: bool,
    /// The shading passes add the light of moving lights and their shadows (shadows.wgsl;
    /// `MOVING_LIGHTS`).
    pub lit: bool,
    /// The moving lights' light is tested for late shadows (shadows.wgsl's
    /// `MOVING_LIGHT_SHADOWS`): off where the frame has no shadow casters, whose test would
    /// otherwise still run once per light, masked.
    pub shadowed: bool,
    /// How the objects drawn move in their rest frame (motion.wgsl's `MOTION_VARIANT`).
    pub motion: MotionCode,
    /// How lit surfaces are coloured (surface.wgsl's `SURFACE_COLOUR_VARIANT`).
    pub colour: SurfaceColourCode,
    /// Whether the part drawn may have a texture (surface.wgsl's `TEXTURED_VARIANT`).
    pub textured: bool,
    /// Whether the object drawn may wear a clock face (surface.wgsl's `CLOCK_VARIANT`).
    pub clock: bool,
    /// Whether the object drawn may be a wireframe (surface.wgsl's `WIREFRAME_VARIANT`).
    pub wireframe: bool,
    /// Whether the frame may write seen events instead of colour (surface.wgsl's
    /// `SEEN_VARIANT`).
    pub seen: bool,
}

impl ObjectVariant {
    /// The variant of the ordinary frame: no counting, no moving lights, bodies at rest, the
    /// paper's colour, no texture, no clock, no wireframe, colour written.
    pub const PLAIN: Self = Self {
        counting: false,
        lit: false,
        shadowed: false,
        motion: MotionCode::REST,
        colour: SurfaceColourCode::PAPER,
        textured: false,
        clock: false,
        wireframe: false,
        seen: false,
    };

    /// How many on/off switches a variant has.
    const SWITCHES: usize = 7;

    /// How many variants there are: the range of [`ObjectVariant::index`].
    pub const COUNT: usize =
        MotionCode::ALL.len() * SurfaceColourCode::ALL.len() * (1 << Self::SWITCHES);

    /// The variant's on/off switches, in the order of [`ObjectVariant::index`].
    fn switches(self) -> [bool; Self::SWITCHES] {
        [
            self.counting,
            self.lit,
            self.shadowed,
            self.textured,
            self.clock,
            self.wireframe,
            self.seen,
        ]
    }

    /// The variant of `motion`, `colour` and the `switches` as [`ObjectVariant::switches`]
    /// lists them.
    fn with_switches(
        motion: MotionCode,
        colour: SurfaceColourCode,
        [counting, lit, shadowed, textured, clock, wireframe, seen]: [bool; Self::SWITCHES],
    ) -> Self {
        Self {
            counting,
            lit,
            shadowed,
            motion,
            colour,
            textured,
            clock,
            wireframe,
            seen,
        }
    }

    /// Every variant, in the order of [`ObjectVariant::index`].
    #[must_use]
    pub fn all() -> Vec<Self> {
        let mut all = Vec::with_capacity(Self::COUNT);
        for motion in MotionCode::ALL {
            for colour in SurfaceColourCode::ALL {
                for bits in 0..1_usize << Self::SWITCHES {
                    let switches =
                        std::array::from_fn(|i| (bits >> (Self::SWITCHES - 1 - i)) & 1 == 1);
                    all.push(Self::with_switches(motion, colour, switches));
                }
            }
        }
        all
    }

    /// Variants that between them compile every piece of the object passes' code, and leave
    /// each out: for each kind of motion and colour, every switch off, every switch on, and
    /// each switch on alone. What tests parse and check instead of all
    /// [`ObjectVariant::COUNT`].
    #[must_use]
    pub fn covering() -> Vec<Self> {
        let mut covering = Vec::new();
        for motion in MotionCode::ALL {
            for colour in SurfaceColourCode::ALL {
                covering.push(Self::with_switches(motion, colour, [false; Self::SWITCHES]));
                covering.push(Self::with_switches(motion, colour, [true; Self::SWITCHES]));
                for on in 0..Self::SWITCHES {
                    let switches = std::array::from_fn(|i| i == on);
                    covering.push(Self::with_switches(motion, colour, switches));
                }
            }
        }
        covering
    }

    /// A dense index in 0..[`ObjectVariant::COUNT`], the position in [`ObjectVariant::all`].
    #[must_use]
    pub fn index(self) -> usize {
        let kind = self.motion.index() * SurfaceColourCode::ALL.len() + self.colour.index();
        let bits = self
            .switches()
            .into_iter()
            .fold(0, |bits, on| (bits << 1) | usize::from(on));
        (kind << Self::SWITCHES) | bits
    }

    /// The variant whose visibility pipelines this one's are: the visibility passes find hits
    /// and shade nothing, so only the counter and the kind of motion matter to them.
    #[must_use]
    pub fn for_visibility(self) -> Self {
        Self {
            counting: self.counting,
            lit: self.lit,
            motion: self.motion,
            ..Self::PLAIN
        }
    }

    /// The variant's part of a shader's name, e.g. " (lit, spin, spectral)"; empty for
    /// [`ObjectVariant::PLAIN`].
    fn describe(self) -> String {
        let words: Vec<&str> = [
            (self.counting, "counting"),
            (self.lit, "lit"),
            (self.shadowed, "shadowed"),
            (self.motion == MotionCode::SPIN, "spin"),
            (self.motion == MotionCode::THRUST, "thrust"),
            (self.colour == SurfaceColourCode::SPECTRAL, "spectral"),
            (self.textured, "textured"),
            (self.clock, "clock"),
            (self.wireframe, "wireframe"),
            (self.seen, "seen"),
        ]
        .into_iter()
        .filter_map(|(on, word)| on.then_some(word))
        .collect();
        if words.is_empty() {
            String::new()
        } else {
            format!(" ({})", words.join(", "))
        }
    }

    /// The overrides of the polygon shader for this variant (the counter aside): motion.wgsl's,
    /// surface.wgsl's, the shadow test's and spectral.wgsl's.
    fn polygon_overrides(self) -> Vec<Override> {
        let mut overrides = vec![
            ("MOTION_VARIANT", f64::from(self.motion.0)),
            (
                "MOTION_SPIN_PIECE_ANGLE",
                srt_physics::motion::SPIN_PIECE_ANGLE,
            ),
            (
                "MOTION_THRUST_PIECES_PER_SIZE",
                srt_physics::motion::THRUST_PIECES_PER_SIZE,
            ),
            ("SURFACE_COLOUR_VARIANT", f64::from(self.colour.0)),
            ("TEXTURED_VARIANT", f64::from(u8::from(self.textured))),
            ("CLOCK_VARIANT", f64::from(u8::from(self.clock))),
            ("WIREFRAME_VARIANT", f64::from(u8::from(self.wireframe))),
            ("SEEN_VARIANT", f64::from(u8::from(self.seen))),
        ];
        overrides.extend(shadow_overrides(
            f64::from(u8::from(self.lit)),
            f64::from(u8::from(self.shadowed)),
        ));
        overrides.extend(SPECTRAL_OVERRIDES);
        overrides
    }

    /// The overrides of the LRT shader (with the ray tracer's): the fragment counter, then
    /// [`ObjectVariant::polygon_overrides`].
    fn lrt_overrides(self) -> Vec<Override> {
        let mut overrides = vec![("COUNT_FRAGMENTS", f64::from(u8::from(self.counting)))];
        overrides.extend(self.polygon_overrides());
        overrides
    }
}

/// The overrides of the sky shader: its workgroup size, the colour temperature of a sky
/// image's light, and spectral.wgsl's.
const SKY_OVERRIDES: [Override; 8] = joined(
    [
        ("WORKGROUP_SIZE", WORKGROUP_SIZE as f64),
        ("SKY_IMAGE_WHITE_K", srt_scene::sky::SKY_IMAGE_WHITE_K),
    ],
    SPECTRAL_OVERRIDES,
);

/// The overrides of the probe shader: its workgroup size and spectral.wgsl's.
const PROBE_OVERRIDES: [Override; 7] = joined(
    [("WORKGROUP_SIZE", WORKGROUP_SIZE as f64)],
    SPECTRAL_OVERRIDES,
);

/// WGSL names of the render passes' blocks of per-frame, per-object and per-part values.
pub const BLOCKS: [&str; 4] = ["frame_uniforms", "object", "part", "sky"];

/// How the render passes' [`BLOCKS`] are bound on a device: as read-only storage buffers, as
/// the WGSL declares them, or as uniform buffers on the GL backend.
///
/// Storage, because Mesa 22.3's lavapipe recompiles a shader at every bind group change while
/// a uniform buffer decides one of its branches (shaders/render_bindings.wgsl says more);
/// uniform on GL, because llvmpipe's GL driver reads a storage-buffer `object` wrongly in the
/// spinning body's ray search (blocks of missed pixels in `rolling-wheel`), and it does not
/// recompile for uniforms. The two read alike on GPUs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BlockSpace {
    /// `var<storage, read>`.
    Storage,
    /// `var<uniform>`.
    Uniform,
}

impl BlockSpace {
    /// The usages of a block's buffer: bindable in either space, written by the queue.
    pub const BUFFER_USAGES: wgpu::BufferUsages = wgpu::BufferUsages::STORAGE
        .union(wgpu::BufferUsages::UNIFORM)
        .union(wgpu::BufferUsages::COPY_DST);

    /// The space of `device`'s backend.
    #[must_use]
    pub fn of(device: &wgpu::Device) -> Self {
        if device.adapter_info().backend == wgpu::Backend::Gl {
            Self::Uniform
        } else {
            Self::Storage
        }
    }

    /// `source` with the blocks declared in this space.
    #[must_use]
    pub fn declare(self, source: &str) -> String {
        match self {
            Self::Uniform => rewrite_each(source, &BLOCKS, |name| {
                (
                    format!("var<storage, read> {name}:"),
                    format!("var<uniform> {name}:"),
                )
            }),
            Self::Storage => source.to_owned(),
        }
    }

    /// The binding type of `slot` (named `wgsl_name`) in this space.
    #[must_use]
    pub fn binding_type(self, wgsl_name: &str, ty: wgpu::BindingType) -> wgpu::BindingType {
        match self {
            Self::Uniform if BLOCKS.contains(&wgsl_name) => wgpu::BindingType::Buffer {
                ty: wgpu::BufferBindingType::Uniform,
                has_dynamic_offset: false,
                min_binding_size: None,
            },
            _ => ty,
        }
    }
}

/// Whether the visibility passes' fragments declare the depth they write to be at least the
/// rasterised depth (WGSL `@early_depth_test(greater_equal)`, SPIR-V `DepthGreater`), so that a
/// GPU may test depth before running them and skip those behind what is already drawn. It holds
/// because every footprint is drawn at its `nearest_depth` (proxy.wgsl), a lower bound of the
/// apparent distance of any hit its fragments can find ([`srt_proxy::nearest_apparent_distance`]);
/// the fragment counter's third word counts fragments that break it (a test requires none).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ConservativeDepth {
    /// Declared: the device has [`wgpu::Features::SHADER_EARLY_DEPTH_TEST`] (Vulkan, GLES 3.1+).
    Declared,
    /// Not declared (WebGPU has no such feature): depth is tested after each fragment.
    Undeclared,
}

/// The fragment entry points of the visibility passes, LRT's (flat and lean varyings) and the
/// ray tracer's: those [`ConservativeDepth::Declared`] marks.
pub const VISIBILITY_FRAGMENT_ENTRIES: [&str; 4] = [
    "lrt_visibility",
    "lrt_visibility_lean",
    "rt_visibility",
    "rt_visibility_lean",
];

impl ConservativeDepth {
    /// What `device` allows.
    #[must_use]
    pub fn of(device: &wgpu::Device) -> Self {
        if device
            .features()
            .contains(wgpu::Features::SHADER_EARLY_DEPTH_TEST)
        {
            Self::Declared
        } else {
            Self::Undeclared
        }
    }

    /// `source` with every [`VISIBILITY_FRAGMENT_ENTRIES`] entry point it defines declared so.
    #[must_use]
    pub fn declare(self, source: &str) -> String {
        match self {
            Self::Declared => rewrite_each(source, &VISIBILITY_FRAGMENT_ENTRIES, |name| {
                (
                    format!("@fragment\nfn {name}("),
                    format!("@fragment @early_depth_test(greater_equal)\nfn {name}("),
                )
            }),
            Self::Undeclared => source.to_owned(),
        }
    }
}

/// `source` with, for each of `names`, every occurrence of the first text `rewrite` gives for
/// it replaced by the second: how a device's declarations ([`BlockSpace`],
/// [`ConservativeDepth`]) are written into the composed WGSL.
fn rewrite_each(
    source: &str,
    names: &[&str],
    rewrite: impl Fn(&str) -> (String, String),
) -> String {
    names.iter().fold(source.to_owned(), |text, name| {
        let (from, to) = rewrite(name);
        text.replace(&from, &to)
    })
}

/// A composed shader and the values of its pipeline-overridable constants.
#[derive(Debug, Clone)]
pub struct Shader {
    /// Name, for labels and test reports.
    pub name: String,
    /// The composed WGSL source.
    pub source: String,
    /// Value of every WGSL `override` of the source, by name, as wgpu takes them.
    pub overrides: Vec<(&'static str, f64)>,
}

impl Shader {
    /// The shader module on `device`, its blocks declared in the device's [`BlockSpace`] and
    /// its visibility fragments' depth as the device's [`ConservativeDepth`] allows.
    #[must_use]
    pub fn module(&self, device: &wgpu::Device) -> wgpu::ShaderModule {
        let source = BlockSpace::of(device).declare(&self.source);
        let source = ConservativeDepth::of(device).declare(&source);
        device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(&self.name),
            source: wgpu::ShaderSource::Wgsl(source.into()),
        })
    }

    /// Pipeline compilation options that set every override of this shader.
    #[must_use]
    pub fn compilation_options(&self) -> wgpu::PipelineCompilationOptions<'_> {
        wgpu::PipelineCompilationOptions {
            constants: &self.overrides,
            ..Default::default()
        }
    }
}

/// The footprint compute shader.
#[must_use]
pub fn proxy() -> Shader {
    Shader {
        name: "proxy".into(),
        source: compose(&[
            ("physics.wgsl", PHYSICS),
            ("types.wgsl", TYPES),
            ("render_bindings.wgsl", RENDER_BINDINGS),
            ("proxy.wgsl", PROXY),
        ]),
        overrides: PROXY_OVERRIDES.to_vec(),
    }
}

/// The local ray tracing shader, with the GPU ray tracer's visibility pass (rt.wgsl), compiled
/// for `variant`.
#[must_use]
pub fn lrt(variant: ObjectVariant) -> Shader {
    Shader {
        name: format!("lrt{}", variant.describe()),
        source: compose(&[
            ("physics.wgsl", PHYSICS),
            ("types.wgsl", TYPES),
            ("colour.wgsl", COLOUR),
            ("spectral.wgsl", SPECTRAL),
            ("light.wgsl", LIGHT),
            ("render_bindings.wgsl", RENDER_BINDINGS),
            ("camera.wgsl", CAMERA),
            ("clock.wgsl", CLOCK),
            ("triangle.wgsl", TRIANGLE),
            ("surface.wgsl", SURFACE),
            ("bvh.wgsl", BVH),
            ("shadows.wgsl", SHADOWS),
            ("motion.wgsl", MOTION),
            ("lrt.wgsl", LRT),
            ("rt.wgsl", RT),
        ]),
        overrides: variant.lrt_overrides(),
    }
}

/// The polygon-rendering shader, compiled for `variant` (which must not count fragments: the
/// polygon pass has no counter).
#[must_use]
pub fn polygon(variant: ObjectVariant) -> Shader {
    Shader {
        name: format!("polygon{}", variant.describe()),
        source: compose(&[
            ("physics.wgsl", PHYSICS),
            ("types.wgsl", TYPES),
            ("colour.wgsl", COLOUR),
            ("spectral.wgsl", SPECTRAL),
            ("light.wgsl", LIGHT),
            ("render_bindings.wgsl", RENDER_BINDINGS),
            ("clock.wgsl", CLOCK),
            ("triangle.wgsl", TRIANGLE),
            ("surface.wgsl", SURFACE),
            ("bvh.wgsl", BVH),
            ("shadows.wgsl", SHADOWS),
            ("motion.wgsl", MOTION),
            ("polygon.wgsl", POLYGON),
        ]),
        overrides: variant.polygon_overrides(),
    }
}

/// The image-based method's shader: the polygon shader's modules with the camera and the cube
/// map's faces and look-up (image_based.wgsl), compiled for `variant` as the polygon shader is.
#[must_use]
pub fn image_based(variant: ObjectVariant) -> Shader {
    let polygon = polygon(variant);
    Shader {
        name: format!("image-based{}", variant.describe()),
        source: polygon.source
            + &compose(&[("camera.wgsl", CAMERA), ("image_based.wgsl", IMAGE_BASED)]),
        overrides: polygon.overrides,
    }
}

/// The sky shader: the stars' compute pass and the background pass.
#[must_use]
pub fn sky() -> Shader {
    Shader {
        name: "sky".into(),
        source: compose(&[
            ("physics.wgsl", PHYSICS),
            ("types.wgsl", TYPES),
            ("colour.wgsl", COLOUR),
            ("spectral.wgsl", SPECTRAL),
            ("light.wgsl", LIGHT),
            ("camera.wgsl", CAMERA),
            ("sky.wgsl", SKY),
        ]),
        overrides: SKY_OVERRIDES.to_vec(),
    }
}

/// The kernel-probe shader of the `probe` module (feature `probe`).
#[must_use]
pub fn probe() -> Shader {
    Shader {
        name: "probe".into(),
        source: compose(&[
            ("physics.wgsl", PHYSICS),
            ("types.wgsl", TYPES),
            ("colour.wgsl", COLOUR),
            ("spectral.wgsl", SPECTRAL),
            ("probe.wgsl", PROBE),
        ]),
        overrides: PROBE_OVERRIDES.to_vec(),
    }
}

/// Composes `modules` into one WGSL source, each preceded by a comment naming it.
#[must_use]
pub fn compose(modules: &[(&str, &str)]) -> String {
    modules
        .iter()
        .map(|(name, source)| format!("// ---- {name}\n{source}\n"))
        .collect()
}

/// The display pass's shader (the `display` module draws with it).
#[must_use]
pub fn display() -> Shader {
    Shader {
        name: "display".into(),
        source: DISPLAY.to_owned(),
        overrides: Vec::new(),
    }
}

/// Every complete shader srt builds, for validation (the object passes in the variants of
/// [`ObjectVariant::covering`]).
#[must_use]
pub fn all() -> Vec<Shader> {
    let variants = ObjectVariant::covering();
    let mut all = vec![
        Shader {
            name: "physics+types".into(),
            source: compose(&[("physics.wgsl", PHYSICS), ("types.wgsl", TYPES)]),
            overrides: Vec::new(),
        },
        proxy(),
        display(),
    ];
    all.extend(variants.iter().map(|&v| lrt(v)));
    all.extend(variants.iter().filter(|v| !v.counting).map(|&v| polygon(v)));
    all.extend(
        variants
            .iter()
            .filter(|v| !v.counting)
            .map(|&v| image_based(v)),
    );
    all.extend([
        sky(),
        Shader {
            name: "colour".into(),
            source: compose(&[("colour.wgsl", COLOUR)]),
            overrides: Vec::new(),
        },
        probe(),
    ]);
    all
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn object_variants_are_indexed_densely_in_their_listed_order() {
        let all = ObjectVariant::all();
        assert_eq!(all.len(), ObjectVariant::COUNT);
        for (position, variant) in all.iter().enumerate() {
            assert_eq!(variant.index(), position, "{variant:?}");
        }
        assert_eq!(ObjectVariant::PLAIN.index(), 0);
        let names: std::collections::HashSet<String> = all.iter().map(|&v| lrt(v).name).collect();
        assert_eq!(names.len(), ObjectVariant::COUNT, "one name per variant");
        let covering = ObjectVariant::covering();
        assert!(covering.iter().all(|v| all.contains(v)));
        assert!(covering.contains(&ObjectVariant::PLAIN));
    }

    #[test]
    fn the_visibility_variant_keeps_only_what_finds_hits() {
        let shaded = ObjectVariant {
            counting: true,
            lit: true,
            shadowed: true,
            motion: MotionCode::SPIN,
            colour: SurfaceColourCode::SPECTRAL,
            textured: true,
            clock: true,
            wireframe: true,
            seen: true,
        };
        assert_eq!(
            shaded.for_visibility(),
            ObjectVariant {
                counting: true,
                lit: true,
                motion: MotionCode::SPIN,
                ..ObjectVariant::PLAIN
            }
        );
    }
}
